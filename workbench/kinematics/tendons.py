"""Tendon (cable) lengths of cylindrical constant-curvature sections and their inverses.

A tendon of section ``j`` is routed parallel to the backbone at distance ``d`` (m) and at
angle ``sigma`` (rad) from the section's base ``x`` axis; the disks are rigidly attached to
the backbone frames of :func:`~workbench.kinematics.forward_kinematics` (no torsion), so a
tendon keeps its angle ``sigma`` in every section it passes through.

For a constant-curvature arc bending towards ``phi`` (centre of curvature at
``(cos phi, sin phi, 0)/kappa``), a tendon is an arc of radius ``1/kappa - d cos(sigma - phi)``
through the same angle ``kappa ell``, hence (Webster & Jones 2010, robot-specific mapping of
tendon-driven robots)

``l = ell (1 - kappa d cos(sigma - phi))``:

the tendon on the inside of the bend (``sigma = phi``) is the shortest. The map is linear in
``(ell, ell kappa cos phi, ell kappa sin phi)``, which gives exact closed-form / least-squares
inverses.
"""

from __future__ import annotations

import numpy as np

from ._checks import as_float, broadcast_named, require_positive, section_arrays

__all__ = [
    "tendon_lengths_from_arc",
    "arc_from_tendon_lengths",
    "tendon_lengths_from_arcs",
    "arcs_from_tendon_lengths",
]


def _check_sigma(sigma, m_expected=None) -> np.ndarray:
    sigma = as_float("sigma", sigma)
    if sigma.ndim != 1 or sigma.size == 0:
        raise ValueError(f"sigma must be a 1-D array of tendon angles, shape (m,); got shape {sigma.shape}")
    if m_expected is not None and sigma.size != m_expected:
        raise ValueError(f"sigma has {sigma.size} angles but lengths has {m_expected} tendons (last axis)")
    return sigma


def tendon_lengths_from_arc(kappa, phi, ell, sigma, d) -> np.ndarray:
    """Tendon lengths of one constant-curvature section.

    Parameters
    ----------
    kappa, phi, ell : array_like, shape (...)
        Curvature [1/m], bending-plane angle [rad], arc length [m] (convention of
        :func:`~workbench.kinematics.section_transform`).
    sigma : array_like, shape (m,)
        Tendon angles from the base ``x`` axis [rad].
    d : float or array_like, shape (...)
        Tendon offset from the backbone [m], ``> 0``.

    Returns
    -------
    lengths : ndarray, shape (..., m)
        ``l_i = ell (1 - kappa d cos(sigma_i - phi))`` [m] (Webster & Jones 2010, robot-specific
        mapping of tendon-driven robots).

    Raises
    ------
    ValueError
        If ``|kappa| d >= 1`` (a tendon would pass through the centre of curvature).
    """
    k = as_float("kappa", kappa)
    f = as_float("phi", phi)
    ll = as_float("ell", ell)
    dd = as_float("d", d)
    require_positive("d", dd)
    if np.any(ll < 0):
        raise ValueError("ell must be >= 0 (arc length, m)")
    k, f, ll, dd = broadcast_named(kappa=k, phi=f, ell=ll, d=dd)
    if np.any(np.abs(k) * dd >= 1.0):
        raise ValueError("|kappa| * d must be < 1: a tendon cannot reach the centre of curvature")
    sig = _check_sigma(sigma)
    return ll[..., None] * (1.0 - (k * dd)[..., None] * np.cos(sig - f[..., None]))


def _equally_spaced(sigma: np.ndarray) -> bool:
    m = sigma.size
    if m < 3:
        return False
    rel = np.mod(sigma - sigma[0], 2 * np.pi)
    rel = np.sort(rel)
    return bool(np.allclose(rel, 2 * np.pi * np.arange(m) / m, rtol=0.0, atol=1e-12))


def arc_from_tendon_lengths(lengths, sigma, d, *, return_residual: bool = False):
    """Arc parameters of one section from its tendon lengths (inverse of
    :func:`tendon_lengths_from_arc`).

    Parameters
    ----------
    lengths : array_like, shape (..., m)
        Tendon lengths [m], ``m >= 3``.
    sigma : array_like, shape (m,)
        Tendon angles [rad]; must contain at least 3 non-collinear directions.
    d : float or array_like, shape (...)
        Tendon offset [m], ``> 0``.
    return_residual : bool
        Also return the RMS residual [m] of the fit (0 for consistent lengths).

    Returns
    -------
    kappa, phi, ell : ndarray, shape (...)
        ``kappa >= 0`` [1/m], ``phi`` in ``(-pi, pi]`` [rad] (0 when ``kappa = 0``), ``ell`` [m].
    residual : ndarray, shape (...), only if ``return_residual``

    Notes
    -----
    With ``a = ell kappa cos phi`` and ``b = ell kappa sin phi``,
    ``l_i = ell - d (a cos sigma_i + b sin sigma_i)`` is linear. For ``m >= 3`` equally spaced
    tendons (3 at 120 deg, 4 at 90 deg, ...) the least-squares solution is the closed form
    ``ell = mean(l)``, ``d a = -(2/m) sum l_i cos sigma_i``, ``d b = -(2/m) sum l_i sin sigma_i``;
    for general angles the 3-parameter linear least-squares problem is solved (pseudo-inverse).
    Then ``kappa = hypot(a, b)/ell``, ``phi = atan2(b, a)``.
    """
    L = as_float("lengths", lengths)
    if L.ndim == 0:
        raise ValueError("lengths must have shape (..., m) with m >= 3 tendons; got a scalar")
    m = L.shape[-1]
    sig = _check_sigma(sigma, m)
    if m < 3:
        raise ValueError(f"need at least 3 tendons to recover (kappa, phi, ell); got m = {m}")
    dd = as_float("d", d)
    require_positive("d", dd)
    A = np.stack([np.ones(m), -np.cos(sig), -np.sin(sig)], axis=-1)  # unknowns (ell, d a, d b)
    if _equally_spaced(sig):
        P = np.stack([np.full(m, 1.0 / m), -(2.0 / m) * np.cos(sig), -(2.0 / m) * np.sin(sig)])
    else:
        if np.linalg.matrix_rank(A, tol=1e-9) < 3:
            raise ValueError("sigma must contain at least 3 tendon directions not all on one line/pair")
        P = np.linalg.pinv(A)
    x = np.einsum("ij,...j->...i", P, L)
    ell = x[..., 0]
    if np.any(ell <= 0):
        raise ValueError("tendon lengths imply a non-positive backbone length (mean length <= 0)")
    ell_b, dd_b = broadcast_named(ell=ell, d=dd)
    a = x[..., 1] / dd_b
    b = x[..., 2] / dd_b
    theta = np.hypot(a, b)
    kappa = theta / ell_b
    phi = np.arctan2(b, a)
    if not return_residual:
        return kappa, phi, ell_b
    fit = np.einsum("ij,...j->...i", A, x)
    res = np.sqrt(np.mean((fit - L) ** 2, axis=-1))
    return kappa, phi, ell_b, res


def _check_multi(kappa, phi, ell, sigma, d):
    k, f, ll = section_arrays(kappa=kappa, phi=phi, ell=ell)
    if np.any(ll < 0):
        raise ValueError("ell must be >= 0 (arc length, m)")
    n = k.shape[-1]
    sig = as_float("sigma", sigma)
    if sig.ndim == 1:
        sig = np.broadcast_to(sig, (n, sig.size))
    if sig.ndim != 2 or sig.shape[0] != n or sig.shape[1] == 0:
        raise ValueError(f"sigma must have shape (m,) or (n_sections, m) = ({n}, m); got {np.shape(sigma)}")
    dd = as_float("d", d)
    if dd.ndim == 0:
        dd = np.full(n, float(dd))
    if dd.shape != (n,):
        raise ValueError(f"d must be a scalar or shape (n_sections,) = ({n},); got {dd.shape}")
    require_positive("d", dd)
    return k, f, ll, sig, dd


def tendon_lengths_from_arcs(kappa, phi, ell, sigma, d) -> np.ndarray:
    """Tendon lengths of a multi-section robot (tendons of section j run through sections 1..j).

    Parameters
    ----------
    kappa, phi, ell : array_like, shape (..., n)
        Per-section arc parameters (see :func:`~workbench.kinematics.forward_kinematics`).
    sigma : array_like, shape (m,) or (n, m)
        Angles [rad] of the ``m`` tendons terminating at the end of each section.
    d : float or array_like, shape (n,)
        Tendon offset [m] within each section (disk radius of the routing holes).

    Returns
    -------
    lengths : ndarray, shape (..., n, m)
        ``L[j, k] = sum_{i <= j} ell_i (1 - kappa_i d_i cos(sigma_jk - phi_i))`` [m].
    """
    k, f, ll, sig, dd = _check_multi(kappa, phi, ell, sigma, d)
    if np.any(np.abs(k) * dd >= 1.0):
        raise ValueError("|kappa_i| * d_i must be < 1: a tendon cannot reach the centre of curvature")
    n = k.shape[-1]
    # term[..., i, j, k]: contribution of section i to tendon k of section j
    term = ll[..., :, None, None] * (
        1.0 - (k * dd)[..., :, None, None] * np.cos(sig[None, :, :] - f[..., :, None, None])
    )
    mask = np.tril(np.ones((n, n)))  # mask[j, i] = 1 if i <= j
    return np.einsum("ji,...ijk->...jk", mask, term)


def arcs_from_tendon_lengths(lengths, sigma, d):
    """Inverse of :func:`tendon_lengths_from_arcs`, section by section from the base.

    Parameters
    ----------
    lengths : array_like, shape (..., n, m)
        Tendon lengths [m]; row ``j`` = tendons terminating at section ``j``, ``m >= 3``.
    sigma : array_like, shape (m,) or (n, m)
    d : float or array_like, shape (n,)

    Returns
    -------
    kappa, phi, ell : ndarray, shape (..., n)

    Notes
    -----
    Section 1 is recovered from its own tendons with :func:`arc_from_tendon_lengths`; for
    section ``j`` the (known) contributions of sections ``< j`` are subtracted first.
    """
    L = as_float("lengths", lengths)
    if L.ndim < 2:
        raise ValueError(f"lengths must have shape (..., n_sections, m); got {L.shape}")
    n, m = L.shape[-2:]
    sig = as_float("sigma", sigma)
    sig = np.broadcast_to(sig, (n, m)) if sig.ndim == 1 else sig
    if sig.shape != (n, m):
        raise ValueError(f"sigma must have shape (m,) or (n_sections, m) = ({n}, {m}); got {np.shape(sigma)}")
    dd = as_float("d", d)
    dd = np.full(n, float(dd)) if dd.ndim == 0 else dd
    if dd.shape != (n,):
        raise ValueError(f"d must be a scalar or shape (n_sections,) = ({n},); got {dd.shape}")
    batch = L.shape[:-2]
    K = np.empty(batch + (n,))
    P = np.empty(batch + (n,))
    E = np.empty(batch + (n,))
    for j in range(n):
        own = L[..., j, :].copy()
        for i in range(j):
            own -= E[..., i, None] * (1.0 - (K[..., i] * dd[i])[..., None] * np.cos(sig[j] - P[..., i, None]))
        K[..., j], P[..., j], E[..., j] = arc_from_tendon_lengths(own, sig[j], dd[j])
    return K, P, E
