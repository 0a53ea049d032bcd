"""Disk weights at the disks in the ANCF models, ``ancf``, ``ancf3d`` and ``contact`` (issue 28, finding 3).

The case of the issue: Rao et al.'s NiTi robot, planar (2 sections of 0.2 m, d = 1.4 mm, E = 54 GPa,
density 6450, tendons at sigma = 0, pi with offset 10 mm and EA_t = 1e7 N), horizontal base, 10 disks of
0.5 g per section, no tendon load.  Each disk's weight acts at its station: at g / 100 (linear range) the
tip deflection is the point-load beam theory (superposition of the cantilever under its own distributed
weight and the disks' point weights); at full g the answer agrees with the Cosserat rod, which puts the
disk weights at the disks as well.  Before the fix ``ancf`` smeared each section's disk mass along the
section (1.076786e-3 m against 1.1288e-3 m at g / 100; 1.09e-2 L from ``cosserat`` at g); ``ancf3d``
lumped each disk's weight onto its element's two nodes (3.4e-3 relative off the theory at 8 elements,
1.4e-2 at 4, order 2 in place of the element's 4); ``contact`` (without an object: the planar ANCF cable)
smeared them as ``ancf`` did.
"""

import math

import numpy as np
import pytest

from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.physics.ancf import run
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonGroup
from workbench.robot.orientation import base_rotation_for

NITI = CrossSection.circular(diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.3)
TENDONS = TendonGroup(angles=(0.0, math.pi), offset=10e-3, axial_stiffness=1e7)
DISK = 0.5e-3  # kg
N_DISKS = 10
SECTION = 0.2  # m


def rao_planar(g: float) -> Robot:
    sec = Section(length=SECTION, cross_section=NITI, tendons=TENDONS, n_disks=N_DISKS, disk_mass=DISK)
    return Robot(sections=(sec, sec), gravity=(0.0, 0.0, -g), base_rotation=base_rotation_for("horizontal"))


def point_load_theory(robot: Robot, g: float) -> float:
    """Linear Euler-Bernoulli tip deflection of the cantilever: own weight q plus point weights P_i at a_i.

    ``delta = q L^4 / (8 EI) + sum_i P_i a_i^2 (3 L - a_i) / (6 EI)`` (superposition; EI uniform here).
    """
    L, EI = robot.length, NITI.EI
    q = NITI.mass_per_length * g
    a = robot.disk_stations()
    return q * L**4 / (8 * EI) + float(np.sum(DISK * g * a**2 * (3 * L - a))) / (6 * EI)


def smeared_theory(robot: Robot, g: float) -> float:
    """The same cantilever with each section's disk mass spread uniformly over it (the old ANCF load)."""
    L, EI = robot.length, NITI.EI
    q_disk = N_DISKS * DISK * g / SECTION
    return (NITI.mass_per_length * g + q_disk) * L**4 / (8 * EI)


def lateral_tip(res) -> float:
    return float(-res.tip_position[0])  # horizontal mount: gravity along base -x


@pytest.mark.parametrize("model", ["ancf", "ancf3d", "contact"])
@pytest.mark.parametrize("n_elements", [20, 8])
def test_disk_weights_are_point_loads_at_their_stations(model, n_elements):
    """g / 100: tip = point-load theory to 5e-5 (geometric nonlinearity ~ (delta / L)^2 = 8e-6); the smeared
    theory is 4.6 % away.  8 elements put disks between nodes (their weight still acts at the station)."""
    g = 9.81 / 100
    robot = rao_planar(g)
    theory = point_load_theory(robot, g)
    assert abs(theory - 1.1288e-3) < 1e-7  # the number quoted in the issue
    assert abs(smeared_theory(robot, g) - theory) > 4e-2 * theory  # the two loads are distinguishable
    tip = lateral_tip(get_model(model)(robot, LoadCase(), SolverOptions(n_elements=n_elements)))
    assert abs(tip - theory) < 5e-5 * theory, (tip, theory, smeared_theory(robot, g))


@pytest.mark.parametrize("model", ["ancf", "ancf3d", "contact"])
def test_full_gravity_agrees_with_cosserat(model):
    """Full g (tip sag 0.28 L, nonlinear): against the Cosserat rod (ancf 1.1e-2 L apart before the fix)."""
    robot = rao_planar(9.81)
    a = get_model(model)(robot, LoadCase(), SolverOptions(n_elements=32))
    c = get_model("cosserat")(robot, LoadCase(), SolverOptions(newton_tolerance=1e-10))
    diff = float(np.linalg.norm(a.tip_position - c.tip_position)) / robot.length
    assert diff < 2e-5, diff  # measured 2.3e-6 L (ancf), 2.3e-6 L (ancf3d) at 32 elements


def test_disk_mass_moves_with_the_backbone_in_dynamics():
    """Dynamics: the disk masses are inertia at the nodes next to each disk (not smeared), their weights at
    the stations; started from the static equilibrium with nothing changing, the rod stays there."""
    robot = rao_planar(9.81)
    opts = SolverOptions(n_elements=20, time_step=2e-3)
    st = run(robot, LoadCase(), opts)
    dyn = run(robot, LoadCase(analysis="dynamic", duration=0.02), opts)
    assert np.linalg.norm(dyn.tip_position - st.tip_position) < 1e-9 * robot.length
