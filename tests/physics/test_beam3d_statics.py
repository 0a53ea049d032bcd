"""beam3d static method of issue 18: stiffness continuation, numerical Jacobian, position-marker eyelets.

The fast path must give the equilibrium of the formulation before issue 18 (rigid-marker eyelets,
Exudyn's beam Jacobian, plain load ramp), solved independently at a tight tolerance; measured
speed is in ``benchmarks/bench_eyelet_statics.py``, not asserted here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from exudyn.itemInterface import MarkerBodyRigid

from workbench.models import SolverOptions
from workbench.physics import _beam3d_system, beam3d
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

TENSIONS = (4.0, 0.0, 0.0, 0.0, 2.0, 0.0)


def _niti(disks: int) -> Robot:
    """Issue 18's two-section NiTi robot (2 x 0.2 m, d 1.4 mm, 3 tendons per section, 10 mm offset)."""
    cs = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, cs, tg, n_disks=disks), Section(0.2, cs, tg, n_disks=disks)))


def test_auto_stages_start_at_unit_slenderness_ratio_and_rise_by_30():
    EA, EI, le = np.full(4, 8.0e4), np.full(4, 1.0e-2), np.full(4, 0.02)
    st = beam3d.auto_stiffness_stages(EA, EI, le)
    ratio = 8.0e4 * 0.02**2 / 1.0e-2
    assert st[0] == pytest.approx(1.0 / ratio)
    assert np.allclose(np.diff(np.log(st)), math.log(30.0))
    assert st[-1] < 1 / 3 <= 30.0 * st[-1]
    assert beam3d.auto_stiffness_stages(EA, 1e4 * EI, le) == ()  # EA le^2 / EI = 0.32: plain ramp


@pytest.mark.parametrize("stages", [(0.5, 0.1), (0.0, 0.1), (1.0,), "fast"])
def test_bad_stages_are_rejected(stages):
    with pytest.raises(ValueError, match="stiffness_stages"):
        beam3d.run(_niti(2), LoadCase(actuation=TendonActuation("tension", TENSIONS)), SolverOptions(n_elements=4),
                   stiffness_stages=stages)


@pytest.mark.slow
def test_fast_static_method_matches_the_old_formulation(monkeypatch):
    """Two sections, 5 disks each, one element per disk interval: the default method (position
    markers, stiffness continuation, numerical Jacobian) against rigid markers, Exudyn's beam
    Jacobian and the plain load ramp at tolerance 1e-12 -- the same equilibrium to 1e-9 m, far below
    the discretisation error (tip moves ~1e-2 m between 1 and 2 elements per interval)."""
    robot, load = _niti(5), LoadCase(actuation=TendonActuation("tension", TENSIONS))
    opts = SolverOptions(n_elements=10, tendon_model="eyelets", newton_tolerance=1e-10, max_load_steps=2000)
    fast = beam3d.run(robot, load, opts)
    monkeypatch.setattr(_beam3d_system, "MarkerBodyPosition", MarkerBodyRigid)
    tight = SolverOptions(n_elements=10, tendon_model="eyelets", newton_tolerance=1e-12, max_load_steps=2000)
    old = beam3d.run(robot, load, tight, stiffness_stages=(), jacobian="exudyn_beam")
    assert np.linalg.norm(fast.tip_position - robot.length * np.array([0, 0, 1])) > 0.05  # a large deflection
    assert np.linalg.norm(fast.tip_position - old.tip_position) < 1e-9
    assert np.allclose(fast.positions, old.positions, atol=1e-9, rtol=0)
    assert fast.length_change == pytest.approx(old.length_change, abs=1e-11)
    assert fast.solver.iterations < old.solver.iterations


def test_stages_and_plain_ramp_agree_with_gravity_and_tip_force():
    """Loads ramped in the soft stage (gravity, tip force) end at the same equilibrium as the plain ramp."""
    robot = _niti(5)
    robot = Robot(sections=robot.sections, gravity=(0.0, 0.0, -9.81))
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 0.0, 0.0, 0.0, 1.0, 0.0)), tip_force=(0.0, 0.05, 0.0))
    opts = SolverOptions(n_elements=10, tendon_model="eyelets", newton_tolerance=1e-11, max_load_steps=2000)
    a = beam3d.run(robot, load, opts)
    b = beam3d.run(robot, load, opts, stiffness_stages=())
    assert np.linalg.norm(a.tip_position - b.tip_position) < 1e-9
    assert np.linalg.norm(a.tip_position - robot.length * np.array([0, 0, 1])) > 0.02


def test_position_marker_eyelets_equal_rigid_marker_eyelets(monkeypatch):
    """The eyelet points are the same with either marker type (default static method for both)."""
    robot, load = _niti(5), LoadCase(actuation=TendonActuation("tension", TENSIONS))
    opts = SolverOptions(n_elements=10, tendon_model="eyelets", newton_tolerance=1e-11, max_load_steps=2000)
    a = beam3d.run(robot, load, opts)
    monkeypatch.setattr(_beam3d_system, "MarkerBodyPosition", MarkerBodyRigid)
    b = beam3d.run(robot, load, opts)
    assert np.linalg.norm(a.tip_position - robot.length * np.array([0, 0, 1])) > 0.05
    assert np.linalg.norm(a.tip_position - b.tip_position) < 1e-9
