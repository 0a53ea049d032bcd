"""Adaptive load stepping: the one load ramp every static Exudyn model uses.

Exudyn ramps only load objects by itself; connector forces, reference curvatures, kinematic-tree
gravity and user-function loads are applied at once (``../shared/notes/exudyn-facts.md``).  So
the models ramp a load factor ``lam`` from 0 to 1 themselves: each attempt applies ``lam`` and
solves from the last converged state; a failed attempt restores that state and halves the
increment; successes grow it again.  :class:`RampPolicy` holds the rules in which the models
differ (when the increment grows, what caps it, when to give up), so each model keeps exactly
its step sequence.  :func:`load_ramp` is the ramp; :func:`ancf_load_ramp` is :func:`load_ramp`
with the ANCF models' policy for an ``apply`` / ``solve`` pair (used by the planar ANCF model
and the contact system).  Pure Python (no Exudyn import).

Checked by ``tests/physics/test_stepping.py`` (step sequences of each policy, limits, state
restore) and, through the models, by their validation tests.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Literal

__all__ = [
    "ContinuationInfo", "LoadRampInfo", "RampExhausted", "RampPolicy", "RampStalled",
    "ancf_load_ramp", "continuation", "load_ramp",
]


@dataclass(frozen=True)
class RampPolicy:
    """How the load-factor increment evolves.

    Attributes
    ----------
    first_increment : float
        First trial increment (0 < . <= 1).
    growth : float
        Factor applied to the increment after ``grow_after`` successes in a row.
    grow_after : int
        Consecutive successes before the increment grows (a failure resets the count).
    cap : {"one", "remaining"}
        After growing, the increment is capped at 1 (``"one"``) or at the load still to go,
        ``1 - lam`` (``"remaining"``).  Trial factors are always capped at 1.
    min_increment : float or None
        Give up (:class:`RampStalled`) when a failure halves the increment below this;
        ``None``: only the attempt cap stops the ramp.
    end_tolerance : float
        The ramp is done once ``lam >= 1 - end_tolerance``.
    """

    first_increment: float = 1.0
    growth: float = 2.0
    grow_after: int = 1
    cap: Literal["one", "remaining"] = "one"
    min_increment: float | None = 1e-6
    end_tolerance: float = 0.0

    def __post_init__(self) -> None:
        if not 0.0 < self.first_increment:
            raise ValueError(f"first_increment must be > 0, got {self.first_increment}")
        if self.growth < 1.0 or self.grow_after < 1:
            raise ValueError(f"growth must be >= 1 and grow_after >= 1, got {self.growth}, {self.grow_after}")
        if self.cap not in ("one", "remaining"):
            raise ValueError(f"cap must be 'one' or 'remaining', got {self.cap!r}")


@dataclass(frozen=True)
class LoadRampInfo:
    """Outcome of :func:`load_ramp`: attempts made, attempts accepted, failures, smallest increment tried."""

    attempts: int
    accepted: int
    failed: int
    smallest_increment: float


class RampExhausted(RuntimeError):
    """The ramp needed more than ``max_attempts`` attempts; ``lam`` is the factor reached."""

    def __init__(self, lam: float, attempts: int):
        super().__init__(f"load ramp exceeded {attempts} attempts at load factor {lam:.6g}")
        self.lam = lam
        self.attempts = attempts


class RampStalled(RuntimeError):
    """The increment fell below ``min_increment`` at load factor ``lam``; ``cause`` is the last failure."""

    def __init__(self, lam: float, increment: float, cause: BaseException | None):
        super().__init__(f"load ramp stalled at load factor {lam:.6g} (increment {increment:.3g})")
        self.lam = lam
        self.increment = increment
        self.cause = cause


def load_ramp(
    attempt: Callable[[float], bool | None],
    save: Callable[[], object],
    restore: Callable[[object], None],
    *,
    max_attempts: int,
    policy: RampPolicy = RampPolicy(),
    failure: type[BaseException] | tuple[type[BaseException], ...] = (),
) -> LoadRampInfo:
    """Ramp a load factor from 0 to 1 with adaptive increments.

    Parameters
    ----------
    attempt : callable
        ``lam -> bool | None``: apply load factor ``lam`` and solve from the current state.
        Returning ``False`` or raising one of ``failure`` marks the attempt failed; any other
        return value accepts it; other exceptions propagate (the state is not restored).
    save, restore : callable
        ``save()`` is called before every attempt; ``restore(saved)`` after a failed one.
    max_attempts : int
        Cap on attempts (accepted plus failed).
    policy : RampPolicy
        Growth, cap and stopping rules.
    failure : exception type(s)
        What a failed solve raises.

    Returns
    -------
    LoadRampInfo

    Raises
    ------
    RampExhausted
        Attempt number ``max_attempts + 1`` would be needed.
    RampStalled
        A failure halved the increment below ``policy.min_increment``.
    """
    p = policy
    lam, inc = 0.0, min(1.0, float(p.first_increment))
    attempts = accepted = failed = in_row = 0
    smallest = inc
    while lam < 1.0 - p.end_tolerance:
        if attempts >= max_attempts:
            raise RampExhausted(lam, max_attempts)
        trial = min(1.0, lam + inc)
        state = save()
        attempts += 1
        cause: BaseException | None = None
        try:
            ok = attempt(trial) is not False
        except failure as err:  # type: ignore[misc] - an empty tuple catches nothing
            ok, cause = False, err
        if not ok:
            failed += 1
            restore(state)
            inc *= 0.5
            smallest = min(smallest, inc)
            in_row = 0
            if p.min_increment is not None and inc < p.min_increment:
                raise RampStalled(lam, inc, cause) from cause
            continue
        lam = trial
        accepted += 1
        in_row += 1
        if in_row >= p.grow_after:
            in_row = 0
            if p.cap == "one":
                inc = min(1.0, p.growth * inc)
            elif lam < 1.0:
                inc = min(1.0 - lam, p.growth * inc)
    return LoadRampInfo(attempts=attempts, accepted=accepted, failed=failed, smallest_increment=smallest)


def ancf_load_ramp(
    apply: Callable[[float], None],
    solve: Callable[[], None],
    save: Callable[[], object],
    restore: Callable[[object], None],
    *,
    max_steps: int,
    first_increment: float = 1.0,
    min_increment: float = 1e-6,
    failure: type[BaseException] | tuple[type[BaseException], ...] = Exception,
) -> LoadRampInfo:
    """:func:`load_ramp` with the ANCF models' policy, for an ``apply`` / ``solve`` pair.

    Used by the planar ANCF model (:mod:`workbench.physics.ancf`) and the contact system
    (:meth:`workbench.physics.contact.system.ContactSystem.load_ramp`).  Each attempt sets the
    factor (``apply(lam)``, outside the failure handling: its exceptions propagate) and solves
    from the last converged state; a failed solve (``failure`` raised) restores the state and
    halves the increment; after two successes the increment doubles again (capped at 1):
    ``RampPolicy(grow_after=2, cap="one")``.  The stopping exceptions of :func:`load_ramp` become
    one ``RuntimeError`` naming the cause and the load factor reached.  Checked by
    ``tests/physics/test_stepping.py`` and, through the ANCF model, ``tests/physics/test_ramp_sequences.py``.

    Parameters
    ----------
    apply : callable
        ``lam -> None``: set every ramped load to ``lam`` times its final value.
    solve : callable
        Solve from the saved state; raise ``failure`` on non-convergence.
    save, restore : callable
        Save / restore the solver state around a trial step.
    max_steps : int
        Cap on solve attempts (successful plus failed).
    first_increment : float
        First trial increment of the factor (0 < . <= 1).
    min_increment : float
        Give up below this increment.
    failure : exception type(s)
        What a failed solve raises.

    Returns
    -------
    LoadRampInfo

    Raises
    ------
    RuntimeError
        The cap on steps or the minimum increment was reached (the message says which and
        at what load factor).
    """
    last: list[BaseException] = []

    def attempt(lam: float) -> bool:
        apply(lam)
        try:
            solve()
        except failure as err:
            last[:] = [err]
            return False
        return True

    policy = RampPolicy(first_increment=first_increment, growth=2.0, grow_after=2, cap="one",
                        min_increment=min_increment)
    try:
        return load_ramp(attempt, save, restore, max_attempts=max_steps, policy=policy)
    except RampExhausted as stop:
        raise RuntimeError(f"load stepping hit max_load_steps={max_steps} at load factor {stop.lam:.6g}") from None
    except RampStalled as stop:
        err = last[0]
        raise RuntimeError(
            f"load stepping failed at load factor {stop.lam:.6g} (increment < {min_increment}): {err}"
        ) from err


# --------------------------------------------------------------------------- parameter continuation
#
# The series-parallel solvers walk a path parameter from 0 to 1 (a leg from the straight shape to
# its tip pose, a leg between two lengths, a stack from its home lengths, a module along the pose
# path from home).  Unlike the load ramp there is nothing to save or restore: each step starts
# from the caller's last accepted state, which the step function replaces only when it accepts.
# Checked by ``tests/physics/test_continuation.py`` (the step sequences of each caller's settings).


@dataclass(frozen=True)
class ContinuationInfo:
    """Outcome of :func:`continuation`.

    Attributes
    ----------
    reached : float
        Last accepted path parameter (1.0 when ``completed``).
    completed : bool
        The walk reached 1; False: it stalled (the step fell below ``min_step``).
    accepted, failed : int
        Steps accepted and rejected.
    step : float
        Step size at the end (the one that fell below ``min_step`` when stalled).
    """

    reached: float
    completed: bool
    accepted: int
    failed: int
    step: float


def continuation(
    step: Callable[[float, float], bool],
    *,
    first: float,
    max_step: float,
    min_step: float,
    growth: float = 2.0,
) -> ContinuationInfo:
    """Walk a path parameter ``lam`` from 0 to 1 with adaptive steps.

    Each trial goes from the accepted ``lam`` to ``target = min(1, lam + h)``.  Accepted:
    ``lam = target`` and ``h = min(growth h, max_step)``; rejected: ``h = h / 2``, and the walk
    stalls once ``h < min_step``.

    Parameters
    ----------
    step : callable
        ``step(lam, target) -> bool``: try to move the caller's state from ``lam`` to ``target``;
        True accepts (the caller has stored the new state), False rejects (the caller keeps the
        state at ``lam``).  Exceptions propagate (a caller's abort).
    first : float
        First step size ``h``.
    max_step : float
        Cap on ``h`` after growing.
    min_step : float
        Stall threshold.
    growth : float
        Factor on ``h`` after an accepted step.

    Returns
    -------
    ContinuationInfo
    """
    lam, h = 0.0, first
    accepted = failed = 0
    while lam < 1.0:
        target = min(1.0, lam + h)
        if step(lam, target):
            lam = target
            accepted += 1
            h = min(growth * h, max_step)
        else:
            failed += 1
            h *= 0.5
            if h < min_step:
                return ContinuationInfo(lam, False, accepted, failed, h)
    return ContinuationInfo(lam, True, accepted, failed, h)
