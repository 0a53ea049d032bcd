"""Backbone and tendon stresses of every model against hand formulas.

* A cantilever under a tip force with a lateral and an axial (tensile) part: at a cross-section
  ``s`` the backbone carries ``N = F . t`` and the moment ``M = (r_tip - r(s)) x F`` (statics of the
  distal part, exact at any deflection), so ``sigma = |N| / A + |M| c / I`` at the model's first
  stress sample: the clamp for the cable models (ANCF, ANCF 3-D), the first element's midpoint for
  the GE beam (constant strain per element), the first joint for the spring-link chain.
* A straight rod pulled by two equal antagonistic tendons: no bending, ``sigma = 2 T / A``, tendon
  stress ``T / A_t``; the stress ratio divides by the declared strengths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.models.stress import combined_stress, stress_extras
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

L = 0.8
YIELD, WIRE_AREA, WIRE_STRENGTH = 1.2e9, 1.9e-7, 2.4e9
ROD = CrossSection.circular(6e-3, yield_strength=YIELD)
A, W = ROD.area, ROD.section_modulus


def _robot(n_disks=8):
    tendons = TendonGroup((0.0, math.pi), 0.02, 4e4, area=WIRE_AREA, strength=WIRE_STRENGTH)
    return Robot(sections=(Section(length=L, cross_section=ROD, tendons=tendons, n_disks=n_disks),))


def test_circular_section_stress_geometry():
    d = 6e-3
    assert A == pytest.approx(math.pi * d**2 / 4, rel=1e-15)
    assert W == pytest.approx(math.pi * d**3 / 32, rel=1e-15)  # I / c
    assert combined_stress(-10.0, 2.0, A, W) == pytest.approx(10.0 / A + 2.0 / W)


# first stress sample of each model at 16 elements / links: station index with n_stations = 33
# (spacing L / 32): the clamp (0), the first element's midpoint (L/32, station 1), the first joint (ds/2, station 1)
FIRST_SAMPLE = {"ancf": 0, "ancf3d": 0, "beam3d": 1, "spring_link": 1}


@pytest.mark.parametrize("model", list(FIRST_SAMPLE))
def test_cantilever_under_tip_load_matches_statics(model):
    F = np.array([0.5 * ROD.EI / L**2, 0.0, 20.0])  # lateral alpha = 0.5 plus 20 N of tension
    res = get_model(model)(_robot(), LoadCase(tip_force=tuple(F)), SolverOptions(n_elements=16, n_stations=33))
    k = FIRST_SAMPLE[model]
    r = res.positions[k]
    t = res.positions[k + 1] - res.positions[k - 1] if k else res.positions[1] - res.positions[0]
    t = t / np.linalg.norm(t)
    M = np.cross(res.tip_position - r, F)
    M_bend = np.linalg.norm(M - (M @ t) * t)
    hand = abs(F @ t) / A + M_bend / W
    got = res.extras["max_stress_backbone"]
    assert got == pytest.approx(hand, rel=2e-3), (model, got, hand)  # measured: within 0.1 %
    assert res.extras["stress_ratio"] == pytest.approx(got / YIELD, rel=1e-12)
    if model != "ancf3d":  # the 3-D cable carries no tendons
        assert res.extras["max_stress_tendon"] == 0.0  # unloaded tendons


@pytest.mark.parametrize("model,tendon_model", [("cc", "continuum"), ("ancf", "continuum"), ("ancf", "eyelets"),
                                                ("beam3d", "eyelets"), ("spring_link", "continuum")])
def test_straight_rod_under_axial_tendon_load(model, tendon_model):
    T = 300.0
    res = get_model(model)(_robot(), LoadCase(actuation=TendonActuation("tension", (T, T))),
                           SolverOptions(n_elements=16, tendon_model=tendon_model))
    assert res.extras["max_stress_backbone"] == pytest.approx(2 * T / A, rel=1e-6)
    assert res.extras["max_stress_tendon"] == pytest.approx(T / WIRE_AREA, rel=1e-12)
    assert res.extras["stress_ratio"] == pytest.approx(max(2 * T / A / YIELD, T / WIRE_AREA / WIRE_STRENGTH), rel=1e-6)


def test_stress_extras_leave_out_what_is_unknown():
    robot = Robot(sections=(Section(length=L, cross_section=CrossSection(EI=1.0, EA=1e3, GJ=1.0, mass_per_length=0.1),
                                    tendons=TendonGroup((0.0, math.pi), 0.02, 4e4)),))
    assert stress_extras(None, None, robot, np.array([1.0, 2.0])) == {}  # no stress geometry, no tendon area
    out = stress_extras(np.array([1e8, 2e8]), np.array([np.nan, 4e8]))
    assert out == {"max_stress_backbone": 2e8, "stress_ratio": 0.5}
    assert "max_stress_tendon" not in stress_extras(None, None, _robot(), np.array([np.nan, np.nan]))  # CC length mode


@pytest.mark.parametrize("model", ["ancf", "beam3d", "spring_link"])
def test_hanging_rod_carries_its_weight(model):
    from workbench.robot.orientation import base_rotation_for

    g = 9.81
    robot = Robot(sections=(Section(length=L, cross_section=ROD),), gravity=(0.0, 0.0, -g),
                  base_rotation=base_rotation_for("upside_down"))
    res = get_model(model)(robot, LoadCase(), SolverOptions(n_elements=16))
    s_first = {"ancf": 0.0, "beam3d": L / 32, "spring_link": L / 32}[model]  # first stress sample (see above)
    hand = ROD.mass_per_length * g * (L - s_first) / A
    assert res.extras["max_stress_backbone"] == pytest.approx(hand, rel=1e-6)


def test_cc_arc_stresses_match_the_closed_form():
    """Two sections: section 0 carries the tendons of both, so its axial force is the sum of all four tensions."""
    tendons = TendonGroup((0.0, math.pi), 0.02, 4e4, area=WIRE_AREA, strength=WIRE_STRENGTH)
    weak = CrossSection.circular(6e-3)  # no yield strength declared
    robot = Robot(sections=(Section(length=0.4, cross_section=ROD, tendons=tendons),
                            Section(length=0.4, cross_section=weak, tendons=tendons)))
    T = np.array([30.0, 0.0, 10.0, 0.0])
    from workbench.models.cc import arc_from_actuation, arc_stresses

    kappa, _, _ = arc_from_actuation(robot, TendonActuation("tension", tuple(T)))
    st = arc_stresses(robot, kappa, T)
    d = 0.02
    assert st.bending == pytest.approx([(30.0 + 10.0) * d / W, 10.0 * d / W], rel=1e-12)  # M = sum T d
    assert st.axial == pytest.approx([40.0 / A, 10.0 / A], rel=1e-12)
    assert st.backbone == pytest.approx(st.bending + st.axial, rel=1e-15)
    assert st.yield_strength[0] == YIELD and np.isnan(st.yield_strength[1])
    assert st.tendon == pytest.approx(T / WIRE_AREA, rel=1e-15)
    length = arc_stresses(robot, kappa, np.full(4, np.nan))  # length mode: no forces
    assert length.tendon is None and np.all(length.axial == 0.0) and length.bending == pytest.approx(st.bending)
