"""Redundancy resolution for constant-curvature robots (Hannan & Walker, papers/000_, Eq. 10-11).

Resolved-rate inverse kinematics with task decomposition (Yoshikawa 1985, as used by
Hannan & Walker): the primary task drives the tip position to a target, the null space of
the task Jacobian drives the curvatures towards a desired configuration ``q_d``. Eq. 11,

``qdot = J^+ (xdot_d - H1 (x - x_d)) - (I - J^+ J) H2 (q - q_d) k``,

is integrated with unit time step: ``dq = J^#(gain (x_d - x) + dx_d) - null_gain N (q - q_d)``
where ``N = I - J^+ J`` (exact Moore-Penrose projector; ``H1 = gain I``, ``H2 k = null_gain S``
with ``S`` selecting the curvature variables) and ``J^#`` is the damped least-squares inverse
``V diag(s / (s^2 + lambda^2)) U^T`` whose damping ``lambda`` switches on smoothly only when the
smallest singular value ``s_min`` falls below ``eps = singular_threshold * s_max``:
``lambda^2 = (1 - (s_min/eps)^2) eps^2`` (Nakamura & Hanafusa 1986 / Maciejewski & Klein 1988).
Far from singularities ``J^# = J^+ = J^T (J J^T)^-1`` (Eq. 10).

Two models are supported: the planar Hannan & Walker model (variables: the ``n`` curvatures,
task: planar ``(x, y)``) and the spatial model (variables ``kappa_i, phi_i``, fixed ``ell``,
task: tip position).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ._checks import as_float, require_positive, section_arrays
from .arc import chain_tip, check_sections, jacobian_unchecked, forward_kinematics
from .planar import planar_fk_unchecked, planar_jacobian_unchecked, planar_forward_kinematics

__all__ = [
    "IKResult",
    "PathResult",
    "planar_inverse_kinematics",
    "spatial_inverse_kinematics",
    "follow_path",
    "line_path",
    "resolved_rate_step",
]


@dataclass(frozen=True, eq=False)
class IKResult:
    """Result of an inverse-kinematics solve.

    Attributes
    ----------
    q : ndarray
        Planar: curvatures, shape (n,) [1/m]. Spatial: shape (2, n), rows ``kappa`` [1/m]
        and ``phi`` [rad].
    success : bool
        ``residual <= tol``.
    iterations : int
        Resolved-rate iterations performed.
    residual : float
        Final tip position error ``|x(q) - x_d|`` [m].
    reason : str
        ``"converged"``, ``"converged (null-space task not settled)"``, ``"stalled"`` (no
        progress, e.g. unreachable target) or ``"max_iterations"``.
    """

    q: np.ndarray
    success: bool
    iterations: int
    residual: float
    reason: str


@dataclass(frozen=True, eq=False)
class PathResult:
    """Per-sample result of :func:`follow_path` (``m`` samples).

    Attributes
    ----------
    q : ndarray, shape (m, n) planar or (m, 2, n) spatial
    tip : ndarray, shape (m, dim)
        Achieved tip positions [m].
    target : ndarray, shape (m, dim)
        Path samples [m].
    error : ndarray, shape (m,)
        ``|tip - target|`` [m].
    iterations : ndarray of int, shape (m,)
    success : bool
        Every sample reached ``error <= tol``.
    """

    q: np.ndarray
    tip: np.ndarray
    target: np.ndarray
    error: np.ndarray
    iterations: np.ndarray
    success: bool


def _dls_step(J, e, tol_rel, null_vec):
    """Damped primary step and exact null-space projection of ``null_vec``."""
    U, S, Vt = np.linalg.svd(J, full_matrices=False)
    smax = S[0] if S.size else 0.0
    eps = tol_rel * smax
    smin = S[-1]
    lam2 = 0.0
    if eps > 0 and smin < eps:  # smooth switch-on of the damping near a singularity
        lam2 = (1.0 - (smin / eps) ** 2) * eps**2
    denom = S * S + lam2
    inv = np.where(denom > 0, S / np.where(denom > 0, denom, 1.0), 0.0)
    dq_task = Vt.T @ (inv * (U.T @ e))
    # exact projector onto null(J): remove the row-space components (rank by rcond)
    rank = int(np.sum(S > 1e-12 * max(smax, 1e-300)))
    Vr = Vt[:rank]
    dq_null = null_vec - Vr.T @ (Vr @ null_vec)
    return dq_task, dq_null


def resolved_rate_step(J, error, null_vector=None, singular_threshold: float = 1e-2) -> tuple[np.ndarray, np.ndarray]:
    """One step of Eq. 11: the damped primary step ``J^# error`` and the null-space projection.

    Parameters
    ----------
    J : array_like, shape (t, v)
        Task Jacobian at the current configuration.
    error : array_like, shape (t,)
        Task-space correction to aim at (Eq. 11: ``xdot_d - H1 (x - x_d)``) [m].
    null_vector : array_like, shape (v,), optional
        Secondary-task direction (Eq. 11: ``-H2 k (q - q_d)``); default none.
    singular_threshold : float
        The damping switches on below ``singular_threshold * s_max`` (module docstring).

    Returns
    -------
    dq_task, dq_null : ndarray, shape (v,)
        ``J^# error`` and ``(I - J^+ J) null_vector``; their sum is the step.  The loops of
        :func:`planar_inverse_kinematics` take exactly these steps (``tests/kinematics``).
    """
    J = as_float("J", J)
    e = as_float("error", error)
    if J.ndim != 2 or e.shape != (J.shape[0],):
        raise ValueError(f"J must have shape (t, v) and error shape (t,); got {J.shape} and {e.shape}")
    nv = np.zeros(J.shape[1]) if null_vector is None else as_float("null_vector", null_vector)
    if nv.shape != (J.shape[1],):
        raise ValueError(f"null_vector must have shape ({J.shape[1]},), got {nv.shape}")
    require_positive("singular_threshold", as_float("singular_threshold", singular_threshold))
    return _dls_step(J, e, float(singular_threshold), nv)


def _resolved_rate(
    fk: Callable[[np.ndarray], np.ndarray],
    jac: Callable[[np.ndarray], np.ndarray],
    q0: np.ndarray,
    x_d: np.ndarray,
    *,
    q_d: np.ndarray | None,
    select: np.ndarray,
    step_scale: np.ndarray,
    gain: float,
    null_gain: float,
    singular_threshold: float,
    tol: float,
    null_tol: float,
    max_iter: int,
    max_step: float,
    stall_iter: int = 50,
):
    q = q0.copy()
    x = fk(q)
    r = float(np.linalg.norm(x - x_d))
    best, since_best = r, 0
    for it in range(1, max_iter + 1):
        if r <= tol and q_d is None:
            return q, True, it - 1, r, "converged"
        J = jac(q)
        null_vec = np.zeros_like(q) if q_d is None else -null_gain * select * (q - q_d)
        dq_task, dq_null = _dls_step(J, gain * (x_d - x), singular_threshold, null_vec)
        if r <= tol and np.linalg.norm(dq_null) <= null_tol:
            return q, True, it - 1, r, "converged"
        dq = dq_task + dq_null
        big = np.max(np.abs(dq * step_scale))
        if big > max_step:
            dq *= max_step / big
        q = q + dq
        x = fk(q)
        r = float(np.linalg.norm(x - x_d))
        # progress = the task error decreases, or the secondary task is still moving
        if r < best * (1 - 1e-9) or r <= tol or np.linalg.norm(dq_null) > null_tol:
            best, since_best = min(r, best), 0
        else:
            since_best += 1
            if since_best >= stall_iter:
                return q, False, it, r, "stalled"
    ok = r <= tol
    if not ok:
        return q, False, max_iter, r, "max_iterations"
    return q, True, max_iter, r, ("converged" if q_d is None else "converged (null-space task not settled)")


def _check_solver_opts(gain, null_gain, singular_threshold, tol, max_iter, max_step):
    require_positive("gain", as_float("gain", gain))
    if null_gain < 0:
        raise ValueError("null_gain must be >= 0")
    require_positive("singular_threshold", as_float("singular_threshold", singular_threshold))
    require_positive("tol", as_float("tol", tol))
    require_positive("max_step", as_float("max_step", max_step))
    if int(max_iter) < 1:
        raise ValueError("max_iter must be >= 1")


def _check_target(target, dim):
    t = as_float("target", target)
    if t.shape != (dim,):
        raise ValueError(f"target must have shape ({dim},) (tip position, m); got {t.shape}")
    return t


def planar_inverse_kinematics(
    target,
    kappa0,
    ell,
    *,
    kappa_d=None,
    gain: float = 1.0,
    null_gain: float = 0.2,
    singular_threshold: float = 1e-2,
    tol: float = 1e-10,
    null_tol: float = 1e-9,
    max_iter: int = 500,
    max_step: float = 0.5,
    target_velocity=None,
) -> IKResult:
    """Resolved-rate IK of the planar Hannan & Walker model (Eq. 9-11).

    Parameters
    ----------
    target : array_like, shape (2,)
        Desired tip position ``x_d`` [m] in the planar frame of
        :func:`~workbench.kinematics.planar_forward_kinematics`.
    kappa0 : array_like, shape (n,)
        Initial curvatures [1/m].
    ell : array_like, shape (n,)
        Section arc lengths [m] (fixed).
    kappa_d : array_like, shape (n,), optional
        Desired configuration ``q_d`` of the secondary (null-space) task, Eq. 11.
    gain : float
        ``H1 = gain I`` (1 = full Newton step).
    null_gain : float
        ``H2 k`` of Eq. 11 (per iteration).
    singular_threshold : float
        Damping switches on when ``s_min < singular_threshold * s_max`` (see module docs).
    tol : float
        Success when ``|x - x_d| <= tol`` [m].
    null_tol : float
        With ``kappa_d``, iterate until the null-space step is below this [1/m].
    max_iter : int
    max_step : float
        Largest change of a section bending angle ``kappa_i ell_i`` per iteration [rad].
    target_velocity : array_like, shape (2,), optional
        Feed-forward ``xdot_d`` added to the first step only (used by :func:`follow_path`).

    Returns
    -------
    IKResult
        ``q`` has shape (n,).
    """
    k0, ll = section_arrays(kappa0=kappa0, ell=ell)
    if k0.ndim != 1:
        raise ValueError(f"kappa0 and ell must have shape (n,); got {k0.shape}")
    if np.any(ll <= 0):
        raise ValueError("ell must be > 0 for inverse kinematics")
    x_d = _check_target(target, 2)
    q_d = None if kappa_d is None else as_float("kappa_d", kappa_d)
    if q_d is not None and q_d.shape != k0.shape:
        raise ValueError(f"kappa_d must have shape {k0.shape}; got {q_d.shape}")
    _check_solver_opts(gain, null_gain, singular_threshold, tol, max_iter, max_step)
    # inputs are checked above; the loop uses the unchecked kernels
    fk = lambda q: planar_fk_unchecked(q, ll)[:2, 3]  # noqa: E731
    jac = lambda q: planar_jacobian_unchecked(q, ll)  # noqa: E731
    q0 = k0.copy()
    if target_velocity is not None:
        v = _check_target(target_velocity, 2)
        dq_task, _ = _dls_step(jac(q0), v, singular_threshold, np.zeros_like(q0))
        q0 = q0 + dq_task
    q, ok, it, r, why = _resolved_rate(
        fk, jac, q0, x_d, q_d=q_d, select=np.ones_like(q0), step_scale=ll, gain=gain,
        null_gain=null_gain, singular_threshold=singular_threshold, tol=tol, null_tol=null_tol,
        max_iter=int(max_iter), max_step=max_step,
    )
    return IKResult(q=q, success=ok, iterations=it, residual=r, reason=why)


def spatial_inverse_kinematics(
    target,
    kappa0,
    phi0,
    ell,
    *,
    kappa_d=None,
    gain: float = 1.0,
    null_gain: float = 0.2,
    singular_threshold: float = 1e-2,
    tol: float = 1e-10,
    null_tol: float = 1e-9,
    max_iter: int = 500,
    max_step: float = 0.5,
) -> IKResult:
    """Resolved-rate position IK of the spatial model (variables ``kappa_i, phi_i``).

    Parameters
    ----------
    target : array_like, shape (3,)
        Desired tip position [m] in the base frame of
        :func:`~workbench.kinematics.forward_kinematics`.
    kappa0, phi0 : array_like, shape (n,)
        Initial curvatures [1/m] and bending-plane angles [rad]. Start away from
        ``kappa = 0`` when possible: there the ``phi`` columns vanish (handled by the damping).
    ell : array_like, shape (n,)
        Fixed arc lengths [m].
    kappa_d : array_like, shape (n,), optional
        Secondary task: drive the curvatures (not the angles) towards ``kappa_d``.
    gain, null_gain, singular_threshold, tol, null_tol, max_iter, max_step
        As in :func:`planar_inverse_kinematics`; ``max_step`` bounds both ``|d kappa_i| ell_i``
        and ``|d phi_i|`` [rad].

    Returns
    -------
    IKResult
        ``q`` has shape (2, n): ``q[0]`` curvatures, ``q[1]`` angles wrapped to ``(-pi, pi]``.
    """
    k0, p0, ll = check_sections(kappa0, phi0, ell)
    if k0.ndim != 1:
        raise ValueError(f"kappa0, phi0 and ell must have shape (n,); got {k0.shape}")
    if np.any(ll <= 0):
        raise ValueError("ell must be > 0 for inverse kinematics")
    n = k0.size
    x_d = _check_target(target, 3)
    q_d = None
    if kappa_d is not None:
        kd = as_float("kappa_d", kappa_d)
        if kd.shape != (n,):
            raise ValueError(f"kappa_d must have shape ({n},); got {kd.shape}")
        q_d = np.concatenate([kd, np.zeros(n)])
    _check_solver_opts(gain, null_gain, singular_threshold, tol, max_iter, max_step)
    cols = np.concatenate([3 * np.arange(n), 3 * np.arange(n) + 1])  # kappa_i, then phi_i

    def fk(q):
        return chain_tip(q[:n], q[n:], ll)[:3, 3]

    def jac(q):
        return jacobian_unchecked(q[:n], q[n:], ll)[:3, cols]

    select = np.concatenate([np.ones(n), np.zeros(n)])
    q, ok, it, r, why = _resolved_rate(
        fk, jac, np.concatenate([k0, p0]), x_d, q_d=q_d, select=select,
        step_scale=np.concatenate([ll, np.ones(n)]), gain=gain, null_gain=null_gain,
        singular_threshold=singular_threshold, tol=tol, null_tol=null_tol,
        max_iter=int(max_iter), max_step=max_step,
    )
    phi = np.angle(np.exp(1j * q[n:]))  # wrap to (-pi, pi]
    return IKResult(q=np.stack([q[:n], phi]), success=ok, iterations=it, residual=r, reason=why)


def line_path(start, end, n_samples: int) -> np.ndarray:
    """Equally spaced samples of the straight segment ``start -> end``.

    Parameters
    ----------
    start, end : array_like, shape (dim,)
        End points [m].
    n_samples : int
        Number of samples (``>= 2``), both end points included.

    Returns
    -------
    path : ndarray, shape (n_samples, dim)
    """
    a = as_float("start", start)
    b = as_float("end", end)
    if a.ndim != 1 or a.shape != b.shape:
        raise ValueError(f"start and end must both have shape (dim,); got {a.shape} and {b.shape}")
    if int(n_samples) < 2:
        raise ValueError("n_samples must be >= 2")
    t = np.linspace(0.0, 1.0, int(n_samples))[:, None]
    return (1 - t) * a + t * b


def follow_path(
    path,
    kappa0,
    ell,
    *,
    phi0=None,
    kappa_d=None,
    feedforward: bool = True,
    max_iter_per_sample: int = 100,
    tol: float = 1e-10,
    **solver_options,
) -> PathResult:
    """Track an end-point path sample by sample with resolved-rate control (Eq. 10-11).

    For each sample ``x_d[j]`` the solver starts from the previous configuration (warm start),
    optionally applies the feed-forward step ``J^# (x_d[j] - x_d[j-1])`` and then iterates
    Eq. 11 (position feedback + null-space task) until ``tol`` or ``max_iter_per_sample``.

    Parameters
    ----------
    path : array_like, shape (m, 2) or (m, 3)
        Tip path samples [m]; 2 columns = planar Hannan & Walker model, 3 columns = spatial
        model (then ``phi0`` is required).
    kappa0 : array_like, shape (n,)
        Initial curvatures [1/m] (the tip needs not start on the path).
    ell : array_like, shape (n,)
        Fixed section lengths [m].
    phi0 : array_like, shape (n,), optional
        Initial bending-plane angles [rad] (spatial model only).
    kappa_d : array_like, shape (n,), optional
        Desired curvatures for the null-space task.
    feedforward : bool
        Use ``x_d[j] - x_d[j-1]`` as the ``xdot_d`` term of Eq. 11 (planar model).
    max_iter_per_sample : int
    tol : float
        Tip error tolerance [m].
    **solver_options
        Passed to :func:`planar_inverse_kinematics` / :func:`spatial_inverse_kinematics`.

    Returns
    -------
    PathResult
    """
    P = as_float("path", path)
    if P.ndim != 2 or P.shape[1] not in (2, 3) or P.shape[0] < 1:
        raise ValueError(f"path must have shape (m, 2) (planar) or (m, 3) (spatial); got {P.shape}")
    spatial = P.shape[1] == 3
    if spatial and phi0 is None:
        raise ValueError("a 3-column (spatial) path needs phi0, shape (n,)")
    if not spatial and phi0 is not None:
        raise ValueError("phi0 is only used with a 3-column (spatial) path")
    m = P.shape[0]
    qs, tips, errs, its = [], [], [], []
    k = as_float("kappa0", kappa0)
    ph = None if phi0 is None else as_float("phi0", phi0)
    for j in range(m):
        if spatial:
            res = spatial_inverse_kinematics(
                P[j], k, ph, ell, kappa_d=kappa_d, tol=tol, max_iter=max_iter_per_sample, **solver_options
            )
            k, ph = res.q[0], res.q[1]
            tip = forward_kinematics(k, ph, ell)[:3, 3]
        else:
            v = (P[j] - P[j - 1]) if (feedforward and j > 0) else None
            res = planar_inverse_kinematics(
                P[j], k, ell, kappa_d=kappa_d, tol=tol, max_iter=max_iter_per_sample,
                target_velocity=v, **solver_options,
            )
            k = res.q
            tip = planar_forward_kinematics(k, ell)[:2, 3]
        qs.append(res.q)
        tips.append(tip)
        errs.append(np.linalg.norm(tip - P[j]))
        its.append(res.iterations)
    err = np.asarray(errs)
    return PathResult(
        q=np.asarray(qs), tip=np.asarray(tips), target=P.copy(), error=err,
        iterations=np.asarray(its, dtype=int), success=bool(np.all(err <= tol)),
    )
