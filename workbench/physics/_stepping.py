"""Adaptive load stepping: the one load ramp every static Exudyn model uses.

Exudyn ramps only load objects by itself; connector forces, reference curvatures, kinematic-tree
gravity and user-function loads are applied at once (``../shared/notes/exudyn-facts.md``).  So
the models ramp a load factor ``lam`` from 0 to 1 themselves: each attempt applies ``lam`` and
solves from the last converged state; a failed attempt restores that state and halves the
increment; successes grow it again.  :class:`RampPolicy` holds the rules in which the models
differ (when the increment grows, what caps it, when to give up), so each model keeps exactly
its step sequence.  :func:`load_ramp` is the ramp; :func:`ancf_load_ramp` is :func:`load_ramp`
with the ANCF models' policy for an ``apply`` / ``solve`` pair (used by the planar ANCF model
and the contact system).  Pure Python and numpy (no Exudyn import).

Load paths, not jumps: an attempt may return a small state measure (:class:`PathPoint`, e.g. the
tip position over L and the tip tangent) instead of a bool.  The ramp then follows the path: a
step whose measure moves more than ``policy.max_motion`` or lands far from the secant prediction
of the accepted history is rejected like a failed solve (the increment halves).  A jump that
persists down to ``policy.jump_min_increment`` is a limit point / snap of the load path: the step
is accepted and the event recorded (:attr:`LoadRampInfo.path_event` = ``"jump"`` and the load
factor where it happened); a change of ``PathPoint.stiffness_sign`` between accepted steps (the
tangent stiffness losing definiteness on a continuous path) is rejected the same way and, when it
persists, recorded as ``"bifurcation"``.  Attempts returning a bool keep the plain step sequence.

Checked by ``tests/physics/test_stepping.py`` (step sequences of each policy, limits, state
restore), ``tests/physics/test_load_path.py`` (the path check: a fold, a smooth path, a sign
change, the branch-jump case of issue 28) and, through the models, by their validation tests.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np

__all__ = [
    "ContinuationInfo", "LoadRampInfo", "PathPoint", "RampExhausted", "RampPolicy", "RampStalled",
    "ancf_load_ramp", "continuation", "load_ramp", "path_fields",
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
    max_motion : float
        Path check (attempts returning a :class:`PathPoint`): a step whose measure moves more
        than this (Euclidean norm) is rejected.  Default ``inf`` (no cap): the first step from
        the start has no secant to be checked against, and a cap cannot tell a large legitimate
        bend from a curl (both move a tip measure by ~2), so it costs extra steps in every
        large-bend case; the models that need it set it (``spring_link``: 2.0).
    jump_ratio, jump_floor : float
        Path check: a step whose measure lands farther than ``max(jump_ratio * |predicted move|,
        jump_floor)`` from the secant prediction of the last two accepted points is rejected
        (the secant error of a smooth path is of second order in the step, a jump's is the whole
        move), unless halving the step halved its move too (a smooth path that the secant of
        a long earlier step mispredicts: its motion per load factor at most 1.5 x the rejected
        step's, where a jump's doubles).  A change of the stiffness sign is rejected as well.
    jump_min_increment : float
        A path-check rejection that would halve the increment below this is accepted instead
        and recorded as an event (``"jump"``, or ``"bifurcation"`` when only the stiffness sign
        changed).
    """

    first_increment: float = 1.0
    growth: float = 2.0
    grow_after: int = 1
    cap: Literal["one", "remaining"] = "one"
    min_increment: float | None = 1e-6
    end_tolerance: float = 0.0
    max_motion: float = math.inf
    jump_ratio: float = 1.5
    jump_floor: float = 0.02
    jump_min_increment: float = 1.0 / 128

    def __post_init__(self) -> None:
        if not 0.0 < self.first_increment:
            raise ValueError(f"first_increment must be > 0, got {self.first_increment}")
        if self.growth < 1.0 or self.grow_after < 1:
            raise ValueError(f"growth must be >= 1 and grow_after >= 1, got {self.growth}, {self.grow_after}")
        if self.cap not in ("one", "remaining"):
            raise ValueError(f"cap must be 'one' or 'remaining', got {self.cap!r}")
        if not (self.max_motion > 0 and self.jump_ratio > 0 and self.jump_floor >= 0 and self.jump_min_increment > 0):
            raise ValueError("max_motion, jump_ratio and jump_min_increment must be > 0 and jump_floor >= 0")


@dataclass(frozen=True)
class PathPoint:
    """What an attempt of :func:`load_ramp` may return instead of a bool: the state it reached.

    Attributes
    ----------
    measure : tuple of float
        A small dimensionless measure of the state (e.g. tip position / L and tip tangent);
        the same components at every step of one ramp.
    stiffness_sign : int
        Sign of the determinant of the tangent (or shooting) Jacobian at the state; 0: unknown.
    """

    measure: tuple[float, ...]
    stiffness_sign: int = 0


@dataclass(frozen=True)
class LoadRampInfo:
    """Outcome of :func:`load_ramp`: attempts made, attempts accepted, failures, smallest increment tried.

    ``path_event`` is ``""`` (none), ``"jump"`` (a jump of the state measure that persisted down
    to the policy's ``jump_min_increment``: a limit point or snap of the load path) or
    ``"bifurcation"`` (the stiffness sign changed between accepted steps); ``path_event_fraction``
    is the load factor where the first event happened (NaN without one).  ``rejected_jumps``
    counts path-check rejections (included in ``failed``).
    """

    attempts: int
    accepted: int
    failed: int
    smallest_increment: float
    path_event: str = ""
    path_event_fraction: float = math.nan
    rejected_jumps: int = 0


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
    attempt: Callable[[float], bool | None | PathPoint],
    save: Callable[[], object],
    restore: Callable[[object], None],
    *,
    max_attempts: int,
    policy: RampPolicy = RampPolicy(),
    failure: type[BaseException] | tuple[type[BaseException], ...] = (),
    start: PathPoint | None = None,
) -> LoadRampInfo:
    """Ramp a load factor from 0 to 1 with adaptive increments, following the load path.

    Parameters
    ----------
    attempt : callable
        ``lam -> bool | None | PathPoint``: apply load factor ``lam`` and solve from the current
        state.  Returning ``False`` or raising one of ``failure`` marks the attempt failed; a
        :class:`PathPoint` is checked against the path (see the module docstring); any other
        return value accepts it; other exceptions propagate (the state is not restored).
    save, restore : callable
        ``save()`` is called before every attempt; ``restore(saved)`` after a rejected one.
    max_attempts : int
        Cap on attempts (accepted plus failed).
    policy : RampPolicy
        Growth, cap and stopping rules, path-check thresholds.
    failure : exception type(s)
        What a failed solve raises.
    start : PathPoint, optional
        The measure of the state at ``lam = 0`` (without it the first step is not checked).

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
    attempts = accepted = failed = in_row = jumps = 0
    smallest = inc
    path = _Path(p, start)
    while lam < 1.0 - p.end_tolerance:
        if attempts >= max_attempts:
            raise RampExhausted(lam, max_attempts)
        trial = min(1.0, lam + inc)
        state = save()
        attempts += 1
        cause: BaseException | None = None
        try:
            out = attempt(trial)
            ok = out is not False
        except failure as err:  # type: ignore[misc] - an empty tuple catches nothing
            ok, cause = False, err
        leaves = path.leaves(lam, trial, out) if ok and isinstance(out, PathPoint) else ""
        jump = bool(leaves)
        if jump and 0.5 * inc < p.jump_min_increment:
            path.record(leaves, lam)  # unresolved down to the smallest step: a limit point, snap or bifurcation
            if leaves == "jump":
                path.history.clear()  # the new branch starts a new history
            jump = False
        if not ok or jump:
            failed += 1
            jumps += int(jump)
            restore(state)
            inc *= 0.5
            smallest = min(smallest, inc)
            in_row = 0
            if not jump and p.min_increment is not None and inc < p.min_increment:
                raise RampStalled(lam, inc, cause) from cause
            continue
        path.accept(trial, out)
        lam = trial
        accepted += 1
        in_row += 1
        if in_row >= p.grow_after:
            in_row = 0
            if p.cap == "one":
                inc = min(1.0, p.growth * inc)
            elif lam < 1.0:
                inc = min(1.0 - lam, p.growth * inc)
    return LoadRampInfo(attempts=attempts, accepted=accepted, failed=failed, smallest_increment=smallest,
                        path_event=path.event, path_event_fraction=path.fraction, rejected_jumps=jumps)


def path_fields(*infos: LoadRampInfo | None) -> dict[str, object]:
    """``path_steps``, ``path_event``, ``path_event_fraction`` of :class:`~workbench.models.result.SolverInfo`
    from the ramps of one solve (``None`` entries skipped): accepted steps summed, the first event."""
    done = [i for i in infos if i is not None]
    events = [i for i in done if i.path_event]
    return {"path_steps": sum(i.accepted for i in done),
            "path_event": events[0].path_event if events else "",
            "path_event_fraction": events[0].path_event_fraction if events else math.nan}


class _Path:
    """The accepted history of :func:`load_ramp`'s path measures and the first recorded event."""

    def __init__(self, policy: RampPolicy, start: PathPoint | None) -> None:
        self.policy = policy
        self.history: list[tuple[float, np.ndarray]] = []
        self.sign = 0
        self.rejected: tuple[float, float] | None = None  # (from lam, motion rate) of the last secant rejection
        self.event, self.fraction = "", math.nan
        if start is not None:
            self.accept(0.0, start)

    def leaves(self, lam: float, trial: float, point: PathPoint) -> str:
        """How the step ``lam -> trial`` landing on ``point`` leaves the path: ``"jump"``,
        ``"bifurcation"`` (continuous, but the stiffness sign changed) or ``""`` (it follows it)."""
        sign_changed = bool(point.stiffness_sign and self.sign and point.stiffness_sign != self.sign)
        if not self.history:
            return "bifurcation" if sign_changed else ""
        m = np.asarray(point.measure, dtype=float)
        la, ma = self.history[-1]
        motion = float(np.linalg.norm(m - ma))
        if not math.isfinite(motion) or motion > self.policy.max_motion:
            return "jump"
        if len(self.history) >= 2:
            lb, mb = self.history[-2]
            move = (trial - la) / (la - lb) * (ma - mb)
            error = float(np.linalg.norm(m - ma - move))
            if error > max(self.policy.jump_ratio * float(np.linalg.norm(move)), self.policy.jump_floor):
                # far from the secant: a jump moves as far for any step, a smooth path that the
                # stale secant mispredicts moves about half as far for half the step
                rate = motion / (trial - la)
                smooth = self.rejected is not None and self.rejected[0] == la and rate <= 1.5 * self.rejected[1]
                self.rejected = (la, rate)
                if not smooth:
                    return "jump"
        return "bifurcation" if sign_changed else ""

    def accept(self, lam: float, out: object) -> None:
        """Append an accepted point (a bool / None attempt result keeps no history)."""
        if not isinstance(out, PathPoint):
            return
        self.history.append((lam, np.asarray(out.measure, dtype=float)))
        del self.history[:-2]
        self.sign = out.stiffness_sign or self.sign

    def record(self, kind: str, lam: float) -> None:
        """Keep the first event of the ramp."""
        if not self.event:
            self.event, self.fraction = kind, float(lam)


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
    start: PathPoint | None = None,
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
        Solve from the saved state; raise ``failure`` on non-convergence; may return the
        :class:`PathPoint` of the state reached (the path check of :func:`load_ramp`).
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
    start : PathPoint, optional
        The measure of the start state (see :func:`load_ramp`).

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

    def attempt(lam: float) -> bool | PathPoint:
        apply(lam)
        try:
            out = solve()
        except failure as err:
            last[:] = [err]
            return False
        return out if isinstance(out, PathPoint) else True

    policy = RampPolicy(first_increment=first_increment, growth=2.0, grow_after=2, cap="one",
                        min_increment=min_increment)
    try:
        return load_ramp(attempt, save, restore, max_attempts=max_steps, policy=policy, start=start)
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
