"""The series_parallel package: its public names, the stack IK's use of the module IK and the CC arc points."""

from __future__ import annotations

import numpy as np

import workbench.physics.series_parallel as sp
from workbench.physics.series_parallel import stack


def test_public_names_are_package_attributes():
    for name in sp.__all__:
        assert hasattr(sp, name), name


def test_stack_inverse_reports_the_failing_module(monkeypatch):
    """``stack_inverse`` solves the modules top down with ``module_inverse``; a module IK that fails
    stops the stack with that module's number and reason (the module IK replaced in ``stack``)."""
    calls = []

    def failing(geometry, target, **kw):
        calls.append(target)
        nan = np.full((6, 3), np.nan)
        return sp.ModuleIK(np.full(6, np.nan), False, 0, float("nan"), "patched", nan, nan, nan, nan,
                           np.full((6, 3, 3), np.nan))

    monkeypatch.setattr(stack, "module_inverse", failing)
    geo = sp.ModuleGeometry()
    H = sp.home_pose(geo)
    poses = np.stack([H, H @ geo.mount_transform() @ H])
    ik = sp.stack_inverse([geo, geo], poses)
    assert len(calls) == 1 and not ik.success and ik.reason == "module 2: patched"


def test_arc_points_start_at_the_base_with_unit_tangents():
    P, t = sp.arc_points(2.0, 0.3, np.array([0.0, 0.5]))
    assert np.array_equal(P[0], np.zeros(3)) and np.allclose(np.linalg.norm(t, axis=1), 1.0)
