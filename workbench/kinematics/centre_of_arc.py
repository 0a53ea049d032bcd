"""Shao et al. centre-of-arc kinematics (papers/002_, Eq. 1-5), ``q = [s, k, phi]``.

For grasping by wrapping, Shao et al. describe a section (arc length ``s``, curvature ``k``,
bending direction ``phi``; same convention as :func:`~workbench.kinematics.section_transform`)
by the frame ``O_1`` at its centre of curvature:

* origin ``(cos phi, sin phi, 0) / k`` (Eq. 2);
* ``x_1``: unit vector from the arc midpoint to the centre,
  ``(cos phi cos(ks/2), sin phi cos(ks/2), -sin(ks/2))``;
* ``z_1``: normal of the bending plane, ``(-sin phi, cos phi, 0)``; ``y_1 = z_1 x x_1``;

which is Eq. 1/3: ``R = Rz(phi) M(ks/2)``, ``M(b) = [[cos b, -sin b, 0], [0, 0, 1],
[-sin b, -cos b, 0]]`` (checked: orthonormal, ``det = +1``).

Singularity: at ``k = 0`` the centre is at infinity (the paper's only singular
configuration). The position and the linear-velocity Jacobian are then undefined; the
functions raise :class:`SingularConfiguration` (a ``ValueError``) by default, or, with
``on_singular="nan"``, return NaN in exactly the undefined entries (useful for batches).
The orientation and the angular-velocity Jacobian stay finite.
"""

from __future__ import annotations

import numpy as np

from ._checks import as_float, broadcast_named

__all__ = ["SingularConfiguration", "centre_of_arc_pose", "centre_of_arc_jacobian"]


class SingularConfiguration(ValueError):
    """The configuration is singular for the requested quantity (e.g. ``k = 0`` for the
    centre of curvature). ``indices`` holds the offending batch indices (tuple of arrays)."""

    def __init__(self, message: str, indices=None):
        super().__init__(message)
        self.indices = indices


def _prepare(s, k, phi, on_singular, k_tol):
    if on_singular not in ("raise", "nan"):
        raise ValueError(f"on_singular must be 'raise' or 'nan'; got {on_singular!r}")
    s = as_float("s", s)
    k = as_float("k", k)
    phi = as_float("phi", phi)
    if np.any(s < 0):
        raise ValueError("s (arc length, m) must be >= 0")
    if k_tol < 0:
        raise ValueError("k_tol must be >= 0")
    s, k, phi = broadcast_named(s=s, k=k, phi=phi)
    sing = (np.abs(k) <= k_tol) | (np.abs(k) < 1e-150)  # 1/k^2 would overflow
    if on_singular == "raise" and np.any(sing):
        idx = np.nonzero(np.atleast_1d(sing)) if sing.ndim == 0 else np.nonzero(sing)
        first = tuple(int(i[0]) for i in idx) if sing.ndim else ()
        raise SingularConfiguration(
            f"centre of arc undefined for |k| <= {k_tol:g} 1/m (straight section): "
            f"{int(sing.sum())} configuration(s), first at batch index {first}; "
            "pass on_singular='nan' to get NaN there instead",
            indices=idx,
        )
    k_safe = np.where(sing, 1.0, k)
    return s, k, phi, sing, k_safe


def centre_of_arc_pose(s, k, phi, *, on_singular: str = "raise", k_tol: float = 0.0) -> np.ndarray:
    """Pose of the centre-of-arc frame ``O_1`` in the section base frame (Shao Eq. 1-3).

    Parameters
    ----------
    s : array_like, shape (...)
        Arc length [m], ``>= 0``.
    k : array_like, shape (...)
        Curvature [1/m]; ``|k| <= k_tol`` is singular.
    phi : array_like, shape (...)
        Bending direction [rad].
    on_singular : {"raise", "nan"}
        Raise :class:`SingularConfiguration`, or put NaN into the position column.
    k_tol : float
        Curvatures with ``|k| <= k_tol`` are treated as singular (default: only ``k = 0``;
        ``|k| < 1e-150`` always is, as ``1/k^2`` would overflow).

    Returns
    -------
    T : ndarray, shape (..., 4, 4)
        ``[[R, x], [0, 1]]`` with ``R`` from Eq. 1 and ``x = (cos phi, sin phi, 0)/k`` (Eq. 2) [m].
    """
    s, k, phi, sing, k_safe = _prepare(s, k, phi, on_singular, k_tol)
    b = 0.5 * k * s
    cb, sb = np.cos(b), np.sin(b)
    cp, sp = np.cos(phi), np.sin(phi)
    T = np.zeros(k.shape + (4, 4))
    T[..., 0, 0] = cp * cb
    T[..., 0, 1] = -cp * sb
    T[..., 0, 2] = -sp
    T[..., 1, 0] = sp * cb
    T[..., 1, 1] = -sp * sb
    T[..., 1, 2] = cp
    T[..., 2, 0] = -sb
    T[..., 2, 1] = -cb
    pos = np.stack([cp / k_safe, sp / k_safe, np.zeros_like(k)], axis=-1)
    T[..., :3, 3] = np.where(sing[..., None], np.nan, pos)
    T[..., 3, 3] = 1.0
    return T


def centre_of_arc_jacobian(s, k, phi, *, on_singular: str = "raise", k_tol: float = 0.0) -> np.ndarray:
    """Jacobian of the centre-of-arc frame w.r.t. ``q = [s, k, phi]`` (Shao Eq. 4-5, corrected).

    Parameters
    ----------
    s, k, phi, on_singular, k_tol
        See :func:`centre_of_arc_pose`.

    Returns
    -------
    J : ndarray, shape (..., 6, 3)
        Rows 0-2: ``J_v = dx/dq`` [m per unit of q]; rows 3-5: ``J_w``, angular velocity
        ``[w]x = Rdot R^T`` in the base frame. Columns ``(s, k, phi)``.

        ``J_v = [[0, -cos phi / k^2, -sin phi / k], [0, -sin phi / k^2, cos phi / k], [0, 0, 0]]``

        ``J_w = [[-k sin phi / 2, -s sin phi / 2, 0], [k cos phi / 2, s cos phi / 2, 0], [0, 0, 1]]``

    Notes
    -----
    **Errata.** Eq. 5 as printed gives the ``phi`` column of ``J_v`` as zero; differentiating
    Eq. 2 gives ``(-sin phi, cos phi, 0)/k``. The printed ``J_w`` is a 9x3 array of
    elementwise derivatives ``dR_ij/dq`` (not an angular-velocity Jacobian) and also carries
    sign slips (e.g. ``dR_11/ds = -k cos phi sin(ks/2)/2``, printed with ``+``). Here
    ``J_w`` is the angular-velocity Jacobian: the frame rotates about the bending-plane normal
    ``z_1`` at rate ``d(ks/2)`` and about the base ``z`` axis at rate ``d phi``. Both blocks
    are checked against central finite differences in the tests. The Jacobian has full rank 3
    for every ``k != 0``; at ``k = 0`` ``J_v`` is undefined (see module docs).
    """
    s, k, phi, sing, k_safe = _prepare(s, k, phi, on_singular, k_tol)
    cp, sp = np.cos(phi), np.sin(phi)
    J = np.zeros(k.shape + (6, 3))
    Jv_k = np.stack([-cp / k_safe**2, -sp / k_safe**2, np.zeros_like(k)], axis=-1)
    Jv_p = np.stack([-sp / k_safe, cp / k_safe, np.zeros_like(k)], axis=-1)
    J[..., :3, 1] = np.where(sing[..., None], np.nan, Jv_k)
    J[..., :3, 2] = np.where(sing[..., None], np.nan, Jv_p)
    J[..., :3, 0] = np.where(sing[..., None], np.nan, 0.0)
    J[..., 3, 0] = -0.5 * k * sp
    J[..., 4, 0] = 0.5 * k * cp
    J[..., 3, 1] = -0.5 * s * sp
    J[..., 4, 1] = 0.5 * s * cp
    J[..., 5, 2] = 1.0
    return J
