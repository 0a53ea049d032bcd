"""Cosserat rod with continuous tendons (model ``"cosserat"``): exact arcs, independent references.

Independent of the model's code: constant-curvature arcs (closed form, ``workbench.kinematics``),
the tendon-free shooting reference (:mod:`workbench.reference.cosserat`, another implementation of
the rod), the planar elastica BVP, the planar ANCF beam (Exudyn) with continuum tendons, and the
spatial geometrically exact beam with eyelets (disk count growing, slow tier).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.kinematics import backbone_points, forward_kinematics
from workbench.models import ModelFailure, SolverOptions, get_model
from workbench.physics.cosserat import run
from workbench.robot import CrossSection, LoadCase, Payload, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.orientation import base_rotation_for
from workbench.robot.presets import build_preset

L = 0.8


def nitinol_robot(disks: int = 10, disk_mass: float = 0.0) -> Robot:
    """Issue 14's spatial robot: 2 x 0.2 m NiTi (E 54 GPa, d 1.4 mm; density 6450 kg/m^3 and
    Poisson 0.33 assumed), 3 tendons per section at 90, -30, 210 deg, offset 10 mm, EA_t 1e7 N."""
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, rod, tg, n_disks=disks, disk_mass=disk_mass),
                           Section(0.2, rod, tg, n_disks=disks, disk_mass=disk_mass)))


def exact_cc(robot: Robot, tensions, stations) -> np.ndarray:
    """Backbone of the unloaded continuum-tendon rod: every section an exact arc whose curvature
    per reference length is ``|sum tau_i r_i| / EI`` towards ``sum tau_i r_i`` (tendons passing the
    section), shortened by ``sum tau_i / EA`` (constant offsets, uniform sections)."""
    table = robot.tendon_table()
    kap, phi, ell = [], [], []
    for j, sec in enumerate(robot.sections):
        m = np.zeros(2)
        comp = 0.0
        for (k, sig, grp), T in zip(table, tensions):
            if k >= j:
                m += T * grp.offset * np.array([math.cos(sig), math.sin(sig)])
                comp += T
        eps = comp / sec.cross_section.EA
        kap.append(np.linalg.norm(m) / sec.cross_section.EI / (1.0 - eps))
        phi.append(math.atan2(m[1], m[0]))
        ell.append(sec.length * (1.0 - eps))
    kap, phi, ell = map(np.asarray, (kap, phi, ell))
    s_def = np.interp(stations, np.concatenate([[0.0], robot.section_ends]), np.concatenate([[0.0], np.cumsum(ell)]))
    return backbone_points(kap, phi, ell, s_def), forward_kinematics(kap, phi, ell)


def test_registered_and_rejections():
    assert get_model("cosserat") is run
    robot = build_preset("steel_rod")
    act = TendonActuation("tension", (10.0, 0.0))
    with pytest.raises(ModelFailure, match="static"):
        run(robot, LoadCase(actuation=act, analysis="dynamic", duration=1.0), SolverOptions())
    with pytest.raises(ModelFailure, match="eyelet"):
        run(robot, LoadCase(actuation=TendonActuation("length", (-1e-3, 0.0))), SolverOptions(tendon_model="eyelets"))


def test_straight_routing_gives_exact_cc_arcs_in_space():
    """The issue's two-section robot, tensions (4, 0, 0, 0, 2, 0) N and (3, 1, 0.5, 0, 2.5, 1) N:
    two arcs in different planes, compression included; observed max station error 1.4e-10 m
    (the dense output of DOP853 at rtol 1e-10), tip 3e-12 m."""
    robot = nitinol_robot()
    for T in ((4.0, 0.0, 0.0, 0.0, 2.0, 0.0), (3.0, 1.0, 0.5, 0.0, 2.5, 1.0)):
        res = run(robot, LoadCase(actuation=TendonActuation("tension", T)), SolverOptions(n_stations=41))
        pts, tip = exact_cc(robot, T, res.stations)
        assert np.abs(res.positions - pts).max() < 1e-9 * 0.4
        assert np.abs(res.tip_frame - tip).max() < 1e-9
        assert abs(res.tip_twist) < 1e-12 and res.solver.converged
        assert res.length_change == pytest.approx(-(sum(T) + sum(T[3:])) * 0.2 / robot.sections[0].cross_section.EA,
                                                  rel=1e-9)


def test_tendon_free_rod_equals_the_shooting_reference():
    """Tip force, tip torque and oblique self-weight: the other Cosserat implementation
    (``workbench.reference.cosserat``, same equations, its own integration and shooting)."""
    from workbench.reference.cosserat import RodStiffness, solve_rod_tip_wrench

    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal", tendon_count=2)
    cs = robot.sections[0].cross_section
    F, M = np.array([3.0, -2.0, 1.0]), np.array([0.5, 1.0, -0.8])
    res = run(robot, LoadCase(tip_force=tuple(F), tip_torque=tuple(M)), SolverOptions(newton_tolerance=1e-11))
    st = RodStiffness(EA=cs.EA, GA=cs.GA, EI=cs.EI, GJ=cs.GJ)
    q = cs.mass_per_length * robot.gravity_in_base()
    ref = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, st, tip_force=F, tip_moment=M, distributed_force=q,
                               n_steps=4, n_eval=res.stations.size)
    assert ref.converged
    assert np.abs(res.positions - ref.positions).max() < 1e-8 * L
    assert np.abs(res.tip_frame[:3, :3] - ref.tip_rotation).max() < 1e-8
    assert abs(res.tip_twist) > 1e-3  # the torque twists the rod


def _stiff_axially(robot: Robot) -> Robot:
    """EA and GA x 1e4 (the inextensible, unshearable elastica as the reference)."""
    secs = []
    for s in robot.sections:
        cs = s.cross_section
        stiff = CrossSection(EI=cs.EI, EA=1e4 * cs.EA, GJ=cs.GJ, mass_per_length=cs.mass_per_length,
                             GA=1e4 * cs.EA, diameter=cs.diameter)
        secs.append(Section(s.length, stiff, s.tendons, s.n_disks, s.disk_mass))
    return Robot(sections=tuple(secs), gravity=robot.gravity, payload=robot.payload,
                 base_rotation=robot.base_rotation, name=robot.name)


@pytest.mark.parametrize("alpha", [5.0])
def test_tip_load_elastica(alpha):
    """Tip load alpha = PL^2/EI = 5 (tip deflection 0.71 L): observed 2.9e-9 L from the elastica."""
    from workbench.reference.elastica import clamped_elastica

    robot = _stiff_axially(build_preset("steel_rod", base_orientation="horizontal"))
    EI = robot.sections[0].cross_section.EI
    P = alpha * EI / L**2
    res = run(robot, LoadCase(tip_force=(-P, 0.0, 0.0)), SolverOptions())
    ref = clamped_elastica(L, EI, tip_force=(0.0, -P), stations=2, n_continuation=10)
    assert np.linalg.norm(res.tip_position - [ref.tip[1], 0.0, ref.tip[0]]) < 1e-6 * L


def _planar_case(taper: float | None, gravity: float, payload: float = 0.0):
    cs = CrossSection(EI=13.36, EA=5.94e6, GJ=10.3, mass_per_length=0.222, diameter=6e-3)  # GA None: shear-rigid
    tg = TendonGroup(angles=(0.0, math.pi), offset=0.02, offset_tip=taper, axial_stiffness=4e4)
    robot = Robot(sections=(Section(0.4, cs, tg, n_disks=4), Section(0.4, cs, tg, n_disks=4)),
                  gravity=(0.0, 0.0, -gravity), payload=Payload(mass=payload),
                  base_rotation=base_rotation_for("horizontal"))
    return robot


def test_planar_case_agrees_with_ancf_continuum_tendons():
    """Two sections in the plane, gravity and a 50 g payload: the ANCF beam with the exact
    continuum-tendon load (constant offsets: exact at any mesh) at 64 elements.  ANCF has no
    shear, so the cross-section has ``GA = None`` (100 EA here).  Observed 2.1e-8 m."""
    robot = _planar_case(None, 9.81, payload=0.05)
    load = LoadCase(actuation=TendonActuation("tension", (120.0, 0.0, 0.0, 60.0)))
    a = get_model("ancf")(robot, load, SolverOptions(n_elements=64))
    c = run(robot, load, SolverOptions())
    assert np.abs(c.positions - a.positions).max() < 1e-6 * L
    assert c.length_change == pytest.approx(a.length_change, rel=1e-6)


def test_tapered_routing_ancf_converges_to_it_at_order_two():
    """Tapered offsets (20 -> 10 mm): ANCF applies the tendon as a per-element constant reference
    curvature, exact only for constant offsets, so it converges to the continuous taper at order 2:
    observed 3.5e-6 / 8.8e-7 / 2.2e-7 m at 32 / 64 / 128 elements."""
    robot = _planar_case(0.01, 9.81, payload=0.05)
    load = LoadCase(actuation=TendonActuation("tension", (120.0, 0.0, 0.0, 60.0)))
    c = run(robot, load, SolverOptions())
    d = [np.abs(c.positions - get_model("ancf")(robot, load, SolverOptions(n_elements=n)).positions).max()
         for n in (32, 64, 128)]
    assert np.all(np.log2(np.asarray(d[:-1]) / d[1:]) > 1.9), d
    assert d[-1] < 1e-6 * L


def test_disk_weights_are_point_loads_at_the_disks():
    """Small loads, massless rod, 4 disks of 20 g per section: the tip sag equals linear theory
    ``sum P a^2 (3L - a) / (6 EI)`` for point loads at the disk stations (observed ratio
    1.0000001; ANCF smears disk masses over the section and gives 0.853, documented there)."""
    cs = CrossSection(EI=13.36, EA=5.94e6, GJ=10.3, mass_per_length=0.0, diameter=6e-3)
    tg = TendonGroup(angles=(0.0, math.pi), offset=0.02)
    g = 0.01
    robot = Robot(sections=(Section(0.4, cs, tg, n_disks=4, disk_mass=0.02), Section(0.4, cs, tg, n_disks=4,
                                                                                       disk_mass=0.02)),
                  gravity=(0.0, 0.0, -g), base_rotation=base_rotation_for("horizontal"))
    lin = sum(0.02 * g * a * a * (3 * L - a) / (6 * 13.36) for a in np.arange(1, 9) * 0.1)
    res = run(robot, LoadCase(), SolverOptions())
    assert -res.tip_position[0] == pytest.approx(lin, rel=1e-5)


def test_length_control_equals_tension_control_with_the_resulting_tensions():
    """Three tendons at 0 / 120 / 240 deg, one reeled in by 2 mm, 5 N pretension, gravity and an
    out-of-plane tip force; observed tensions (66.5, 19.5, 26.9) N, shapes equal to 5e-11 m."""
    robot = build_preset("steel_rod", tendon_count=3, gravity=9.81, base_orientation="horizontal")
    act = TendonActuation("length", (-2e-3, 0.0, 0.0), pretension=5.0)
    lc = run(robot, LoadCase(actuation=act, tip_force=(0.0, 0.5, 0.0)), SolverOptions())
    assert np.all(lc.tendon_tensions > 5.0) and lc.tendon_tensions[0] > 50.0
    tc = run(robot, LoadCase(actuation=TendonActuation("tension", tuple(lc.tendon_tensions)),
                             tip_force=(0.0, 0.5, 0.0)), SolverOptions())
    assert np.abs(lc.positions - tc.positions).max() < 1e-9


@pytest.mark.slow
def test_beam3d_eyelets_converge_to_the_continuum_tendon():
    """Planar: one tendon, 300 N at 20 mm on the 0.8 m steel rod, GE beam with 2 elements per disk
    interval: observed tip gap 1.8e-2 / 4.6e-3 / 1.2e-3 m at 4 / 8 / 16 disks (order 2)."""
    robot0 = build_preset("steel_rod")
    load = LoadCase(actuation=TendonActuation("tension", (300.0, 0.0)))
    c = run(robot0, load, SolverOptions())
    gaps = []
    for n in (4, 8, 16):
        b = get_model("beam3d")(build_preset("steel_rod", disks_per_section=n), load,
                                SolverOptions(n_elements=2 * n, tendon_model="eyelets"))
        gaps.append(np.linalg.norm(b.tip_position - c.tip_position))
    orders = np.log2(np.asarray(gaps[:-1]) / gaps[1:])
    assert np.all(orders > 1.8), gaps
