"""Planar contact physics (workbench.physics.contact) against hand cases and the other models.

* without an object it is the planar ANCF model with continuum tendons (to round-off);
* a cantilever pressed on a cylinder: the contact force of linear beam theory, the error of second
  order in the lift (geometric nonlinearity), action = reaction;
* capstan: a flexible rod pulled over a fixed cylinder with friction keeps ``T_anchor = T e^(-mu theta)``;
* fluidic chamber strains bend and lengthen the rod exactly into the CC arc of the pressures;
* Exudyn facts behind the choice of contact element (the frictionless element's reaction).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.models.cc import actuation_from_arc
from workbench.physics._exudyn import quiet_exudyn
from workbench.physics.contact import (
    ContactLaw, PlanarContactSystem, RigidCircle, chamber_strains, planar_setup, section_tendon_strains, tendon_strains,
    without_tendons,
)
from workbench.physics.contact.procedures import contact_force_on_object, contact_summary
from workbench.robot import CrossSection, LoadCase, Robot, Section
from workbench.robot.fluidic import ChamberLayout, arc_from_pressures, pressures_for_bend
from workbench.robot.presets import build_preset


def test_without_object_equals_ancf_with_continuum_tendons():
    robot = build_preset("hannan_walker")  # gravity, four tapered sections
    load = LoadCase(actuation=actuation_from_arc(robot, kappa=[0.5, 1.0, 2.0, 3.0], phi=[0.0] * 4, mode="tension"))
    opt = SolverOptions(n_elements=16, tendon_model="continuum")
    a = get_model("ancf")(robot, load, opt)
    c = get_model("contact")(robot, load, opt)
    np.testing.assert_allclose(c.positions, a.positions, rtol=0, atol=1e-12)
    assert c.length_change == pytest.approx(a.length_change, abs=1e-12)


def test_projected_tendon_strains_equal_the_planar_ones():
    robot = build_preset("hannan_walker")
    pb, _ = planar_setup(robot, SolverOptions(n_elements=16))
    T = np.linspace(5.0, 40.0, robot.n_tendons)
    k1, e1 = tendon_strains(pb, T)
    k2, e2 = section_tendon_strains(robot, pb, T)
    np.testing.assert_allclose(k2, k1, rtol=1e-13)
    np.testing.assert_allclose(e2, e1, rtol=1e-13)


def _cantilever(delta: float, n: int = 16, stiffness: float = 1e8):
    """EI = 1 N m^2, L = 1 m, a cylinder (R = 5 cm) lifted into the beam by ``delta`` at 0.6 m."""
    R, a = 0.05, 0.6
    robot = Robot(sections=(Section(length=1.0, cross_section=CrossSection(EI=1.0, EA=1e4, GJ=1.0, mass_per_length=0.1)),))
    pb, hw = planar_setup(robot, SolverOptions(n_elements=n))
    with quiet_exudyn():
        s = PlanarContactSystem(pb, hw, RigidCircle(radius=R, centre=(-R - 1e-3, a)), ContactLaw(stiffness=stiffness))
        s.hold((0.0, 0.0))
        s.solve()
        s.load_ramp(lambda lam: s.hold((lam * (delta + 1e-3), 0.0)), 50, first_increment=0.1)
    # linear Euler-Bernoulli: F = 3 EI w_c / x_c^3 at the contact point of the circle (slope theta)
    th = 0.0
    for _ in range(60):
        xc, wc = a - R * math.sin(th), delta - R + R * math.cos(th)
        F = 3.0 * wc / xc**3
        th = F * xc**2 / 2.0
    return s, F


def test_cantilever_pressed_on_cylinder_matches_beam_theory():
    errs = []
    for delta in (0.005, 0.0025):
        s, F = _cantilever(delta)
        fix = s.fixture_force()  # what holds the cylinder up against the beam (= minus the beam's push)
        errs.append(fix[0] / F - 1.0)
        # action = reaction: the segment forces the beam feels sum to the force on the cylinder
        assert contact_summary(s)["normal_force"] == pytest.approx(fix[0], rel=1e-4)
        np.testing.assert_allclose(contact_force_on_object(s), -fix, atol=1e-14)
        assert s.active_set_error()[0] == 0.0
    # the remaining error is beam theory's (geometric nonlinearity ~ delta^2), not the contact's
    assert abs(errs[0]) < 3e-4 and abs(errs[1]) < 1e-4
    assert 2.5 < errs[0] / errs[1] < 6.0


def test_exudyn_plain_circle_contact_double_counts_its_reaction():
    """Exudyn 1.13.6 fact: ObjectContactCircleCable2D's force on the circle counts the point shared by two
    touching segments twice (0.207 N on the circle for 0.139 N on the beam); the friction element does not."""
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint, MarkerBodyCable2DShape, MarkerBodyRigid, MarkerNodeCoordinate, NodeGenericData,
        NodePoint2DSlope1, NodePointGround, NodeRigidBody2D, ObjectANCFCable2D, ObjectContactCircleCable2D,
        ObjectRigidBody2D,
    )

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    n, le, R = 16, 1.0 / 16, 0.05
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[i * le, 0, 1, 0])) for i in range(n + 1)]
    els = [mbs.AddObject(ObjectANCFCable2D(nodeNumbers=[nodes[i], nodes[i + 1]], length=le, bendingStiffness=1.0,
                                           axialStiffness=1e4, massPerLength=0.1, useReducedOrderIntegration=2))
           for i in range(n)]
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    clamp = [mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=c))]))
             for c in (0, 1, 3)]
    nR = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.6, -R, 0]))
    mR = mbs.AddMarker(MarkerBodyRigid(bodyNumber=mbs.AddObject(ObjectRigidBody2D(nodeNumber=nR, mass=1, inertia=1))))
    cons = [mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nR, coordinate=c))]))
            for c in range(3)]
    for e in els:
        mc = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=e, numberOfSegments=8))
        nd = mbs.AddNode(NodeGenericData(initialCoordinates=[0.1] * 8, numberOfDataCoordinates=8))
        mbs.AddObject(ObjectContactCircleCable2D(markerNumbers=[mR, mc], nodeNumber=nd, numberOfContactSegments=8,
                                                 contactStiffness=1e3, circleRadius=R))
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.staticSolver.verboseMode = 0
    s.staticSolver.newton.relativeTolerance = 1e-10
    s.staticSolver.newton.residualMode = 1
    s.staticSolver.adaptiveStep = False
    s.staticSolver.discontinuous.iterationTolerance = 1e-9
    s.staticSolver.discontinuous.maxIterations = 50
    with quiet_exudyn():
        for i in range(1, 11):
            mbs.SetObjectParameter(cons[1], "offset", -0.01 + 0.02 * i / 10)
            mbs.SolveStatic(s, updateInitialValues=True)
    on_circle = mbs.GetObjectOutput(cons[1], exu.OutputVariableType.Force)
    on_beam = -mbs.GetObjectOutput(clamp[1], exu.OutputVariableType.Force)  # the clamp's y reaction
    assert on_beam == pytest.approx(0.1375, rel=1e-2)  # the beam side is right (k = 1e3: ~1 % penetration)
    assert on_circle / on_beam > 1.4  # measured 1.50: not action = reaction


def _capstan(mu: float, theta: float, n: int):
    """A flexible rod (EI 1e-4, EA 1e3) clamped at one end, draped frictionlessly over a fixed cylinder
    (R = 0.1 m) by a small end force, friction on, then pulled to T1 = 10 N at wrap angle ``theta``."""
    R, T0, T1 = 0.1, 0.2, 10.0
    L = 0.4 + R * theta
    robot = Robot(sections=(Section(length=L, cross_section=CrossSection(EI=1e-4, EA=1e3, GJ=1e-4, mass_per_length=0.01)),))
    pb, hw = planar_setup(robot, SolverOptions(n_elements=n))
    d = np.array([-math.sin(theta), math.cos(theta)])  # direction (base x, z) of the rod after a wrap of theta
    with quiet_exudyn():
        s = PlanarContactSystem(pb, hw, RigidCircle(radius=R, centre=(-R, 0.2), friction=mu),
                                ContactLaw(stiffness=1e6, friction_stiffness=1e6))
        s.hold((0.0, 0.0))
        s.set_friction(False)
        s.load_ramp(lambda lam: s.set_tip_force(lam * T0 * np.array([-1.0, 0.0])), 200, first_increment=0.05)

        def turn(lam):
            a = 0.5 * math.pi + lam * (theta - 0.5 * math.pi)
            s.set_tip_force(T0 * np.array([-math.sin(a), math.cos(a)]))

        if theta != 0.5 * math.pi:
            s.load_ramp(turn, 400, first_increment=0.05)
        s.set_friction(True)
        s.load_ramp(lambda lam: s.set_tip_force((T0 + lam * (T1 - T0)) * d), 400, first_increment=0.02)
        clamp = -(s.fixture_force() + T1 * d)  # rod equilibrium: clamp + contact + end force = 0
    return float(np.linalg.norm(clamp)) / T1


def test_capstan_friction_quarter_wrap():
    ratio = _capstan(0.3, 0.5 * math.pi, 24)
    assert ratio == pytest.approx(math.exp(-0.3 * 0.5 * math.pi), rel=2e-3)  # measured 3.2e-4


@pytest.mark.slow
def test_capstan_frictionless_loses_nothing():
    # no loss but what the rod's bending stiffness takes (EI / (T R^2) ~ 1e-3): measured 2.8e-4
    assert _capstan(0.0, 0.5 * math.pi, 24) == pytest.approx(1.0, abs=1e-3)


@pytest.mark.slow
@pytest.mark.parametrize("mu, theta", [(0.6, 0.5 * math.pi), (0.3, 0.75 * math.pi), (0.3, math.pi)])
def test_capstan_friction_other_wraps(mu, theta):
    assert _capstan(mu, theta, 32) == pytest.approx(math.exp(-mu * theta), rel=2e-3)  # measured <= 8.5e-4 (mu 0.6)


def test_chamber_strains_give_the_fluidic_cc_arc():
    """Chambers bend by |m| L / EI per reference length and lengthen by sum F / EA (Reissner): the rod
    converges to the CC arc of the pressures at order ~4 (tip 6.2e-6 / 3.9e-7 m at 16 / 32 elements)."""
    robot = build_preset("shao_harvester", gravity=0.0)
    lay = ChamberLayout(angles=robot.sections[0].tendons.angles, offset=0.022, area=3e-4)
    p = pressures_for_bend(lay, 1.5 * math.pi, 0.0, 0.3, 0.4)
    s_cc, k_cc, _ = arc_from_pressures(lay, p, 0.3, 2.0e3, 0.4)
    th = k_cc * s_cc
    phys = without_tendons(robot)
    tip_err, len_err = [], []
    for n in (16, 32):
        pb, hw = planar_setup(phys, SolverOptions(n_elements=n))
        kap, eps = chamber_strains(phys, pb, [lay], [p])
        with quiet_exudyn():
            s = PlanarContactSystem(pb, hw)
            s.load_ramp(lambda lam: s.set_strains(lam * kap, lam * eps), 50)
            tip = s.positions([0.4])[0][0]
            len_err.append(abs(s.arc_length() - s_cc))
        tip_err.append(math.hypot(tip[0] - (1 - math.cos(th)) / k_cc, tip[2] - math.sin(th) / k_cc))
    assert tip_err[1] < 1e-6 and len_err[1] < 1e-6
    assert math.log2(tip_err[0] / tip_err[1]) > 3.5
    assert s_cc == pytest.approx(0.4 * (1 + p.sum() * 3e-4 / 2e3))  # it lengthens (16 %) where tendons shorten
