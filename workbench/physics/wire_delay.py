"""Deprecated: import from ``workbench.experiments.wire_delay.analysis``.

The wire-delay experiment (Cojocaru) moved to ``workbench/experiments/wire_delay/``; its
research notes are in ``docs/models.md``.  This shim keeps the old names, resolved lazily
through registry-style strings (a generic package never imports ``workbench.experiments``):
``wire_lengths_tronconic`` is ``wire_lengths_tronconic_workbench`` (the workbench-convention
adapter; the paper-convention map is :func:`workbench.kinematics.wire_lengths_tronconic_paper`).
"""

from __future__ import annotations

from typing import Any

from ..registry import resolve

__all__ = [
    "wire_lengths_tronconic",
    "arc_from_wire_lengths_tronconic",
    "WireDelayResult",
    "simulate_wire_delay",
    "default_options",
]

_TARGET = "workbench.experiments.wire_delay.analysis"
_MOVED = {
    "wire_lengths_tronconic": "wire_lengths_tronconic_workbench",
    "arc_from_wire_lengths_tronconic": "arc_from_wire_lengths_tronconic_workbench",
    "WireDelayResult": "WireDelayResult",
    "simulate_wire_delay": "simulate_wire_delay",
    "default_options": "default_options",
    "_cc_tip": "cc_tip_positions",
    "_eq12": "eq12_compression",
}


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        return resolve(f"{_TARGET}:{_MOVED[name]}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
