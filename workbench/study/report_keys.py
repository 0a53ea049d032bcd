"""Validation of the ``[report]`` hints of a sweep study: axes and labels must name columns that will exist.

A report axis or label names a column of the result table: a case parameter (``p.robot.length``,
also written without ``p.``), a ``[report] derived`` column, one of the report's dimensionless
columns (``kappaL``, ``gamma``, ``d_over_L``) or a result column (``tip_x``, ...).  A typo used
to be accepted silently and the report then plotted other axes; :func:`check_report` names it,
with the closest known name.  ``reference`` (one of the models) is checked in :mod:`.spec`.

Checked by ``tests/study/test_capabilities.py`` (the one-pass corpus).
"""

from __future__ import annotations

from typing import Any, Iterable, Mapping

from .store import CORE_COLUMNS

__all__ = ["DIMENSIONLESS", "check_report", "report_columns"]

#: Columns the comparison table derives from the parameters (``workbench.compare.table``).
DIMENSIONLESS = ("kappaL", "gamma", "d_over_L")


def report_columns(paths: Iterable[str], report: Mapping[str, Any]) -> set[str]:
    """Every name an axis may use: ``p.<path>`` and ``<path>``, derived, dimensionless and result columns."""
    names = set(DIMENSIONLESS) | {c for c, _ in CORE_COLUMNS} | set((report.get("derived") or {}))
    for p in paths:
        names.update((p, f"p.{p}"))
    return names


def _hint(name: str, known: set[str]) -> str:
    import difflib

    close = difflib.get_close_matches(name, sorted(known), n=1, cutoff=0.6)
    if close:
        return f"; did you mean {close[0]!r}?"
    return ("; use a case parameter (p.<section>.<key>), a [report] derived name, "
            f"{', '.join(DIMENSIONLESS)} or a result column")


def check_report(report: Mapping[str, Any], paths: Iterable[str]) -> list[str]:
    """Problems of ``[report] axes`` / ``labels`` (one line each, ``report.axes[i]: ...``)."""
    known = report_columns(list(paths), report)
    out = []
    for i, a in enumerate(report.get("axes") or []):
        if a not in known:
            out.append(f"report.axes[{i}]: unknown column {a!r}{_hint(a, known)}")
    for k in report.get("labels") or {}:
        if k not in known and not k.startswith(("x.", "series.")):
            out.append(f'report.labels["{k}"]: labels an unknown column{_hint(k, known)}')
    return out
