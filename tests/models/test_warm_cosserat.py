"""Warm starts of the ``cosserat`` shooting (:mod:`workbench.physics.cosserat.warm`).

References: the cold solve of the same load (the load ramp from the unloaded rod), and, on the
branch-jump robot of ``tests/physics/test_load_path.py`` (diagnostics.md "Branch jump"), the
answer of that ramp, which a 20-step continuation reproduces there.  A state from a neighbour on
the same load ray continues the cold path (answers agree to the Newton tolerance); a state from a
neighbour off the ray is refused -- Newton started from it lands on another equilibrium 0.8 L away.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from workbench.models import SolverOptions
from workbench.physics.cosserat import Shooter, rod_problem, run
from workbench.physics.cosserat.rod import integrate_segments
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

JUMP_TENSIONS = np.array((0.0, 0.69, 0.0, 0.0, 0.0, 0.0, 3.11, 0.0, 0.0))
JUMP_TIP_FORCE = np.array((0.0, -0.259, 0.0))
# a load off the branch-jump load's ray whose state leads Newton to another equilibrium
OFF_RAY_TENSIONS = (0.5512058105987409, 0.0, 0.0, 0.0, 0.0, 0.3495441841103239, 0.0, 0.0, 0.43464386204512717)
OFF_RAY_TIP_FORCE = (0.032704226346464256, -0.3682056162733722, -0.20496799853416867)
OPTS = SolverOptions(newton_tolerance=1e-10)


def _robot(n_sections: int = 3, **kw) -> Robot:
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=tuple(Section(0.2, rod, tg, n_disks=10, **kw) for _ in range(n_sections)))


def _jump_load(scale: float) -> LoadCase:
    return LoadCase(actuation=TendonActuation("tension", tuple(scale * JUMP_TENSIONS)),
                    tip_force=tuple(scale * JUMP_TIP_FORCE))


@pytest.fixture(scope="module")
def jump_robot():
    return _robot(3)


@pytest.fixture(scope="module")
def jump_cold(jump_robot):
    return run(jump_robot, _jump_load(1.0), OPTS)


@pytest.mark.parametrize("scale", [0.3, 0.7])
def test_a_neighbour_on_the_load_ray_continues_the_cold_path(jump_robot, jump_cold, scale):
    nb = run(jump_robot, _jump_load(scale), OPTS)
    assert nb.warm_state is not None and nb.solver.path_event == ""
    warm = run(jump_robot, _jump_load(1.0), replace(OPTS, warm_state=nb.warm_state))
    assert warm.extras["warm_started"] == 1.0 and warm.solver.path_event == ""
    # the Newton tolerance 1e-10 on the scaled tip residual: positions agree to ~1e-10 L
    assert np.abs(warm.positions - jump_cold.positions).max() < 1e-8 * jump_robot.length
    assert np.abs(warm.tendon_tensions - jump_cold.tendon_tensions).max() == 0.0
    assert abs(warm.tip_twist - jump_cold.tip_twist) < 1e-8


def test_a_neighbour_off_the_ray_is_refused_where_newton_from_it_jumps(jump_robot, jump_cold):
    off = LoadCase(actuation=TendonActuation("tension", OFF_RAY_TENSIONS), tip_force=OFF_RAY_TIP_FORCE)
    nb = run(jump_robot, off, OPTS)
    assert nb.warm_state is not None
    # a naive warm start: Newton at the full load from the neighbour's base wrench
    pb = rod_problem(jump_robot, _jump_load(1.0))
    sh = Shooter(pb, 1e-10)
    x = sh.newton(nb.warm_state[-6:], 1.0, JUMP_TENSIONS)
    tip, _ = integrate_segments(pb, x[None], JUMP_TENSIONS, 1.0, sh.rtol)
    assert np.linalg.norm(tip[0, 0:3] - jump_cold.positions[-1]) > 0.5 * jump_robot.length  # another branch
    warm = run(jump_robot, _jump_load(1.0), replace(OPTS, warm_state=nb.warm_state))
    assert warm.extras["warm_started"] == 0.0  # refused: solved cold, the same answer bit for bit
    assert np.array_equal(warm.positions, jump_cold.positions)


def test_a_neighbour_at_a_larger_load_is_refused(jump_robot, jump_cold):
    nb = run(jump_robot, _jump_load(1.2), OPTS)
    warm = run(jump_robot, _jump_load(1.0), replace(OPTS, warm_state=nb.warm_state))
    assert warm.extras["warm_started"] == 0.0 and np.array_equal(warm.positions, jump_cold.positions)


def test_without_a_state_the_result_is_the_cold_one_and_carries_no_warm_extra(jump_robot, jump_cold):
    again = run(jump_robot, _jump_load(1.0), OPTS)
    assert np.array_equal(again.positions, jump_cold.positions) and "warm_started" not in again.extras


def test_states_of_another_rod_or_another_weight_are_refused():
    planar = LoadCase(actuation=TendonActuation("tension", (2.0, 0.0, 0.0, 0.0, 1.0, 0.0)), tip_force=(0.0, 0.05, 0.0))
    half = LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0, 0.0, 0.5, 0.0)), tip_force=(0.0, 0.025, 0.0))
    robot = _robot(2)
    state = run(robot, half, OPTS).warm_state
    assert run(robot, planar, replace(OPTS, warm_state=state)).extras["warm_started"] == 1.0
    stiffer = Robot(sections=tuple(replace(s, cross_section=CrossSection.circular(1.5e-3, 54e9, 6450.0, 0.33))
                                   for s in robot.sections))
    assert run(stiffer, planar, replace(OPTS, warm_state=state)).extras["warm_started"] == 0.0
    # with gravity and mass the weights are on the ray only at the same load: half the load is refused
    heavy = Robot(sections=robot.sections, gravity=(0.0, -9.81, 0.0))
    h_state = run(heavy, half, OPTS).warm_state
    assert run(heavy, planar, replace(OPTS, warm_state=h_state)).extras["warm_started"] == 0.0
    same = run(heavy, planar, OPTS)
    again = run(heavy, planar, replace(OPTS, warm_state=same.warm_state))
    assert again.extras["warm_started"] == 1.0
    assert np.abs(again.positions - same.positions).max() < 1e-9 * robot.length


def test_length_control_ignores_the_state():
    robot = _robot(1)
    load = LoadCase(actuation=TendonActuation("length", (-2e-3, 0.0, 0.0), pretension=0.5))
    tension = LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0)))
    state = run(robot, tension, OPTS).warm_state
    cold = run(robot, load, OPTS)
    warm = run(robot, load, replace(OPTS, warm_state=state))
    assert warm.extras["warm_started"] == 0.0 and np.array_equal(warm.positions, cold.positions)
    assert cold.warm_state is None  # its tensions came from the length solve, not the straight load path
