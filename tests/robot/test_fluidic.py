"""Fluidic chamber actuation (workbench.robot.fluidic): signs, the arc map and its inverses, limits."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.robot import RobotDescriptionError
from workbench.robot.fluidic import (
    ChamberLayout, arc_from_pressures, chamber_forces, pressures_for_bend, pressures_from_arc, section_loads,
)

THREE = ChamberLayout(angles=(0.0, 2 * math.pi / 3, 4 * math.pi / 3), offset=0.022, area=3e-4, max_pressure=0.6e6)
EI, EA, L = 0.3, 2.0e3, 0.4


def test_a_chamber_pushes_where_a_tendon_pulls():
    # one chamber at sigma = 0: the section lengthens and bends away from it (towards phi = pi);
    # a tendon at the same place with tension T = F gives the opposite moment and shortens it
    lay = ChamberLayout(angles=(0.0,), offset=0.02, area=1e-4)
    N, m = section_loads(lay, [1e5])
    F = 10.0
    assert N == pytest.approx(F)
    np.testing.assert_allclose(m, [-F * 0.02, 0.0], atol=1e-15)
    s, kappa, phi = arc_from_pressures(lay, [1e5], EI, EA, L)
    assert s == pytest.approx(L * (1 + F / EA))
    assert kappa * s == pytest.approx(F * 0.02 * L / EI)  # bend angle per reference length (Reissner)
    assert math.cos(phi) == pytest.approx(-1.0)


def test_equal_pressures_only_lengthen():
    s, kappa, _ = arc_from_pressures(THREE, [2e5] * 3, EI, EA, L)
    assert kappa == pytest.approx(0.0, abs=1e-12)
    assert s == pytest.approx(L * (1 + 3 * 2e5 * 3e-4 / EA))


@pytest.mark.parametrize("phi", [0.0, 0.7, math.pi, -2.0])
def test_least_pressures_round_trip(phi):
    p = pressures_from_arc(THREE, 8.0, phi, EI, EA, L)
    assert np.min(p) == pytest.approx(0.0, abs=1e-6)  # least force: one chamber group stays off
    s, kappa, phi2 = arc_from_pressures(THREE, p, EI, EA, L)
    assert kappa == pytest.approx(8.0, rel=1e-9)
    assert math.cos(phi2 - phi) == pytest.approx(1.0, abs=1e-9)
    assert s > L


def test_given_arc_length_round_trip():
    lay = ChamberLayout(angles=THREE.angles, offset=THREE.offset, area=THREE.area)  # no pressure limit
    s0 = 1.15 * L
    p = pressures_from_arc(lay, 6.0, 0.3, EI, EA, L, s=s0)
    s, kappa, phi = arc_from_pressures(lay, p, EI, EA, L)
    assert (s, kappa, phi) == pytest.approx((s0, 6.0, 0.3), rel=1e-9)


def test_pressures_for_bend_gives_that_bend():
    p = pressures_for_bend(THREE, 1.5 * math.pi, 0.0, EI, L)
    s, kappa, phi = arc_from_pressures(THREE, p, EI, EA, L)
    assert kappa * s == pytest.approx(1.5 * math.pi, rel=1e-10)
    assert p[0] == pytest.approx(0.0, abs=1e-6) and p[1] == pytest.approx(p[2], rel=1e-9)
    # the study's assumption: A = 3e-4 m^2 makes this scoop need 0.54 MPa (< 0.6 MPa, the paper's limit)
    assert p.max() == pytest.approx(0.5355e6, rel=1e-3)


def test_limits_and_bad_input():
    with pytest.raises(ValueError, match="more extension"):
        pressures_from_arc(THREE, 8.0, 0.0, EI, EA, L, s=1.001 * L)  # that bend needs more chamber force
    with pytest.raises(ValueError, match="only lengthen"):
        pressures_from_arc(THREE, 1.0, 0.0, EI, EA, L, s=0.9 * L)
    with pytest.raises(ValueError, match="MPa"):
        pressures_for_bend(THREE, 2.5 * math.pi, 0.0, EI, L)
    with pytest.raises(ValueError, match=">= 0"):
        chamber_forces(THREE, [1.0, -1.0, 0.0])
    with pytest.raises(ValueError, match="one pressure per chamber"):
        chamber_forces(THREE, [1.0, 1.0])
    with pytest.raises(RobotDescriptionError, match="area"):
        ChamberLayout(angles=(0.0,), offset=0.02, area=0.0)
    one = ChamberLayout(angles=(0.0,), offset=0.02, area=1e-4)
    with pytest.raises(ValueError, match="cannot bend"):
        pressures_for_bend(one, 1.0, 0.0, EI, L)  # a single chamber bends only towards pi
