"""The Cosserat rod's right-hand side and its DOP853 integration as a compiled kernel (numba, optional).

The same equations as the numpy right-hand side of :mod:`.rod` (the strain law with continuous
tendons solved by Newton, then ``p' = R v``, ``R' = R u^``, ``N' = -f``, ``M' = -p' x N``, the
centreline, twist and tendon lengths), written shot by shot with explicit loops so that numba
compiles it; the 6 x 6 Newton system of the strain law is solved by Gaussian elimination with
partial pivoting.  One difference in the iteration: each shot stops its strain Newton on its own
step (the numpy path stops the batch on the largest step), with the same criterion
``c delta^2 < 1e-16`` (see :func:`.rod.strains`), so both return the strains to round-off.

:func:`dop853_segment` integrates a segment with scipy's DOP853 algorithm (the same step control
and dense output as ``solve_ivp(method="DOP853")``, so the same steps to round-off) without a Python
call per step or per evaluation.

numba is an optional dependency: :data:`AVAILABLE` says whether it imported; without it the
model runs the numpy right-hand side (``tests/physics/test_cosserat_kernel.py`` checks that the two
paths give the same right-hand side and the same integration to round-off, and the same solves to
the tolerance).
"""

from __future__ import annotations

import numpy as np

try:  # optional: the numpy right-hand side in rod.py is the fallback
    from numba import njit
    AVAILABLE = True
except ImportError:  # pragma: no cover - depends on the environment
    AVAILABLE = False

    def njit(*args, **kwargs):  # noqa: ANN002, ANN003, D103 - identity decorator without numba
        if args and callable(args[0]):
            return args[0]
        return lambda f: f

__all__ = ["AVAILABLE", "segment_rhs", "dop853_segment"]


@njit(cache=True)
def _solve6(J, F):  # noqa: ANN001, ANN202
    """``J x = F`` for a 6 x 6 system by Gaussian elimination with partial pivoting (J, F overwritten)."""
    n = 6
    for k in range(n):
        p = k
        big = abs(J[k, k])
        for i in range(k + 1, n):
            if abs(J[i, k]) > big:
                big = abs(J[i, k])
                p = i
        if p != k:
            for j in range(n):
                J[k, j], J[p, j] = J[p, j], J[k, j]
            F[k], F[p] = F[p], F[k]
        piv = J[k, k]
        for i in range(k + 1, n):
            m = J[i, k] / piv
            if m != 0.0:
                for j in range(k + 1, n):
                    J[i, j] -= m * J[k, j]
                F[i] -= m * F[k]
    x = np.empty(n)
    for i in range(n - 1, -1, -1):
        acc = F[i]
        for j in range(i + 1, n):
            acc -= J[i, j] * x[j]
        x[i] = acc / J[i, i]
    return x


@njit(cache=True)
def _strain_system(nb, mb, kse, kbt, r, dr, ta, v, u, J, F):  # noqa: ANN001, ANN202
    """Residual ``F`` and Jacobian ``J`` of the strain law at ``(v, u)`` (written in place): R&W's
    ``[K_se + A, G; B, K_bt + H]`` (as the numpy :func:`.rod.strains`)."""
    J[:, :] = 0.0
    for a in range(3):
        F[a] = kse[a] * (v[a] - (1.0 if a == 2 else 0.0)) - nb[a]
        F[3 + a] = kbt[a] * u[a] - mb[a]
        J[a, a] = kse[a]
        J[3 + a, 3 + a] = kbt[a]
    t = np.empty(3)
    P = np.empty((3, 3))
    PR = np.empty((3, 3))
    RP = np.empty((3, 3))
    for i in range(ta.shape[0]):
        rx, ry, rz = r[i, 0], r[i, 1], r[i, 2]
        w0 = v[0] + u[1] * rz - u[2] * ry + dr[i, 0]
        w1 = v[1] + u[2] * rx - u[0] * rz + dr[i, 1]
        w2 = v[2] + u[0] * ry - u[1] * rx + dr[i, 2]
        nw = np.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
        t[0], t[1], t[2] = w0 / nw, w1 / nw, w2 / nw
        ti = ta[i]
        F[0] += ti * t[0]
        F[1] += ti * t[1]
        F[2] += ti * t[2]
        F[3] += ti * (ry * t[2] - rz * t[1])
        F[4] += ti * (rz * t[0] - rx * t[2])
        F[5] += ti * (rx * t[1] - ry * t[0])
        c = ti / nw
        for a in range(3):
            for b in range(3):
                P[a, b] = c * ((1.0 if a == b else 0.0) - t[a] * t[b])
        # P r^ (column b of r^ is r x e_b) and r^ P (row a of r^ is (e_a x r)^T... written out)
        for a in range(3):
            PR[a, 0] = P[a, 1] * rz - P[a, 2] * ry
            PR[a, 1] = P[a, 2] * rx - P[a, 0] * rz
            PR[a, 2] = P[a, 0] * ry - P[a, 1] * rx
        for b in range(3):
            RP[0, b] = ry * P[2, b] - rz * P[1, b]
            RP[1, b] = rz * P[0, b] - rx * P[2, b]
            RP[2, b] = rx * P[1, b] - ry * P[0, b]
        for a in range(3):
            for b in range(3):
                J[a, b] += P[a, b]
                J[a, 3 + b] -= PR[a, b]
                J[3 + a, b] += RP[a, b]
        # r^ P r^ = (r^ P) r^
        for a in range(3):
            J[3 + a, 3] -= RP[a, 1] * rz - RP[a, 2] * ry
            J[3 + a, 4] -= RP[a, 2] * rx - RP[a, 0] * rz
            J[3 + a, 5] -= RP[a, 0] * ry - RP[a, 1] * rx


@njit(cache=True)
def _strains(nb, mb, kse, kbt, r, dr, ta, v, u, w):  # noqa: ANN001, ANN202, PLR0912, PLR0915
    """Strains ``v``, ``u`` and tendon tangents ``w`` (written in place) of one section; as
    :func:`.rod.strains` for one shot."""
    k = ta.shape[0]
    tsum = 0.0
    mx = 0.0
    my = 0.0
    loaded = False
    for i in range(k):
        tsum += ta[i]
        mx += ta[i] * r[i, 1]
        my -= ta[i] * r[i, 0]
        if ta[i] > 0.0:
            loaded = True
    for a in range(3):
        v[a] = nb[a] / kse[a]
    v[2] = 1.0 + (nb[2] - tsum) / kse[2]
    u[0] = (mb[0] - mx) / kbt[0]
    u[1] = (mb[1] - my) / kbt[1]
    u[2] = mb[2] / kbt[2]
    if loaded:
        arm = 1e-12
        for i in range(k):
            for a in range(3):
                arm = max(arm, abs(r[i, a]))
        contraction = tsum / min(min(kse[0], min(kse[1], kse[2])), min(kbt[0], kbt[1]) / arm**2, kbt[2] / arm**2)
        J = np.empty((6, 6))
        F = np.empty(6)
        for _ in range(8):
            _strain_system(nb, mb, kse, kbt, r, dr, ta, v, u, J, F)
            for a in range(6):
                F[a] = -F[a]
            dx = _solve6(J, F)
            delta = 0.0
            for a in range(3):
                v[a] += dx[a]
                u[a] += dx[3 + a]
                delta = max(delta, abs(dx[a]), abs(dx[3 + a]) * arm)
            if contraction * delta * delta < 1e-16:
                break
    for i in range(k):
        w[i, 0] = v[0] + u[1] * r[i, 2] - u[2] * r[i, 1] + dr[i, 0]
        w[i, 1] = v[1] + u[2] * r[i, 0] - u[0] * r[i, 2] + dr[i, 1]
        w[i, 2] = v[2] + u[0] * r[i, 1] - u[1] * r[i, 0] + dr[i, 2]


@njit(cache=True)
def segment_rhs(s, y, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx):  # noqa: ANN001, ANN201, PLR0913
    """``y'`` of a batch of shots (flat ``y``, ``n_state`` per shot) on one segment; the arguments
    are those of :func:`.rod.segment_rhs` (``c``, ``d0``, ``d1``, ``se``, ``ta``, ``dr``, ``idx``:
    the tendons present on the segment)."""
    B = y.shape[0] // n_state
    out = np.zeros_like(y)
    f = (s - s0) / ls
    kse = np.empty(3)
    kbt = np.empty(3)
    for a in range(3):
        kse[a] = k0[a] + (k1[a] - k0[a]) * f
        kbt[a] = k0[3 + a] + (k1[3 + a] - k0[3 + a]) * f
    mu = mu0 + (mu1 - mu0) * f
    k = ta.shape[0]
    r = np.empty((k, 3))
    for i in range(k):
        d = d0[i] + (d1[i] - d0[i]) * s / se[i]
        for a in range(3):
            r[i, a] = d * c[i, a]
    nb = np.empty(3)
    mb = np.empty(3)
    v = np.empty(3)
    u = np.empty(3)
    w = np.empty((k, 3))
    dp = np.empty(3)
    for b in range(B):
        o = b * n_state
        # R row-major at y[o+3 : o+12]: R[i, j] = y[o + 3 + 3 i + j]
        for j in range(3):
            nb[j] = 0.0
            mb[j] = 0.0
            for i in range(3):
                nb[j] += y[o + 3 + 3 * i + j] * y[o + 12 + i]
                mb[j] += y[o + 3 + 3 * i + j] * y[o + 15 + i]
        _strains(nb, mb, kse, kbt, r, dr, ta, v, u, w)
        for i in range(3):
            Ri0, Ri1, Ri2 = y[o + 3 + 3 * i], y[o + 4 + 3 * i], y[o + 5 + 3 * i]
            dp[i] = Ri0 * v[0] + Ri1 * v[1] + Ri2 * v[2]
            out[o + i] = dp[i]
            # R' = R u^: column j of R' is R (u x e_j)
            out[o + 3 + 3 * i] = Ri1 * u[2] - Ri2 * u[1]
            out[o + 4 + 3 * i] = Ri2 * u[0] - Ri0 * u[2]
            out[o + 5 + 3 * i] = Ri0 * u[1] - Ri1 * u[0]
            out[o + 12 + i] = -mu * g[i]
        N0, N1, N2 = y[o + 12], y[o + 13], y[o + 14]
        out[o + 15] = -(dp[1] * N2 - dp[2] * N1)
        out[o + 16] = -(dp[2] * N0 - dp[0] * N2)
        out[o + 17] = -(dp[0] * N1 - dp[1] * N0)
        out[o + 18] = np.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        out[o + 19] = u[2]
        for i in range(k):
            out[o + 20 + idx[i]] = np.sqrt(w[i, 0] ** 2 + w[i, 1] ** 2 + w[i, 2] ** 2)
    return out


@njit(cache=True)
def _rms(x, scale):  # noqa: ANN001, ANN202
    acc = 0.0
    for i in range(x.shape[0]):
        q = x[i] / scale[i]
        acc += q * q
    return np.sqrt(acc / x.shape[0])


@njit(cache=True)
def _initial_step(y, f, t, interval, rtol, atol,  # noqa: ANN001, ANN202, PLR0913
                  n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx):
    """scipy's ``select_initial_step`` for DOP853 (error order 7; Hairer, Norsett & Wanner II.4)."""
    scale = atol + np.abs(y) * rtol
    dd0 = _rms(y, scale)
    dd1 = _rms(f, scale)
    h0 = 1e-6 if (dd0 < 1e-5 or dd1 < 1e-5) else 0.01 * dd0 / dd1
    h0 = min(h0, interval)
    f1 = segment_rhs(t + h0, y + h0 * f, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
    dd2 = _rms(f1 - f, scale) / h0
    if dd1 <= 1e-15 and dd2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(dd1, dd2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, interval)


@njit(cache=True)
def _stage_state(y, K, a, s, h):  # noqa: ANN001, ANN202
    """The state of a Runge-Kutta stage: ``y + h sum_j a[j] K[j]`` over the first ``s`` stages (zeros skipped)."""
    ys = y.copy()
    n = y.shape[0]
    for j in range(s):
        aj = a[j] * h
        if aj != 0.0:
            for i in range(n):
                ys[i] += aj * K[j, i]
    return ys


@njit(cache=True)
def _rk_step(K, y, f, t, h, A, Bw, C, y_new,  # noqa: ANN001, ANN202, PLR0913
             n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx):
    """One explicit Runge-Kutta step (scipy's ``rk_step``): stages into ``K``, ``y_new``; returns ``f(t+h, y_new)``."""
    n = y.shape[0]
    n_stages = C.shape[0]
    K[0, :] = f
    for s in range(1, n_stages):
        ys = _stage_state(y, K, A[s], s, h)
        K[s, :] = segment_rhs(t + C[s] * h, ys, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
    for i in range(n):
        acc = 0.0
        for j in range(n_stages):
            acc += K[j, i] * Bw[j]
        y_new[i] = y[i] + h * acc
    f_new = segment_rhs(t + h, y_new, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
    K[n_stages, :] = f_new
    return f_new


@njit(cache=True)
def _error_norm(K, y, y_new, h, rtol, atol, E3, E5):  # noqa: ANN001, ANN202
    """DOP853's error norm (scipy's ``DOP853._estimate_error_norm``: the 5th- and 3rd-order estimates)."""
    n = y.shape[0]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        sc = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
        q5 = 0.0
        q3 = 0.0
        for j in range(E5.shape[0]):
            q5 += K[j, i] * E5[j]
            q3 += K[j, i] * E3[j]
        e5 += (q5 / sc) ** 2
        e3 += (q3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / np.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True)
def dop853_segment(y0, a, b, rtol, atol, max_evaluations, stations, A, Bw, C, E3, E5, A_extra, C_extra, D,  # noqa: ANN001, ANN201, PLR0912, PLR0913, PLR0915
                   n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx):
    """Integrate ``y' = segment_rhs(s, y, ...)`` from ``s = a`` to ``b`` with DOP853: the step
    control of scipy's :class:`scipy.integrate.DOP853` (Hairer, Norsett & Wanner, Sec. II.4 initial
    step, II.10 error estimate; safety 0.9, factors 0.2 ... 10, exponent -1/8) and its 7th-order
    dense output at the sorted ``stations`` in ``[a, b]``, the same steps and values as
    ``solve_ivp(method="DOP853", t_eval=stations)`` up to round-off; ``A`` ... ``D`` are that class's
    coefficients.  Returns ``(y(b), status, evaluations, y(stations))``: status 0 done, 1 more than
    ``max_evaluations`` right-hand sides, 2 step size below 10 ulp of ``s``."""
    n = y0.shape[0]
    n_stages = C.shape[0]
    K = np.empty((n_stages + 1 + C_extra.shape[0], n))
    at = np.empty((stations.shape[0], n))
    js = 0
    y = y0.copy()
    t = a
    f = segment_rhs(t, y, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
    nfev = 1
    h_abs = _initial_step(y, f, t, b - a, rtol, atol, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr,
                          idx)
    nfev += 1
    y_new = np.empty(n)
    while t < b:
        min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
        if h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if h_abs < min_step:
                return y, 2, nfev, at
            t_new = t + h_abs
            if t_new - b > 0:
                t_new = b
            h = t_new - t
            h_abs = abs(h)
            if nfev + n_stages > max_evaluations:
                return y, 1, nfev, at
            f_new = _rk_step(K, y, f, t, h, A, Bw, C, y_new,
                             n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
            nfev += n_stages
            err = _error_norm(K, y, y_new, h, rtol, atol, E3, E5)
            if err < 1.0:
                factor = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            # a non-finite error (a diverging shot) shrinks the step like scipy's max(0.2, nan) = 0.2
            shrink = 0.9 * err ** (-1.0 / 8.0)
            h_abs *= shrink if shrink > 0.2 else 0.2
            rejected = True
        if js < stations.shape[0] and stations[js] <= t_new:
            _dense(K, y, y_new, f, f_new, t, h, stations, js, at, A_extra, C_extra, D, n_stages,
                   n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx)
            nfev += C_extra.shape[0]
            while js < stations.shape[0] and stations[js] <= t_new:
                js += 1
        t = t_new
        y[:] = y_new
        f = f_new
    return y, 0, nfev, at


@njit(cache=True)
def _dense(K, y, y_new, f, f_new, t, h, stations, js, at, A_extra, C_extra, D, n_stages,  # noqa: ANN001, ANN202, PLR0913
           n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr, idx):
    """DOP853's dense output over the step ``[t, t + h]`` (scipy's ``Dop853DenseOutput``: three
    extra stages, a degree-7 polynomial in Horner form), written into ``at`` from row ``js`` for
    every station in the step."""
    n = y.shape[0]
    for e in range(C_extra.shape[0]):
        s = n_stages + 1 + e
        ys = _stage_state(y, K, A_extra[e], s, h)
        K[s, :] = segment_rhs(t + C_extra[e] * h, ys, n_state, s0, ls, k0, k1, mu0, mu1, g, c, d0, d1, se, ta, dr,
                              idx)
    F = np.empty((3 + D.shape[0], n))
    for i in range(n):
        dy = y_new[i] - y[i]
        F[0, i] = dy
        F[1, i] = h * f[i] - dy
        F[2, i] = 2.0 * dy - h * (f_new[i] + f[i])
    for r in range(D.shape[0]):
        for i in range(n):
            acc = 0.0
            for j in range(K.shape[0]):
                acc += D[r, j] * K[j, i]
            F[3 + r, i] = h * acc
    while js < stations.shape[0] and stations[js] <= t + h:
        x = (stations[js] - t) / h
        for i in range(n):
            acc = 0.0
            for q in range(F.shape[0]):
                acc += F[F.shape[0] - 1 - q, i]
                acc *= x if q % 2 == 0 else 1.0 - x
            at[js, i] = acc + y[i]
        js += 1
