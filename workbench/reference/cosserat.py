"""Cosserat-rod statics by shooting: an independent reference for the geometrically exact beam.

Huang et al. (Biomimetics 2022, 7, 228) model each flexible leg of their parallel module as a
Cosserat rod (their Eq 18-20).  With ``p(s)`` the centreline, ``R(s)`` the cross-section frame
(material axis 3 = tangent in the straight reference state), ``n(s)``, ``m(s)`` the internal force
and moment in the global frame, ``f``, ``l`` distributed force and moment per length:

.. math::

    p' = R v, \\qquad R' = R \\hat u                                   \\qquad (18)

    n' = -f, \\qquad m' = -p' \\times n - l                              \\qquad (19)

    n = R K_{se} (v - v^*), \\quad m = R K_{bt} (u - u^*)                \\qquad (20)

with ``K_se = diag(GA, GA, EA)``, ``K_bt = diag(EI, EI, GJ)``, ``v* = (0, 0, 1)``, ``u* = 0``.

Errata / extraction notes (checked numerically in ``tests/reference/test_cosserat.py``):

* Eq 19 lost its signs in the extraction; the form above is the classical one (equilibrium of a
  segment [s, L] under the internal force of the proximal part) and is what reproduces the
  pure-moment arc and the Euler-Bernoulli tip deflection.
* Eq 20 in the paper premultiplies by ``R``; the internal force/moment are global vectors, so the
  inverse relations ``v = v* + K_se^{-1} R^T n`` and ``u = u* + K_bt^{-1} R^T m`` are integrated.
* No shear correction factor: ``GA`` uses the full area, as in the paper's ``K_se``.

The boundary-value problem is solved by shooting: the unknown base force and moment (and,
for a base that is free to rotate about its tangent, the base twist angle) are found by
``scipy.optimize.least_squares`` so that the tip conditions hold; every shot is one
``scipy.integrate.solve_ivp`` (DOP853) integration.  Large deformations are reached by
continuation over the tip load or tip pose (``n_steps``).

No Exudyn here: this module is the independent check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation, Slerp

from ..robot.description import circular_section

__all__ = [
    "RodStiffness",
    "RodSolution",
    "integrate_cosserat_rod",
    "solve_rod_tip_wrench",
    "solve_rod_tip_pose",
    "rotation_log",
]


@dataclass(frozen=True)
class RodStiffness:
    """Linear constitutive law of a rod with an isotropic cross-section (Eq 20).

    Parameters
    ----------
    EA : float
        Axial stiffness [N].
    GA : float
        Shear stiffness [N] (no shear correction factor, as in Huang et al.).
    EI : float
        Bending stiffness about both cross-section axes [N m^2].
    GJ : float
        Torsional stiffness [N m^2].
    """

    EA: float
    GA: float
    EI: float
    GJ: float

    def __post_init__(self) -> None:
        for name in ("EA", "GA", "EI", "GJ"):
            v = float(getattr(self, name))
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"RodStiffness.{name} must be finite and > 0, got {v!r}")
            object.__setattr__(self, name, v)

    @classmethod
    def circular(cls, diameter: float, youngs_modulus: float, shear_modulus: float) -> "RodStiffness":
        """Solid circular section: ``A = pi d^2/4``, ``I = pi d^4/64``, ``J = pi d^4/32`` (Eq 15).

        Areas from :func:`workbench.robot.description.circular_section`, the formula shared with
        ``CrossSection.circular`` and the series-parallel ``ModuleGeometry.rod_params``.
        """
        d = float(diameter)
        if not (math.isfinite(d) and d > 0):
            raise ValueError(f"diameter must be finite and > 0, got {diameter!r}")
        A, I, J = circular_section(d)
        return cls(EA=youngs_modulus * A, GA=shear_modulus * A, EI=youngs_modulus * I, GJ=shear_modulus * J)

    @property
    def K_se(self) -> np.ndarray:
        """``(3, 3)`` shear/extension stiffness ``diag(GA, GA, EA)`` [N]."""
        return np.diag([self.GA, self.GA, self.EA])

    @property
    def K_bt(self) -> np.ndarray:
        """``(3, 3)`` bending/torsion stiffness ``diag(EI, EI, GJ)`` [N m^2]."""
        return np.diag([self.EI, self.EI, self.GJ])


@dataclass(frozen=True)
class RodSolution:
    """A solved (or integrated) rod.

    Parameters
    ----------
    s : ndarray, shape (k,)
        Arc-length stations of the reference rod [m], 0..L.
    positions : ndarray, shape (k, 3)
        Centreline ``p(s)`` [m].
    rotations : ndarray, shape (k, 3, 3)
        Cross-section frames ``R(s)`` (column 3 = material tangent direction).
    forces : ndarray, shape (k, 3)
        Internal force ``n(s)`` in the global frame [N].
    moments : ndarray, shape (k, 3)
        Internal moment ``m(s)`` in the global frame [N m].
    converged : bool
        Shooting residual below tolerance (always True for a plain integration).
    residual : float
        Final max-norm of the boundary residual (position part in m, rotation/wrench part scaled).
    iterations : int
        Number of residual evaluations used by the shooting method.
    base_twist : float
        Base twist angle about the base tangent [rad] (nonzero only for a twist-free base).
    """

    s: np.ndarray
    positions: np.ndarray
    rotations: np.ndarray
    forces: np.ndarray
    moments: np.ndarray
    converged: bool = True
    residual: float = 0.0
    iterations: int = 0
    base_twist: float = 0.0

    @property
    def tip_position(self) -> np.ndarray:
        """``(3,)`` tip position [m]."""
        return self.positions[-1]

    @property
    def tip_rotation(self) -> np.ndarray:
        """``(3, 3)`` tip frame."""
        return self.rotations[-1]


def _hat(u: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])


def rotation_log(R: np.ndarray) -> np.ndarray:
    """Rotation vector ``(log R)^vee`` of a rotation matrix (Huang et al. Eq 27-28).

    Parameters
    ----------
    R : array_like, shape (3, 3)

    Returns
    -------
    ndarray, shape (3,)
        Axis times angle [rad], angle in [0, pi].
    """
    R = np.asarray(R, dtype=float)
    if R.shape != (3, 3):
        raise ValueError(f"R must have shape (3, 3), got {R.shape}")
    return Rotation.from_matrix(R).as_rotvec()


def _check_frame(p0, R0):
    p0 = np.asarray(p0, dtype=float)
    R0 = np.asarray(R0, dtype=float)
    if p0.shape != (3,):
        raise ValueError(f"base position must have shape (3,), got {p0.shape}")
    if R0.shape != (3, 3):
        raise ValueError(f"base rotation must have shape (3, 3), got {R0.shape}")
    if not np.all(np.isfinite(R0)) or not np.allclose(R0.T @ R0, np.eye(3), atol=1e-6) or np.linalg.det(R0) < 0:
        raise ValueError("base rotation must be a proper rotation matrix (R^T R = I, det R = +1)")
    U, _, Vt = np.linalg.svd(R0)  # remove round-off (e.g. frames read back from a solver)
    return p0, U @ Vt


def _vec3(x, name):
    if x is None:
        return np.zeros(3)
    a = np.asarray(x, dtype=float)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be a finite vector of shape (3,), got shape {a.shape}")
    return a


def _check_length(length):
    L = float(length)
    if not (math.isfinite(L) and L > 0):
        raise ValueError(f"rod length must be finite and > 0, got {length!r}")
    return L


def _rhs_factory(stiffness: RodStiffness, f: np.ndarray, l: np.ndarray):
    """Right-hand side of Eq 18-20 for the state ``y = (p, R (row-major), n, m)``."""
    cse = np.array([1.0 / stiffness.GA, 1.0 / stiffness.GA, 1.0 / stiffness.EA])
    cbt = np.array([1.0 / stiffness.EI, 1.0 / stiffness.EI, 1.0 / stiffness.GJ])
    f = np.asarray(f, dtype=float)
    l = np.asarray(l, dtype=float)
    out = np.empty(18)

    def rhs(s, y):
        R = y[3:12].reshape(3, 3)
        n = y[12:15]
        m = y[15:18]
        v = cse * (n @ R)  # R^T n
        v[2] += 1.0
        u = cbt * (m @ R)  # R^T m
        dp = R @ v
        # R' = R u^  (columns: R[:, j]' = R (u x e_j))
        out[0:3] = dp
        dR = np.empty((3, 3))
        dR[:, 0] = R[:, 1] * u[2] - R[:, 2] * u[1]
        dR[:, 1] = R[:, 2] * u[0] - R[:, 0] * u[2]
        dR[:, 2] = R[:, 0] * u[1] - R[:, 1] * u[0]
        out[3:12] = dR.ravel()
        out[12:15] = -f
        out[15] = -(dp[1] * n[2] - dp[2] * n[1]) - l[0]
        out[16] = -(dp[2] * n[0] - dp[0] * n[2]) - l[1]
        out[17] = -(dp[0] * n[1] - dp[1] * n[0]) - l[2]
        return out.copy()

    return rhs


def integrate_cosserat_rod(
    p0,
    R0,
    n0,
    m0,
    length: float,
    stiffness: RodStiffness,
    distributed_force=None,
    distributed_moment=None,
    n_eval: int = 33,
    rtol: float = 1e-10,
    atol: float = 1e-12,
) -> RodSolution:
    """Integrate the Cosserat statics (Eq 18-20) from the base as an initial-value problem.

    Parameters
    ----------
    p0 : array_like, shape (3,)
        Base position [m].
    R0 : array_like, shape (3, 3)
        Base cross-section frame (column 3 = tangent of the unloaded rod).
    n0, m0 : array_like, shape (3,)
        Internal force [N] and moment [N m] at the base, global frame.
    length : float
        Reference (unstretched) rod length [m].
    stiffness : RodStiffness
    distributed_force, distributed_moment : array_like, shape (3,), optional
        Uniform ``f`` [N/m] and ``l`` [N m/m], global frame (e.g. ``rho A g`` for self-weight).
    n_eval : int
        Number of output stations.
    rtol, atol : float
        ``solve_ivp`` tolerances (DOP853).

    Returns
    -------
    RodSolution
    """
    p0, R0 = _check_frame(p0, R0)
    n0 = _vec3(n0, "n0")
    m0 = _vec3(m0, "m0")
    L = _check_length(length)
    f = _vec3(distributed_force, "distributed_force")
    l = _vec3(distributed_moment, "distributed_moment")
    if int(n_eval) < 2:
        raise ValueError(f"n_eval must be >= 2, got {n_eval!r}")
    s_eval = np.linspace(0.0, L, int(n_eval))
    return _integrate(p0, R0, n0, m0, L, stiffness, f, l, s_eval, rtol, atol)


def _integrate(p0, R0, n0, m0, L, stiffness, f, l, s_eval, rtol=1e-10, atol=1e-12, tip_only=False):
    y0 = np.concatenate([p0, R0.ravel(), n0, m0])
    sol = solve_ivp(
        _rhs_factory(stiffness, f, l),
        (0.0, L),
        y0,
        method="DOP853",
        t_eval=None if tip_only else s_eval,
        rtol=rtol,
        atol=atol,
    )
    if not sol.success:
        raise RuntimeError(f"Cosserat rod integration failed: {sol.message}")
    Y = sol.y[:, -1:] if tip_only else sol.y
    k = Y.shape[1]
    rotations = Y[3:12].T.reshape(k, 3, 3)
    # project to SO(3) (integration drift is ~rtol)
    U, _, Vt = np.linalg.svd(rotations)
    rotations = U @ Vt
    return RodSolution(
        s=np.array([L]) if tip_only else s_eval,
        positions=Y[0:3].T.copy(),
        rotations=rotations,
        forces=Y[12:15].T.copy(),
        moments=Y[15:18].T.copy(),
    )


def _rz(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _shoot(residual, x0, scale, tol, max_nfev):
    res = least_squares(residual, x0, x_scale=scale, xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=max_nfev, method="lm")
    return res.x, float(np.max(np.abs(res.fun))), int(res.nfev)


def solve_rod_tip_wrench(
    p0,
    R0,
    length: float,
    stiffness: RodStiffness,
    tip_force=None,
    tip_moment=None,
    distributed_force=None,
    n_steps: int = 1,
    n_eval: int = 33,
    tol: float = 1e-10,
) -> RodSolution:
    """Cantilever: clamped base, dead force and moment applied at the free tip.

    Shoots on the base force and moment ``(n(0), m(0))`` so that ``n(L) = F`` and
    ``m(L) = M`` (Eq 19 at the tip).

    Parameters
    ----------
    p0, R0 : array_like, shapes (3,) and (3, 3)
        Clamped base position and frame (column 3 = tangent).
    length : float
        Rod length [m].
    stiffness : RodStiffness
    tip_force, tip_moment : array_like, shape (3,), optional
        Global tip force [N] and moment [N m].
    distributed_force : array_like, shape (3,), optional
        Uniform force per length [N/m] (self-weight).
    n_steps : int
        Continuation steps on the load (use > 1 for large deflections).
    n_eval : int
        Output stations.
    tol : float
        Required max-norm of the scaled tip residual (forces / |F| scale, moments / (|F| L)).

    Returns
    -------
    RodSolution
        ``converged`` tells whether the tip residual met ``tol``.
    """
    p0, R0 = _check_frame(p0, R0)
    L = _check_length(length)
    F = _vec3(tip_force, "tip_force")
    M = _vec3(tip_moment, "tip_moment")
    f = _vec3(distributed_force, "distributed_force")
    fs = max(np.linalg.norm(F), np.linalg.norm(M) / L, np.linalg.norm(f) * L, stiffness.EI / L**2 * 1e-6)
    s_eval = np.linspace(0.0, L, int(n_eval))
    x = np.concatenate([F + f * L, M + np.cross(L * R0[:, 2], F)])  # straight-rod guess
    nfev = 0
    lam_list = np.linspace(0.0, 1.0, int(n_steps) + 1)[1:]
    x = x * lam_list[0]
    for lam in lam_list:
        Fl, Ml, fl = lam * F, lam * M, lam * f

        def residual(xx):
            tip = _integrate(p0, R0, xx[:3], xx[3:], L, stiffness, fl, np.zeros(3), s_eval, tip_only=True)
            return np.concatenate([(tip.forces[-1] - Fl) / fs, (tip.moments[-1] - Ml) / (fs * L)])

        x, r, k = _shoot(residual, x, np.concatenate([np.full(3, fs), np.full(3, fs * L)]), tol, 200)
        nfev += k
    sol = _integrate(p0, R0, x[:3], x[3:], L, stiffness, f, np.zeros(3), s_eval)
    return RodSolution(sol.s, sol.positions, sol.rotations, sol.forces, sol.moments, bool(r <= tol), r, nfev, 0.0)


def solve_rod_tip_pose(
    p0,
    R0,
    length: float,
    stiffness: RodStiffness,
    tip_position,
    tip_rotation,
    free_base_twist: bool = True,
    distributed_force=None,
    n_steps: int = 1,
    n_eval: int = 33,
    tol: float = 1e-11,
    initial_guess=None,
) -> RodSolution:
    """Both ends prescribed: the leg problem of Huang et al. (Eq 21, 25, 26).

    The base sits in a hole: position and tangent fixed; with ``free_base_twist`` the section may
    rotate about the tangent, ``R(0) = R0 Rz(theta)`` with ``m(0) . R(0) e3 = 0`` (Eq 21).  The tip
    is clamped to the prescribed pose, ``p(L) = p_d``, ``R(L) = R_d`` (Eq 25-26, the rotation
    condition written as ``log(R(L)^T R_d)^vee = 0``, Eq 28).

    Unknowns: base force (3), base moment (3, or its 2 components normal to the tangent plus the
    twist angle theta).

    Parameters
    ----------
    p0, R0 : array_like, shapes (3,) and (3, 3)
        Base (hole) position and frame; column 3 is the hole axis.
    length : float
        Free rod length between hole and tip [m] (the insertion length L_i).
    stiffness : RodStiffness
    tip_position : array_like, shape (3,)
    tip_rotation : array_like, shape (3, 3)
        Tip frame (column 3 = rod tangent at the tip).
    free_base_twist : bool
        True: hole condition (Eq 21).  False: fully clamped base.
    distributed_force : array_like, shape (3,), optional
        Uniform force per length [N/m].
    n_steps : int
        Continuation steps from the straight rod to the target pose (geodesic in SE(3)).
    n_eval : int
        Output stations.
    tol : float
        Required max-norm of the residual (position in units of L, rotation in rad).
    initial_guess : array_like, shape (6,), optional
        ``(n(0), m(0))`` (for a free twist: ``(n(0), m_x, m_y, theta)`` in base-section axes).

    Returns
    -------
    RodSolution
    """
    p0, R0 = _check_frame(p0, R0)
    L = _check_length(length)
    pd = _vec3(tip_position, "tip_position")
    Rd = np.asarray(tip_rotation, dtype=float)
    if Rd.shape != (3, 3):
        raise ValueError(f"tip_rotation must have shape (3, 3), got {Rd.shape}")
    f = _vec3(distributed_force, "distributed_force")
    s_eval = np.linspace(0.0, L, int(n_eval))
    fs = stiffness.EI / L**2

    def base_state(xx):
        if free_base_twist:
            Rb = R0 @ _rz(xx[5])
            m0 = Rb[:, 0] * xx[3] + Rb[:, 1] * xx[4]
            return Rb, xx[:3], m0, float(xx[5])
        return R0, xx[:3], xx[3:6], 0.0

    # continuation path: straight rod -> target
    p_str = p0 + L * R0[:, 2]
    key = Rotation.from_matrix(np.stack([R0, Rd]))
    slerp = Slerp([0.0, 1.0], key)
    x = np.zeros(6) if initial_guess is None else np.asarray(initial_guess, dtype=float).copy()
    if x.shape != (6,):
        raise ValueError(f"initial_guess must have shape (6,), got {x.shape}")
    lams = [1.0] if initial_guess is not None else np.linspace(0.0, 1.0, int(n_steps) + 1)[1:]
    nfev = 0
    r = np.inf
    for lam in lams:
        p_t = (1 - lam) * p_str + lam * pd
        R_t = slerp([lam]).as_matrix()[0]
        f_t = lam * f

        def residual(xx):
            Rb, n0, m0, _ = base_state(xx)
            tip = _integrate(p0, Rb, n0, m0, L, stiffness, f_t, np.zeros(3), s_eval, tip_only=True)
            e_p = (tip.positions[-1] - p_t) / L
            e_r = rotation_log(tip.rotations[-1].T @ R_t)
            return np.concatenate([e_p, e_r])

        scale = np.array([fs, fs, fs, fs * L, fs * L, 1.0 if free_base_twist else fs * L])
        x, r, k = _shoot(residual, x, scale, tol, 400)
        nfev += k
    Rb, n0, m0, theta = base_state(x)
    sol = _integrate(p0, Rb, n0, m0, L, stiffness, f, np.zeros(3), s_eval)
    return RodSolution(sol.s, sol.positions, sol.rotations, sol.forces, sol.moments, bool(r <= tol), r, nfev, theta)
