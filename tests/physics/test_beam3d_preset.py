"""The Cojocaru tronconic preset and beam3d on tapered (tronconic) tendon routes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import SolverOptions
from workbench.physics import beam3d
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.presets import build_preset


def test_preset_structure():
    r = build_preset("cojocaru_tronconic")
    assert r.n_sections == 3 and r.length > 1.0
    assert r.n_tendons == 9
    for k, sec in enumerate(r.sections):
        g = sec.tendons
        np.testing.assert_allclose(np.diff(g.angles), 2 * np.pi / 3)
        # every wire starts on the base disk's rim and ends on its terminating disk's rim
        assert g.offset == pytest.approx(0.05)
        assert g.offset_tip == pytest.approx(0.05 - 0.01 * (k + 1))
    # the cone is continuous: at the end of section 0 every later wire sits where section 0's wires end
    s0 = r.section_ends[0]
    for sec in r.sections[1:]:
        g = sec.tendons
        j_end = r.section_ends[list(r.sections).index(sec)]
        assert g.offset_at(s0 / j_end) == pytest.approx(r.sections[0].tendons.offset_tip)
    with pytest.raises(ValueError, match="diameters"):
        build_preset("cojocaru_tronconic", base_disk_diameter=0.05, disk_diameter_step=0.02)


def test_tapered_tendon_curvature_matches_T_d_cos_beta():
    """Small deflection: the tendon force at a cut is T along the slanted rope at offset d(s),
    so M(s) = T d(s) cos(beta), tan(beta) = (d1 - d2) / L.  Tip rotation =
    T L cos(beta) (d1 + d2) / (2 EI).  Measured relative error with the cos(beta) factor:
    2.9e-4 / 6.7e-5 / 9e-6 at 8 / 16 / 32 disks (without it: -0.16 %, the taper slope)."""
    cs = CrossSection.circular(4e-3)
    L, d1, d2, T, sigma = 0.35, 0.05, 0.03, 5.0, 0.5
    rod = Robot(sections=(Section(length=L, cross_section=cs, n_disks=16,
                                  tendons=TendonGroup(angles=(sigma,), offset=d1, offset_tip=d2)),))
    res = beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (T,))),
                     SolverOptions(n_elements=16, tendon_model="eyelets"))
    t = res.tip_frame[:3, 2]
    beta = math.atan((d1 - d2) / L)
    ref = T * L * math.cos(beta) * 0.5 * (d1 + d2) / cs.EI
    assert math.acos(t[2]) == pytest.approx(ref, rel=3e-4)
    assert math.atan2(t[1], t[0]) == pytest.approx(sigma, abs=1e-9)


def test_equal_tensions_on_three_section_tronconic_robot_give_pure_compression():
    robot = build_preset("cojocaru_tronconic")
    T = 20.0
    values = (0.0,) * 6 + (T, T, T)  # the three wires of the last section
    res = beam3d.run(robot, LoadCase(actuation=TendonActuation("tension", values)),
                     SolverOptions(n_elements=12, tendon_model="eyelets"))
    L = robot.length
    assert np.hypot(*res.tip_position[:2]) < 1e-9 * L
    EA = robot.sections[0].cross_section.EA
    H = robot.sections[2].length
    beta = math.atan(0.01 / H)
    expected = -3 * T * (2 * H + H * math.cos(beta)) / EA
    assert res.length_change == pytest.approx(expected, rel=1e-3)
    assert abs(res.tip_twist) < 1e-12
