"""``workbench list models|presets|scenarios|kinds|represents``: what the registry offers, with each model's
capabilities (``represents``: the markdown table "What each model represents" of ``docs/models.md``).

Reads ``workbench.registry`` (data only) and, for presets and scenarios, their keyword
parameters with defaults; imports no model code (no Exudyn).  Checked by
``tests/study/test_cli_errors.py``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["TOPICS", "list_command"]

TOPICS = ("models", "presets", "scenarios", "kinds", "represents")


def _params(params: dict[str, Any]) -> str:
    return ", ".join(f"{k}={v!r}" for k, v in params.items())


def list_lines(topic: str) -> list[str]:
    """The lines ``workbench list <topic>`` prints."""
    from . import registry

    if topic == "models":
        from .study.capabilities import describe

        w = max(len(n) for n in [*registry.MODELS, *registry.LABELS])
        out = []
        for name, info in registry.MODELS.items():
            out.append(f"{name:<{w}}  {info.label}: {describe(info.capabilities)}")
            if info.capabilities is not None and info.capabilities.note:
                out.append(f"{'':<{w}}  ({info.capabilities.note})")
        out += [f"{name:<{w}}  {row.label}: {describe(None)}" for name, row in registry.LABELS.items()]
        return out
    if topic == "represents":
        from .study.capabilities import represents_table

        return represents_table().splitlines()
    if topic == "presets":
        from .robot.presets import preset_parameters

        return [f"{name}: {_params(preset_parameters(name))}" for name in registry.PRESETS]
    if topic == "scenarios":
        from .study.scenarios import scenario_parameters

        return [f"{name}: {_params(scenario_parameters(name))}" for name in registry.SCENARIOS]
    return [f"{name}: {row.target}" for name, row in registry.KINDS.items()]


def list_command(args) -> int:
    """Print the registry rows of ``args.topic`` (exit 0)."""
    for line in list_lines(args.topic):
        print(line)
    return 0
