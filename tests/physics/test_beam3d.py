"""Validation of the spatial geometrically exact beam model (``workbench.physics.beam3d``).

Every test compares against an analytic reference (arc under pure moment, torsion
T L / GJ, pure compression, T d / EI, Euler-Bernoulli cantilever, first bending
frequency) or an independent model (``ancf3d``).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import ModelFailure, SolverOptions
from workbench.physics import beam3d
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.presets import build_preset


def arc_points(s, kappa, phi):
    """Constant-curvature arc in plane phi, base frame, (m, 3)."""
    s = np.asarray(s, dtype=float)
    if kappa == 0:
        return np.stack([0 * s, 0 * s, s], axis=1)
    r = (1 - np.cos(kappa * s)) / kappa
    return np.stack([r * np.cos(phi), r * np.sin(phi), np.sin(kappa * s) / kappa], axis=1)


@pytest.mark.parametrize("phi", [0.0, 0.7, 2.5, -1.9])
def test_pure_tip_moment_bends_into_exact_arc_in_any_plane(phi):
    rod = build_preset("steel_rod", tendon_count=3)
    EI, L = rod.sections[0].cross_section.EI, rod.length
    theta = math.pi / 2
    M = EI * theta / L
    # a moment about (-sin phi, cos phi, 0) bends the rod towards phi
    res = beam3d.run(rod, LoadCase(tip_torque=(-M * math.sin(phi), M * math.cos(phi), 0.0)),
                     SolverOptions(n_elements=8, n_stations=17))
    ref = arc_points(res.stations, theta / L, phi)
    assert np.max(np.abs(res.positions - ref)) < 1e-9 * L
    # tip tangent and in-plane twist-free frame
    np.testing.assert_allclose(res.tip_frame[:3, 2], [math.cos(phi), math.sin(phi), 0.0], atol=1e-9)
    assert abs(res.tip_twist) < 1e-9
    assert abs(res.length_change) < 1e-9 * L


def test_torsion_matches_TL_over_GJ():
    rod = build_preset("steel_rod")
    GJ, L = rod.sections[0].cross_section.GJ, rod.length
    Mt = 2.0
    res = beam3d.run(rod, LoadCase(tip_torque=(0.0, 0.0, Mt)), SolverOptions(n_elements=8))
    expected = Mt * L / GJ
    assert res.tip_twist == pytest.approx(expected, rel=1e-9)
    # independent: rotation of the tip frame about z
    assert math.atan2(res.tip_frame[1, 0], res.tip_frame[0, 0]) == pytest.approx(expected, rel=1e-9)
    np.testing.assert_allclose(res.tip_position, [0, 0, L], atol=1e-12)


def test_three_equal_tensions_give_pure_compression():
    rod = build_preset("steel_rod", tendon_count=3, first_tendon_angle=0.3)
    EA, L = rod.sections[0].cross_section.EA, rod.length
    T = 100.0
    res = beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (T, T, T))),
                     SolverOptions(n_elements=16, tendon_model="eyelets"))
    assert np.hypot(*res.tip_position[:2]) <= 1e-9 * L
    assert res.length_change == pytest.approx(-3 * T * L / EA, rel=1e-6)
    assert res.tip_position[2] == pytest.approx(L - 3 * T * L / EA, rel=1e-9)
    np.testing.assert_allclose(res.tendon_tensions, [T, T, T])


def _single_tendon_curvature(n_disks, T=30.0, sigma=0.9):
    rod = Robot(sections=(Section(length=0.8, cross_section=CrossSection.circular(6e-3),
                                  tendons=TendonGroup(angles=(sigma,), offset=0.02), n_disks=n_disks),))
    res = beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (T,))),
                     SolverOptions(n_elements=max(8, n_disks), tendon_model="eyelets"))
    t = res.tip_frame[:3, 2]
    theta = math.atan2(math.hypot(t[0], t[1]), t[2])
    phi = math.atan2(t[1], t[0])
    return theta / rod.length, phi, rod.sections[0].cross_section.EI


def test_single_tendon_curvature_converges_to_Td_over_EI_with_eyelets():
    """Observed: relative error 7.5e-3 / 1.87e-3 / 4.7e-4 (/ 1.17e-4 at 32) at 4 / 8 / 16 disks: order 2.00."""
    T, d, sigma = 30.0, 0.02, 0.9
    errs = []
    for n in (4, 8, 16):
        kappa, phi, EI = _single_tendon_curvature(n, T, sigma)
        assert phi == pytest.approx(sigma, abs=1e-9)  # bends towards the tendon
        errs.append(abs(kappa - T * d / EI) / (T * d / EI))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert errs[-1] < 2e-3
    assert np.all(orders > 1.8) and np.all(orders < 2.2), (errs, orders)


def test_sag_matches_euler_bernoulli_and_ancf3d():
    from workbench.physics import ancf3d

    rod = build_preset("steel_rod", gravity=1.0, base_orientation="horizontal")  # gravity along base -x
    cs, L = rod.sections[0].cross_section, rod.length
    q = cs.mass_per_length * 1.0
    assert q * L**3 / cs.EI < 0.01  # small gamma: linear theory applies
    eb = q * L**4 / (8 * cs.EI)
    opts = SolverOptions(n_elements=16)
    b = beam3d.run(rod, LoadCase(), opts)
    a = ancf3d.run(rod, LoadCase(), opts)
    assert -b.tip_position[0] == pytest.approx(eb, rel=1e-3)
    assert -a.tip_position[0] == pytest.approx(eb, rel=1e-3)
    assert np.max(np.abs(b.positions - a.positions)) < 1e-3 * eb
    assert abs(b.tip_position[1]) < 1e-15


def test_tip_force_beam3d_vs_ancf3d_converges():
    """GE beam (shear-deformable, 2nd order) vs ANCF cable under a lateral tip force."""
    from workbench.physics import ancf3d

    rod = build_preset("steel_rod")
    cs, L = rod.sections[0].cross_section, rod.length
    F = 0.1
    ref = F * L**3 / (3 * cs.EI) + F * L / cs.GA  # Timoshenko, linear
    a = ancf3d.run(rod, LoadCase(tip_force=(0.0, F, 0.0)), SolverOptions(n_elements=8))
    assert a.tip_position[1] == pytest.approx(F * L**3 / (3 * cs.EI), rel=1e-4)
    e = [abs(beam3d.run(rod, LoadCase(tip_force=(0.0, F, 0.0)), SolverOptions(n_elements=n)).tip_position[1] - ref)
         for n in (8, 16)]
    assert e[1] < e[0] / 3.5  # observed 3.9e-3 -> 9.8e-4 relative: 2nd order
    assert e[1] / ref < 1.5e-3


def test_length_controlled_tendons_reproduce_cc_arc():
    """Commands from the CC tendon map dl_i = -d theta cos(sigma_i - phi) (local closed form,
    to be replaced by the kinematics branch's map), stiff tendons EA_t = 1e8 N, no gravity.

    The physics does not reproduce the arc exactly: (a) a rope through n disks is shorter
    than the CC arc-wire by ~theta^2 / (24 n^2) per unit length (eyelet chord geometry,
    falls with n); (b) the tendon tensions (~850 N) compress the backbone by
    sum(T) L / EA ~ 1.6e-4 m, so the outer tendon goes slack (unilateral rope) and the
    arc is set by two tendons only: a floor that does not fall with n.
    Measured tip error (L = 0.8 m, theta = 1 rad, phi = 0.4, 8 elements):
    8 disks 2.38e-2 m, 16 disks 1.10e-2 m (EA_t = 1e6: 3.9e-2 / 2.8e-2 / 2.5e-2 m at
    8 / 16 / 32 disks, dominated by tendon stretch).  Tolerance: those values + 10 %.
    """
    L, d, theta, phi = 0.8, 0.02, 1.0, 0.4
    sig = np.array([0.0, 2 * np.pi / 3, 4 * np.pi / 3])
    dl = -d * theta * np.cos(sig - phi)
    errs = {}
    for nd in (8, 16):
        rod = build_preset("steel_rod", tendon_count=3, tendon_stiffness=1e8, disks_per_section=nd)
        res = beam3d.run(rod, LoadCase(actuation=TendonActuation("length", tuple(dl), pretension=5.0)),
                         SolverOptions(n_elements=8, tendon_model="eyelets"))
        tip_cc = arc_points([L], theta / L, phi)[0]
        errs[nd] = np.linalg.norm(res.tip_position - tip_cc)
        t = res.tip_frame[:3, 2]
        assert math.atan2(t[1], t[0]) == pytest.approx(phi, abs=0.05)
        assert math.acos(t[2]) == pytest.approx(theta, abs=0.06)
        assert res.tendon_tensions.min() >= 0.0
    assert errs[8] < 1.1 * 2.38e-2
    assert errs[16] < 1.1 * 1.10e-2
    assert errs[16] < 0.6 * errs[8]


def test_free_vibration_first_frequency():
    """Cantilever first bending frequency 1.8751^2 sqrt(EI / (rho A L^4)) / (2 pi) within 1 %.

    Excitation: a tiny tendon tension (1e-3 N, far below the buckling load 51 N, so the
    axial load shifts the frequency by < 1e-4) switched on at t = 1 ms; the frequency is
    taken from the upward zero crossings of the tip deflection about its mean.
    Measured: -0.11 % (16 el., h = 1 ms), +0.03 % (8 el.), -0.03 % (16 el., h = 0.5 ms).
    """
    rod = build_preset("steel_rod", tendon_count=1, disks_per_section=8)
    cs, L = rod.sections[0].cross_section, rod.length
    f_ref = 1.8751**2 * math.sqrt(cs.EI / (cs.mass_per_length * L**4)) / (2 * math.pi)
    act = TendonActuation("tension", (1e-3,), start_times=(1e-3,), ramp_durations=(0.0,))
    res = beam3d.run(rod, LoadCase(actuation=act, analysis="dynamic", duration=1.0),
                     SolverOptions(n_elements=16, tendon_model="eyelets", time_step=1e-3, spectral_radius=0.9))
    t = res.time
    x = res.series["tip_position"][:, 0]
    keep = t > 0.01
    t, x = t[keep], x[keep]
    x = x - 0.5 * (x.max() + x.min())
    i = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    tc = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    f = (len(tc) - 1) / (tc[-1] - tc[0])
    assert len(tc) >= 5
    assert f == pytest.approx(f_ref, rel=1e-2)


def _ge_cantilever_tip_history(beta: float) -> np.ndarray:
    """Tip displacement history of a 4-element Exudyn GE-beam cantilever under a suddenly applied
    tip force, with section damping ``beta * K`` (plain Exudyn, independent of beam3d)."""
    import exudyn as exu
    from exudyn.itemInterface import (CoordinateConstraint, LoadForceVector, MarkerNodeCoordinate, MarkerNodeRigid,
                                      NodePointGround, NodeRigidBodyEP, ObjectBeamGeometricallyExact)

    from workbench.physics._exudyn import dynamic_settings, quiet_exudyn

    L, n, EI, EA, mu = 0.5, 4, 13.36, 5.94e6, 0.222
    K = np.diag([EA, EA / 2.6, EA / 2.6, EI / 1.3, EI, EI])
    with quiet_exudyn():
        sc = exu.SystemContainer()
        mbs = sc.AddSystem()
        nodes = [mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=[L * k / n, 0, 0, 1, 0, 0, 0])) for k in range(n + 1)]
        for a, b in zip(nodes[:-1], nodes[1:]):
            bs = exu.BeamSection()
            bs.stiffnessMatrix = K
            bs.dampingMatrix = beta * K
            bs.massPerLength = mu
            bs.inertia = mu * EI / EA * np.diag([2.0, 1.0, 1.0])
            mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[a, b], length=L / n, sectionData=bs))
        mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
        for c in (0, 1, 2, 4, 5, 6):  # clamp: position and e1..e3 of node 0 (e0 follows from |e| = 1)
            m = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=c))
            mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, m]))
        tip = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[-1]))
        mbs.AddLoad(LoadForceVector(markerNumber=tip, loadVector=[0.0, 2.0, 0.0]))
        mbs.Assemble()
        opts = SolverOptions(n_elements=n, time_step=1e-3, spectral_radius=1.0)
        sim = dynamic_settings(opts, 0.05)
        out = []
        mbs.SetPreStepUserFunction(lambda mbs_, t: out.append(mbs_.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)[1]) or True)
        exu.SolveDynamic(mbs, sim, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    return np.asarray(out)


def test_exudyn_ge_beam_ignores_section_damping():
    """Why beam3d adds its damping by connectors (``options.damping``): Exudyn 1.13.6's geometrically
    exact beam gives the same trajectory with and without a (large) section damping matrix.  If a
    future Exudyn applies it, this test fails: then beam3d can use the section matrix instead."""
    free = _ge_cantilever_tip_history(0.0)
    damped = _ge_cantilever_tip_history(1e-2)
    assert np.ptp(free) > 1e-4  # the tip does vibrate (mm scale)
    np.testing.assert_array_equal(free, damped)


def _first_mode_decay(beta: float, n_elements: int = 8):
    """Cantilever of test_free_vibration_first_frequency with damping ``beta``: (omega_1 ref, zeta seen).

    zeta from the ratio of successive peak-to-peak amplitudes of the tip deflection, over periods 2-6
    (the higher modes, damped ~ omega, have died out by then), with no numerical damping
    (spectral radius 1)."""
    rod = build_preset("steel_rod", tendon_count=1, disks_per_section=8)
    cs, L = rod.sections[0].cross_section, rod.length
    w1 = 1.8751**2 * math.sqrt(cs.EI / (cs.mass_per_length * L**4))
    act = TendonActuation("tension", (1e-3,), start_times=(1e-3,), ramp_durations=(0.0,))
    T1 = 2 * math.pi / w1
    res = beam3d.run(rod, LoadCase(actuation=act, analysis="dynamic", duration=7 * T1),
                     SolverOptions(n_elements=n_elements, tendon_model="eyelets", time_step=T1 / 200,
                                   spectral_radius=1.0, damping=beta))
    t, x = res.time, res.series["tip_position"][:, 0]
    amp = [np.ptp(x[(t >= k * T1) & (t < (k + 1) * T1)]) for k in range(2, 7)]
    delta = np.mean(np.log(np.asarray(amp[:-1]) / np.asarray(amp[1:])))  # log decrement per period
    return w1, delta / math.sqrt(4 * math.pi**2 + delta**2)


def test_kelvin_voigt_damping_gives_the_modal_damping_ratio():
    """options.damping = beta [s] (stiffness-proportional, added by inter-node connectors): the first
    bending mode decays with zeta_1 = beta omega_1 / 2 (Rayleigh, stiffness part) within 5 %; without
    damping the amplitude stays (|zeta| < 1e-3)."""
    w1, z0 = _first_mode_decay(0.0)
    assert abs(z0) < 1e-3
    beta = 2 * 0.03 / w1  # zeta_1 = 3 %
    _, z = _first_mode_decay(beta)
    assert z == pytest.approx(0.03, rel=0.05)


def test_continuum_tendons_rejected_and_tendon_free_cases_run_with_it():
    rod = build_preset("steel_rod", tendon_count=3)
    with pytest.raises(ModelFailure, match="eyelets"):
        beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0))),
                   SolverOptions(tendon_model="continuum"))
    res = beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (0.0, 0.0, 0.0))),
                     SolverOptions(n_elements=4, tendon_model="continuum"))
    np.testing.assert_allclose(res.tendon_tensions, 0.0)


def test_bad_actuation_length_is_rejected():
    rod = build_preset("steel_rod", tendon_count=3)
    with pytest.raises(ValueError, match="3 tendons"):
        beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0))), SolverOptions())


def test_ramp_cap_raises_model_failure():
    rod = build_preset("steel_rod", tendon_count=3)
    # bending to 3 rad by a tip moment fails in one increment (measured); cap at 1 attempt
    M = rod.sections[0].cross_section.EI * 3.0 / rod.length
    with pytest.raises(ModelFailure, match="max_load_steps"):
        beam3d.run(rod, LoadCase(tip_torque=(0.0, M, 0.0)), SolverOptions(n_elements=8, max_load_steps=1))


def test_tapered_section_properties_per_element():
    """Linear EI taper under a pure moment: curvature M/EI(s) per element, so the tip
    rotation is sum(L_e M / EI(s_mid)) -> integral of M/EI(s) ds (midpoint rule)."""
    a = CrossSection.circular(8e-3)
    b = CrossSection.circular(5e-3)
    rod = Robot(sections=(Section(length=0.6, cross_section=a, cross_section_tip=b),))
    M = 0.5
    n = 12
    res = beam3d.run(rod, LoadCase(tip_torque=(0.0, M, 0.0)), SolverOptions(n_elements=n))
    s_mid = (np.arange(n) + 0.5) / n
    EI = a.EI + (b.EI - a.EI) * s_mid
    theta_expected = np.sum(0.6 / n * M / EI)
    t = res.tip_frame[:3, 2]
    assert math.atan2(t[0], t[2]) == pytest.approx(theta_expected, rel=1e-9)


def test_quiet_and_file_free(capfd, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rod = build_preset("steel_rod", tendon_count=3)
    beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (5.0, 0.0, 0.0))),
               SolverOptions(n_elements=4, tendon_model="eyelets"))
    beam3d.run(rod, LoadCase(actuation=TendonActuation("length", (-1e-3, 0.0, 0.0), pretension=2.0),
                             analysis="dynamic", duration=0.02),
               SolverOptions(n_elements=4, tendon_model="eyelets"))
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    assert list(tmp_path.iterdir()) == []


def test_dynamic_series_shapes_and_start_from_equilibrium():
    rod = build_preset("steel_rod", tendon_count=3, gravity=9.81, base_orientation="horizontal")
    res = beam3d.run(rod, LoadCase(actuation=TendonActuation("tension", (20.0, 0.0, 0.0), start_times=(0.05, 0, 0)),
                                   analysis="dynamic", duration=0.1, ramp_time=0.02),
                     SolverOptions(n_elements=4, tendon_model="eyelets", time_step=2e-3))
    k = res.time.size
    assert res.series["tip_position"].shape == (k, 3)
    assert res.series["tendon_tensions"].shape == (k, 3)
    assert res.series["length_change"].shape == (k,) and res.series["tip_twist"].shape == (k,)
    # at rest under gravity until the tendon starts: no motion before t = 0.05 s
    before = res.time < 0.05
    tip = res.series["tip_position"][before]
    assert np.max(np.abs(tip - tip[0])) < 1e-9
    np.testing.assert_allclose(res.series["tendon_tensions"][-1], [20.0, 0.0, 0.0])


@pytest.mark.parametrize("ramps", [None, (4.0, 2.0, 0.0)])
def test_dynamic_command_function_equals_command_at_bit_for_bit(ramps):
    # the pre-step's plain-float commands must be exactly TendonActuation.command_at (same arithmetic)
    act = TendonActuation("length", (0.01, -0.02, 0.005), start_times=(3.0, 0.0, 1.5), ramp_durations=ramps)
    command = act.command_function(2.5)
    for t in np.linspace(-1.0, 12.0, 2601):
        assert np.array_equal(command(t), act.command_at(t, 2.5)), t
