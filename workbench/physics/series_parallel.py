"""Huang et al.'s flexible series-parallel trunk: six-rod parallel modules stacked in series.

Source: Huang, Wang, Wang, Xia, Li, "Kinematic Analysis of Bionic Elephant Trunk Robot Based on
Flexible Series-Parallel Structure", Biomimetics 2022, 7, 228 (``/work/shared/papers/004_*``).

A module (their Fig 5) is a Stewart-like platform whose six legs are flexible rods.  Each rod is
clamped in the moving platform and passes through a hole in the base platform; the free length
between hole and platform, the *insertion length* ``L_i``, is the actuator.  Model here:

* each leg is a chain of Exudyn ``ObjectBeamGeometricallyExact`` elements (Simo-Reissner rod, the
  same continuum as the paper's Cosserat rod Eq 18-20, section stiffness
  ``diag(EA, GA, GA, GJ, EI, EI)``, no shear correction factor, as in the paper's ``K_se``), with a
  straight stress-free reference of length ``L_i`` along the hole axis;
* hole condition (Eq 21): position and tangent fixed, rotation about the tangent free, so the
  torsional moment vanishes there (``m(0) . t = 0``).  Implemented as an ``ObjectJointRevoluteZ``
  whose joint z axis is the hole axis (= beam axis): it constrains the three translations and the
  two rotations normal to the tangent, and stays exact for any twist angle (a generic joint with
  one free rotation would do the same; "clamp and release torsion" cannot be expressed with a
  beam whose end node carries all six coordinates).  The sliding of the rod through the hole is
  quasi-static actuation: a new ``L_i`` is a new reference length;
* platform clamp (Eq 23-24): ``p_i(L_i) = p + R a_i``, ``R_i(L_i) = R`` -- every rod leaves the
  moving platform along its normal, with the rod's section frame equal to the platform frame;
* the moving platform is a rigid body (Euler-parameter node); optional gravity (rods lumped at
  the nodes, platform at its centre) and an external wrench at the platform origin (Eq 22).

Forward kinematics (Eq 21-24) is one static equilibrium solve with the platform free.  Inverse
kinematics (Eq 25-28): with the platform pose prescribed every leg is an independent two-point
boundary-value problem; Newton over ``L`` drives the platform wrench balance Eq 22 to zero, with
the 6x6 Jacobian by finite differences (one extra leg solve per column, since leg ``i`` depends
on ``L_i`` only).  Modules in series (Eq 29-32): module k's base frame is module k-1's platform
frame times a constant mount transform.  Stack forward kinematics solves all modules in one
system (so loads above a module are carried correctly); stack inverse kinematics walks from the
top module down, passing each module's hole reactions to the platform below (exact because all
platform poses are given).

Paper errata / gaps (the extraction lost symbols; re-derived):

* Eq 19 signs: ``n' = -f``, ``m' = -p' x n - l`` (see ``workbench.reference.cosserat``).
* Eq 22 is the platform balance ``sum_i n_i(L_i) - F = 0`` and
  ``sum_i (p_i(L_i) x n_i(L_i) + m_i(L_i)) - p_c x F - M = 0``, where ``n_i(L_i)`` is the force the
  platform exerts on rod i.
* Eq 30/31 (stack recursion): the extraction shows ``R_k = R'_k R_{k-1}^{b_k} R_{k-1}``; the
  composition that is a valid frame chain is ``T_k = T_{k-1} M T'_k`` with ``T`` homogeneous
  transforms (global <- platform), ``M`` the constant mount (platform k-1 <- base k), ``T'_k``
  the module-local pose (Eq 29).  Inverse: ``T'_k = (T_{k-1} M)^{-1} T_k`` (Eq 31).
* The paper gives no dimensions or materials.  The defaults of :class:`ModuleGeometry` are ours
  (documented there), chosen so that the module reaches the paper's Fig 6 motions.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from . import _series_parallel_exudyn as _ex

__all__ = [
    "ModuleGeometry",
    "ModulePose",
    "ModuleIK",
    "StackPose",
    "StackIK",
    "ArcFit",
    "LegSolution",
    "hole_frames",
    "attachment_points",
    "pose_from_xyz_rotvec",
    "home_pose",
    "leg_lengths_from_pose_hermite",
    "leg_static",
    "module_forward",
    "module_inverse",
    "stack_forward",
    "stack_inverse",
    "fit_constant_curvature",
]


# --------------------------------------------------------------------------- geometry


@dataclass(frozen=True)
class ModuleGeometry:
    """Plain parameters of one flexible six-rod parallel module (Huang et al. Fig 5).

    Huang et al. give no numbers for the prototype; every default below is our assumption,
    sized so that the module reaches the paper's Fig 6 motions (+-200 mm, +-45 deg, +-30 deg).

    Parameters
    ----------
    base_radius : float
        Radius of the hole circle on the base platform [m] (default 0.12).
    platform_radius : float
        Radius of the attachment circle on the moving platform [m] (default 0.12).
    base_angles_deg : tuple of 6 float
        Hole angles about the base z axis [deg]; Stewart-like pairs at 120 k +- 15
        (default (-15, 15, 105, 135, 225, 255)).
    platform_angles_deg : tuple of 6 float
        Attachment angles of the same legs about the platform z axis [deg]; the classic
        6-6 Stewart crossing, legs 2k/2k+1 go to 120 k -+ 45 (default
        (-45, 45, 75, 165, 195, 285)).  The angular offset between a leg's hole and its
        attachment gives the legs their S-shape and makes all six platform motions first-order
        controllable (with parallel straight legs, lateral translation and twist are singular).
    height : float
        Platform height above the base at the home pose [m] (default 0.5); the nominal insertion
        lengths are the inverse kinematics of the home pose.
    rod_diameter : float
        Rod diameter d [m] (default 0.006).
    youngs_modulus : float
        E [Pa] (default 200e9, spring steel).
    poisson_ratio : float
        mu; shear modulus G = E / (2 + 2 mu) (Eq 15) (default 0.3).
    density : float
        Rod density [kg/m^3] (default 7850).
    platform_mass : float
        Moving-platform mass [kg] (default 0.5); inertia is that of a thin disk of
        ``platform_radius``.
    mount_offset : float
        Distance along the platform z axis from module k's platform frame to module k+1's base
        frame [m] (default 0.0, the constant matrix of Eq 29-32).
    mount_twist_deg : float
        Rotation of module k+1's base about that z axis [deg] (default 0.0).
    """

    base_radius: float = 0.12
    platform_radius: float = 0.12
    base_angles_deg: tuple[float, ...] = (-15.0, 15.0, 105.0, 135.0, 225.0, 255.0)
    platform_angles_deg: tuple[float, ...] = (-45.0, 45.0, 75.0, 165.0, 195.0, 285.0)
    height: float = 0.5
    rod_diameter: float = 0.006
    youngs_modulus: float = 200e9
    poisson_ratio: float = 0.3
    density: float = 7850.0
    platform_mass: float = 0.5
    mount_offset: float = 0.0
    mount_twist_deg: float = 0.0

    def __post_init__(self) -> None:
        for name in ("base_radius", "platform_radius", "height", "rod_diameter", "youngs_modulus", "density"):
            v = float(getattr(self, name))
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"ModuleGeometry.{name} must be finite and > 0, got {getattr(self, name)!r}")
            object.__setattr__(self, name, v)
        for name in ("base_angles_deg", "platform_angles_deg"):
            a = tuple(float(x) for x in getattr(self, name))
            if len(a) != 6 or not all(math.isfinite(x) for x in a):
                raise ValueError(f"ModuleGeometry.{name} must hold 6 finite angles [deg], got {getattr(self, name)!r}")
            object.__setattr__(self, name, a)
        if not (-1.0 < self.poisson_ratio < 0.5):
            raise ValueError(f"ModuleGeometry.poisson_ratio must be in (-1, 0.5), got {self.poisson_ratio!r}")
        if not (math.isfinite(self.platform_mass) and self.platform_mass >= 0):
            raise ValueError(f"ModuleGeometry.platform_mass must be finite and >= 0, got {self.platform_mass!r}")
        for name in ("mount_offset", "mount_twist_deg"):
            if not math.isfinite(float(getattr(self, name))):
                raise ValueError(f"ModuleGeometry.{name} must be finite, got {getattr(self, name)!r}")

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 + 2 mu) [Pa] (Eq 15)."""
        return self.youngs_modulus / (2.0 + 2.0 * self.poisson_ratio)

    def rod_params(self) -> _ex.RodParams:
        d = self.rod_diameter
        A = math.pi * d**2 / 4.0
        I = math.pi * d**4 / 64.0
        return _ex.RodParams(
            EA=self.youngs_modulus * A,
            GA=self.shear_modulus * A,
            EI=self.youngs_modulus * I,
            GJ=self.shear_modulus * 2.0 * I,
            weight_per_length=self.density * A,
        )

    def platform_inertia(self) -> np.ndarray:
        """``(3,)`` principal inertia of a thin disk [kg m^2]."""
        m, r = self.platform_mass, self.platform_radius
        return np.array([m * r**2 / 4.0, m * r**2 / 4.0, m * r**2 / 2.0])

    def mount_transform(self) -> np.ndarray:
        """``(4, 4)`` constant transform platform k <- base k+1 (Eq 29-32)."""
        T = np.eye(4)
        T[:3, :3] = _rz(math.radians(self.mount_twist_deg))
        T[2, 3] = self.mount_offset
        return T


def _rz(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def hole_frames(geometry: ModuleGeometry) -> tuple[np.ndarray, np.ndarray]:
    """Hole positions and rod frames at the holes, module base frame (Eq 21).

    Returns
    -------
    positions : ndarray, shape (6, 3)
        ``r_b (cos beta_i, sin beta_i, 0)`` [m].
    rotations : ndarray, shape (6, 3, 3)
        ``R_i(0) = Rz(beta_i)`` (column 3 = hole axis = base z).
    """
    b = np.radians(geometry.base_angles_deg)
    P = np.stack([geometry.base_radius * np.cos(b), geometry.base_radius * np.sin(b), np.zeros(6)], axis=1)
    R = np.stack([_rz(t) for t in b])
    return P, R


def attachment_points(geometry: ModuleGeometry) -> np.ndarray:
    """``(6, 3)`` attachment points ``a_i`` in the platform frame [m] (Eq 24, 26)."""
    a = np.radians(geometry.platform_angles_deg)
    return np.stack([geometry.platform_radius * np.cos(a), geometry.platform_radius * np.sin(a), np.zeros(6)], axis=1)


def pose_from_xyz_rotvec(xyz, rotvec) -> np.ndarray:
    """``(4, 4)`` homogeneous transform from a position [m] and a rotation vector [rad]."""
    xyz = np.asarray(xyz, dtype=float)
    rv = np.asarray(rotvec, dtype=float)
    if xyz.shape != (3,) or rv.shape != (3,):
        raise ValueError(f"xyz and rotvec must have shape (3,), got {xyz.shape} and {rv.shape}")
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rv).as_matrix()
    T[:3, 3] = xyz
    return T


def home_pose(geometry: ModuleGeometry) -> np.ndarray:
    """``(4, 4)`` home pose of the platform: ``height`` along the base z axis, no rotation."""
    T = np.eye(4)
    T[2, 3] = geometry.height
    return T


def _check_pose(T, name="pose") -> np.ndarray:
    T = np.asarray(T, dtype=float)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise ValueError(f"{name} must be a finite (4, 4) homogeneous transform, got shape {T.shape}")
    R = T[:3, :3]
    if not np.allclose(R.T @ R, np.eye(3), atol=1e-8) or np.linalg.det(R) < 0:
        raise ValueError(f"{name}[:3, :3] must be a proper rotation matrix")
    return T


def _check_lengths(L) -> np.ndarray:
    L = np.asarray(L, dtype=float)
    if L.shape != (6,) or not np.all(np.isfinite(L)) or np.any(L <= 0):
        raise ValueError(f"insertion_lengths must be 6 finite positive lengths [m], shape (6,), got {np.asarray(L).shape}: {L!r}")
    return L


def _check_gravity(g):
    if g is None:
        return None
    g = np.asarray(g, dtype=float)
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise ValueError(f"gravity must be None or a finite (3,) vector [m/s^2] in the base frame, got shape {g.shape}")
    return g


def _check_wrench(w):
    if w is None:
        return None
    w = np.asarray(w, dtype=float)
    if w.shape != (6,) or not np.all(np.isfinite(w)):
        raise ValueError(f"wrench must be None or a finite (6,) vector (Fx, Fy, Fz, Mx, My, Mz) [N, N m], got shape {w.shape}")
    return w


# --------------------------------------------------------------------------- Hermite predictor


_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)
_GL_U = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W


def _hermite(p0, t0, p1, t1, u):
    """Cubic Hermite curve with end tangents scaled by the chord; returns points and derivatives."""
    c = np.linalg.norm(p1 - p0)
    u = np.asarray(u)[:, None]
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    P = h00 * p0 + h10 * c * t0 + h01 * p1 + h11 * c * t1
    d00 = 6 * u**2 - 6 * u
    d10 = 3 * u**2 - 4 * u + 1
    d01 = -6 * u**2 + 6 * u
    d11 = 3 * u**2 - 2 * u
    D = d00 * p0 + d10 * c * t0 + d01 * p1 + d11 * c * t1
    return P, D


def leg_lengths_from_pose_hermite(geometry: ModuleGeometry, pose) -> np.ndarray:
    """Geometric predictor: arc lengths of cubic Hermite legs for a platform pose.

    Each leg is approximated by the cubic Hermite curve from its hole (tangent = base z) to its
    attachment (tangent = platform z), tangents scaled by the chord.  Not an equilibrium: used
    only as the starting guess of the inverse kinematics and, inverted, of the forward
    kinematics.

    Parameters
    ----------
    geometry : ModuleGeometry
    pose : array_like, shape (4, 4)
        Platform pose in the module base frame.

    Returns
    -------
    ndarray, shape (6,)
        Predicted insertion lengths [m].
    """
    T = _check_pose(pose)
    return _hermite_lengths(geometry, T)


def _hermite_lengths(geometry, T):
    P0, R0 = hole_frames(geometry)
    A = attachment_points(geometry)
    out = np.empty(6)
    for i in range(6):
        p1 = T[:3, :3] @ A[i] + T[:3, 3]
        _, D = _hermite(P0[i], R0[i][:, 2], p1, T[:3, 2], _GL_U)
        out[i] = np.sum(_GL_W * np.linalg.norm(D, axis=1))
    return out


def _pose_from_lengths_hermite(geometry, L, T_guess):
    def res(x):
        T = T_guess @ pose_from_xyz_rotvec(x[:3], x[3:])
        return (_hermite_lengths(geometry, T) - L) / geometry.height

    sol = least_squares(res, np.zeros(6), method="lm", xtol=1e-14, ftol=1e-14)
    return T_guess @ pose_from_xyz_rotvec(sol.x[:3], sol.x[3:])


def _leg_shape(p0, R0, length, p1, R1, n_elements, free_twist=True) -> _ex.LegShape:
    """Node positions (equal arc length along the Hermite curve) and parallel-transported frames."""
    u = np.linspace(0.0, 1.0, 401)
    P, D = _hermite(p0, R0[:, 2], p1, R1[:, 2], u)
    sp = np.linalg.norm(D, axis=1)
    s = np.concatenate([[0.0], np.cumsum(0.5 * (sp[1:] + sp[:-1]) * np.diff(u))])
    tan = D / sp[:, None]
    frames = np.empty((u.size, 3, 3))
    frames[0] = R0
    for j in range(1, u.size):
        a, b = tan[j - 1], tan[j]
        ax = np.cross(a, b)
        sn, cs = np.linalg.norm(ax), float(np.dot(a, b))
        Rm = np.eye(3) if sn < 1e-15 else Rotation.from_rotvec(ax / sn * math.atan2(sn, cs)).as_matrix()
        frames[j] = Rm @ frames[j - 1]
    # twist mismatch at the tip about the tangent
    rel = frames[-1].T @ R1
    phi = math.atan2(rel[1, 0], rel[0, 0])
    s_nodes = np.linspace(0.0, s[-1], n_elements + 1)
    u_nodes = np.interp(s_nodes, s, u)
    idx = np.clip(np.searchsorted(u, u_nodes), 0, u.size - 1)
    Pn, _ = _hermite(p0, R0[:, 2], p1, R1[:, 2], u_nodes)
    Rn = np.empty((n_elements + 1, 3, 3))
    for j in range(n_elements + 1):
        frac = 1.0 if free_twist else s_nodes[j] / s[-1]
        Fj = frames[idx[j]]
        # re-align with the exact tangent at u_nodes[j]
        _, Dj = _hermite(p0, R0[:, 2], p1, R1[:, 2], [u_nodes[j]])
        tj = Dj[0] / np.linalg.norm(Dj[0])
        ax = np.cross(Fj[:, 2], tj)
        sn = np.linalg.norm(ax)
        if sn > 1e-15:
            Fj = Rotation.from_rotvec(ax / sn * math.asin(min(sn, 1.0))).as_matrix() @ Fj
        Rn[j] = Fj @ _rz(frac * phi)
    Rn[-1] = R1 if free_twist else Rn[-1]
    Pn[-1] = p1
    return _ex.LegShape(positions=Pn, rotations=Rn)


# --------------------------------------------------------------------------- one leg


@dataclass(frozen=True)
class LegSolution:
    """Static state of one leg (Exudyn GE beam).

    Parameters
    ----------
    positions : ndarray, shape (N+1, 3)
        Node positions [m], hole first.
    rotations : ndarray, shape (N+1, 3, 3)
        Section frames (column 3 = material tangent; Cosserat convention).
    tip_force, tip_moment : ndarray, shape (3,)
        ``n(L)``, ``m(L)``: force [N] and moment [N m] the tip support exerts on the rod, global
        frame (zero-size arrays' NaN when not converged; for a tip-wrench problem: the applied wrench).
    converged : bool
    iterations : int
        Newton iterations.
    reason : str
        Failure reason ("" when converged).
    """

    positions: np.ndarray
    rotations: np.ndarray
    tip_force: np.ndarray
    tip_moment: np.ndarray
    converged: bool
    iterations: int
    reason: str = ""


def leg_static(
    geometry: ModuleGeometry,
    base_position,
    base_rotation,
    length: float,
    *,
    tip_pose=None,
    tip_wrench=None,
    free_base_twist: bool = True,
    gravity=None,
    n_elements: int = 8,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
    n_load_steps: int = 1,
) -> LegSolution:
    """Static equilibrium of one flexible leg (GE beam) for given end conditions.

    Exactly one of ``tip_pose`` (both ends prescribed: the inverse-kinematics leg problem,
    Eq 21, 25, 26) and ``tip_wrench`` (cantilever with a dead tip load; base clamped,
    ``free_base_twist`` must be False) is given.

    Parameters
    ----------
    geometry : ModuleGeometry
        Supplies the rod section and material (``rod_diameter``, ``youngs_modulus``, ...).
    base_position : array_like, shape (3,)
        Hole position [m].
    base_rotation : array_like, shape (3, 3)
        Rod frame at the hole (column 3 = hole axis).
    length : float
        Free length hole -> tip [m] (the insertion length L_i).
    tip_pose : array_like, shape (4, 4), optional
        Prescribed tip frame (column 3 of the rotation = rod tangent).
    tip_wrench : array_like, shape (6,), optional
        Dead tip force and moment, global frame [N, N m].
    free_base_twist : bool
        Hole condition (revolute about the hole axis) if True, full clamp if False.
    gravity : array_like, shape (3,), optional
        Gravitational acceleration [m/s^2]; rod weight lumped at the nodes.
    n_elements : int
        Beam elements of the leg.
    tolerance : float
        Newton relative tolerance on the step size.
    max_iterations : int
        Newton iteration cap per load step.
    n_load_steps : int
        Load steps (tip-wrench problems only; constraints are not ramped by Exudyn).

    Returns
    -------
    LegSolution
    """
    p0 = np.asarray(base_position, dtype=float)
    R0 = np.asarray(base_rotation, dtype=float)
    if p0.shape != (3,) or R0.shape != (3, 3):
        raise ValueError(f"base_position must be (3,) and base_rotation (3, 3), got {p0.shape}, {R0.shape}")
    L = float(length)
    if not (math.isfinite(L) and L > 0):
        raise ValueError(f"length must be finite and > 0, got {length!r}")
    if (tip_pose is None) == (tip_wrench is None):
        raise ValueError("give exactly one of tip_pose and tip_wrench")
    n_el = _check_n_elements(n_elements)
    g = _check_gravity(gravity)
    rod = geometry.rod_params()
    if tip_pose is not None:
        T = _check_pose(tip_pose, "tip_pose")
        shape = _leg_shape(p0, R0, L, T[:3, 3], T[:3, :3], n_el, free_base_twist)
        out, F, M, P, R = _ex.solve_leg_tip_pose(
            rod, p0, R0, L, T[:3, 3], T[:3, :3], shape, g, tolerance, max_iterations, free_base_twist
        )
    else:
        if free_base_twist:
            raise ValueError("a tip-wrench leg needs a clamped base (free_base_twist=False): the twist would be a free mode")
        w = _check_wrench(tip_wrench)
        s = np.linspace(0.0, L, n_el + 1)
        shape = _ex.LegShape(positions=p0 + s[:, None] * R0[:, 2], rotations=np.tile(R0, (n_el + 1, 1, 1)))
        out, P, R = _ex.solve_leg_tip_wrench(rod, p0, R0, L, w[:3], w[3:], shape, g, tolerance, max_iterations, n_load_steps)
        F, M = (w[:3], w[3:]) if out.converged else (None, None)
    if not out.converged:
        nan = np.full(3, np.nan)
        return LegSolution(np.full((n_el + 1, 3), np.nan), np.full((n_el + 1, 3, 3), np.nan), nan, nan, False, out.iterations, out.reason)
    return LegSolution(P, R, np.asarray(F, float), np.asarray(M, float), True, out.iterations, "")


def _check_n_elements(n):
    if int(n) != n or n < 1:
        raise ValueError(f"n_elements must be a positive integer, got {n!r}")
    return int(n)
