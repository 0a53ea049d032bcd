"""The report page: one self-contained HTML file rendered from ``assets/page.html.j2`` (Jinja2).

The page is a list of :class:`Section` objects in :data:`SECTIONS` order; each comes from a
builder ``builder(ctx: PageContext) -> Section | None`` (``None``: the section does not apply).
**To add a section** (e.g. a study's question, findings, assumptions, sensitivity): write its
builder (in :mod:`.sections` or its own module) and put its name in :data:`SECTIONS` where it
belongs; nothing else changes.  Data the page's scripts read is embedded as JSON blocks
(``<script type="application/json">``, ``</`` and ``://`` escaped), the scripts and the style
sheet are inlined from ``assets/``: the page references nothing outside itself and works
offline.  Checked by ``tests/report/test_report_build.py`` and the browser tests.
"""

from __future__ import annotations

import json
from importlib import resources
from typing import Any, Callable, Mapping, Sequence

from jinja2 import Environment, select_autoescape
from markupsafe import Markup

from .context import PageContext, Section

__all__ = ["PageContext", "SECTIONS", "Section", "asset_text", "json_block", "render_page"]


#: The page's sections, in order: names of builders in :mod:`.sections` (``module:function`` for others).
SECTIONS: tuple[str, ...] = (
    "workbench.report.findings:question_section", "workbench.report.findings:findings_section",
    "workbench.report.findings:assumptions_section", "workbench.report.findings:sensitivity_section",
    "provenance", "failed", "workbench.report.measurements:measurements_section", "summary", "cases", "viewer", "figures", "spec",
)


def asset_text(name: str) -> str:
    """Text of ``workbench/report/assets/<name>`` (package data)."""
    return resources.files(__package__).joinpath("assets", name).read_text(encoding="utf-8")


def json_block(obj: Any) -> str:
    """JSON safe to inline in ``<script type="application/json">`` (no ``</``, no ``://``)."""
    text = json.dumps(obj, separators=(",", ":"), allow_nan=False, default=str)
    return text.replace("</", "<\\/").replace("://", ":\\/\\/")


def _builder(name: str) -> Callable[[PageContext], Section | None]:
    if ":" in name:
        import importlib

        mod, attr = name.split(":", 1)
        return getattr(importlib.import_module(mod), attr)
    from . import sections

    return getattr(sections, f"{name}_section")


def render_page(ctx: PageContext, banners: Sequence[str], data_blocks: Mapping[str, Any],
                scripts: Sequence[str] = ("table.js", "viewer.js", "selftest.js")) -> str:
    """The whole HTML page of ``ctx``: banners (plain text), the sections, JSON blocks, inlined scripts."""
    built = [s for s in (_builder(n)(ctx) for n in SECTIONS) if s is not None]
    env = Environment(autoescape=select_autoescape(default=True, default_for_string=True))
    template = env.from_string(asset_text("page.html.j2"))
    return template.render(
        name=ctx.study.name,
        css=Markup(asset_text("report.css")),
        banners=[b.replace("://", ":\u200b//") for b in banners],
        sections=[{"id": s.id, "title": s.title, "heading": s.heading, "html": Markup(s.html)} for s in built],
        data_blocks=[(k, Markup(json_block(v))) for k, v in data_blocks.items()],
        scripts=[Markup(asset_text(n)) for n in scripts],
    )
