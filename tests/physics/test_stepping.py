"""The one load ramp (workbench.physics._stepping): step sequences of each policy, limits, restore."""

import numpy as np
import pytest

from workbench.physics._stepping import RampExhausted, RampPolicy, RampStalled, ancf_load_ramp, load_ramp


class _Radius:
    """A fake solver that converges only when the factor grows by at most ``r`` from the last state."""

    def __init__(self, r):
        self.r, self.lam, self.trials = (r if callable(r) else (lambda lam: r)), 0.0, []

    def attempt(self, trial):
        self.trials.append(trial)
        if trial - self.lam > self.r(self.lam) + 1e-15:
            self.lam = float("nan")  # a failed solve leaves garbage behind
            return False
        self.lam = trial
        return True

    def save(self):
        return self.lam

    def restore(self, lam):
        self.lam = lam


def _run(r, policy, max_attempts=100):
    s = _Radius(r)
    info = load_ramp(s.attempt, s.save, s.restore, max_attempts=max_attempts, policy=policy)
    return s, info


def test_grow_every_success_capped_at_one():
    # 1 fails, 0.5 fails, 0.25 ok (inc 0.5), 0.75 fails, 0.5 ok (inc 0.5), 1 fails, 0.75 ok, 1 ok
    s, info = _run(0.3, RampPolicy())
    assert s.trials == [1.0, 0.5, 0.25, 0.75, 0.5, 1.0, 0.75, 1.0]
    assert (info.attempts, info.accepted, info.failed, info.smallest_increment) == (8, 4, 4, 0.25)
    assert s.lam == 1.0


def test_cap_to_remaining_changes_the_retry_after_a_failure():
    # the solver takes 0.6 from the start, then only 0.2: after 0.5 the increment grows to 1.0
    # (cap at one) and retries 1.0 twice, or to the remaining 0.5 (cap at remaining) and retries once.
    r = lambda lam: 0.6 if lam == 0.0 else 0.2  # noqa: E731
    s1, _ = _run(r, RampPolicy(cap="one"))
    s2, _ = _run(r, RampPolicy(cap="remaining", end_tolerance=1e-14))
    assert s1.trials[:6] == [1.0, 0.5, 1.0, 1.0, 0.75, 0.625]
    assert s2.trials[:5] == [1.0, 0.5, 1.0, 0.75, 0.625]
    assert s1.lam == s2.lam == 1.0


def test_grow_after_two_successes():
    s, info = _run(0.3, RampPolicy(grow_after=2, first_increment=0.2))
    assert s.trials == pytest.approx([0.2, 0.4, 0.8, 0.6, 0.8, 1.0])
    assert info.failed == 1


def test_stall_below_min_increment_reports_load_factor():
    with pytest.raises(RampStalled) as e:
        _run(1e-3, RampPolicy(min_increment=0.01))
    assert e.value.lam == 0.0 and e.value.increment < 0.01


def test_no_min_increment_stops_only_at_attempt_cap():
    with pytest.raises(RampExhausted) as e:
        _run(0.0, RampPolicy(min_increment=None), max_attempts=40)
    assert e.value.attempts == 40 and e.value.lam == 0.0


def test_attempt_cap_counts_failed_attempts():
    _, info = _run(0.3, RampPolicy(), max_attempts=8)
    assert info.attempts == 8
    with pytest.raises(RampExhausted):
        _run(0.3, RampPolicy(), max_attempts=7)


def test_failure_exceptions_restore_state_and_others_propagate():
    state = {"lam": 0.0}
    seen = []

    def attempt(lam):
        seen.append(state["lam"])  # the state each attempt starts from
        if lam - state["lam"] > 0.3:
            state["lam"] = -1.0  # garbage left by the failed solve
            raise ArithmeticError("did not converge")
        state["lam"] = lam

    info = load_ramp(attempt, lambda: state["lam"], lambda v: state.update(lam=v), max_attempts=20,
                failure=ArithmeticError)
    assert -1.0 not in seen and state["lam"] == 1.0 and info.failed == 4
    with pytest.raises(KeyError):  # not a declared failure: propagates
        load_ramp(lambda lam: {}["x"], lambda: None, lambda s: None, max_attempts=5, failure=ArithmeticError)


@pytest.mark.parametrize("bad", [dict(first_increment=0.0), dict(growth=0.5), dict(grow_after=0), dict(cap="x")])
def test_policy_rejects_bad_values(bad):
    with pytest.raises(ValueError):
        RampPolicy(**bad)


def test_ancf_load_ramp_halves_on_failure_and_respects_cap():
    state = {"lam": 0.0, "x": 0.0}
    history = []

    def apply(lam):
        state["lam"] = lam

    def solve():
        # "Newton" converges only for increments <= 0.3
        if state["lam"] - state["x"] > 0.3:
            raise ArithmeticError("diverged")
        state["x"] = state["lam"]
        history.append(state["lam"])

    info = ancf_load_ramp(apply, solve, lambda: state["x"], lambda x: state.update(x=x), max_steps=100,
                          failure=ArithmeticError)
    assert history[-1] == 1.0 and info.failed >= 2
    assert np.all(np.diff(history) <= 0.3 + 1e-12)
    with pytest.raises(RuntimeError, match="max_load_steps=3"):
        ancf_load_ramp(apply, solve, lambda: state["x"], lambda x: state.update(x=x), max_steps=3,
                       failure=ArithmeticError) if state.update(x=0.0) is None else None
