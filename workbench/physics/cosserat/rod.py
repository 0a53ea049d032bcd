"""Cosserat rod with continuously routed tendons: the strain law and the integration (numpy/scipy).

Kinematics and balance (Rucker & Webster, IEEE T-RO 27(6), 2011, Eq 1-4; Antman ch. 8): centreline
``p``, frame ``R`` (material axis 3 = tangent of the straight reference), strains ``v = R^T p'``,
``u`` with ``R' = R u^``, linear law ``n = R K_se (v - e3)``, ``m = R K_bt u``.  A frictionless
tendon ``i`` with tension ``tau_i`` at ``r_i(s)`` in the material frame runs along
``p_i = p + R r_i`` with unit tangent ``t_i = R w_i / |w_i|``, ``w_i = v + u x r_i + r_i'``.

Instead of R&W's distributed tendon loads (Eq 12-14, which need ``u'``, ``v'`` and lead to their
implicit system Eq 17) this module integrates the *total* internal force and moment of the rod
plus the tendons it carries,

    N = n + sum_i tau_i t_i,        M = m + sum_i (R r_i) x tau_i t_i,

which obey the tendon-free equations ``N' = -f``, ``M' = -p' x N - l`` (the tendons' distributed
loads are internal to the pair; with ``(R r_i)' x t_i = -p' x t_i`` the moment terms cancel) and are
continuous where a tendon terminates (its end force is exactly the jump of ``n``).  The tendons
enter only through the strain law: ``(v, u)`` solve

    K_se (v - e3) + sum_i tau_i w_i/|w_i| = R^T N,     K_bt u + sum_i tau_i r_i x w_i/|w_i| = R^T M,

by Newton from the guess ``w_i || e3`` (exact without shear and twist, where every section is an
exact arc).  The Jacobian of this system is R&W's matrix ``[K_se + A, G; B, K_bt + H]`` (Eq 17).
Checked by ``tests/physics/test_cosserat_model.py`` (CC arcs exact, elastica, tendon-free rod = the
shooting reference :mod:`workbench.reference.cosserat`, planar ANCF, beam3d eyelets).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853, solve_ivp

from . import kernel
from .problem import RodProblem

__all__ = ["cross", "hat", "strains", "N_BASE", "MAX_EVALUATIONS", "kernel_arguments", "segment_rhs", "integrate_segments"]

_E3 = np.array([0.0, 0.0, 1.0])
_I3 = np.eye(3)
#: State layout: p (3), R row-major (9), N (3), M (3), then centreline length, twist, tendon lengths.
N_BASE = 18
#: Right-hand-side evaluations allowed per segment and shot batch (a converging shot needs ~100-600).
MAX_EVALUATIONS = 6000


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` over the last axis of broadcastable ``(..., 3)`` arrays (faster than ``np.cross``
    for the small batches of the right-hand side)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def hat(v: np.ndarray) -> np.ndarray:
    """Skew matrices ``(..., 3, 3)`` of vectors ``(..., 3)`` (``hat(a) b = a x b``)."""
    z = np.zeros(v.shape[:-1])
    return np.stack([np.stack([z, -v[..., 2], v[..., 1]], -1),
                     np.stack([v[..., 2], z, -v[..., 0]], -1),
                     np.stack([-v[..., 1], v[..., 0], z], -1)], -2)


def strains(nb: np.ndarray, mb: np.ndarray, kse: np.ndarray, kbt: np.ndarray, r: np.ndarray,
            dr: np.ndarray, tau: np.ndarray, iterations: int = 8) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Strains ``(v, u)`` of the tendon-loaded section from the total wrench in the material frame.

    Parameters
    ----------
    nb, mb : ndarray, shape (B, 3)
        ``R^T N`` [N] and ``R^T M`` [N m] of ``B`` rods (a batch of shots).
    kse, kbt : ndarray, shape (3,)
        ``diag(GA, GA, EA)`` [N] and ``diag(EI, EI, GJ)`` [N m^2].
    r, dr : ndarray, shape (k, 3)
        Offsets ``r_i`` [m] and their derivatives ``r_i'`` of the tendons present here.
    tau : ndarray, shape (k,)
        Tensions [N] (>= 0).

    Returns
    -------
    v, u : ndarray, shape (B, 3)
        Linear and angular strains (per reference length).
    w : ndarray, shape (B, k, 3)
        Tendon tangents ``w_i`` in the material frame (length = tendon stretch ratio ``|p_i'|``).
    """
    v = _E3 + (nb - tau.sum() * _E3) / kse
    # r x e3 = (r_y, -r_x, 0)
    u = (mb - np.array([tau @ r[:, 1], -(tau @ r[:, 0]), 0.0])) / kbt
    if tau.size == 0 or not np.any(tau > 0):
        return v, u, v[:, None, :] + cross(u[:, None, :], r) + dr
    rh = hat(r)
    arm = max(float(np.max(np.abs(r))), 1e-12)
    kdiag = np.concatenate([kse, kbt])
    contraction = float(np.sum(tau)) / min(float(kse.min()), float(kbt[:2].min()) / arm**2, float(kbt[2]) / arm**2)
    for _ in range(iterations):
        w = v[:, None, :] + cross(u[:, None, :], r) + dr
        nw = np.sqrt(np.einsum("bki,bki->bk", w, w))
        t = w / nw[..., None]
        F = np.concatenate([kse * (v - _E3) + np.einsum("k,bki->bi", tau, t) - nb,
                            kbt * u + np.einsum("k,bki->bi", tau, cross(r, t)) - mb], axis=1)
        tP = (tau[None, :, None, None] / nw[..., None, None]) * (_I3 - t[..., :, None] * t[..., None, :])
        S = tP.sum(1)                      # sum tau P
        SR = np.matmul(tP, rh).sum(1)      # sum tau P r^
        RS = np.matmul(rh, tP).sum(1)      # sum tau r^ P
        RSR = np.matmul(np.matmul(rh, tP), rh).sum(1)
        J = np.empty((v.shape[0], 6, 6))
        J[:, :3, :3] = S
        J[:, :3, 3:] = -SR
        J[:, 3:, :3] = RS
        J[:, 3:, 3:] = -RSR
        J[:, np.arange(6), np.arange(6)] += kdiag
        dx = np.linalg.solve(J, -F[..., None])[..., 0]
        v = v + dx[:, :3]
        u = u + dx[:, 3:]
        # Newton is quadratic: in units (v, u |r|) the next step is ~ c delta^2 with
        # c = sum(tau) / min(GA, EA, EI/|r|^2); the guess w || e3 errs only by the shear strain
        # and twist x offset, so one step usually suffices
        delta = max(float(np.max(np.abs(dx[:, :3]))), float(np.max(np.abs(dx[:, 3:]))) * arm)
        if contraction * delta * delta < 1e-16:
            break
    return v, u, v[:, None, :] + cross(u[:, None, :], r) + dr


def kernel_arguments(pb: RodProblem, sec: int, active: np.ndarray, tau: np.ndarray, lam: float) -> tuple:
    """The constants of one segment in the order of :func:`.kernel.segment_rhs` (after ``s, y``):
    ``n_state``, section start and length, stiffness at its ends, mass per length at its ends,
    ``lam`` x gravity, and of the tendons present (``active``): directions, offsets at base and end,
    end arc lengths, tensions, offset derivatives, global indices."""
    idx = np.flatnonzero(active)
    c = np.ascontiguousarray(pb.tendon_dirs[idx], dtype=float)
    d0 = np.ascontiguousarray(pb.tendon_offsets[idx, 0], dtype=float)
    d1 = np.ascontiguousarray(pb.tendon_offsets[idx, 1], dtype=float)
    se = np.ascontiguousarray(pb.tendon_ends[idx], dtype=float)
    ta = np.ascontiguousarray(np.asarray(tau, dtype=float)[idx])
    dr = np.ascontiguousarray(((d1 - d0) / se)[:, None] * c)
    return (N_BASE + 2 + pb.n_tendons, float(pb.section_starts[sec]), float(pb.section_lengths[sec]),
            np.asarray(pb.stiffness0[sec], dtype=float), np.asarray(pb.stiffness1[sec], dtype=float),
            float(pb.mass_per_length0[sec]), float(pb.mass_per_length1[sec]), np.asarray(lam * pb.gravity, dtype=float),
            c, d0, d1, se, ta, dr, idx.astype(np.int64))


def segment_rhs(pb: RodProblem, sec: int, active: np.ndarray, tau: np.ndarray, lam: float, B: int,
                compiled: bool = False):
    """Right-hand side ``(s, y) -> y'`` of one segment for a batch of ``B`` states (flat ``y``);
    ``compiled``: the numba kernel of :mod:`.kernel`, else numpy.  Either raises ``RuntimeError``
    after :data:`MAX_EVALUATIONS` calls (a diverging shot curls up and needs ever smaller steps)."""
    calls = [0]
    if compiled:
        args = kernel_arguments(pb, sec, active, tau, lam)

        def compiled_rhs(s, y):
            calls[0] += 1
            if calls[0] > MAX_EVALUATIONS:
                raise RuntimeError(f"integration needs more than {MAX_EVALUATIONS} evaluations on one segment")
            return kernel.segment_rhs(float(s), y, *args)

        return compiled_rhs
    s0, ls = pb.section_starts[sec], pb.section_lengths[sec]
    k0, k1 = pb.stiffness0[sec], pb.stiffness1[sec]
    mu0, mu1 = pb.mass_per_length0[sec], pb.mass_per_length1[sec]
    idx = np.flatnonzero(active)
    c = pb.tendon_dirs[idx]
    d0, d1 = pb.tendon_offsets[idx, 0], pb.tendon_offsets[idx, 1]
    se = pb.tendon_ends[idx]
    ta = np.asarray(tau, dtype=float)[idx]
    dr = ((d1 - d0) / se)[:, None] * c
    g = lam * pb.gravity
    nt = pb.n_tendons
    n_state = N_BASE + 2 + nt

    def rhs(s, y):
        calls[0] += 1
        if calls[0] > MAX_EVALUATIONS:
            # a diverging shot (a wild base wrench) curls up and needs ever smaller steps
            raise RuntimeError(f"integration needs more than {MAX_EVALUATIONS} evaluations on one segment")
        Y = y.reshape(B, n_state)
        R = Y[:, 3:12].reshape(B, 3, 3)
        N, M = Y[:, 12:15], Y[:, 15:18]
        f = (s - s0) / ls
        K = k0 + (k1 - k0) * f
        r = (d0 + (d1 - d0) * s / se)[:, None] * c
        v, u, w = strains(np.einsum("bji,bj->bi", R, N), np.einsum("bji,bj->bi", R, M), K[:3], K[3:], r, dr, ta)
        out = np.zeros_like(Y)
        dp = np.einsum("bij,bj->bi", R, v)
        out[:, 0:3] = dp
        dR = out[:, 3:12].reshape(B, 3, 3)  # R' = R u^: column j of R' is R (u x e_j)
        dR[:, :, 0] = R[:, :, 1] * u[:, 2, None] - R[:, :, 2] * u[:, 1, None]
        dR[:, :, 1] = R[:, :, 2] * u[:, 0, None] - R[:, :, 0] * u[:, 2, None]
        dR[:, :, 2] = R[:, :, 0] * u[:, 1, None] - R[:, :, 1] * u[:, 0, None]
        out[:, 12:15] = -(mu0 + (mu1 - mu0) * f) * g
        out[:, 15:18] = -cross(dp, N)
        out[:, N_BASE] = np.sqrt(np.einsum("bi,bi->b", v, v))
        out[:, N_BASE + 1] = u[:, 2]
        if idx.size:
            out[:, N_BASE + 2 + idx] = np.sqrt(np.einsum("bki,bki->bk", w, w))
        return out.reshape(-1)

    return rhs


_DOP853 = tuple(np.ascontiguousarray(getattr(DOP853, k), dtype=float)
                for k in ("A", "B", "C", "E3", "E5", "A_EXTRA", "C_EXTRA", "D"))


def _compiled_segment(pb: RodProblem, sec: int, active: np.ndarray, tau: np.ndarray, lam: float, y: np.ndarray,
                      a: float, b: float, rtol: float, atol: np.ndarray,
                      stations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(B, n_state)`` states at ``b`` and ``(m, B, n_state)`` at the ``stations`` in ``[a, b]`` from
    ``y`` at ``a`` by the kernel's DOP853 (scipy's steps and dense output)."""
    B, n_state = y.shape
    yb, status, _, at = kernel.dop853_segment(np.ascontiguousarray(y.reshape(-1)), float(a), float(b), float(rtol),
                                              atol, MAX_EVALUATIONS, np.ascontiguousarray(stations, dtype=float),
                                              *_DOP853, *kernel_arguments(pb, sec, active, tau, lam))
    if status == 1:
        raise RuntimeError(f"integration needs more than {MAX_EVALUATIONS} evaluations on one segment")
    if status == 2:
        raise RuntimeError(f"cosserat: integration failed on [{a:.4g}, {b:.4g}] m: the step size fell below "
                           "10 ulp of s")
    if not np.all(np.isfinite(yb)):
        raise RuntimeError("cosserat: non-finite state in the integration")
    return yb.reshape(B, n_state), at.reshape(-1, B, n_state)


def integrate_segments(pb: RodProblem, x0: np.ndarray, tau: np.ndarray, lam: float, rtol: float,
                       stations: np.ndarray | None = None,
                       compiled: bool | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    """Integrate ``B`` shots from the clamped base to the tip.

    Parameters
    ----------
    x0 : ndarray, shape (B, 6)
        Base total force ``N(0)`` [N] and moment ``M(0)`` [N m], base frame.
    tau : ndarray, shape (n_t,)
        Tendon tensions [N] (as applied; the load ramp scales them itself).
    lam : float
        Load factor of gravity and the point forces (tip loads are applied by the caller).
    rtol : float
        Relative tolerance of DOP853; absolute tolerances are ``rtol`` times the scale of each
        state group (length, 1, force and moment scales of ``x0``).
    stations : ndarray, shape (m,), optional
        Arc lengths at which to return the states.
    compiled : bool, optional
        Evaluate the right-hand side with the numba kernel (:mod:`.kernel`); default: where numba
        is installed.  Both paths integrate the same equations with the same steps: numpy through
        ``solve_ivp``, the kernel by :func:`.kernel.dop853_segment` (scipy's DOP853 step control and
        dense output).

    Returns
    -------
    tip : ndarray, shape (B, n_state)
        States at s = L (before the point force at L, which the tip condition takes).
    at_stations : ndarray, shape (m, B, n_state) or None
    """
    B = x0.shape[0]
    nt = pb.n_tendons
    n_state = N_BASE + 2 + nt
    compiled = kernel.AVAILABLE if compiled is None else compiled
    y = np.zeros((B, n_state))
    y[:, 3:12] = np.eye(3).reshape(9)
    y[:, 12:18] = x0
    L = pb.length
    fs = max(float(np.max(np.abs(x0[:, :3]), initial=0.0)), 1e-9)
    ms = max(float(np.max(np.abs(x0[:, 3:]), initial=0.0)), fs * L)
    scale = np.concatenate([np.full(3, L), np.ones(9), np.full(3, fs), np.full(3, ms), np.full(2 + nt, L)])
    atol = rtol * np.tile(scale, B)
    bp = pb.breakpoints
    out = None if stations is None else np.zeros((stations.size, B, n_state))
    for a, b, F in zip(bp[:-1], bp[1:], pb.point_forces[:-1]):
        if a > 0:
            y[:, 12:15] -= lam * F  # N(s+) = N(s-) - point force at s
        sec = pb.section_of(0.5 * (a + b))
        active = pb.tendon_ends >= b - 1e-12 * L
        t_eval, sel = None, None
        if stations is not None:
            sel = (stations >= a) & ((stations < b) | (b == L))
            t_eval = np.append(stations[sel][stations[sel] < b], b)
        if compiled:
            y, at = _compiled_segment(pb, sec, active, tau, lam, y, a, b, rtol, atol,
                                      np.zeros(0) if sel is None else stations[sel])
            if sel is not None:
                out[sel] = at
            continue
        fun = segment_rhs(pb, sec, active, tau, lam, B, compiled)
        sol = solve_ivp(fun, (a, b), y.reshape(-1), method="DOP853", rtol=rtol, atol=atol, t_eval=t_eval)
        if not sol.success:
            raise RuntimeError(f"cosserat: integration failed on [{a:.4g}, {b:.4g}] m: {sol.message}")
        if sel is not None and np.any(sel):
            Y = sol.y.T.reshape(t_eval.size, B, n_state)
            out[sel] = Y[: int(np.sum(sel))]  # t_eval = the stations in [a, b) (and L), then b
        y = sol.y[:, -1].reshape(B, n_state)
        if not np.all(np.isfinite(y)):
            raise RuntimeError("cosserat: non-finite state in the integration")
    return y, out
