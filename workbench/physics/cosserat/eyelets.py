"""Eyelet routing for the Cosserat rod: tendons straight between disks, point loads at the disks.

The subsegment Cosserat rod of Rao, Peyron, Lilge & Burgner-Kahrs (Front. Robot. AI 7:630245, 2021, and
its C++ code tdcr-modeling): a tendon runs through an eyelet at every disk of its route
(:func:`workbench.physics._beam3d_layout.tendon_routes`, the same eyelets as ``beam3d``: the anchor on the
base plate at ``s = 0``, then every disk up to the end of its section) and is straight between consecutive
eyelets; between disks the rod carries no tendon load, so it obeys the tendon-free Cosserat equations
(the kernel's right-hand side with no tendons present: ``v = e3 + K_se^-1 R^T n``, ``u = K_bt^-1 R^T m``).
At disk ``k`` a tendon with tension ``tau`` whose chords run in from the previous eyelet (unit ``t_in``) and
out to the next one (``t_out``) pulls the disk with ``F = tau (t_out - t_in)`` at its eyelet ``p + R r``
(``F = -tau t_in`` at the terminating disk), so the rod's internal force and moment jump:
``n+ = n- - F``, ``m+ = m- - (R r) x F``.  The force on the base anchor goes to the base plate.

The implicit part: ``t_out`` depends on the next disk's pose, i.e. on the integration of the segment that
starts with the jump.  Rao et al. make every disk's wrench a shooting unknown (6 per disk, solved together
by Levenberg-Marquardt: 120 unknowns on the benchmark robot).  Here the base wrench stays the only shooting
unknown and each segment's chords are a fixed point solved as the integration reaches the segment: predict
``t_out = R_k R_{k-1}^T t_in`` (exact on a constant-curvature, evenly spaced stretch), integrate the
segment, replace ``t_out`` by the chord to the eyelets reached (Anderson mixing), and repeat until the chords move less
than ``chord_tol`` (the map contracts: a change ``dt`` of a chord changes the next eyelet's chord by
``~ tau dt (h^2 / 6 EI + r^2 / GJ)``, ~0.1 dt on the benchmark robot; the converged shot is then a
function of the base wrench to ``chord_tol``).  A batch of shots iterates together with common
integration steps and iteration count, so the Newton difference quotients see one discretisation.
Tendon lengths are the sums of the chord lengths.  Checked by ``tests/physics/test_cosserat_eyelets.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import DOP853

from ...robot import Robot
from .._beam3d_layout import tendon_routes
from . import kernel
from .kernel import njit
from .problem import RodProblem

__all__ = ["EyeletRoute", "eyelet_route", "integrate_eyelets", "eyelet_shots", "N_EYELET_STATE", "MAX_CHORD_ITERATIONS"]

#: State of an eyelet shot: p (3), R row-major (9), n (3), m (3), centreline length, twist.
N_EYELET_STATE = 20
#: Chord iterations allowed per segment before the shot is declared failed.
MAX_CHORD_ITERATIONS = 60
_MAX_EVALUATIONS = 6000


@dataclass(frozen=True)
class EyeletRoute:
    """The disks of an eyelet-routed rod and what acts there.

    Attributes
    ----------
    stations : ndarray, shape (K + 1,)
        Segment ends from 0 to L: the base, every disk, every section end [m].
    section : ndarray of int, shape (K,)
        Section of each segment ``[stations[j], stations[j + 1]]``.
    weights : ndarray, shape (K + 1, 3)
        Point force on the centreline at each station [N] at full load (disk weights; the tip's is
        taken by the tip condition, the base's by the clamp).
    eyelet : ndarray of bool, shape (K + 1, n_t)
        Whether tendon ``i`` has an eyelet at station ``j`` (the base anchor at ``j = 0``).
    offsets : ndarray, shape (K + 1, n_t, 3)
        Eyelet offsets ``r`` in the material frame at each station [m] (0 where there is none).
    last : ndarray of int, shape (n_t,)
        Station index where each tendon terminates.
    """

    stations: np.ndarray
    section: np.ndarray
    weights: np.ndarray
    eyelet: np.ndarray
    offsets: np.ndarray
    last: np.ndarray


def eyelet_route(robot: Robot, pb: RodProblem) -> EyeletRoute:
    """The :class:`EyeletRoute` of ``robot`` (disks from its sections, weights from ``pb``).  Every
    section has a disk at its end (``Section.n_disks >= 1``), so every station past the base is a disk
    and a tendon has an eyelet at every station up to its end (the chords run station to station)."""
    L = pb.length
    routes = tendon_routes(robot)
    keys = sorted({0.0, L, *map(float, robot.section_ends), *map(float, pb.breakpoints),
                   *(s for route in routes for s, _ in route)})
    st = [keys[0]]
    for s in keys[1:]:  # merge stations closer than round-off (a disk at a section end)
        if s - st[-1] >= 1e-12 * L:
            st.append(s)
    st[-1] = L
    st = np.asarray(st)

    def index(s: float) -> int:
        return int(np.argmin(np.abs(st - s)))

    n_t = pb.n_tendons
    eyelet = np.zeros((st.size, n_t), dtype=bool)
    offsets = np.zeros((st.size, n_t, 3))
    last = np.zeros(n_t, dtype=np.int64)
    for i, route in enumerate(routes):
        for s, d in route:
            j = index(s)
            eyelet[j, i] = True
            offsets[j, i] = d * pb.tendon_dirs[i]
        last[i] = index(route[-1][0])
    weights = np.zeros((st.size, 3))
    for s, f in zip(pb.breakpoints, pb.point_forces):
        weights[index(float(s))] += f
    section = np.array([pb.section_of(0.5 * (a + b)) for a, b in zip(st[:-1], st[1:])], dtype=np.int64)
    return EyeletRoute(stations=st, section=section, weights=weights, eyelet=eyelet, offsets=offsets, last=last)


_DOP853 = tuple(np.ascontiguousarray(getattr(DOP853, k), dtype=float)
                for k in ("A", "B", "C", "E3", "E5", "A_EXTRA", "C_EXTRA", "D"))
_NO_TENDON = (np.zeros((0, 3)), np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 3)),
              np.zeros(0, dtype=np.int64))


@njit(cache=True)
def _eyelet_points(y, B, r, P):  # noqa: ANN001, ANN202
    """Eyelet points ``p + R r_i`` (written into ``P`` ``(B, n_t, 3)``) of the states ``y`` (flat)."""
    n_t = r.shape[0]
    for b in range(B):
        o = b * N_EYELET_STATE
        for i in range(n_t):
            for a in range(3):
                P[b, i, a] = (y[o + a] + y[o + 3 + 3 * a] * r[i, 0] + y[o + 4 + 3 * a] * r[i, 1]
                              + y[o + 5 + 3 * a] * r[i, 2])


@njit(cache=True)
def _apply_disk(y, B, r, P, mask, tau, t_in, t_out, passing):  # noqa: ANN001, ANN202, PLR0913
    """The tendons' point loads at a disk: ``n -= F``, ``m -= (P - p) x F`` with ``F = tau (t_out - t_in)``
    for a tendon passing the disk and ``-tau t_in`` where it terminates (``mask``: eyelet here)."""
    F = np.empty(3)
    for b in range(B):
        o = b * N_EYELET_STATE
        for i in range(r.shape[0]):
            if not mask[i] or tau[i] == 0.0:
                continue
            for a in range(3):
                F[a] = tau[i] * ((t_out[b, i, a] if passing[i] else 0.0) - t_in[b, i, a])
            ax = P[b, i, 0] - y[o]
            ay = P[b, i, 1] - y[o + 1]
            az = P[b, i, 2] - y[o + 2]
            y[o + 12] -= F[0]
            y[o + 13] -= F[1]
            y[o + 14] -= F[2]
            y[o + 15] -= ay * F[2] - az * F[1]
            y[o + 16] -= az * F[0] - ax * F[2]
            y[o + 17] -= ax * F[1] - ay * F[0]


@njit(cache=True)
def _chords(P0, P1, mask, t, lengths):  # noqa: ANN001, ANN202
    """Unit chords ``t`` and their lengths from ``P0`` to ``P1`` of the tendons in ``mask``; returns the
    largest change of a chord."""
    change = 0.0
    for b in range(P0.shape[0]):
        for i in range(P0.shape[1]):
            if not mask[i]:
                continue
            dx = P1[b, i, 0] - P0[b, i, 0]
            dy = P1[b, i, 1] - P0[b, i, 1]
            dz = P1[b, i, 2] - P0[b, i, 2]
            ln = np.sqrt(dx * dx + dy * dy + dz * dz)
            lengths[b, i] = ln
            change = max(change, abs(dx / ln - t[b, i, 0]), abs(dy / ln - t[b, i, 1]), abs(dz / ln - t[b, i, 2]))
            t[b, i, 0] = dx / ln
            t[b, i, 1] = dy / ln
            t[b, i, 2] = dz / ln
    return change


@njit(cache=True)
def _anderson(z, g, z_prev, g_prev, passing):  # noqa: ANN001, ANN202
    """Anderson mixing of depth 1 on each shot's chords (Walker & Ni, SIAM J. Numer. Anal. 49(4), 2011):
    from the last two iterates ``z -> g`` the next chords ``g - gamma (g - g_prev)`` (written into ``g``)
    with ``gamma`` minimising ``|f - gamma (f - f_prev)|``, ``f = g - z``."""
    for b in range(z.shape[0]):
        num = 0.0
        den = 0.0
        for i in range(z.shape[1]):
            if passing[i]:
                for a in range(3):
                    df = (g[b, i, a] - z[b, i, a]) - (g_prev[b, i, a] - z_prev[b, i, a])
                    num += (g[b, i, a] - z[b, i, a]) * df
                    den += df * df
        if den == 0.0:
            continue
        gamma = num / den
        for i in range(z.shape[1]):
            if passing[i]:
                for a in range(3):
                    g[b, i, a] -= gamma * (g[b, i, a] - g_prev[b, i, a])


@njit(cache=True)
def _predict(y, B, R_prev, t_in, passing, t_out):  # noqa: ANN001, ANN202
    """``t_out = R_k R_{k-1}^T t_in`` of the passing tendons: the incoming chord carried by the frame's
    rotation over the last segment (exact on an evenly spaced constant-curvature stretch)."""
    w = np.empty(3)
    for b in range(B):
        o = b * N_EYELET_STATE
        for i in range(t_in.shape[1]):
            if not passing[i]:
                continue
            for a in range(3):
                w[a] = R_prev[b, 0, a] * t_in[b, i, 0] + R_prev[b, 1, a] * t_in[b, i, 1] + R_prev[b, 2, a] * t_in[b, i, 2]
            for a in range(3):
                t_out[b, i, a] = y[o + 3 + 3 * a] * w[0] + y[o + 4 + 3 * a] * w[1] + y[o + 5 + 3 * a] * w[2]


@njit(cache=True)
def _arrive(y, B, weight, r, mask, passing, P, P_prev, t_in, t_out, seg_len, lengths, R_prev):  # noqa: ANN001, ANN202, PLR0913
    """Arrival at a disk: its weight on the centreline, its eyelet points ``P``, the incoming chords
    ``t_in`` (their lengths added to ``lengths``; ``P_prev`` moves on) and the predicted ``t_out``."""
    for b in range(B):
        for a in range(3):
            y[b * N_EYELET_STATE + 12 + a] -= weight[a]
    _eyelet_points(y, B, r, P)
    _chords(P_prev, P, mask, t_in, seg_len)
    for b in range(B):
        for i in range(mask.shape[0]):
            if mask[i]:
                lengths[b, i] += seg_len[b, i]
                for a in range(3):
                    P_prev[b, i, a] = P[b, i, a]
    _predict(y, B, R_prev, t_in, passing, t_out)


@njit(cache=True)
def eyelet_shots(y0, stations, section, weights, eyelet, offsets, last, tau, lam, rtol, atol, chord_tol,  # noqa: ANN001, ANN201, PLR0912, PLR0913, PLR0915
                 out_s, A, Bw, C, E3, E5, A_extra, C_extra, D, s0s, lss, k0s, k1s, mu0s, mu1s, g,
                 c, d0, d1, se, ta, dr, idx):
    """Integrate a batch of eyelet shots from the clamp to the tip (see the module docstring).

    ``y0`` flat ``(B * 20,)`` clamp states; the route arrays of :class:`EyeletRoute`; ``tau`` tensions,
    ``lam`` load factor of the disk weights; ``rtol``, ``atol`` DOP853's tolerances; ``chord_tol`` of the
    chord fixed point; ``out_s`` sorted arc lengths for dense output; DOP853's coefficients; the
    sections' constants (``s0s`` ... ``mu1s``), ``g`` (= ``lam`` x gravity) and the kernel's empty tendon
    arrays.  Returns ``(y(L) after the tip's tendon loads, status, tendon lengths (B, n_t), (chord
    iterations, right-hand sides), states at out_s (m, B*20))``; status 0 done, 1 too many evaluations on a segment, 2 step
    below 10 ulp, 3 the chords did not settle in :data:`MAX_CHORD_ITERATIONS`.
    """
    NS = N_EYELET_STATE
    B = y0.shape[0] // NS
    K = stations.shape[0] - 1
    n_t = tau.shape[0]
    y = y0.copy()
    at_all = np.zeros((out_s.shape[0], y0.shape[0]))
    P_prev = np.empty((B, n_t, 3))
    P = np.empty((B, n_t, 3))
    Pn = np.empty((B, n_t, 3))
    t_in = np.zeros((B, n_t, 3))
    t_out = np.zeros((B, n_t, 3))
    z = np.zeros((B, n_t, 3))
    z_prev = np.zeros((B, n_t, 3))
    g_prev = np.zeros((B, n_t, 3))
    lengths = np.zeros((B, n_t))
    seg_len = np.zeros((B, n_t))
    R_prev = np.zeros((B, 3, 3))
    for b in range(B):
        for i in range(n_t):
            for a in range(3):
                P_prev[b, i, a] = offsets[0, i, a]
        for a in range(3):
            R_prev[b, a, a] = 1.0
    iterations = 0
    nfev = 0
    mask = np.zeros(n_t, dtype=np.bool_)
    passing = np.zeros(n_t, dtype=np.bool_)
    for j in range(K + 1):
        for i in range(n_t):
            mask[i] = eyelet[j, i] and j > 0
            passing[i] = mask[i] and last[i] > j
        if j > 0:
            _arrive(y, B, lam * weights[j] if j < K else np.zeros(3), offsets[j], mask, passing, P, P_prev, t_in,
                    t_out, seg_len, lengths, R_prev)
        if j == K:
            _apply_disk(y, B, offsets[j], P, mask, tau, t_in, t_out, passing)
            break
        for b in range(B):
            for a in range(9):
                R_prev[b, a // 3, a % 3] = y[b * NS + 3 + a]
        lo = np.searchsorted(out_s, stations[j], side="left")
        hi = np.searchsorted(out_s, stations[j + 1], side="left") if j + 1 < K else out_s.shape[0]
        sec = section[j]
        y_start = y.copy()
        settled = False
        for q in range(MAX_CHORD_ITERATIONS):
            iterations += 1
            y = y_start.copy()
            _apply_disk(y, B, offsets[j], P, mask, tau, t_in, t_out, passing)
            yb, status, nf, at = kernel.dop853_segment(
                y, stations[j], stations[j + 1], rtol, atol, _MAX_EVALUATIONS, out_s[lo:hi], A, Bw, C, E3, E5,
                A_extra, C_extra, D, NS, s0s[sec], lss[sec], k0s[sec], k1s[sec], mu0s[sec], mu1s[sec], g,
                c, d0, d1, se, ta, dr, idx)
            nfev += nf
            if status != 0:
                return yb, status, lengths, (iterations, nfev), at_all
            at_all[lo:hi] = at
            if not np.any(passing):
                settled = True
                break
            _eyelet_points(yb, B, offsets[j + 1], Pn)
            z[:] = t_out
            if _chords(P_prev, Pn, passing, t_out, seg_len) <= chord_tol:
                settled = True
                break
            if q > 0:
                _anderson(z, t_out, z_prev, g_prev, passing)
            z_prev[:] = z
            g_prev[:] = t_out
        if not settled:
            return yb, 3, lengths, (iterations, nfev), at_all
        y = yb
    return y, 0, lengths, (iterations, nfev), at_all


def integrate_eyelets(pb: RodProblem, route: EyeletRoute, x0: np.ndarray, tau: np.ndarray, lam: float, rtol: float,
                      stations: np.ndarray | None = None, chord_tol: float | None = None,
                      compiled: bool | None = None) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Integrate ``B`` eyelet shots from the clamp to the tip.

    Parameters
    ----------
    x0 : ndarray, shape (B, 6)
        Rod force ``n(0)`` [N] and moment ``m(0)`` [N m] at the clamp, base frame.
    tau : ndarray, shape (n_t,)
        Tendon tensions [N].
    lam : float
        Load factor of gravity and the disk weights (tip loads are applied by the caller).
    rtol : float
        DOP853's relative tolerance; absolute ones scaled per state group as in
        :func:`~workbench.physics.cosserat.rod.integrate_segments`.
    stations : ndarray, shape (m,), optional
        Sorted arc lengths at which to return the states.
    chord_tol : float, optional
        Convergence of the chords (unit vectors); default ``rtol``.
    compiled : bool, optional
        ``False``: run :func:`eyelet_shots` as Python (its ``py_func``; the functions it calls stay
        compiled where numba is installed), checked against the compiled one by the tests.

    Returns
    -------
    tip : ndarray, shape (B, 20)
        States at s = L after the terminating tendons' loads there (before the disk weight at L,
        which the tip condition takes).
    at_stations : ndarray, shape (m, B, 20) or None
    lengths : ndarray, shape (B, n_t)
        Tendon path lengths (sums of the chords) [m].

    Raises
    ------
    RuntimeError
        A failed integration or chords that do not settle.
    """
    B = x0.shape[0]
    NS = N_EYELET_STATE
    y = np.zeros((B, NS))
    y[:, 3:12] = np.eye(3).reshape(9)
    y[:, 12:18] = x0
    L = pb.length
    fs = max(float(np.max(np.abs(x0[:, :3]), initial=0.0)), float(np.sum(tau)), 1e-9)
    ms = max(float(np.max(np.abs(x0[:, 3:]), initial=0.0)), fs * L)
    scale = np.concatenate([np.full(3, L), np.ones(9), np.full(3, fs), np.full(3, ms), np.full(2, L)])
    out_s = np.zeros(0) if stations is None else np.ascontiguousarray(stations, dtype=float)
    shots = eyelet_shots if compiled is None or compiled else getattr(eyelet_shots, "py_func", eyelet_shots)
    yb, status, lengths, _, at = shots(
        np.ascontiguousarray(y.reshape(-1)), route.stations, route.section, route.weights, route.eyelet,
        route.offsets, route.last, np.ascontiguousarray(tau, dtype=float), float(lam), float(rtol),
        rtol * np.tile(scale, B), float(rtol if chord_tol is None else chord_tol), out_s, *_DOP853,
        pb.section_starts, pb.section_lengths, np.ascontiguousarray(pb.stiffness0), np.ascontiguousarray(pb.stiffness1),
        pb.mass_per_length0, pb.mass_per_length1, np.asarray(lam * pb.gravity, dtype=float), *_NO_TENDON)
    if status == 1:
        raise RuntimeError(f"integration needs more than {_MAX_EVALUATIONS} evaluations on one segment")
    if status == 2:
        raise RuntimeError("cosserat: integration failed: the step size fell below 10 ulp of s")
    if status == 3:
        raise RuntimeError(f"cosserat: the tendon chords between two disks did not settle in {MAX_CHORD_ITERATIONS} "
                           "iterations")
    if not np.all(np.isfinite(yb)):
        raise RuntimeError("cosserat: non-finite state in the integration")
    return yb.reshape(B, NS), (None if stations is None else at.reshape(-1, B, NS)), lengths


def straight_tendon_wrench(route: EyeletRoute, tau: np.ndarray) -> np.ndarray:
    """``(6,)`` the tendons' share of the clamp's rod wrench ``(n(0), m(0))`` on the straight rod:
    each tendon pulls its terminating disk by ``-tau e3`` at its eyelet (the chords are parallel to
    the rod elsewhere); the Newton predictor adds it to the external loads' reaction."""
    out = np.zeros(6)
    e3 = np.array([0.0, 0.0, 1.0])
    for i, t in enumerate(np.asarray(tau, dtype=float)):
        F = -t * e3
        arm = route.offsets[route.last[i], i] + route.stations[route.last[i]] * e3
        out[:3] += F
        out[3:] += np.cross(arm, F)
    return out


def rod_wrench_from_total(route: EyeletRoute, x_total: np.ndarray, tau: np.ndarray, p1: np.ndarray,
                          R1: np.ndarray) -> np.ndarray:
    """``(6,)`` the rod's own clamp wrench from a total (rod + tendons) one ``x_total`` (the
    continuous model's unknowns) and that solution's pose ``p1``, ``R1`` at the first disk: each
    tendon's first chord ``t_0`` runs from its anchor ``r_0`` to ``p1 + R1 r_1``, so ``n = N - sum
    tau t_0``, ``m = M - sum r_0 x tau t_0``.  A predictor only (the rest of the shape is continuous)."""
    out = np.array(x_total, dtype=float)
    for i, t in enumerate(np.asarray(tau, dtype=float)):
        chord = p1 + R1 @ route.offsets[1, i] - route.offsets[0, i]
        F = t * chord / np.linalg.norm(chord)
        out[:3] -= F
        out[3:] -= np.cross(route.offsets[0, i], F)
    return out
