"""Deprecated: import from ``workbench.physics.series_parallel._systems``.

The Exudyn systems of the series-parallel module moved into the ``series_parallel`` package;
this thin re-export keeps the old path working.
"""

from __future__ import annotations

from .series_parallel._systems import (  # noqa: F401 - re-exports
    C_EXU,
    LegShape,
    ModuleSpec,
    RodParams,
    StaticOutcome,
    _TORQUE_SIGNS,
    _add_leg,
    _clamp_joint,
    _ep,
    _hole_joint,
    _section,
    _settings,
    _solve,
    _tip_wrench_on_leg,
    node_state,
    solve_leg_tip_pose,
    solve_leg_tip_wrench,
    solve_stack,
)
