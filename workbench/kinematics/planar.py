"""Planar constant-curvature kinematics of Hannan & Walker (papers/000_, Eq. 6-9, App. A-B).

Convention of the paper (Eq. 6, D-H frames of Fig. 4): each section is a rotation about the
planar ``z`` axis by ``omega = kappa l`` plus the chord; the section starts along the planar
``+y`` axis and, for ``kappa > 0``, bends towards ``-x``:

``A = [[cos w, -sin w, 0, (cos w - 1)/kappa], [sin w, cos w, 0, sin w/kappa], [0, 0, 1, 0],
[0, 0, 0, 1]]``.

Mapping to the spatial model of :mod:`.arc` (base tangent ``z``): with the constant proper
rotation ``M`` taking spatial ``(x, y, z)`` to planar ``(x, z, -y)``,

``A(kappa, l) = M . T_spatial(kappa, phi = pi, l) . M^T = M . T_spatial(-kappa, phi = 0, l) . M^T``,

i.e. the planar model is the spatial one restricted to ``phi in {0, pi}`` (planar curvature
``kappa`` = spatial ``(kappa, pi)`` or ``(-kappa, 0)``); see :func:`spatial_from_planar`.

Everything is evaluated with ``(1 - cos x)/x`` and ``sin x/x`` so ``kappa -> 0`` is exact.
"""

from __future__ import annotations

import numpy as np

from ._series import dsinc, dversinc, sinc, versinc
from ._checks import as_float, require_nonnegative, section_arrays

__all__ = [
    "planar_forward_kinematics",
    "planar_jacobian",
    "spatial_from_planar",
    "planar_from_spatial_transform",
]


def _check(kappa, ell):
    k, ll = section_arrays(kappa=kappa, ell=ell)
    require_nonnegative("ell", ll)
    return k, ll


def _planar_chain(k, ll):
    """Section-end points (..., n, 2), cumulative angles (..., n), per-section omega."""
    w = k * ll
    Om = np.cumsum(w, axis=-1)
    Om_prev = Om - w
    lx = -ll * versinc(w)  # (cos w - 1)/kappa
    ly = ll * sinc(w)  # sin w / kappa
    c, s = np.cos(Om_prev), np.sin(Om_prev)
    dx = c * lx - s * ly
    dy = s * lx + c * ly
    ends = np.stack([np.cumsum(dx, axis=-1), np.cumsum(dy, axis=-1)], axis=-1)
    return ends, Om, Om_prev, w


def planar_forward_kinematics(kappa, ell) -> np.ndarray:
    """End frame of a planar chain of constant-curvature sections (Hannan & Walker Eq. 6-7).

    Parameters
    ----------
    kappa : array_like, shape (..., n)
        Section curvatures [1/m] (``kappa > 0`` bends towards planar ``-x``).
    ell : array_like, shape (..., n)
        Section arc lengths [m], ``>= 0``. For the last section any ``0 <= l <= l_n`` gives the
        corresponding point of that section (paper, after Eq. 7).

    Returns
    -------
    A : ndarray, shape (..., 4, 4)
        ``A_0^{3n} = prod_i A_i`` (Eq. 6 per section); for ``n = 4`` its entries equal App. A:
        ``A11 = cos(sum w)``, ``A14 = sum_j (cos W_j - cos W_{j-1})/kappa_j``,
        ``A24 = sum_j (sin W_j - sin W_{j-1})/kappa_j`` with ``W_j = w_1 + ... + w_j``,
        ``w_j = kappa_j l_j`` (evaluated without dividing by ``kappa``).
    """
    k, ll = _check(kappa, ell)
    return planar_fk_unchecked(k, ll)


def planar_fk_unchecked(k, ll):
    """:func:`planar_forward_kinematics` without input checks."""
    ends, Om, _, _ = _planar_chain(k, ll)
    W = Om[..., -1]
    out = np.zeros(k.shape[:-1] + (4, 4))
    out[..., 0, 0] = np.cos(W)
    out[..., 0, 1] = -np.sin(W)
    out[..., 1, 0] = np.sin(W)
    out[..., 1, 1] = np.cos(W)
    out[..., 2, 2] = 1.0
    out[..., 3, 3] = 1.0
    out[..., :2, 3] = ends[..., -1, :]
    return out


def planar_jacobian(kappa, ell) -> np.ndarray:
    """Curvature Jacobian of the planar tip position (Hannan & Walker Eq. 8-9, App. B corrected).

    Parameters
    ----------
    kappa, ell : array_like, shape (..., n)
        See :func:`planar_forward_kinematics`.

    Returns
    -------
    J : ndarray, shape (..., 2, n)
        ``[xdot, ydot]^T = J [kappa_1dot, ..., kappa_ndot]^T`` (arc lengths fixed); columns are
        the curvatures in section order, units m / (1/m) = m^2.

    Notes
    -----
    Differentiating App. A (``W_j = w_1 + ... + w_j``, ``dW_j/dkappa_i = l_i`` for ``j >= i``):

    ``J_1i = -(cos W_i - cos W_{i-1})/kappa_i^2 - l_i sin W_i / kappa_i
    + sum_{j>i} l_i (sin W_{j-1} - sin W_j)/kappa_j``

    ``J_2i = -(sin W_i - sin W_{i-1})/kappa_i^2 + l_i cos W_i / kappa_i
    + sum_{j>i} l_i (cos W_j - cos W_{j-1})/kappa_j``

    **Erratum** (checked against central finite differences in the tests): the printed
    App. B has three sign errors --

    * ``J12``: printed ``(-cos(w1+w2) - cos w1)/k2^2``; correct ``(-cos(w1+w2) + cos w1)/k2^2``;
    * ``J21``: printed ``- l1 cos w1 / k1``; correct ``+ l1 cos w1 / k1``;
    * ``J22``: printed ``(-sin(w1+w2) - sin w1)/k2^2``; correct ``(-sin(w1+w2) + sin w1)/k2^2``.

    The implementation does not use the ``1/kappa`` form: column ``i`` is evaluated as
    ``Rot(W_{i-1}) l_i^2 (-g'(w_i), f'(w_i)) + l_i e_z x (p_tip - p_i)`` with
    ``g = (1 - cos x)/x``, ``f = sin x/x`` and ``p_i`` the end of section ``i``, which is
    identical for ``kappa != 0`` and smooth through ``kappa = 0``.
    """
    k, ll = _check(kappa, ell)
    return planar_jacobian_unchecked(k, ll)


def planar_jacobian_unchecked(k, ll):
    """:func:`planar_jacobian` without input checks."""
    ends, Om, Om_prev, w = _planar_chain(k, ll)
    tip = ends[..., -1:, :]
    l2 = ll * ll
    ax = -l2 * dversinc(w)
    ay = l2 * dsinc(w)
    c, s = np.cos(Om_prev), np.sin(Om_prev)
    lever = tip - ends  # (..., n, 2)
    jx = c * ax - s * ay - ll * lever[..., 1]
    jy = s * ax + c * ay + ll * lever[..., 0]
    return np.stack([jx, jy], axis=-2)


def spatial_from_planar(kappa, ell):
    """Spatial arc parameters equivalent to planar Hannan & Walker curvatures.

    Parameters
    ----------
    kappa, ell : array_like, shape (..., n)
        Planar curvatures [1/m] and arc lengths [m].

    Returns
    -------
    kappa_s, phi_s, ell_s : ndarray, shape (..., n)
        ``(kappa, pi, ell)``: with these, ``forward_kinematics(kappa_s, phi_s, ell_s)`` equals
        :func:`planar_forward_kinematics` after :func:`planar_from_spatial_transform`.
        (``(-kappa, 0, ell)`` is the same configuration.)
    """
    k, ll = _check(kappa, ell)
    return k.copy(), np.full_like(k, np.pi), ll.copy()


def _m_matrix():
    M = np.zeros((4, 4))
    M[0, 0] = 1.0  # x_p = x_s
    M[1, 2] = 1.0  # y_p = z_s
    M[2, 1] = -1.0  # z_p = -y_s
    M[3, 3] = 1.0
    return M


def planar_from_spatial_transform(T) -> np.ndarray:
    """Express a spatial-model transform in the planar Hannan & Walker axes.

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)
        Homogeneous transform in the spatial convention of :mod:`.arc` (tangent ``z``).

    Returns
    -------
    A : ndarray, shape (..., 4, 4)
        ``M T M^T`` with ``M``: spatial ``(x, y, z)`` -> planar ``(x, z, -y)`` (a proper
        rotation, ``det M = 1``).
    """
    T = as_float("T", T)
    if T.ndim < 2 or T.shape[-2:] != (4, 4):
        raise ValueError(f"T must have shape (..., 4, 4); got {T.shape}")
    M = _m_matrix()
    return M @ T @ M.T
