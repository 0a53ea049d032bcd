"""physics._stepping.continuation: the one path-parameter walk of the series-parallel solvers.

The step sequences of each caller's settings are pinned here, and the helper is compared with
the loop it replaced (written out below as the four call sites had it) on random accept/reject
scripts: same trial targets, bit for bit.
"""

from __future__ import annotations

import random

import pytest

from workbench.physics._stepping import ContinuationInfo, continuation

#: (first, max_step, min_step, growth) of the four call sites in workbench.physics.series_parallel
LEG_POSE = (0.125, 0.25, 1.0 / 512, 2.0)  # leg.leg_static fallback (straight leg -> tip pose)
LEG_HOMOTOPY = (0.25, 0.5, 1.0 / 64, 2.0)  # leg._leg_homotopy (neighbouring state -> new length/pose)
STACK = (0.25, 0.5, 1.0 / 256, 2.0)  # stack._stack_continuation (home lengths -> lengths)


def module_path(n_steps):  # branch.walk_from_home (home pose -> target pose)
    return (1.0 / n_steps, 2.0 / n_steps, 1.0 / (16 * n_steps), 1.5)


def _run(settings, accept):
    first, max_step, min_step, growth = settings
    trials = []

    def step(lam, target):
        trials.append((lam, target))
        return accept(len(trials) - 1, lam, target)

    info = continuation(step, first=first, max_step=max_step, min_step=min_step, growth=growth)
    return trials, info


def _old_loop(settings, accept):
    """The loop as the call sites wrote it before the helper (lam, step; grow, cap; halve, stall)."""
    first, max_step, min_step, growth = settings
    trials = []
    lam, step = 0.0, first
    while lam < 1.0:
        lt = min(1.0, lam + step)
        trials.append((lam, lt))
        if accept(len(trials) - 1, lam, lt):
            lam = lt
            step = min(growth * step, max_step)
        else:
            step *= 0.5
            if step < min_step:
                break
    return trials, lam


def test_all_accepted_sequences():
    assert [t for _, t in _run(LEG_POSE, lambda *a: True)[0]] == [0.125, 0.375, 0.625, 0.875, 1.0]
    assert [t for _, t in _run(LEG_HOMOTOPY, lambda *a: True)[0]] == [0.25, 0.75, 1.0]
    assert [t for _, t in _run(STACK, lambda *a: True)[0]] == [0.25, 0.75, 1.0]
    trials, info = _run(module_path(4), lambda *a: True)
    assert [t for _, t in trials] == [0.25, 0.625, 1.0]
    assert info == ContinuationInfo(reached=1.0, completed=True, accepted=3, failed=0, step=0.5)


def test_a_rejected_step_is_retried_at_half_the_size_then_grows_again():
    trials, info = _run(LEG_HOMOTOPY, lambda i, lam, t: i != 1)
    assert trials == [(0.0, 0.25), (0.25, 0.75), (0.25, 0.5), (0.5, 1.0)]
    assert info.completed and info.accepted == 3 and info.failed == 1


def test_stall_reports_the_last_accepted_parameter():
    trials, info = _run(STACK, lambda i, lam, t: lam < 0.25)
    # accepted 0.25; then 0.75, 0.5, 0.375, ..., 0.25 + 1/256, until the step 1/512 < 1/256
    assert trials[0] == (0.0, 0.25) and all(lam == 0.25 for lam, _ in trials[1:])
    assert [t - 0.25 for _, t in trials[1:]] == [0.5 / 2**k for k in range(8)]
    assert not info.completed and info.reached == 0.25 and info.step == 1.0 / 512 and info.failed == 8


def test_immediate_stall_never_accepts():
    trials, info = _run(LEG_POSE, lambda *a: False)
    assert [t for _, t in trials] == [0.125 / 2**k for k in range(7)]  # 0.125 ... 1/512, then 1/1024 < 1/512
    assert info == ContinuationInfo(reached=0.0, completed=False, accepted=0, failed=7, step=1.0 / 1024)


def test_exceptions_of_the_step_propagate():
    def step(lam, target):
        raise KeyError("abort")

    with pytest.raises(KeyError, match="abort"):
        continuation(step, first=0.5, max_step=0.5, min_step=0.1)


@pytest.mark.parametrize("settings", [LEG_POSE, LEG_HOMOTOPY, STACK, module_path(3), module_path(7), module_path(40)])
def test_same_trials_as_the_loops_it_replaced(settings):
    rng = random.Random(12)
    for _ in range(200):
        p = rng.random()
        script = [rng.random() < p for _ in range(400)]
        new, info = _run(settings, lambda i, lam, t: script[i])
        old, lam = _old_loop(settings, lambda i, lam, t: script[i])
        assert new == old
        assert info.reached == lam and info.completed == (lam >= 1.0)
