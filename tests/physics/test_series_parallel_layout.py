"""Guards of the series_parallel package layout: old import paths, re-exported private names,
and the call-time lookup of ``module_inverse`` that monkeypatching relies on."""

from __future__ import annotations

import numpy as np

import workbench.physics.series_parallel as sp


def test_public_and_used_private_names_are_package_attributes():
    for name in sp.__all__:
        assert hasattr(sp, name), name
    for name in ("_segment_distances", "_arc_points", "_hermite_lengths", "_ik_newton", "_ik_jacobian"):
        assert callable(getattr(sp, name)), name


def test_old_exudyn_module_path_still_works():
    from workbench.physics import _series_parallel_exudyn as old
    from workbench.physics.series_parallel import _systems as new

    for name in ("RodParams", "LegShape", "StaticOutcome", "ModuleSpec", "solve_leg_tip_pose",
                 "solve_leg_tip_wrench", "solve_stack", "_settings", "C_EXU"):
        assert getattr(old, name) is getattr(new, name), name
    assert "Deprecated" in old.__doc__


def test_stack_inverse_calls_the_package_module_inverse(monkeypatch):
    """A patch of ``workbench.physics.series_parallel.module_inverse`` reaches ``stack_inverse``
    (as when the code was one module): the stack looks the function up on the package at call time."""
    calls = []

    def failing(geometry, target, **kw):
        calls.append(target)
        nan = np.full((6, 3), np.nan)
        return sp.ModuleIK(np.full(6, np.nan), False, 0, float("nan"), "patched", nan, nan, nan, nan,
                           np.full((6, 3, 3), np.nan))

    monkeypatch.setattr(sp, "module_inverse", failing)
    geo = sp.ModuleGeometry()
    H = sp.home_pose(geo)
    poses = np.stack([H, H @ geo.mount_transform() @ H])
    ik = sp.stack_inverse([geo, geo], poses)
    assert len(calls) == 1 and not ik.success and ik.reason == "module 2: patched"


def test_arc_points_is_public_and_the_old_name_is_an_alias():
    assert sp._arc_points is sp.arc_points and "arc_points" in sp.__all__
    P, t = sp.arc_points(2.0, 0.3, np.array([0.0, 0.5]))
    assert np.array_equal(P[0], np.zeros(3)) and np.allclose(np.linalg.norm(t, axis=1), 1.0)
