"""Load paths, not jumps (issue 28): the path check of the load ramp and the models that use it.

Synthetic paths (:func:`workbench.physics._stepping.load_ramp` with :class:`PathPoint` attempts):
a fold whose branch ends (the state must snap: the event and its load fraction are recorded), a
smooth path (no event, the step sequence of the policy), a stiffness sign change on a continuous
path.  The models: the exact branch-jump case of ``../shared/notes/diagnostics.md`` for
``cosserat`` against a 20-step continuation of the same rod (independent of the ramp), and the
spatial length-mode case that ran for ever, which must now end within a bounded number of solves.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.physics._stepping import PathPoint, RampPolicy, load_ramp

FOLD = 0.9  # load factor of the fold of the synthetic snap path below


class _Cubic:
    """Equilibria ``x^3 - 3 x = g(lam)`` with ``g(lam) = -2.5 + 5 lam`` (or another ``g``); a solve
    lands on the real root nearest to the last state (a Newton solve started there).  The branch
    ``x < -1`` exists while ``g <= 2``, i.e. up to ``lam = FOLD``; beyond it the state must snap to
    ``x > 2``.  The measure is ``x`` (dimensionless, order 1)."""

    def __init__(self, g=lambda lam: -2.5 + 5.0 * lam, sign=None):
        self.g, self.sign, self.trials = g, sign, []
        self.x = self.root(-10.0, 0.0)

    def root(self, near: float, lam: float) -> float:
        r = np.roots([1.0, 0.0, -3.0, -self.g(lam)])
        real = r[np.abs(r.imag) < 1e-9].real
        return float(real[np.argmin(np.abs(real - near))])

    def attempt(self, lam: float) -> PathPoint:
        self.trials.append(lam)
        self.x = self.root(self.x, lam)
        return PathPoint((self.x,), self.sign(lam) if self.sign else 0)

    def save(self) -> float:
        return self.x

    def restore(self, x: float) -> None:
        self.x = x


def _ramp(s: _Cubic, policy: RampPolicy = RampPolicy(), max_attempts: int = 200):
    return load_ramp(s.attempt, s.save, s.restore, max_attempts=max_attempts, policy=policy,
                     start=PathPoint((s.x,), s.sign(0.0) if s.sign else 0))


SNAP = RampPolicy(max_motion=2.0)  # the first full step has no secant: the motion cap catches it


def test_snap_through_is_refined_and_recorded_with_its_load_fraction():
    s = _Cubic()
    info = _ramp(s, SNAP)
    assert info.path_event == "jump"
    # the fold lies in the unresolved step: [fraction, fraction + jump_min_increment]
    assert info.path_event_fraction <= FOLD <= info.path_event_fraction + SNAP.jump_min_increment
    assert s.x == pytest.approx(s.root(10.0, 1.0))  # on the far branch at the full load
    assert info.rejected_jumps > 0 and info.accepted == info.attempts - info.failed


def test_without_motion_cap_a_first_full_step_is_not_checked():
    # the default policy (no cap): nothing to compare the first step with, accepted as before
    s = _Cubic()
    info = _ramp(s)
    assert (s.trials, info.path_event) == ([1.0], "")


def test_without_path_measure_the_same_solver_jumps_silently():
    # the old behaviour: a bool attempt is accepted at the full load, no event
    s = _Cubic()
    info = load_ramp(lambda lam: s.attempt(lam) is not None, s.save, s.restore, max_attempts=10)
    assert (info.attempts, info.path_event) == (1, "")
    assert s.x == pytest.approx(s.root(10.0, 1.0))


def test_smooth_path_keeps_the_policy_step_sequence():
    # x^3 - 3x = -2.5 + 0.5 lam stays on the one real branch (x from -2.10 to -2.05): one step
    s = _Cubic(g=lambda lam: -2.5 + 0.5 * lam)
    info = _ramp(s)
    assert (s.trials, info.path_event, info.failed) == ([1.0], "", 0)
    assert math.isnan(info.path_event_fraction)


def test_smooth_large_motion_is_split_by_the_motion_cap_without_event():
    # x from -2.10 to -3.3 (measure moves 1.2 > max_motion 1.0): halved once, no event
    s = _Cubic(g=lambda lam: -2.5 - 23.0 * lam)
    info = _ramp(s, RampPolicy(max_motion=1.0))
    assert s.trials[:2] == [1.0, 0.5] and info.path_event == "" and info.rejected_jumps == 1
    assert s.x == pytest.approx(s.root(-10.0, 1.0))


def test_stiffness_sign_change_on_a_continuous_path_is_a_bifurcation():
    s = _Cubic(g=lambda lam: -2.5 + 0.5 * lam, sign=lambda lam: 1 if lam < 0.3 else -1)
    info = _ramp(s)
    assert info.path_event == "bifurcation"
    assert info.path_event_fraction <= 0.3 <= info.path_event_fraction + RampPolicy().jump_min_increment
    assert s.x == pytest.approx(s.root(-10.0, 1.0))


# --------------------------------------------------------------------------- the models

def _rao_niti(n_sections: int, axial_stiffness: float = 1e7, disk_mass: float = 0.0, **robot_kw):
    """The Rao et al. NiTi robot of ``../shared/notes/peer-benchmark.md``: 0.2 m sections, d 1.4 mm,
    E 54 GPa, 3 tendons at 90, -30, 210 deg, offset 10 mm, 10 disks per section."""
    from workbench.robot import CrossSection, Robot, Section, TendonGroup

    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=axial_stiffness)
    return Robot(sections=tuple(Section(0.2, rod, tg, n_disks=10, disk_mass=disk_mass) for _ in range(n_sections)),
                 **robot_kw)


JUMP_TENSIONS = (0.0, 0.69, 0.0, 0.0, 0.0, 0.0, 3.11, 0.0, 0.0)
JUMP_TIP_FORCE = (0.0, -0.259, 0.0)


def _continuation_tip(robot, load, tensions, steps: int = 20) -> np.ndarray:
    """Tip of the Cosserat rod reached in ``steps`` equal load steps (tensions and tip force
    together), each Newton started from the secant of the last two: the path from the unloaded rod,
    independent of the load ramp."""
    from workbench.physics.cosserat.problem import rod_problem
    from workbench.physics.cosserat.rod import integrate_segments
    from workbench.physics.cosserat.shooting import Shooter, straight_rod_base_wrench

    pb = rod_problem(robot, load)
    sh = Shooter(pb, 1e-10)
    T = np.asarray(tensions, dtype=float)
    prev, x = None, np.zeros(6)
    for k in range(1, steps + 1):
        lam = k / steps
        guess = straight_rod_base_wrench(pb, lam) if prev is None else 2.0 * x - prev
        prev, x = x, sh.newton(guess, lam, lam * T)
    tip, _ = integrate_segments(pb, x[None], T, 1.0, sh.rtol)
    return tip[0, 0:3]


@pytest.mark.slow
def test_cosserat_follows_the_load_path_in_the_branch_jump_case():
    # diagnostics.md "Branch jump": the whole load in one step landed on a curled state 1.2 L away
    from workbench.models import SolverOptions, get_model
    from workbench.physics.cosserat import run
    from workbench.robot import LoadCase, TendonActuation

    robot = _rao_niti(3)
    load = LoadCase(actuation=TendonActuation("tension", JUMP_TENSIONS), tip_force=JUMP_TIP_FORCE)
    res = run(robot, load, SolverOptions(newton_tolerance=1e-10))
    ref = _continuation_tip(robot, load, JUMP_TENSIONS)
    assert np.linalg.norm(res.positions[-1] - ref) < 1e-4 * robot.length
    assert res.solver.path_steps > 1 and res.solver.path_event == ""  # refined, and the path is continuous
    # another model: beam3d with eyelets at the 10 disks per section (routing differs from continuous
    # by ~3e-3 L here; the curled branch was 1.2 L away)
    b3 = get_model("beam3d")(robot, load, SolverOptions(n_elements=60, tendon_model="eyelets"))
    assert np.linalg.norm(res.positions[-1] - b3.positions[-1]) < 1e-2 * robot.length


HANG_COMMANDS = (-3e-3, 0.0, 0.0, 0.0, -2e-3, 0.0)


def _hang_case():
    """diagnostics.md "Dropped silently": spatial, length mode, tendon EA 2e4 N, pretension 0.3 N,
    tip force 0.05 N, gravity along base x (horizontal base), heavy (0.5 g) disks; 2 sections."""
    from workbench.robot import LoadCase, TendonActuation
    from workbench.robot.orientation import base_rotation_for

    robot = _rao_niti(2, axial_stiffness=2e4, disk_mass=5e-4, gravity=(0.0, 0.0, -9.81),
                      base_rotation=base_rotation_for("horizontal"))
    load = LoadCase(actuation=TendonActuation("length", HANG_COMMANDS, pretension=0.3), tip_force=(0.0, 0.05, 0.0))
    return robot, load


@pytest.mark.slow
def test_cosserat_length_mode_ends_within_its_load_step_budget():
    # the length solve's tension solves share one budget of max_load_steps ramp attempts: with 6
    # the case (about 40 tension solves to converge) stops after at most 6 shooting solves
    from workbench.models import ModelFailure, SolverOptions
    from workbench.physics.cosserat import run

    robot, load = _hang_case()
    with pytest.raises(ModelFailure, match="length-controlled tendon solve used all max_load_steps=6 load steps"):
        run(robot, load, SolverOptions(max_load_steps=6))


def test_cosserat_ramp_doubles_capped_at_the_remaining_load(monkeypatch):
    # deliberately changed with the path check (issue 28): growth capped at the load still to go, as
    # beam3d and ancf3d (the cap at one retried the failed full step once more); no jump here
    from workbench.models import SolverOptions
    from workbench.physics.cosserat import run, shooting
    from workbench.robot import LoadCase
    from workbench.robot.presets import build_preset

    trials: list[float] = []
    orig = shooting.Shooter.newton

    def newton(self, x, lam, tau):
        trials.append(lam)
        out = orig(self, x, lam, tau)
        if len(trials) - 1 in (0, 2, 4):
            raise shooting.ShootingFailure("injected failure")
        return out

    monkeypatch.setattr(shooting.Shooter, "newton", newton)
    res = run(build_preset("steel_rod"), LoadCase(tip_force=(1.0, 0.0, 0.0)), SolverOptions())
    assert trials == [1.0, 0.5, 1.0, 0.75, 1.0, 0.875, 1.0]
    assert (res.solver.path_steps, res.solver.path_event) == (4, "")


def test_spring_link_results_carry_their_path_fields():
    """The registered run and the warm-started session report the steps of their load paths
    (spring_link collects each static ramp's info; a session solve reports its own ramp)."""
    from workbench.models import SolverOptions, get_model
    from workbench.physics.spring_link.session import StaticSession
    from workbench.robot import LoadCase, TendonActuation
    from workbench.robot.presets import build_preset

    robot = build_preset("steel_rod")
    load = LoadCase(actuation=TendonActuation("tension", (5.0,) + (0.0,) * (robot.n_tendons - 1)))
    opts = SolverOptions(n_elements=16)
    res = get_model("spring_link")(robot, load, opts)
    assert res.solver.path_steps >= 1 and res.solver.path_event == ""
    session = StaticSession(robot, load, opts)
    assert session.result.solver.path_steps >= 1
    again = session.solve((10.0,) + (0.0,) * (robot.n_tendons - 1))
    assert again.solver.path_steps >= 1 and again.solver.path_event == ""
