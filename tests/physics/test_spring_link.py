"""Spring-link chain: convergence to the rod, CC kinematic limit, tendon models, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import get_model
from workbench.models.result import ModelFailure, SolverOptions
from workbench.physics.spring_link import run
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset

L = 0.8


def _EI(robot):
    return robot.sections[0].cross_section.EI


def _orders(errors):
    e = np.abs(np.asarray(errors))
    return np.log2(e[:-1] / e[1:])


def test_registered_name():
    assert get_model("spring_link") is run


def test_pure_moment_converges_to_arc_second_order():
    """Tip moment M = theta EI / L bends the rod into an arc of angle theta (exact)."""
    robot = build_preset("steel_rod")
    theta = math.pi / 2
    M = theta * _EI(robot) / L
    R = L / theta
    exact = np.array([R * (1 - math.cos(theta)), 0.0, R * math.sin(theta)])
    errs = []
    for n in (8, 16, 32):
        res = run(robot, LoadCase(tip_torque=(0.0, M, 0.0)), SolverOptions(n_elements=n))
        errs.append(np.linalg.norm(res.tip_position - exact))
        # tip orientation is exact in the half-link layout: tangent at angle theta
        assert res.tip_frame[:3, 2] == pytest.approx([math.sin(theta), 0.0, math.cos(theta)], abs=1e-9)
        assert res.joint_angles.shape == (n, 1)
        assert np.sum(res.joint_angles) == pytest.approx(theta, rel=1e-9)
    orders = _orders(errs)
    # observed: errors 2.3e-3 / 5.8e-4 / 1.4e-4 m, order 2.00
    assert np.all(orders > 1.9), (errs, orders)
    assert errs[1] < 1e-3


def test_self_weight_sag_converges_to_heavy_elastica():
    """Horizontal cantilever under self-weight, gamma = q L^3 / EI = 1: tip deflection/L = 0.123471."""
    EI = _EI(build_preset("steel_rod"))
    area = math.pi * 0.006**2 / 4
    rho = 1.0 * EI / L**3 / (area * 9.81)
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal", density=rho)
    errs = []
    for n in (8, 16, 32):
        res = run(robot, LoadCase(), SolverOptions(n_elements=n))
        # base x is world up: deflection is along base -x
        errs.append(res.tip_position[0] / L + 0.123471)
    orders = _orders(errs)
    # observed: 9.7e-4 / 2.4e-4 / 6.0e-5 (relative), order 2.00
    assert np.all(orders > 1.9), (errs, orders)
    assert abs(errs[-1]) < 1e-4


def test_continuum_tendons_reproduce_constant_curvature_per_section():
    """Kinematic limit: pure tendon moments give equal joint angles per section (a CC shape)."""
    robot = build_preset("steel_rod", n_sections=2, tendon_count=2)
    EI, d = _EI(robot), 0.02
    T = (40.0, 0.0, 0.0, 25.0)  # section 1 pulled towards +x, section 2 towards -x
    res = run(robot, LoadCase(actuation=TendonActuation("tension", T)),
              SolverOptions(n_elements=16, tendon_model="continuum"))
    q = res.joint_angles[:, 0]
    # moment in section 1: (T0 - T1 + T2 - T3) d; in section 2: (T2 - T3) d
    m1 = (T[0] - T[1] + T[2] - T[3]) * d
    m2 = (T[2] - T[3]) * d
    l = L / 2
    assert np.allclose(q[:8], q[0], atol=1e-10) and np.allclose(q[8:], q[8], atol=1e-10)
    assert np.sum(q[:8]) == pytest.approx(m1 * l / EI, rel=1e-9)
    assert np.sum(q[8:]) == pytest.approx(m2 * l / EI, rel=1e-9)
    # the chain is the tangent polygon of the CC curve: compare the eyelet points with the arcs
    k1, k2 = m1 / EI, m2 / EI
    s = res.stations
    beta = np.where(s <= l, k1 * s, k1 * l + k2 * (s - l))
    # CC positions by integrating the tangent analytically per arc
    def arc(s0, b0, k, u):
        return np.array([(math.cos(b0) - math.cos(b0 + k * u)) / k, 0.0, (math.sin(b0 + k * u) - math.sin(b0)) / k])
    cc_tip = arc(0, 0, k1, l) + arc(l, k1 * l, k2, l)
    assert res.tip_frame[:3, 2] == pytest.approx([math.sin(beta[-1]), 0, math.cos(beta[-1])], abs=1e-10)
    assert np.linalg.norm(res.tip_position - cc_tip) < 2e-3  # O(1/N^2) polygon error at N = 16


def test_reeving_length_control_equals_constant_force_rope():
    """Eyelet tendons: a length-controlled reeving rope and a constant-force rope chain with the
    resulting tension give the same equilibrium (justifies using both)."""
    robot = build_preset("steel_rod")
    opts = SolverOptions(n_elements=8, tendon_model="eyelets")
    res_l = run(robot, LoadCase(actuation=TendonActuation("length", (-0.01, 0.0), pretension=10.0)), opts)
    assert np.all(res_l.tendon_tensions > 0)
    res_t = run(robot, LoadCase(actuation=TendonActuation("tension", tuple(res_l.tendon_tensions))), opts)
    assert np.abs(res_t.positions - res_l.positions).max() < 1e-7


def test_eyelet_and_continuum_close_for_dense_eyelets():
    """Discrete eyelets bend less (chord lever arm); the gap shrinks as eyelets (disks) get denser."""
    gaps = []
    for n in (8, 16):
        robot = build_preset("steel_rod", disks_per_section=n)
        a = run(robot, LoadCase(actuation=TendonActuation("tension", (100.0, 0.0))), SolverOptions(n_elements=16, tendon_model="eyelets"))
        b = run(robot, LoadCase(actuation=TendonActuation("tension", (100.0, 0.0))), SolverOptions(n_elements=16, tendon_model="continuum"))
        gaps.append(np.linalg.norm(a.tip_position - b.tip_position))
    assert gaps[1] < 0.5 * gaps[0]


@pytest.mark.parametrize("model", ["continuum", "eyelets"])
def test_released_tendon_goes_slack(model):
    robot = build_preset("steel_rod")
    res = run(robot, LoadCase(actuation=TendonActuation("length", (-0.02, 0.05))),
              SolverOptions(n_elements=8, tendon_model=model))
    assert res.tendon_tensions[0] > 0
    assert res.tendon_tensions[1] == 0.0
    assert res.tip_position[0] > 0


def test_continuum_length_mode_tension_consistent():
    """Length control: tension equals EA_t * stretch / L_0 of the continuum tendon path, whose
    length includes the backbone's compression (the default chain has axial springs in planar
    continuum length mode), and the compression is the tensions' ``-sum(T) L / EA``."""
    robot = build_preset("steel_rod")
    dl = -0.005
    res = run(robot, LoadCase(actuation=TendonActuation("length", (dl, 0.0))),
              SolverOptions(n_elements=16, tendon_model="continuum"))
    beta = np.sum(res.joint_angles)
    L0 = L + dl
    g = res.length_change
    T_expected = 4.0e4 * ((L - 0.02 * beta + g) - L0) / L0
    assert res.tendon_tensions[0] == pytest.approx(T_expected, rel=1e-9)
    # the antagonist (dl = 0, no pretension) is stretched by the bend and pulls back
    T_anta = 4.0e4 * ((L + 0.02 * beta + g) - L) / L
    assert res.tendon_tensions[1] == pytest.approx(T_anta, rel=1e-9)
    EA = robot.sections[0].cross_section.EA
    assert g == pytest.approx(-np.sum(res.tendon_tensions) * L / EA, rel=1e-3)  # shear gaps excluded
    # moment balance at the base: (T0 - T1) d = EI * beta / L
    net = (res.tendon_tensions[0] - res.tendon_tensions[1]) * 0.02
    assert net == pytest.approx(_EI(robot) * beta / L, rel=1e-6)


def test_dynamic_settles_to_static():
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    opts = SolverOptions(n_elements=8, damping=0.05, time_step=5e-3)
    stat = run(robot, LoadCase(actuation=TendonActuation("tension", (30.0, 0.0))), opts)
    dyn = run(robot, LoadCase(actuation=TendonActuation("tension", (30.0, 0.0)), analysis="dynamic",
                              duration=3.0, ramp_time=0.5), opts)
    assert dyn.time is not None and dyn.series["tip_position"].shape == (dyn.time.size, 3)
    assert np.linalg.norm(dyn.tip_position - stat.tip_position) < 1e-4


def test_dynamic_series_labels_each_state_with_its_own_time():
    """Exudyn's pre-step callback gets the END time of the coming step: the recorded state (at
    the step's start) is labelled with the start time, its tensions are the commands of that
    time, and the time axis is the one ANCF records for the same case (0, h, ..., duration)."""
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    act = TendonActuation("tension", (30.0, 0.0))
    load = LoadCase(actuation=act, analysis="dynamic", duration=0.05, ramp_time=0.02)
    opts = SolverOptions(n_elements=8, damping=0.05, time_step=5e-3)
    dyn = run(robot, load, opts)
    steps = np.linspace(0.0, 0.05, 11)
    np.testing.assert_allclose(dyn.time, steps, atol=1e-12)
    np.testing.assert_allclose(get_model("ancf")(robot, load, opts).time, dyn.time, atol=1e-12)
    commands = np.array([act.command_at(t, load.ramp_time) for t in steps])
    np.testing.assert_allclose(dyn.series["tendon_tensions"], commands, atol=1e-12)
    start = run(robot, LoadCase(actuation=TendonActuation("tension", (0.0, 0.0))), opts)
    np.testing.assert_allclose(dyn.series["tip_position"][0], start.tip_position, atol=1e-9)
    assert np.linalg.norm(dyn.series["tip_position"][1] - start.tip_position) > 1e-7  # it moved after one step


def test_bad_inputs():
    robot = build_preset("steel_rod", n_sections=2)
    with pytest.raises(ValueError, match="multiple of the number of sections"):
        run(robot, LoadCase(), SolverOptions(n_elements=5))
    r3 = build_preset("steel_rod", tendon_count=3)
    with pytest.raises(ModelFailure, match="not planar"):
        solve(r3, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0))), SolverOptions(n_elements=4),
              SpringLinkParams(dimension="2d"))
    with pytest.raises(ValueError, match="dimension"):
        SpringLinkParams(dimension="4d")


def test_max_load_steps_is_a_failure():
    from workbench.physics.spring_link import SpringLinkParams, solve

    robot = build_preset("steel_rod")
    # a huge tension in an eyelet tendon: buckling-like snap that cannot be reached in 1 step
    with pytest.raises(ModelFailure, match="max_load_steps"):
        solve(robot, LoadCase(actuation=TendonActuation("length", (-0.5, 0.0))),
              SolverOptions(n_elements=8, tendon_model="eyelets", max_load_steps=1), SpringLinkParams(backend="bodies"))


# --------------------------------------------------------------------------------------------
# 3-D chain
# --------------------------------------------------------------------------------------------
from workbench.physics.spring_link import SpringLinkParams, solve  # noqa: E402


@pytest.mark.parametrize("tendon_model", ["continuum", "eyelets"])
def test_spatial_chain_equals_planar_chain_on_planar_case(tendon_model):
    """Eyelet ropes: the 3-D chain equals the planar one.  Continuum tendons: the 3-D chain's rope
    through every link eyelet converges to the planar chain's exact internal moments at order 2
    (the chord's lever arm), staying in the plane without twist."""
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    load = LoadCase(actuation=TendonActuation("tension", (300.0, 0.0)))
    diffs = []
    for n in ((8,) if tendon_model == "eyelets" else (8, 16)):
        opts = SolverOptions(n_elements=n, tendon_model=tendon_model)
        r2 = solve(robot, load, opts, SpringLinkParams(dimension="2d"))
        r3 = solve(robot, load, opts, SpringLinkParams(dimension="3d"))
        diffs.append(np.abs(r2.positions - r3.positions).max())
        assert np.abs(r3.positions[:, 1]).max() < 1e-12
        assert np.abs(r3.joint_angles[:, 0]).max() < 1e-12
        assert abs(r3.tip_twist) < 1e-12
    if tendon_model == "eyelets":
        assert diffs[0] < 1e-9
        assert np.abs(r2.joint_angles[:, 0] - r3.joint_angles[:, 1]).max() < 1e-9
    else:
        assert 3.5 < diffs[0] / diffs[1] < 4.5


def test_spatial_out_of_plane_bend_is_rotated_planar_bend():
    """In the 3-D chain a tendon at sigma = pi/2 bends towards +y exactly like sigma = 0 bends
    towards +x."""
    base = build_preset("steel_rod", tendon_count=2)
    rot = build_preset("steel_rod", tendon_count=2, first_tendon_angle=math.pi / 2)
    load = LoadCase(actuation=TendonActuation("tension", (200.0, 0.0)))
    opts = SolverOptions(n_elements=8, tendon_model="continuum")
    a = solve(base, load, opts, SpringLinkParams(dimension="3d"))
    b = run(rot, load, opts)  # auto -> 3-D
    assert b.extras["dimension"] == 3.0 and a.extras["dimension"] == 3.0
    assert b.positions[:, 1] == pytest.approx(a.positions[:, 0], abs=1e-10)
    assert b.positions[:, 2] == pytest.approx(a.positions[:, 2], abs=1e-10)
    assert np.abs(b.positions[:, 0]).max() < 1e-10


def test_spatial_pure_moment_in_oblique_plane_converges():
    robot = build_preset("steel_rod")
    theta, phi = 1.2, 0.7
    M = theta * _EI(robot) / L
    # a moment about the axis (-sin phi, cos phi, 0) bends towards phi
    torque = (-M * math.sin(phi), M * math.cos(phi), 0.0)
    R = L / theta
    exact = np.array([R * (1 - math.cos(theta)) * math.cos(phi), R * (1 - math.cos(theta)) * math.sin(phi),
                      R * math.sin(theta)])
    errs, twists = [], []
    for n in (8, 16):
        res = run(robot, LoadCase(tip_torque=torque), SolverOptions(n_elements=n))
        errs.append(np.linalg.norm(res.tip_position - exact))
        twists.append(res.tip_twist)
        # rotation-vector springs on rigid bodies: a bend in a fixed plane has no twist at any N
        bod = solve(robot, LoadCase(tip_torque=torque), SolverOptions(n_elements=n), SpringLinkParams(backend="bodies"))
        assert abs(bod.tip_twist) < 1e-9
        assert np.linalg.norm(bod.tip_position - exact) < 1.1 * errs[-1]
    assert _orders(errs)[0] > 1.9
    # the default tree splits each joint into three revolute joints: its spring law differs from the
    # rotation vector's at third order per joint, so the twist is a discretisation error of order 2
    # (observed -5.7e-4 / -1.5e-4 / -3.7e-5 rad at N = 8 / 16 / 32)
    assert abs(twists[0]) < 1e-3 and _orders(twists)[0] > 1.9


def test_spatial_equal_tensions_three_tendons_do_not_bend():
    robot = build_preset("steel_rod", tendon_count=3)
    res = run(robot, LoadCase(actuation=TendonActuation("tension", (50.0, 50.0, 50.0))),
              SolverOptions(n_elements=8, tendon_model="continuum"))
    assert np.abs(res.tip_position - [0, 0, L]).max() < 1e-12


def test_spatial_torsion_spring_and_locked_cardan_twist():
    robot = build_preset("steel_rod")
    GJ = robot.sections[0].cross_section.GJ
    Mt = 2.0
    res = run(robot, LoadCase(tip_torque=(0.0, 0.0, Mt)), SolverOptions(n_elements=8))
    assert res.joint_angles.shape == (8, 3)
    assert res.tip_twist == pytest.approx(Mt * L / GJ, rel=1e-9)
    # locked torsion: no twist under a torsional moment ...
    lk = solve(robot, LoadCase(tip_torque=(0.0, 0.0, Mt)), SolverOptions(n_elements=8),
               SpringLinkParams(dimension="3d", torsion="locked"))
    assert lk.joint_angles.shape == (8, 2) and abs(lk.tip_twist) < 1e-12
    # ... but an oblique bend through Cardan joints twists the tip frame (Hooke-joint kinematics)
    theta, phi = 1.2, 0.7
    M = theta * _EI(robot) / L
    ob = solve(robot, LoadCase(tip_torque=(-M * math.sin(phi), M * math.cos(phi), 0.0)),
               SolverOptions(n_elements=8), SpringLinkParams(dimension="3d", torsion="locked"))
    assert abs(ob.tip_twist) > 1e-3


@pytest.mark.parametrize("dimension", ["2d", "3d"])
@pytest.mark.parametrize("tendon_model", ["continuum", "eyelets"])
def test_axial_springs_compress_exactly(dimension, tendon_model):
    """Equal antagonistic tensions on a straight rod: pure compression sum(T) L / EA."""
    robot = build_preset("steel_rod")
    EA = robot.sections[0].cross_section.EA
    res = solve(robot, LoadCase(actuation=TendonActuation("tension", (100.0, 100.0))),
                SolverOptions(n_elements=8, tendon_model=tendon_model),
                SpringLinkParams(dimension=dimension, axial=True))
    assert res.length_change == pytest.approx(-200.0 * L / EA, rel=1e-9)
    assert res.tip_position == pytest.approx([0.0, 0.0, L - 200.0 * L / EA], abs=1e-12)


def test_axial_springs_do_not_change_pure_bending():
    robot = build_preset("steel_rod")
    load = LoadCase(tip_torque=(0.0, 20.0, 0.0))
    a = solve(robot, load, SolverOptions(n_elements=8), SpringLinkParams(axial=True))
    b = solve(robot, load, SolverOptions(n_elements=8))
    assert np.abs(a.positions - b.positions).max() < 1e-10
    assert abs(a.length_change) < 1e-12 and b.length_change == 0.0
    with pytest.raises(ValueError, match="axial"):
        SpringLinkParams(axial=True, torsion="locked")


@pytest.mark.parametrize("dimension", ["2d", "3d"])
def test_kinematic_tree_variant_matches_rigid_body_chain(dimension):
    """The ObjectKinematicTree chain timed in the benchmark (planar or Cardan joints, tendons as
    the exact planar moments ``T d``) solves the planar chain's model."""
    from workbench.physics.spring_link.tree import tree_tip_position

    robot = build_preset("steel_rod", n_sections=2, gravity=9.81, base_orientation="horizontal")
    load = LoadCase(actuation=TendonActuation("tension", (100.0, 0.0, 0.0, 50.0)))
    opts = SolverOptions(n_elements=8, tendon_model="continuum")
    a = tree_tip_position(robot, load, opts, dimension)
    b = solve(robot, load, opts, SpringLinkParams(dimension="2d")).tip_position
    assert np.abs(a - b).max() < 1e-12


def test_dynamic_wire_delay_with_axial_springs_settles_to_static():
    """Length-controlled eyelet ropes, one motor starting 0.3 s late (Cojocaru's wire delay)."""
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    act = TendonActuation("length", (-0.01, 0.005), start_times=(0.0, 0.3), pretension=20.0)
    opts = SolverOptions(n_elements=8, tendon_model="eyelets", damping=0.02, time_step=5e-3)
    p = SpringLinkParams(axial=True)
    dyn = solve(robot, LoadCase(actuation=act, analysis="dynamic", duration=1.5, ramp_time=0.5), opts, p)
    sta = solve(robot, LoadCase(actuation=act), opts, p)
    T = dyn.series["tendon_tensions"]
    assert T.shape == (dyn.time.size, 2) and np.all(T >= 0)
    # while only the first motor reels in, the backbone is compressed more than at the end
    assert dyn.length_change < 0
    assert np.linalg.norm(dyn.tip_position - sta.tip_position) < 1e-6
    assert dyn.tendon_tensions == pytest.approx(sta.tendon_tensions, rel=1e-5)


def test_quiet_and_file_free(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    run(robot, LoadCase(actuation=TendonActuation("length", (-0.01, 0.0), pretension=5.0)),
        SolverOptions(n_elements=4, tendon_model="eyelets"))
    solve(build_preset("steel_rod", tendon_count=3),
          LoadCase(actuation=TendonActuation("tension", (5.0, 0.0, 0.0)), analysis="dynamic", duration=0.02),
          SolverOptions(n_elements=4))
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("offset_tip", [None, 0.01])
def test_continuum_tendon_with_axial_springs_converges_to_ancf(offset_tip):
    """Independent model check: the planar ANCF beam (64 el.) with the same continuum tendon,
    constant or tapered offset, compression included (axial springs)."""
    ancf = pytest.importorskip("workbench.physics.ancf")
    from workbench.robot import CrossSection, Robot, Section, TendonGroup

    cs = CrossSection.circular(6e-3)
    robot = Robot(sections=(Section(length=L, cross_section=cs,
                                    tendons=TendonGroup(angles=(0.0, math.pi), offset=0.03, offset_tip=offset_tip)),))
    load = LoadCase(actuation=TendonActuation("tension", (300.0, 0.0)))
    ref = ancf.run(robot, load, SolverOptions(n_elements=64))
    errs = []
    for n in (8, 16, 32):
        res = solve(robot, load, SolverOptions(n_elements=n), SpringLinkParams(axial=True))
        errs.append(np.linalg.norm(res.tip_position - ref.tip_position))
    # observed 3.0e-4 / 7.5e-5 / 1.9e-5 (constant), 3.9e-4 / 9.3e-5 / 1.9e-5 (tapered)
    assert np.all(_orders(errs) > 1.8), errs
    assert errs[-1] < 3e-5
    assert res.length_change == pytest.approx(ref.length_change, rel=1e-3)


_TREE_CASES = {
    "tip loads + gravity + payload": ("continuum", LoadCase(tip_force=(1.0, 0.0, 0.5), tip_torque=(0.0, 0.3, 0.0))),
    "continuum tension": ("continuum", LoadCase(actuation=TendonActuation("tension", (100.0, 0.0, 0.0, 50.0)))),
    "continuum length": ("continuum", LoadCase(actuation=TendonActuation("length", (-0.01, 0.0, -0.005, 0.01), pretension=5.0))),
    "eyelet tension": ("eyelets", LoadCase(actuation=TendonActuation("tension", (100.0, 0.0, 0.0, 50.0)))),
    "eyelet length (reeving), one slack": ("eyelets", LoadCase(actuation=TendonActuation("length", (-0.01, 0.0, -0.005, 0.01), pretension=5.0))),
}


@pytest.mark.parametrize("case", sorted(_TREE_CASES))
def test_kinematic_tree_backend_equals_rigid_bodies(case):
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal", n_sections=2, payload_mass=0.05)
    model, load = _TREE_CASES[case]
    opts = SolverOptions(n_elements=16, tendon_model=model)
    a = solve(robot, load, opts, SpringLinkParams(backend="bodies", axial=False))  # the inextensible chain
    b = solve(robot, load, opts, SpringLinkParams(backend="tree"))
    assert np.abs(a.positions - b.positions).max() < 1e-9
    assert np.abs(a.joint_angles - b.joint_angles).max() < 1e-9
    assert a.tendon_tensions == pytest.approx(b.tendon_tensions, rel=1e-6, abs=1e-9)
    if "slack" in case:
        assert b.tendon_tensions[3] == 0.0 and np.all(b.tendon_tensions[:3] > 0)


def test_tree_backend_rejects_what_it_cannot_do():
    with pytest.raises(ModelFailure, match="tree"):
        solve(build_preset("steel_rod"), LoadCase(), SolverOptions(n_elements=4),
              SpringLinkParams(backend="tree", axial=True))


def test_sprung_torsion_tree_converges_to_rotation_vector_bodies_at_order_two():
    """3-D chain with torsion springs: the tree (three revolute joints per joint, X-Y-Z and Z-Y-X
    alternating) against rigid bodies with springs on the rotation vector, under an oblique tendon
    bend, tip force and tip torque with gravity.  Observed max position difference 4.2e-5 /
    1.1e-5 / 2.6e-6 m at N = 8 / 16 / 32 (order 2.0); with X-Y-Z at every joint it is 6.2e-4 /
    3.0e-4 / 1.5e-4 m (order 1: the Cardan splitting's bending-to-twist coupling accumulates)."""
    robot = build_preset("steel_rod", tendon_count=4, gravity=9.81, base_orientation="horizontal")
    load = LoadCase(actuation=TendonActuation("tension", (300.0, 150.0, 0.0, 0.0)), tip_force=(0.5, -1.0, 2.0),
                    tip_torque=(0.3, -0.2, 0.4))
    diffs, twist = [], []
    for n in (8, 16):
        o = SolverOptions(n_elements=n, tendon_model="continuum", newton_tolerance=1e-11)
        a = solve(robot, load, o, SpringLinkParams(dimension="3d", backend="bodies"))
        b = solve(robot, load, o)
        assert b.joint_angles.shape == a.joint_angles.shape == (n, 3)
        diffs.append(np.abs(a.positions - b.positions).max())
        twist.append(abs(a.tip_twist - b.tip_twist))
    assert diffs[0] < 1e-4 and _orders(diffs)[0] > 1.8, diffs
    assert twist[0] < 1e-3 and twist[1] < twist[0] / 3, twist


def test_dynamic_reeving_on_tree_backend_settles_to_static():
    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    act = TendonActuation("length", (-0.01, 0.005), start_times=(0.0, 0.3), pretension=20.0)
    opts = SolverOptions(n_elements=8, tendon_model="eyelets", damping=0.02, time_step=5e-3)
    dyn = run(robot, LoadCase(actuation=act, analysis="dynamic", duration=1.5, ramp_time=0.5), opts)
    sta = run(robot, LoadCase(actuation=act), opts)
    assert dyn.series["tip_position"].shape == (dyn.time.size, 3)
    assert np.linalg.norm(dyn.tip_position - sta.tip_position) < 1e-6
    # the delayed motor: its tension stays at the pretension-plus-gravity level before 0.3 s
    T = dyn.series["tendon_tensions"]
    early = dyn.time < 0.25
    assert np.ptp(T[early, 1]) < np.ptp(T[:, 1])


@pytest.mark.parametrize("tendon_model,mode", [("continuum", "tension"), ("eyelets", "tension"), ("eyelets", "length")])
def test_spatial_tree_backend_matches_cardan_bodies(tendon_model, mode):
    """3-D Cardan chains: minimal-coordinate tree vs rigid bodies + GenericJoint (torsion locked).
    A bend about one Cardan axis is identical; an oblique bend differs only by the spring law
    (springs on the two Cardan angles vs on the rotation vector), which is second order in the
    joint angles and vanishes with refinement: observed 1.5-1.7e-6 m at N = 8, 2.8e-7 m at 16."""
    vals = (100.0, 60.0, 0.0, 0.0) if mode == "tension" else (-0.01, -0.006, 0.0, 0.0)
    act = TendonActuation(mode, vals, pretension=5.0 if mode == "length" else 0.0)
    p_b = SpringLinkParams(dimension="3d", torsion="locked", backend="bodies")
    p_t = SpringLinkParams(dimension="3d", torsion="locked", backend="tree")
    oblique = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal", tendon_count=4)
    diffs = []
    for n in (8, 16):
        o = SolverOptions(n_elements=n, tendon_model=tendon_model)
        a, b = solve(oblique, LoadCase(actuation=act), o, p_b), solve(oblique, LoadCase(actuation=act), o, p_t)
        assert a.joint_angles.shape == b.joint_angles.shape == (n, 2)
        assert abs(b.tip_twist - a.tip_twist) < 1e-5 * abs(a.tip_twist) + 1e-7
        diffs.append(np.abs(a.positions - b.positions).max())
    assert diffs[0] < 5e-6 and diffs[1] < diffs[0] / 3, diffs
    opts = SolverOptions(n_elements=8, tendon_model=tendon_model)
    single = build_preset("steel_rod", tendon_count=4)
    only_y = TendonActuation(mode, (0.0, vals[0], 0.0, 0.0) if mode == "tension" else (0.0, vals[0], 0.0, 0.0),
                             pretension=act.pretension)
    a, b = solve(single, LoadCase(actuation=only_y), opts, p_b), solve(single, LoadCase(actuation=only_y), opts, p_t)
    assert np.abs(a.positions - b.positions).max() < 1e-9
    assert a.tip_position[1] > 0.01


def test_equal_joint_angles_put_every_disk_exactly_on_a_cc_arc():
    """Kinematic limit, exact: with equal joint angles theta in a section, the chain is a regular
    polygon whose edge midpoints (the disks/eyelets, every ds) lie on a circle of radius
    ds / (2 tan(theta/2)) tangent to the links, so each section is exactly a CC arc of curvature
    kappa' = 2 tan(theta/2) / ds through its disks (kappa' -> theta/ds as N grows)."""
    from workbench.kinematics import forward_kinematics

    robot = build_preset("steel_rod", n_sections=2, tendon_count=2)
    N = 16
    res = run(robot, LoadCase(actuation=TendonActuation("tension", (60.0, 0.0, 0.0, 45.0))),
              SolverOptions(n_elements=N, tendon_model="continuum", n_stations=N + 1))
    q = res.joint_angles[:, 0]
    ds = L / N
    theta = np.array([q[0], q[N // 2]])
    kappa = 2.0 * np.tan(theta / 2.0) / ds
    assert np.allclose(q[: N // 2], theta[0], atol=1e-12) and np.allclose(q[N // 2 :], theta[1], atol=1e-12)
    assert theta[0] > 0 > theta[1]
    per = N // 2
    # CC with phi = 0 bends towards +x for kappa > 0, phi = pi for kappa < 0
    kap, phi = np.abs(kappa), np.where(kappa >= 0, 0.0, np.pi)
    for k in range(N + 1):  # disk k at s = k ds: arc angle theta per disk interval
        n_in = np.clip(k - per * np.arange(2), 0, per)  # disk intervals covered in each section
        T = forward_kinematics(kap, phi, n_in * np.abs(theta) / kap)
        assert res.positions[k] == pytest.approx(T[:3, 3], abs=1e-12)
    assert res.tip_frame == pytest.approx(T, abs=1e-12)
