"""Calibrate one model on the training rows of one fold: nonlinear least squares and confidence intervals.

The unknowns (``[calibration.parameters]``, command zero, registration; :class:`FitParameter`) are
found by scipy's ``least_squares`` (trust-region reflective, ``method="trf"``) within their bounds,
each variable scaled by its bound span: the fit runs in ``u = (x - lower) / (upper - lower)`` in
``[0, 1]`` (scipy's ``x_scale`` would scale the steps but not its ``xtol`` test, which compares a step
with ``norm(x)``: with E ~ 6e10 Pa among the unknowns it stopped fits early), at most
``max_evaluations`` residual evaluations (scipy's ``max_nfev``, which does not count the Jacobian's).

Residuals: the tip position differences ``predicted - measured`` [m], three per training sample,
in the measurement frame.  Measured orientations and backbone points do not enter the fit yet
(they are stored and drawn; weighting them against positions is left for later).

Jacobian: forward differences (scipy ``"2-point"``) with the step ``diff_step`` in ``u``, i.e. that
fraction of each bound span (:func:`diff_step`): CC is closed-form arithmetic, so the default
``sqrt(eps) ~ 1.5e-8``; a physics model solves to a relative Newton tolerance ``tau``, so its tips
carry errors up to ~``tau`` and the step is ``sqrt(tau)`` (the step that balances truncation
against that noise).  For CC one
evaluation covers every training row in one vectorised call, so a Jacobian costs at most ``p``
batched calls.

Confidence intervals (linearised at the optimum, stated as such): ``cov = s^2 (J^T J)^-1`` with
``s^2 = SSR / (m - p)`` (``m`` residuals, ``p`` parameters), half-width
``t_{(1+c)/2, m-p} sqrt(cov_ii)``.  They assume independent, equal-variance residuals and a model
that is linear in the parameters over the interval; they are not clipped to the bounds.  A
parameter in a direction the data cannot see (singular values of the column-normalised ``J``
below ``10 (h + noise / h)``: a forward difference with step ``h`` on values of relative accuracy
``noise`` -- machine epsilon for CC, ``tau`` for a physics model (:func:`evaluation_noise`) -- errs by
about ``h + noise / h``, relative, so smaller singular values cannot be told from zero; measured on
the worked example's Cosserat fit, weakly identifiable directions sit at 2e-3 to 4e-3, above the
6e-4 this gives, and CC's exactly unidentifiable ones at 2e-7, below its 3e-7) gets an infinite
interval and the message names it.
A value within ``1e-6`` of its bound span from a bound is flagged ``at_bound`` (its interval then
means little).  A Jacobian's registration columns cost no model evaluation (the predictor moves
its last prediction, :class:`~workbench.measure.predict.Predictor`).

Checked by ``tests/measure/test_measure_calibrate.py`` (recovery within the intervals, coverage over
seeds, at-bound flag, unidentifiable parameters, held-out rows never in the fit) and
``tests/measure/test_measure_calibrate_physics.py`` (a Cosserat rod recovers its own values).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

from .predict import PredictionFailure, Predictor
from .types import FitParameter

__all__ = ["AT_BOUND", "CalibrationResult", "calibrate_on", "diff_step", "evaluation_noise", "fit_parameters",
           "linearised_intervals"]

#: a value this fraction of its bound span from a bound is flagged at the bound
AT_BOUND = 1e-6


@dataclass(frozen=True, eq=False)
class CalibrationResult:
    """The outcome of one calibration (:func:`fit_parameters`).

    Attributes
    ----------
    success : bool
        ``least_squares`` met a convergence test (and no model evaluation failed).
    message : str
        scipy's message, the failure reason, and the unidentifiable parameters if any.
    evaluations : int
        Residual evaluations, the finite-difference Jacobian's included.
    seconds : float
        Wall time of the fit [s].
    values, ci_low, ci_high : ndarray, shape (p,)
        Calibrated values and the linearised confidence interval (SI; NaN when failed).
    at_bound : ndarray of bool, shape (p,)
    unidentifiable : tuple of str
        Parameters the data cannot determine (infinite intervals).
    confidence : float
    residuals : ndarray, shape (m,)
        The residual vector at the optimum (``predicted - measured`` [m], three per training
        sample, for :func:`calibrate_on`; empty when failed).
    sigma : float
        ``s``, the residual standard deviation per coordinate [m].
    covariance : ndarray, shape (p, p)
        The linearised covariance ``s^2 (J^T J)^-1`` of the values (SI; NaN in the rows and columns
        of unidentifiable parameters and when failed): the joint confidence region
        ``d^T C^-1 d <= p' F(p', m - p; confidence)`` over the ``p'`` identifiable parameters
        (Bates & Watts 1988, Sec. 2.3) -- the marginal intervals hold one parameter at a time.
    """

    success: bool
    message: str
    evaluations: int
    seconds: float
    values: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    at_bound: np.ndarray
    unidentifiable: tuple[str, ...]
    confidence: float
    residuals: np.ndarray
    sigma: float
    covariance: np.ndarray | None = None


def evaluation_noise(model: str, newton_tolerance: float) -> float:
    """Relative accuracy of one model evaluation: machine epsilon for CC, the Newton tolerance otherwise."""
    return float(np.finfo(float).eps) if model == "cc" else float(newton_tolerance)


def diff_step(model: str, newton_tolerance: float) -> float | None:
    """Relative finite-difference step (module docstring): ``None`` (scipy's default) for CC,
    ``sqrt(newton_tolerance)`` for a physics model."""
    return None if model == "cc" else max(math.sqrt(float(newton_tolerance)), math.sqrt(np.finfo(float).eps))


def linearised_intervals(J: np.ndarray, residuals: np.ndarray, x: np.ndarray, confidence: float,
                         null_tolerance: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, np.ndarray]:
    """Linearised confidence intervals at ``x`` from the Jacobian ``J`` (m, p) (module docstring).

    Returns
    -------
    low, high : ndarray, shape (p,)
        Interval ends (``-inf`` / ``inf`` where not identifiable or ``m <= p``).
    unidentifiable : ndarray of bool, shape (p,)
    s : float
        Residual standard deviation (NaN when ``m <= p``).
    cov : ndarray, shape (p, p)
        ``s^2 (J^T J)^-1`` on the identifiable subspace, NaN rows / columns for the others.
    """
    from scipy.special import stdtrit

    m, p = J.shape
    if m <= p:
        inf = np.full(p, np.inf)
        return x - inf, x + inf, np.zeros(p, dtype=bool), float("nan"), np.full((p, p), np.nan)
    s2 = float(residuals @ residuals) / (m - p)
    norms = np.linalg.norm(J, axis=0)
    dead = ~(norms > 0)
    Jn = J / np.where(dead, 1.0, norms)
    _, S, Vt = np.linalg.svd(Jn, full_matrices=False)
    null = S < null_tolerance * S[0] if S[0] > 0 else np.ones_like(S, dtype=bool)
    bad = dead | (np.abs(Vt[null]) > 1e-2).any(axis=0)
    keep = ~null
    cov_n = (Vt[keep].T / S[keep] ** 2) @ Vt[keep]  # pseudo-inverse of Jn^T Jn on the identifiable subspace
    sd = np.sqrt(s2 * np.clip(np.diag(cov_n), 0.0, None)) / np.where(dead, 1.0, norms)
    half = np.where(bad, np.inf, float(stdtrit(m - p, 0.5 + confidence / 2.0)) * sd)
    scale = 1.0 / np.where(dead, 1.0, norms)
    cov = s2 * cov_n * np.outer(scale, scale)
    cov[bad, :] = np.nan
    cov[:, bad] = np.nan
    return x - half, x + half, bad, math.sqrt(s2), cov


def _failed(parameters: Sequence[FitParameter], message: str, evaluations: int, seconds: float,
            confidence: float) -> CalibrationResult:
    nan = np.full(len(parameters), np.nan)
    return CalibrationResult(False, message, evaluations, seconds, nan, nan, nan.copy(),
                             np.zeros(len(parameters), dtype=bool), (), confidence, np.zeros(0),
                             float("nan"))


def fit_parameters(residual: Callable[[np.ndarray], np.ndarray], parameters: Sequence[FitParameter],
                   confidence: float, max_evaluations: int, step: float | None,
                   noise: float = float(np.finfo(float).eps)) -> CalibrationResult:
    """Least-squares fit of ``residual(x) -> (m,)`` over ``parameters`` (module docstring; never raises
    for a model: a :class:`PredictionFailure` ends the fit as failed with its reason).

    Parameters
    ----------
    residual : callable
        ``x -> residual vector`` [m].
    parameters : sequence of FitParameter
        The unknowns in vector order (initial values and bounds).
    confidence : float
    max_evaluations : int
        scipy ``max_nfev``.
    step : float or None
        Finite-difference step as a fraction of each bound span (:func:`diff_step`).
    noise : float
        Relative accuracy of a residual evaluation (:func:`evaluation_noise`): sets the singular
        values below which a direction counts as unidentifiable (module docstring).
    """
    from scipy.optimize import least_squares

    lo = np.array([p.lower for p in parameters], dtype=float)
    hi = np.array([p.upper for p in parameters], dtype=float)
    span = hi - lo
    u0 = np.clip((np.array([p.initial for p in parameters], dtype=float) - lo) / span, 0.0, 1.0)
    calls = [0]

    def counted(u: np.ndarray) -> np.ndarray:
        calls[0] += 1
        return residual(lo + span * u)

    t0 = time.perf_counter()
    try:  # in u = (x - lower) / span: scipy's xtol compares the step with norm(x), blind to x_scale
        res = least_squares(counted, u0, jac="2-point", bounds=(0.0, 1.0), method="trf",
                            max_nfev=int(max_evaluations), diff_step=step)
    except PredictionFailure as e:
        return _failed(parameters, str(e), calls[0], time.perf_counter() - t0, confidence)
    seconds = time.perf_counter() - t0
    x = lo + span * np.asarray(res.x, dtype=float)
    J = np.asarray(res.jac, dtype=float) / span
    h = step if step is not None else math.sqrt(np.finfo(float).eps)
    null_tol = 10.0 * (h + noise / h)
    low, high, bad, s, cov = linearised_intervals(J, np.asarray(res.fun, dtype=float), x, confidence, null_tol)
    at_bound = (x - lo <= AT_BOUND * span) | (hi - x <= AT_BOUND * span)
    names = tuple(p.name for p, b in zip(parameters, bad) if b)
    message = str(res.message)
    if names:
        message += f"; not identifiable from these data: {', '.join(names)} (infinite intervals)"
    if res.fun.size <= len(parameters):
        message += f"; {res.fun.size} residuals for {len(parameters)} parameters: no intervals"
    return CalibrationResult(bool(res.status > 0), message, calls[0], seconds, x, low, high, at_bound, names,
                             float(confidence), np.asarray(res.fun, dtype=float), s, cov)


def calibrate_on(predictor: Predictor, parameters: Sequence[FitParameter], measured: np.ndarray,
                 train: np.ndarray, confidence: float, max_evaluations: int, step: float | None,
                 noise: float = float(np.finfo(float).eps)) -> CalibrationResult:
    """Fit ``predictor``'s parameters on the samples ``train`` only: the residual function is built
    from those rows (``measured[train]``) and never evaluates another sample."""
    train = np.asarray(train, dtype=int)
    target = np.asarray(measured, dtype=float)[train]

    def residual(x: np.ndarray) -> np.ndarray:
        return (predictor.tips(x, train) - target).reshape(-1)

    return fit_parameters(residual, parameters, confidence, max_evaluations, step, noise)
