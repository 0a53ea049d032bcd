"""Derived quantities of a robot (``workbench.robot.derived``, ``workbench.study.robot_summary``) against
hand-calculated and analytic values.

Hand calculations (4-5 significant figures, so ``rel=2e-4``):

* steel_rod defaults: d = 6 mm, E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3, L = 0.8 m:
  I = pi d^4 / 64 = 6.3617e-11 m^4, EI = 13.360 N m^2; A = pi d^2 / 4 = 2.8274e-5 m^2, EA = 5.9376e6 N;
  G = E / 2.6 = 80.769 GPa, J = 2 I, GJ = 10.277 N m^2; m' = rho A = 0.22195 kg/m, mass 0.17756 kg.
* the Rao et al. 2021 robot (2 x 0.2 m, E = 54 GPa, d = 1.4 mm; NiTi density 6450 kg/m^3, nu = 0.33):
  I = pi (1.4e-3)^4 / 64 = 1.8857e-13 m^4, EI = 0.010183 N m^2; A = 1.5394e-6 m^2, EA = 83127 N;
  G = 54e9 / 2.66 = 20.301 GPa, GJ = 0.0076564 N m^2; m' = 9.9290e-3 kg/m.
"""

from __future__ import annotations

import math

import pytest
from scipy.optimize import brentq

from workbench.robot import CrossSection, Payload, Robot, Section
from workbench.robot.derived import (BETA1_L, cantilever_frequency, finite_element_frequency,
                                     first_bending_frequency, section_properties, tendon_properties, total_mass)
from workbench.robot.presets import build_preset
from workbench.study.build import resolve_robot
from workbench.study.robot_summary import STANDARD_GRAVITY, command_stresses, gravity_parameter, summarize_robot

HAND = 2e-4


def rao(**kw):
    """The Rao et al. 2021 robot as a steel_rod preset: 2 x 0.2 m NiTi, 3 tendons at 90/210/330 deg, 10 mm."""
    params = dict(length=0.4, diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.33,
                  n_sections=2, tendon_count=3, first_tendon_angle=math.pi / 2, tendon_offset=0.01,
                  disks_per_section=10)
    return build_preset("steel_rod", **{**params, **kw})


def test_steel_rod_section_by_hand():
    (p,) = section_properties(build_preset("steel_rod"))
    assert p.EI == pytest.approx(13.360, rel=HAND)
    assert p.EA == pytest.approx(5.9376e6, rel=HAND)
    assert p.GJ == pytest.approx(10.277, rel=HAND)
    assert p.mass_per_length == pytest.approx(0.22195, rel=HAND)
    assert p.mass == pytest.approx(0.17756, rel=HAND)
    assert p.EI_tip is None and p.mass_per_length_tip is None


def test_rao_sections_by_hand():
    ps = section_properties(rao())
    assert len(ps) == 2
    for p in ps:
        assert p.EI == pytest.approx(0.010183, rel=HAND)
        assert p.EA == pytest.approx(83127.0, rel=HAND)
        assert p.GJ == pytest.approx(7.6564e-3, rel=HAND)
        assert p.mass_per_length == pytest.approx(9.9290e-3, rel=HAND)
        assert p.backbone_mass == pytest.approx(9.9290e-3 * 0.2, rel=HAND)


def test_disks_smeared_and_total_mass_with_payload():
    r = build_preset("steel_rod", n_sections=2, disks_per_section=5, disk_mass=0.01, payload_mass=0.2)
    ps = section_properties(r)
    # 5 disks of 10 g over 0.4 m: 0.125 kg/m on top of the backbone's 0.22195
    assert ps[0].mass_per_length_smeared == pytest.approx(0.22195 + 0.125, rel=HAND)
    assert ps[0].disk_mass == pytest.approx(0.05)
    assert total_mass(r) == pytest.approx(0.17756 + 0.1 + 0.2, rel=HAND)


def test_tendon_stiffness_and_strength_by_hand():
    (t,) = tendon_properties(build_preset("steel_rod"))
    # EA_t = 4e4 N over L_t = 0.8 m; A_t = 4e4 / 210e9 = 1.9048e-7 m^2; F = 2.41e9 A_t = 459.05 N
    assert t.spring_stiffness == pytest.approx(5.0e4)
    assert t.area == pytest.approx(1.9048e-7, rel=HAND)
    assert t.force_at_strength == pytest.approx(459.05, rel=HAND)
    t1, t2 = tendon_properties(rao())
    assert (t1.routed_length, t2.routed_length) == (pytest.approx(0.2), pytest.approx(0.4))
    assert t2.spring_stiffness == pytest.approx(1.0e5)
    assert [round(math.degrees(a)) for a in t2.angles] == [90, 210, 330]


def test_tapered_group_offsets():
    r = build_preset("cojocaru_tronconic")
    for t, s in zip(tendon_properties(r), r.sections):
        assert t.offset == s.tendons.offset
        assert t.offset_tip == s.tendons.offset_tip != t.offset


def test_uniform_frequency_is_the_analytic_cantilever_by_hand():
    # f1 = 1.8751^2 / (2 pi) sqrt(13.360 / (0.22195 0.8^4)) = 0.55960 x 12.1229 = 6.7840 Hz
    f = first_bending_frequency(build_preset("steel_rod"))
    assert f.method == "analytic"
    assert f.hertz == pytest.approx(6.7840, rel=HAND)
    assert 1 + math.cos(BETA1_L) * math.cosh(BETA1_L) == pytest.approx(0.0, abs=1e-12)


def test_finite_elements_converge_to_the_analytic_cantilever():
    r = rao()
    cs = r.sections[0].cross_section
    exact = cantilever_frequency(cs.EI, cs.mass_per_length, r.length)
    coarse, fine = finite_element_frequency(r, 1), finite_element_frequency(r, 24)
    assert fine == pytest.approx(exact, rel=1e-6)
    assert abs(fine - exact) < abs(coarse - exact)


def test_finite_elements_with_a_tip_mass_solve_the_frequency_equation():
    """Cantilever with tip mass M: 1 + cos x cosh x + mu x (cos x sinh x - sin x cosh x) = 0, mu = M / (m' L)."""
    r = build_preset("steel_rod", payload_mass=0.1)
    cs = r.sections[0].cross_section
    mu = 0.1 / (cs.mass_per_length * r.length)
    x = brentq(lambda x: 1 + math.cos(x) * math.cosh(x)
               + mu * x * (math.cos(x) * math.sinh(x) - math.sin(x) * math.cosh(x)), 0.3, BETA1_L)
    exact = x**2 * math.sqrt(cs.EI / (cs.mass_per_length * r.length**4)) / (2 * math.pi)
    f = first_bending_frequency(r)
    assert f.method == "finite elements"
    assert f.hertz == pytest.approx(exact, rel=1e-6)


def test_massless_backbone_with_a_tip_mass_is_a_spring():
    """m' = 0: f = sqrt(3 EI / (M L^3)) / (2 pi) (the singular mass matrix path)."""
    rod = CrossSection(EI=2.0, EA=1e6, GJ=1.0, mass_per_length=0.0)
    r = Robot(sections=(Section(length=0.5, cross_section=rod, n_disks=4),), payload=Payload(mass=0.3))
    exact = math.sqrt(3 * 2.0 / (0.3 * 0.5**3)) / (2 * math.pi)
    assert first_bending_frequency(r).hertz == pytest.approx(exact, rel=1e-9)
    massless = Robot(sections=(Section(length=0.5, cross_section=rod),))
    assert first_bending_frequency(massless) is None


def test_gravity_parameter_by_hand_and_round_trip():
    # gamma = m' g L^3 / EI = 0.22195 x 9.80665 x 0.512 / 13.360 = 0.083414
    r = build_preset("steel_rod")
    assert gravity_parameter(r) == 0.0
    assert gravity_parameter(r, STANDARD_GRAVITY) == pytest.approx(0.083414, rel=HAND)
    robot, _ = resolve_robot({"preset": "steel_rod"}, {"gravity_parameter": 2.5})
    assert gravity_parameter(robot) == pytest.approx(2.5, rel=1e-12)
    assert gravity_parameter(build_preset("hannan_walker")) is None  # sections differ


def test_stresses_at_90_degrees_by_hand():
    """kappa = (pi/2) / 0.8 = 1.9635 /m, M = EI kappa = 26.232 N m, T = M / d = 1311.6 N;
    backbone T / A + M / W = 46.39 + 1236.9 = 1283.3 MPa (W = pi d^3 / 32 = 2.1206e-8 m^3);
    tendon T / A_t = 1311.6 / 1.9048e-7 = 6885.9 MPa."""
    st = command_stresses(build_preset("steel_rod"))
    assert st.tensions == (pytest.approx(1311.6, rel=HAND), 0.0)
    assert st.bend_angles == (pytest.approx(math.pi / 2),)
    assert st.backbone[0] == pytest.approx(1283.3e6, rel=HAND)
    assert st.tendon[0] == pytest.approx(6885.9e6, rel=HAND)
    assert st.backbone_ratio == pytest.approx(1283.3 / 1200, rel=HAND)
    assert st.tendon_ratio == pytest.approx(6885.9 / 2410, rel=HAND)


def test_stresses_at_a_given_tension_by_hand():
    """5 N on the 90 deg tendon of both sections: section 1 carries M = 2 x 5 N x 0.01 m = 0.1 N m,
    section 2 0.05 N m; bend angle kappa L = M L / EI = 0.1 x 0.2 / 0.010183 = 1.9641 rad."""
    st = command_stresses(rao(), 5.0)
    assert st.tensions == (5.0, 0.0, 0.0, 5.0, 0.0, 0.0)
    assert st.bend_angles == (pytest.approx(1.9641, rel=HAND), pytest.approx(0.98203, rel=HAND))
    # backbone of section 1: 10 N / A + 0.1 N m / W, W = pi (1.4e-3)^3 / 32 = 2.6939e-10 m^3
    assert st.backbone[0] == pytest.approx(10 / 1.5394e-6 + 0.1 / 2.6939e-10, rel=HAND)
    per_tendon = command_stresses(rao(), (5.0, 0.0, 0.0, 5.0, 0.0, 0.0))
    assert per_tendon.bend_angles == st.bend_angles


@pytest.mark.parametrize("tension, words", [((1.0, 2.0, 3.0), "one tension per tendon"), (-1.0, ">= 0"),
                                            (float("nan"), ">= 0")])
def test_bad_tensions_are_one_line(tension, words):
    with pytest.raises(ValueError, match=words):
        command_stresses(build_preset("steel_rod"), tension)


def test_summary_reports_a_command_the_tendons_cannot_make():
    rod = CrossSection.circular(6e-3)
    r = Robot(sections=(Section(length=0.5, cross_section=rod),))  # no tendons at all
    s = summarize_robot(r)
    assert s.stresses is None and s.stress_problem == "the robot has no tendons"
