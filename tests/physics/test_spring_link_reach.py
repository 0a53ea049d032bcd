"""Spring-link reach: large dead loads and the spatial eyelet robot (issue 14, item 1).

The rigid-body chain's static Newton stalls under large joint reactions because Exudyn's
iteration matrix lacks their geometric stiffness (``docs/models.md``, "Spring-link"); the
default backend is the kinematic tree.  These tests check that every tip load alpha = PL^2/EI
and self-weight gamma = qL^3/EI of the issue solves at N = 8 ... 128 links with observed order 2
towards the inextensible elastica, and that the two-section NiTi robot with eyelet tendons solves
for tensions up to 10 N and tip forces up to 0.2 N in any direction.  The full grids are in the
slow tier; the default suite keeps alpha = 5, gamma = 16 and the issue's spatial case.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.reference.elastica import clamped_elastica
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.presets import build_preset

L = 0.8
OPTS = dict(newton_tolerance=1e-10, max_load_steps=2000)


def _orders(errors):
    e = np.asarray(errors)
    return np.log2(e[:-1] / e[1:])


def _dead_load(kind: str, value: float):
    """Horizontal 0.8 m, 6 mm steel rod (base x = world up); tip load or self-weight of the
    given dimensionless size; the elastica tip (base frame) as reference."""
    rod = build_preset("steel_rod")
    cs = rod.sections[0].cross_section
    EI = cs.EI
    if kind == "alpha":
        P = value * EI / L**2
        robot = build_preset("steel_rod", base_orientation="horizontal")
        load = LoadCase(tip_force=(-P, 0.0, 0.0))
        ref = clamped_elastica(L, EI, tip_force=(0.0, -P), stations=2, n_continuation=10)
    else:
        g = value * EI / (cs.mass_per_length * L**3)
        robot = build_preset("steel_rod", base_orientation="horizontal", gravity=g)
        load = LoadCase()
        ref = clamped_elastica(L, EI, distributed_load=(0.0, -value * EI / L**3), stations=2, n_continuation=10)
    # elastica plane: a = base z (along the rod), b = base x
    return robot, load, np.array([ref.tip[1], 0.0, ref.tip[0]])


def _errors(kind, value, links):
    robot, load, tip = _dead_load(kind, value)
    run = get_model("spring_link")
    out = []
    for n in links:
        res = run(robot, load, SolverOptions(n_elements=n, **OPTS))
        assert res.solver.converged
        out.append(np.linalg.norm(res.tip_position - tip) / L)
    return out


@pytest.mark.parametrize("kind,value", [("alpha", 5.0), ("gamma", 16.0)])
def test_largest_dead_loads_converge_to_the_elastica(kind, value):
    """Observed (tip error / L): alpha = 5: 3.0e-3 / 7.4e-4 / 1.8e-4, gamma = 16: 1.1e-2 / 2.7e-3
    / 6.7e-4 at N = 8 / 16 / 32; the rigid-body chain stalled at alpha ~ 2.4 at every N."""
    errs = _errors(kind, value, (8, 16, 32))
    assert np.all(_orders(errs) > 1.9), errs
    assert errs[-1] < 2e-3


@pytest.mark.slow
@pytest.mark.parametrize("kind,value", [("alpha", a) for a in (0.25, 0.5, 1, 2, 3, 5, 10)]
                         + [("gamma", g) for g in (0.5, 1, 2, 4, 8, 16)])
def test_dead_load_grid_converges_at_order_two(kind, value):
    errs = _errors(kind, float(value), (8, 16, 32, 64, 128))
    assert np.all(_orders(errs) > 1.9), errs
    assert errs[-1] < 1e-4


def nitinol_robot(disks: int = 10) -> Robot:
    """The issue's spatial robot: 2 x 0.2 m NiTi (E 54 GPa, d 1.4 mm, density 6450 kg/m^3 and
    Poisson 0.33 assumed), ``disks`` disks per section, 3 tendons per section at 90, -30, 210 deg,
    offset 10 mm, EA_t = 1e7 N (stiff), no gravity."""
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, rod, tg, n_disks=disks), Section(0.2, rod, tg, n_disks=disks)))


def _spatial(tensions, force, n=20):
    load = LoadCase(actuation=TendonActuation("tension", tuple(tensions)), tip_force=tuple(force))
    return get_model("spring_link")(nitinol_robot(), load, SolverOptions(n_elements=n, tendon_model="eyelets", **OPTS))


def test_spatial_eyelet_robot_of_the_issue_solves():
    """Tensions (4, 0, 0, 0, 2, 0) N: the rigid-body chain failed at load factor 0.77 after 28 s.
    Tip vs CC (the continuum-tendon arc): 1.2e-2 m at N = 20 links, 5.9e-3 m at N = 40 (the chain's
    O(1/N^2) error with eyelet ropes), 2.9e-3 m at N = 40 with 20 disks per section (the eyelet
    effect falls with the disk count); the continuum-tendon chain is within 1.5e-4 m of CC at N = 20."""
    robot = nitinol_robot()
    T = (4.0, 0.0, 0.0, 0.0, 2.0, 0.0)
    res = _spatial(T, (0.0, 0.0, 0.0))
    cc = get_model("cc")(robot, LoadCase(actuation=TendonActuation("tension", T)), SolverOptions())
    assert res.solver.converged and res.extras["dimension"] == 3.0
    assert np.linalg.norm(res.tip_position - cc.tip_position) < 0.04 * 0.4
    assert res.tendon_tensions == pytest.approx(T)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(8))
def test_spatial_eyelet_robot_solves_any_tension_and_tip_force(seed):
    """Seeded random tensions in [0, 10] N and tip forces of 0.2 N in random directions (seed 0:
    every tendon at 10 N; seed 1: one tendon per section at 10 N, the largest bend)."""
    rng = np.random.default_rng(seed)
    T = rng.uniform(0.0, 10.0, 6)
    if seed == 0:
        T[:] = 10.0
    elif seed == 1:
        T[:] = [10.0, 0.0, 0.0, 0.0, 10.0, 0.0]
    f = rng.normal(size=3)
    f *= 0.2 / np.linalg.norm(f)
    res = _spatial(T, f)
    assert res.solver.converged and np.all(np.isfinite(res.positions))
    # the tip stays on the robot's reachable sphere and the backbone is inextensible
    assert np.linalg.norm(res.tip_position) <= 0.4 + 1e-12
    assert res.length_change == 0.0
