"""Spring-link chain cross-examined against independent models (issue 28, findings 2, 3, 4).

Robot "Rao NiTi" of ``../shared/notes/diagnostics.md``: sections of 0.2 m, NiTi rod d = 1.4 mm
(E = 54 GPa, rho = 6450 kg/m^3, nu = 0.3), tendons at (pi/2, -pi/6, 7 pi/6) (planar: (0, pi)) at
10 mm, 10 disks per section.  The chain's error bar is its own link refinement: Richardson
extrapolation of ``N`` and ``2N`` links with the observed order 2, bar ``|x_2N - x_R|``; the
references are the Cosserat rod (continuous tendons, shooting to 1e-9) and point-load beam theory.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.physics.spring_link import SpringLinkParams, solve
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.orientation import base_rotation_for

L_SEC = 0.2


def rao(n_sec: int = 2, planar: bool = False, disk_mass: float = 0.0, horizontal: bool = False,
        gravity: float = 0.0, tendon_ea: float = 1e7, offset_tip: float | None = None) -> Robot:
    cs = CrossSection.circular(diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.3)
    angles = (0.0, math.pi) if planar else (math.pi / 2, -math.pi / 6, 7 * math.pi / 6)
    tg = TendonGroup(angles=angles, offset=10e-3, axial_stiffness=tendon_ea, offset_tip=offset_tip)
    secs = tuple(Section(length=L_SEC, cross_section=cs, tendons=tg, n_disks=10, disk_mass=disk_mass)
                 for _ in range(n_sec))
    kw = {"base_rotation": base_rotation_for("horizontal")} if horizontal else {}
    return Robot(sections=secs, gravity=(0.0, 0.0, -gravity), **kw)


def richardson(coarse: np.ndarray, fine: np.ndarray, order: float = 2.0) -> tuple[np.ndarray, float]:
    """Extrapolated value and its error bar ``|fine - extrapolated|``."""
    r = fine + (fine - coarse) / (2.0**order - 1.0)
    return r, float(np.linalg.norm(fine - r))


def _spring(robot, load, n, **kw):
    return get_model("spring_link")(robot, load, SolverOptions(n_elements=n, **kw))


def _tip_and_twist_against_cosserat(robot, load, links):
    ref = get_model("cosserat")(robot, load, SolverOptions())
    res = [_spring(robot, load, n) for n in links]
    errs = [np.linalg.norm(r.tip_position - ref.tip_position) for r in res]
    tip, bar = richardson(res[0].tip_position, res[1].tip_position)
    twist, twist_bar = richardson(np.array([res[0].tip_twist]), np.array([res[1].tip_twist]))
    return ref, errs, tip, bar, float(twist[0]), twist_bar


def test_3d_continuum_tendons_under_a_tip_force_converge_to_the_cosserat_rod():
    """Finding 2: tensions (2, 2, 0 | 0, 3, 0) N and tip force (0, 0.1, 0) N.  Before the fix the chain
    (body-fixed end torques) converged in links to 8.4e-2 L from the Cosserat rod with no twist;
    the tendon as a rope through every link eyelet converges to it at order 2, twist included."""
    robot = rao(2)
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 2.0, 0.0, 0.0, 3.0, 0.0)), tip_force=(0.0, 0.1, 0.0))
    ref, errs, tip, bar, twist, twist_bar = _tip_and_twist_against_cosserat(robot, load, (20, 40))
    floor = 1e-4 * robot.length
    assert np.linalg.norm(tip - ref.tip_position) <= bar + floor
    assert 1.7 < math.log2(errs[0] / errs[1]) < 2.5
    assert abs(twist - ref.tip_twist) <= twist_bar + 1e-3
    assert abs(ref.tip_twist) > 0.3  # the case twists: the old end torques gave ~0


def test_3d_continuum_tendon_under_gravity_converges_to_the_cosserat_rod():
    """Finding 2, gravity alone with one tendon: horizontal base, 5.89 N on section 2's third tendon
    (1.0e-2 L before the fix, converged in links)."""
    robot = rao(2, horizontal=True, gravity=9.81)
    load = LoadCase(actuation=TendonActuation("tension", (0.0, 0.0, 0.0, 0.0, 0.0, 5.89)))
    ref, errs, tip, bar, twist, twist_bar = _tip_and_twist_against_cosserat(robot, load, (20, 40))
    assert np.linalg.norm(tip - ref.tip_position) <= bar + 1e-4 * robot.length
    assert 1.7 < math.log2(errs[0] / errs[1]) < 2.5
    assert abs(twist - ref.tip_twist) <= twist_bar + 1e-3


def _point_load_tip_deflection(robot: Robot, g: float) -> float:
    """Linear cantilever: uniform self-weight ``q L^4 / 8 EI`` plus every disk ``P a^2 (3L - a) / 6 EI``."""
    cs = robot.sections[0].cross_section
    L, EI = robot.length, cs.EI
    w = cs.mass_per_length * g * L**4 / (8.0 * EI)
    m = robot.sections[0].disk_mass
    return w + sum(m * g * a**2 * (3.0 * L - a) / (6.0 * EI) for a in robot.disk_stations())


def test_disk_weights_act_at_the_disks():
    """Finding 3: planar, 2 sections, horizontal base, 10 x 0.5 g disks per section, g/100 (linear).
    Point-load beam theory: 1.1288e-3 m.  The disks' weights spread over the links converged away
    from it (1.10e-3 at 40 links); at their stations the chain converges towards it at order 2."""
    g = 9.81 / 100
    robot = rao(2, planar=True, disk_mass=0.5e-3, horizontal=True, gravity=g)
    theory = _point_load_tip_deflection(robot, g)
    assert theory == pytest.approx(1.1288e-3, abs=1e-7)
    defl = np.array([-_spring(robot, LoadCase(), n).tip_position[0] for n in (10, 20, 40)])
    errs = np.abs(defl - theory)
    assert errs[0] > errs[1] > errs[2]
    assert 1.7 < math.log2(errs[1] / errs[2]) < 2.5
    r, bar = richardson(defl[1:2], defl[2:3])
    # floor 1e-5 relative: geometric nonlinearity of a 0.3 % L sag
    assert abs(r[0] - theory) <= bar + 1e-5 * theory


@pytest.mark.parametrize("n_sec", [1, 2])
def test_length_mode_tensions_match_the_cosserat_rod(n_sec):
    """Finding 4: planar, tendon EA 2e4 N, commands -5 mm on the second tendon of every section,
    pretension 0.32 N.  The inextensible chain gives 253 / 254 N (1 section) where the extensible
    rods give 170 / 171 N (the backbone's compression, -0.82 mm, shortens the tendons too); the
    default chain (axial springs in planar continuum length mode) matches the Cosserat rod."""
    robot = rao(n_sec, planar=True, tendon_ea=2e4)
    cmd = (0.0, -5e-3) * n_sec
    load = LoadCase(actuation=TendonActuation("length", cmd, pretension=0.32))
    ref = get_model("cosserat")(robot, load, SolverOptions())
    res = [_spring(robot, load, n) for n in (16, 32)]
    T, bar = richardson(res[0].tendon_tensions, res[1].tendon_tensions)
    assert np.all(np.abs(T - ref.tendon_tensions) <= bar + 1e-5 * np.abs(ref.tendon_tensions))
    tip, tip_bar = richardson(res[0].tip_position, res[1].tip_position)
    assert np.linalg.norm(tip - ref.tip_position) <= tip_bar + 1e-6 * robot.length
    assert res[1].length_change == pytest.approx(ref.length_change, rel=1e-4)
    stiff = solve(robot, load, SolverOptions(n_elements=32), SpringLinkParams(axial=False))
    assert stiff.length_change == 0.0
    assert np.max(stiff.tendon_tensions / ref.tendon_tensions) > 1.4  # the option keeps the old chain


def test_axial_default_only_where_the_lagged_coupling_applies():
    """Axial springs by default for planar, static, constant-offset continuum length mode only; an
    explicit axial chain in dynamics is refused before it runs (the coupling is static only)."""
    from workbench.models.result import ModelFailure
    from workbench.physics.spring_link import resolve_axial

    length = TendonActuation("length", (0.0, -1e-3), pretension=0.32)
    planar = rao(1, planar=True)
    assert resolve_axial(SpringLinkParams(), planar, LoadCase(actuation=length), "continuum", True)
    assert not resolve_axial(SpringLinkParams(), planar, LoadCase(actuation=length), "eyelets", True)
    assert not resolve_axial(SpringLinkParams(), planar, LoadCase(actuation=length), "continuum", False)
    assert not resolve_axial(SpringLinkParams(), rao(1, planar=True, offset_tip=5e-3), LoadCase(actuation=length),
                             "continuum", True)
    dyn = LoadCase(actuation=length, analysis="dynamic", duration=0.01)
    assert not resolve_axial(SpringLinkParams(), planar, dyn, "continuum", True)
    assert resolve_axial(SpringLinkParams(axial=False, backend="tree"), planar, LoadCase(actuation=length),
                         "continuum", True) is False
    with pytest.raises(ModelFailure, match="static only"):
        solve(planar, dyn, SolverOptions(n_elements=4), SpringLinkParams(axial=True))


def test_3d_tapered_continuum_tendons_converge_to_the_cosserat_rod():
    """Tapered offsets (10 -> 5 mm) in 3-D under a tip force, refused at run time before the fix:
    the rope through every link eyelet follows the taper (order 2 towards the Cosserat rod)."""
    robot = rao(2, offset_tip=5e-3)
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 0.0, 0.0, 0.0, 1.0, 0.0)), tip_force=(0.0, 0.05, 0.0))
    ref, errs, tip, bar, _, _ = _tip_and_twist_against_cosserat(robot, load, (20, 40))
    assert np.linalg.norm(tip - ref.tip_position) <= bar + 1e-4 * robot.length
    assert 1.7 < math.log2(errs[0] / errs[1]) < 2.5


def test_3d_continuum_length_mode_runs_and_agrees_with_tension_mode():
    """3-D continuum tendons in length mode (refused before): the reeving law on the link ropes.
    Re-solving in tension mode with the tensions it found gives the same shape."""
    robot = rao(1, tendon_ea=2e4)
    load = LoadCase(actuation=TendonActuation("length", (-2e-3, 0.0, 0.0), pretension=0.32))
    a = _spring(robot, load, 10)
    assert a.extras["dimension"] == 3.0 and np.all(a.tendon_tensions > 1.0)
    b = _spring(robot, LoadCase(actuation=TendonActuation("tension", tuple(a.tendon_tensions))), 10)
    assert np.abs(a.positions - b.positions).max() < 1e-9


@pytest.mark.slow
def test_3d_continuum_tendons_refined_to_80_links():
    """Finding 2's case at 40 / 80 links: the order-2 convergence continues (tip error vs Cosserat
    4.0e-3 / 1.0e-3 m measured) and the extrapolation lands within its bar."""
    robot = rao(2)
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 2.0, 0.0, 0.0, 3.0, 0.0)), tip_force=(0.0, 0.1, 0.0))
    ref, errs, tip, bar, twist, twist_bar = _tip_and_twist_against_cosserat(robot, load, (40, 80))
    assert np.linalg.norm(tip - ref.tip_position) <= bar + 1e-4 * robot.length
    assert 1.7 < math.log2(errs[0] / errs[1]) < 2.5
    assert abs(twist - ref.tip_twist) <= twist_bar + 1e-3
