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
    ``x > 2``.  The measure is ``x / 2`` (dimensionless, order 1)."""

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
        return PathPoint((self.x / 2.0,), self.sign(lam) if self.sign else 0)

    def save(self) -> float:
        return self.x

    def restore(self, x: float) -> None:
        self.x = x


def _ramp(s: _Cubic, policy: RampPolicy = RampPolicy(), max_attempts: int = 200):
    return load_ramp(s.attempt, s.save, s.restore, max_attempts=max_attempts, policy=policy,
                     start=PathPoint((s.x / 2.0,), s.sign(0.0) if s.sign else 0))


def test_snap_through_is_refined_and_recorded_with_its_load_fraction():
    s = _Cubic()
    info = _ramp(s)
    assert info.path_event == "jump"
    # the fold lies in the unresolved step: [fraction, fraction + jump_min_increment]
    assert info.path_event_fraction <= FOLD <= info.path_event_fraction + RampPolicy().jump_min_increment
    assert s.x == pytest.approx(s.root(10.0, 1.0))  # on the far branch at the full load
    assert info.rejected_jumps > 0 and info.accepted == info.attempts - info.failed


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
    # x from -2.10 to -3.3 (measure moves 0.6 > max_motion 0.5): halved once, no event
    s = _Cubic(g=lambda lam: -2.5 - 23.0 * lam)
    info = _ramp(s, RampPolicy(max_motion=0.5))
    assert s.trials[:2] == [1.0, 0.5] and info.path_event == "" and info.rejected_jumps == 1
    assert s.x == pytest.approx(s.root(-10.0, 1.0))


def test_stiffness_sign_change_on_a_continuous_path_is_a_bifurcation():
    s = _Cubic(g=lambda lam: -2.5 + 0.5 * lam, sign=lambda lam: 1 if lam < 0.3 else -1)
    info = _ramp(s)
    assert info.path_event == "bifurcation"
    assert info.path_event_fraction <= 0.3 <= info.path_event_fraction + RampPolicy().jump_min_increment
    assert s.x == pytest.approx(s.root(-10.0, 1.0))
