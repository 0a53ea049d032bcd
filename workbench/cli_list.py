"""``workbench list models|presets|scenarios|kinds|figures|represents``: what the registry offers -- the
built-in rows and those of installed plug-ins, each with its package in brackets (``[built-in]`` or
``[<distribution> <version>]``) -- with each model's capabilities (``represents``: the markdown table
"What each model represents" of ``docs/models.md``).

Reads ``workbench.registry.table`` (data only) and, for presets and scenarios, their keyword
parameters with defaults; imports no model code (no Exudyn).  Checked by
``tests/study/test_cli_errors.py`` and, for plug-in rows, ``tests/test_plugins.py``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["TOPICS", "list_command", "list_lines"]

TOPICS = ("models", "presets", "scenarios", "kinds", "figures", "represents")


def _params(params: dict[str, Any]) -> str:
    return ", ".join(f"{k}={v!r}" for k, v in params.items())


def _models() -> list[str]:
    from . import registry
    from .study.capabilities import describe

    rows = registry.table("models")
    w = max(len(n) for n in [*rows, *registry.LABELS])
    out = []
    for name, info in rows.items():
        out.append(f"{name:<{w}}  {info.label}: {describe(info.capabilities)} [{registry.package('models', name)}]")
        if info.capabilities is not None and info.capabilities.note:
            out.append(f"{'':<{w}}  ({info.capabilities.note})")
    out += [f"{name:<{w}}  {row.label}: {describe(None)} [{registry.BUILT_IN}]" for name, row in registry.LABELS.items()]
    return out


def list_lines(topic: str) -> list[str]:
    """The lines ``workbench list <topic>`` prints (one of :data:`TOPICS`)."""
    from . import registry

    if topic == "models":
        return _models()
    if topic == "represents":
        from .study.capabilities import represents_table

        return represents_table().splitlines()
    return [f"{name}: {_what(topic, name, row)} [{registry.package(topic, name)}]"
            for name, row in registry.table(topic).items()]


def _what(topic: str, name: str, row: Any) -> str:
    """What a row of ``topic`` offers: a preset's or scenario's parameters, a kind's or figure set's code."""
    if topic == "presets":
        from .robot.presets import data_preset, preset_parameters

        described = data_preset(name)
        if described is not None:  # a description-form data preset: no scalar parameters, changed by key path
            return (f"{described.title}; a robot description, changed with [[robot.sections]] tables "
                    f"(docs/robot-format.md)")
        return _params(preset_parameters(name))
    if topic == "scenarios":
        from .study.scenarios import scenario_parameters

        return _params(scenario_parameters(name))
    return row.target if topic == "kinds" else row.figures


def list_command(args) -> int:
    """Print the registry rows of ``args.topic`` (exit 0)."""
    for line in list_lines(args.topic):
        print(line)
    return 0
