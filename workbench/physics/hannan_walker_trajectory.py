"""Deprecated: import from ``workbench.experiments.hannan_walker.replay``.

The Hannan & Walker replay (CC line plan -> cable lengths -> spring-link physics) moved to
``workbench/experiments/hannan_walker/``; its measured tip errors are in ``docs/models.md``.
This shim keeps the old names, resolved lazily through registry-style strings (a generic
package never imports ``workbench.experiments``).
"""

from __future__ import annotations

from typing import Any

from ..registry import resolve

__all__ = [
    "cable_changes_from_joint_angles",
    "joint_angles_from_cable_changes",
    "HannanWalkerReplay",
    "replay_hannan_walker",
]

_TARGET = "workbench.experiments.hannan_walker.replay"
_MOVED = set(__all__) | {"_routing", "cc_cable_plan", "CCCablePlan"}


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        return resolve(f"{_TARGET}:{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
