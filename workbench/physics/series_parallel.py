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

Forward kinematics (Eq 21-24) is one static equilibrium solve with the platform free, started
from a geometric predictor with every leg pre-solved at the predicted pose; if that fails (large
motions), the lengths are walked from the home configuration with a secant predictor.  Inverse
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
  (documented there), chosen so that the module reaches the paper's Fig 6 translations (+-200 mm
  along x, y, z) and twists (rz +-30 deg); rotations about x / y are limited, see below.

Reachable range and solver notes (default geometry, 8 elements per leg, measured with
``studies/series_parallel.toml`` and single runs):

* FK of y +200 mm failed while y -200 mm worked: the Hermite predictor lands on a wrong branch
  (the 6-6 crossing is chiral, +y and -y are not mirror images) and the length continuation from
  home then stalled even at 1/256 of the way, because it reused the old leg shapes with the new
  stress-free lengths (an axial misfit ``EA dL / L``, kN for 0.1 mm).  Fixed: every continuation
  step pre-solves each leg at its new length (:func:`_presolve_legs`).  Numerical.
* IK of rx / ry beyond ~17-19 deg failed in a leg solve started from the neighbouring state (same
  axial-misfit mechanism, strongly S-bent legs).  Fixed: :func:`_leg_homotopy` walks the leg from
  the neighbouring state, and a line search that fails with a reused (chord) Jacobian rebuilds
  it before giving up.  rx 26 and 29 deg now round-trip (FK(IK) = target to 5e-15 m; but 29 deg
  lies on a second branch, see below, and is rejected by the branch check).  Numerical.  (A
  trust region on the Newton step, 5 % of the height, was tried and removed: it made rx stop at
  26.5 deg -- i.e. at the fold.)
* Remaining limit: the pose continuation home -> target stops at rx +-34 deg, ry -21.5 deg and
  ry +37 deg ("line search failed to reduce the platform balance residual", or at ry -21.5 deg a
  Newton step to a 1.69 m leg whose solve fails); for ry -45 deg the stop point does not move
  with the path step (0.479 of the way with 8 steps, 0.483 with 40 steps).

Diagnosis of the rx / ry limit (measured; ``_ik_jacobian``, test
``test_rx_limit_is_a_fold_of_the_ik_branch``).  It is a property of the model with this assumed
geometry (a fold of the IK solution branch, i.e. the workspace boundary of that branch), not a
Newton failure of a leg solve:

* rx: the compression-side leg 1 (leg 0 for -rx, mirror image) carries its compression near its
  limit and buckles into a growing loop.  Along rx its length goes 0.545 m (18 deg), 0.598
  (22.5), 0.768 (25.2), 0.817 (26.1), 0.887 m (26.76 deg); ``dL_1/drx`` grows without bound.  The
  scaled IK Jacobian ``diag(1,1,1,1/r,1/r,1/r) d(balance)/dL`` keeps the sign of its determinant
  and its determinant goes to zero linearly (-3.3e28 at 26.1 deg, -1.1e28 at 26.65, -5.4e27 at
  26.76, extrapolated zero at 26.9 deg); smallest singular value 5.1e5 (4.5 deg), 1.1e3 (22.5),
  3.6e2 (26.1), 81 (26.76 deg), null vector ~ leg 1 (0.99) with some leg 4.  That is a regular
  turning point: on the branch connected to home no rx beyond ~26.8 deg exists.  Actuated from
  home (FK) the module would snap through there.  Without a branch check (``check_branch=False``)
  the pose continuation in ``module_inverse`` jumps over the fold with a large step and lands on
  a second branch (determinant positive:
  +5.6e27 at 28.1 deg), on which leg 1 is a 1.10 m loop bulging 0.37 m (3x the platform radius)
  from its chord and leg 4 a 0.85 m loop bulging 0.28 m; that branch ends at 33.7 deg with its
  smallest singular value falling again (3.4e2 at 28.1-32.3 deg, 1.2e2 at 33.7 deg).
* At the 33.7 deg stop pose every single-leg solve converges over a wide length range (leg 4:
  0.46-1.24 m, leg 1: 0.71-1.49 m, warm-started 10 mm steps): no leg has a fold in L.  Leg 4's
  axial compression there peaks at 1008 N at L = 0.564 m and decreases for longer L (post-buckled
  loop), i.e. the legs the IK needs are far past their own force maximum.
* ry -: legs 2 and 5 (a mirror-symmetric pair, L_2 = L_5 along the path) are the compressed
  ones (1216 N at L = 0.55-0.58 m).  Secant continuation with the IK Jacobian: smallest singular
  value 1.0e4 (18 deg), 2.9e3 (20.2), 1.2e3 (21.1), 37 (21.6 deg); from 21.1 deg on its null
  vector is antisymmetric, (leg 2 - leg 5) / sqrt 2, and the determinant changes sign between
  21.6 and 21.7 deg (-9.9e27 -> +3.4e28) while the path stays symmetric: a symmetry-breaking
  (pitchfork) bifurcation at ~21.6 deg, after which the symmetric branch is lost at 21.8 deg
  (the stop at 21.5 deg of ``module_inverse``).  The asymmetric branches born there were not
  followed.
* ry +: legs 0, 1, 3, 4 are compressed (700-1050 N), legs 2 and 5 tensioned (1800 N), the path
  stays symmetric; the determinant keeps its sign and falls (-4.6e26 at 36.0 deg, -2.0e26 at 36.9,
  -1.1e26 at 37.3 deg, linear extrapolation to zero at ~37.9 deg) while L_0 = L_1 turns from
  shrinking to growing ever faster (0.493 at 33.7 deg, then 0.505, 0.513, 0.521 m at 36.0, 36.9,
  37.3 deg), but the smallest singular value does not drop (1.5e3) and Newton fails at 37.8 deg.
  This points to a fold near 38 deg, but, unlike rx and ry -, it was not settled.
* Branch check (default ``check_branch=True``): ``module_inverse`` accepts a solution only if the
  sign of ``det d(balance)/dL`` equals its sign at home, at the solution and at every continuation
  step (a step that converges on another branch is retried smaller).  rx 29 deg about the platform
  centre now fails with "stalled at ... rotation 26.6 deg ...; smallest singular value of the IK
  Jacobian there 0.00021 x its home value (near a fold ...)" instead of returning the looped legs
  of the second branch.  Cost: one home IK plus one Jacobian (6 leg solves) per check, e.g. the
  45 deg mid-height tilt 0.5 -> 0.9 s.
* So the paper's +-45 deg about x / y, read as rotations about the platform centre, cannot be
  reached with this assumed geometry by any solver on the branch connected to home.  Not
  modelled either: contact between legs, which the loops of the second branch would need.
* The paper does not say about which point Fig 6 rotates.  About a centre lower on the module
  axis the legs bend instead of buckling (traced with the same continuation, default geometry):
  rotation centre at 0.75 h: fold at ~41 deg (leg 1 lengthens to 1.09 m); at 0.5 h (the
  platform tilts and swings sideways, close to a constant-curvature bend of the module): +-45 deg
  is reached by a direct Newton solve (7-8 iterations, 0.5 s; leg axial forces <= 0.41 kN,
  smallest singular value of the scaled IK Jacobian 1.25e4) and the branch folds only at ~77 deg
  (leg 2 loops out to 1.56 m).  ``workbench.motion.worker.module_target`` takes this centre as
  ``pivot`` (fraction of the height).
* Geometry (rotation about the platform centre, rx fold): platform / base radius 0.12 -> 0.25 m
  moves it from 26.8 to 29.5 deg only; a 1.0 m tall module folds at 13.9 deg; a 10 deg
  hole-to-attachment angle (instead of 30 deg) at 15.5 deg; 5 deg hole pairs with 50 deg legs
  (r = 0.25 m) at 37.6 deg (ry -: 39.5 deg).  Hole-to-attachment angles above 45 deg with the
  default 30 deg pair spacing make the legs of neighbouring pairs intersect.
* The study sweeps rx / ry to +-45 deg about mid-height, and about the platform centre rx to
  +-0.45 rad (25.8 deg, home branch; FK(IK) = target to 4e-15 m) and ry to +-0.35 rad.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation, Slerp

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
    "min_leg_gap",
    "rotation_vector",
]


# --------------------------------------------------------------------------- geometry


@dataclass(frozen=True)
class ModuleGeometry:
    """Plain parameters of one flexible six-rod parallel module (Huang et al. Fig 5).

    Huang et al. give no numbers for the prototype; every default below is our assumption,
    sized so that the module reaches the paper's Fig 6 translations (+-200 mm) and twists (+-30 deg),
    and +-45 deg about x / y as tilts about the module's mid-height point.  Rotations about x / y
    about the platform centre stop short of 45 deg: the IK branch connected to home ends at
    rx +-26.8 deg (fold), ry -21.6 deg (symmetry-breaking bifurcation) and ry ~+38 deg (see the
    module docstring).

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


def _hermite(p0, t0, p1, t1, u, scale=None):
    """Cubic Hermite curve with end tangents scaled by ``scale`` (default: the chord); points and derivatives."""
    c = np.linalg.norm(p1 - p0) if scale is None else scale
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


def _tangent_scale_for_length(p0, t0, p1, t1, length):
    """Tangent scale of the Hermite leg whose arc length equals ``length`` (secant iteration).

    Falls back to the chord-scaled curve when no scale reaches the length (leg shorter than
    the chord would require stretching).
    """
    c = float(np.linalg.norm(p1 - p0))

    def arc(a):
        _, D = _hermite(p0, t0, p1, t1, _GL_U, a)
        return float(np.sum(_GL_W * np.linalg.norm(D, axis=1)))

    a0, a1 = c, 1.1 * c
    f0, f1 = arc(a0) - length, arc(a1) - length
    for _ in range(30):
        if abs(f1) < 1e-13 * length or f1 == f0:
            break
        a0, a1, f0 = a1, max(a1 - f1 * (a1 - a0) / (f1 - f0), 1e-3 * c), f1
        f1 = arc(a1) - length
    return a1 if abs(f1) < 1e-9 * length else c


def _leg_shape(p0, R0, length, p1, R1, n_elements, free_twist=True) -> _ex.LegShape:
    """Node positions (equal arc length along the Hermite curve) and parallel-transported frames."""
    u = np.linspace(0.0, 1.0, 401)
    scale = _tangent_scale_for_length(p0, R0[:, 2], p1, R1[:, 2], length)
    P, D = _hermite(p0, R0[:, 2], p1, R1[:, 2], u, scale)
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
    Pn, _ = _hermite(p0, R0[:, 2], p1, R1[:, 2], u_nodes, scale)
    Rn = np.empty((n_elements + 1, 3, 3))
    for j in range(n_elements + 1):
        frac = 1.0 if free_twist else s_nodes[j] / s[-1]
        Fj = frames[idx[j]]
        # re-align with the exact tangent at u_nodes[j]
        _, Dj = _hermite(p0, R0[:, 2], p1, R1[:, 2], [u_nodes[j]], scale)
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
        frame (NaN when not converged; for a tip-wrench problem: the applied wrench).
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
    n_load_steps: int = 10,
    initial_guess: "LegSolution | None" = None,
    continuation: bool = True,
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
        Load steps of a tip-wrench problem (adaptive halving on failure); a tip-pose problem is
        solved in one step (constraints are not ramped by Exudyn).
    initial_guess : LegSolution, optional
        Converged state of a nearby problem (same ``n_elements``) to start Newton from, instead
        of the length-matched cubic-Hermite shape.
    continuation : bool
        Tip-pose problems: if Newton fails from the start shape, walk from the straight leg to
        the target (tip pose interpolated on SE(3), leg length following the Hermite length of
        each intermediate pose and blending into ``length``), warm-starting every step and
        halving the step on failure.

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
        if initial_guess is not None and initial_guess.converged and initial_guess.positions.shape == (n_el + 1, 3):
            shape = _ex.LegShape(positions=initial_guess.positions.copy(), rotations=initial_guess.rotations.copy())
            shape.positions[-1] = T[:3, 3]
            shape.rotations[-1] = T[:3, :3]
        else:
            shape = _leg_shape(p0, R0, L, T[:3, 3], T[:3, :3], n_el, free_base_twist)
        out, F, M, P, R = _ex.solve_leg_tip_pose(  # one step: nothing to ramp
            rod, p0, R0, L, T[:3, 3], T[:3, :3], shape, g, tolerance, max_iterations, free_base_twist
        )
        if not out.converged and continuation:
            out, F, M, P, R = _leg_pose_continuation(
                rod, p0, R0, L, T, n_el, g, tolerance, max_iterations, free_base_twist, out
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


def _leg_pose_continuation(rod, p0, R0, L, T, n_el, g, tol, max_it, free_twist, last_out, min_step=1.0 / 512):
    """Continuation fallback of :func:`leg_static` for a prescribed tip pose (see there)."""

    def hlen(pt, Rt):
        _, D = _hermite(p0, R0[:, 2], pt, Rt[:, 2], _GL_U)
        return float(np.sum(_GL_W * np.linalg.norm(D, axis=1)))

    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([R0, T[:3, :3]])))
    p_start = p0 + L * R0[:, 2]
    dL = L - hlen(T[:3, 3], T[:3, :3])
    s_nodes = np.linspace(0.0, 1.0, n_el + 1)
    P = p0 + np.outer(s_nodes * L, R0[:, 2])
    R = np.tile(R0, (n_el + 1, 1, 1))
    lam, step = 0.0, 0.125
    out = last_out
    F = M = None
    while lam < 1.0:
        lt = min(1.0, lam + step)
        pt = (1.0 - lt) * p_start + lt * T[:3, 3]
        Rt = slerp([lt]).as_matrix()[0]
        Lt = hlen(pt, Rt) + lt * dL
        Pg = P + np.outer(s_nodes, pt - P[-1])
        Rg = R.copy()
        Rg[-1] = Rt
        out, Ft, Mt, Pt, Rr = _ex.solve_leg_tip_pose(
            rod, p0, R0, Lt, pt, Rt, _ex.LegShape(positions=Pg, rotations=Rg), g, tol, max_it, free_twist
        )
        if out.converged:
            lam, P, R, F, M = lt, Pt, Rr, Ft, Mt
            step = min(2.0 * step, 0.25)
        else:
            step *= 0.5
            if step < min_step:
                reason = f"continuation stalled at {lam:.3f} of the way to the tip pose: {out.reason}"
                return _ex.StaticOutcome(False, out.iterations, out.residual, reason, out.wall_time), None, None, None, None
    return out, F, M, P, R


def _check_n_elements(n):
    if int(n) != n or n < 1:
        raise ValueError(f"n_elements must be a positive integer, got {n!r}")
    return int(n)


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class ModulePose:
    """Forward kinematics of one module (static equilibrium, Eq 21-24).

    Parameters
    ----------
    pose : ndarray, shape (4, 4)
        Platform pose in the module base frame (base <- platform).
    tip_forces, tip_moments : ndarray, shape (6, 3)
        ``n_i(L_i)``, ``m_i(L_i)``: force [N] and moment [N m] the platform exerts on each rod
        tip, module base frame.
    leg_positions : ndarray, shape (6, N+1, 3)
        Leg node positions [m], hole first.
    converged : bool
    iterations : int
        Newton iterations of the static solve.
    residual : float
        Max-norm of the platform balance Eq 22 recomputed from the leg tip wrenches (forces in N,
        moments divided by the platform radius, in N): an independent equilibrium check.
    reason : str
        Failure reason, "" when converged.
    wall_time : float
        Seconds.
    """

    pose: np.ndarray
    tip_forces: np.ndarray
    tip_moments: np.ndarray
    leg_positions: np.ndarray
    converged: bool
    iterations: int
    residual: float
    reason: str = ""
    wall_time: float = 0.0


@dataclass(frozen=True)
class ModuleIK:
    """Inverse kinematics of one module (Eq 25-28).

    Parameters
    ----------
    lengths : ndarray, shape (6,)
        Insertion lengths L_i [m] (NaN when the IK failed: no partial answer is passed off as one).
    success : bool
        Newton converged (length update below ``length_tolerance``) and every leg solve converged.
    iterations : int
        Newton iterations over L.
    residual : float
        Max-norm of the platform balance Eq 22 at the returned L (forces in N, moments / platform
        radius in N).
    reason : str
        Failure reason, "" on success.
    tip_forces, tip_moments : ndarray, shape (6, 3)
        ``n_i(L_i)``, ``m_i(L_i)`` at the solution, module base frame.
    base_forces, base_moments : ndarray, shape (6, 3)
        Force and moment (about the hole) each rod exerts on the base platform, ``n_i(0)``,
        ``m_i(0)``, module base frame (what stack IK passes to the module below).
    leg_positions : ndarray, shape (6, N+1, 3)
        Leg node positions [m].
    leg_solves : int
        Number of single-leg static solves used.
    wall_time : float
        Seconds.
    """

    lengths: np.ndarray
    success: bool
    iterations: int
    residual: float
    reason: str
    tip_forces: np.ndarray
    tip_moments: np.ndarray
    base_forces: np.ndarray
    base_moments: np.ndarray
    leg_positions: np.ndarray
    leg_solves: int = 0
    wall_time: float = 0.0


@dataclass(frozen=True)
class StackPose:
    """Forward kinematics of n modules in series (Eq 29-30).

    Parameters
    ----------
    poses : ndarray, shape (n, 4, 4)
        Platform poses in the stack base frame (global <- platform k).
    local_poses : ndarray, shape (n, 4, 4)
        Platform k in module k's base frame (Eq 29).
    leg_positions : ndarray, shape (n, 6, N+1, 3)
        Leg node positions, stack base frame [m].
    converged, iterations, residual, reason, wall_time
        As in :class:`ModulePose`; ``residual`` is the worst platform balance over the stack.
    """

    poses: np.ndarray
    local_poses: np.ndarray
    leg_positions: np.ndarray
    converged: bool
    iterations: int
    residual: float
    reason: str = ""
    wall_time: float = 0.0


@dataclass(frozen=True)
class StackIK:
    """Inverse kinematics of n modules in series (Eq 31-32).

    Parameters
    ----------
    lengths : ndarray, shape (n, 6)
        Insertion lengths per module [m].
    success : bool
    iterations : ndarray, shape (n,)
        Newton iterations per module.
    residual : float
        Worst module residual (see :class:`ModuleIK`).
    reason : str
    modules : tuple of ModuleIK
        Per-module results (module base frames).
    wall_time : float
    """

    lengths: np.ndarray
    success: bool
    iterations: np.ndarray
    residual: float
    reason: str
    modules: tuple
    wall_time: float = 0.0


# --------------------------------------------------------------------------- module kinematics


def _spec(geometry: ModuleGeometry, L: np.ndarray) -> _ex.ModuleSpec:
    P, R = hole_frames(geometry)
    return _ex.ModuleSpec(
        hole_positions=P,
        hole_rotations=R,
        attachments=attachment_points(geometry),
        lengths=np.asarray(L, float),
        rod=geometry.rod_params(),
        platform_mass=geometry.platform_mass,
        platform_inertia=geometry.platform_inertia(),
        mount=geometry.mount_transform(),
    )


def _balance(geometry, T, F_legs, M_legs, wrench, gravity):
    """Platform balance Eq 22 in the module base frame, returns the (6,) residual [N, N m]."""
    A = attachment_points(geometry)
    p = T[:3, :3] @ A.T + T[:3, 3:4]  # (3, 6)
    F_tot = np.zeros(3)
    M_ext = np.zeros(3)
    if wrench is not None:
        F_tot = F_tot + wrench[:3]
        M_ext = M_ext + wrench[3:]
    if gravity is not None:
        F_tot = F_tot + geometry.platform_mass * gravity
    rf = F_legs.sum(axis=0) - F_tot
    rm = np.sum(np.cross(p.T, F_legs) + M_legs, axis=0) - np.cross(T[:3, 3], F_tot) - M_ext
    return np.concatenate([rf, rm])


def _resnorm(geometry, r):
    return float(max(np.max(np.abs(r[:3])), np.max(np.abs(r[3:])) / geometry.platform_radius))


def module_forward(
    geometry: ModuleGeometry,
    insertion_lengths,
    wrench=None,
    gravity=None,
    *,
    n_elements: int = 8,
    initial_pose=None,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
) -> ModulePose:
    """Forward kinematics of one module: static equilibrium for given insertion lengths (Eq 21-24).

    One Exudyn static solve of six GE-beam legs and the free platform.  The start is a geometric
    predictor: the platform pose whose cubic-Hermite legs have the given lengths.

    Parameters
    ----------
    geometry : ModuleGeometry
    insertion_lengths : array_like, shape (6,)
        Free leg lengths hole -> platform L_i [m].
    wrench : array_like, shape (6,), optional
        External force [N] and moment [N m] on the platform at its origin, base frame.
    gravity : array_like, shape (3,), optional
        Gravitational acceleration in the base frame [m/s^2], e.g. ``(0, 0, -9.81)``; None = off.
    n_elements : int
        GE beam elements per leg.
    initial_pose : array_like, shape (4, 4), optional
        Starting guess for the predictor (default: home pose).
    tolerance : float
        Newton relative tolerance on the step size.
    max_iterations : int
        Newton iteration cap.

    Returns
    -------
    ModulePose
    """
    L = _check_lengths(insertion_lengths)
    st = stack_forward(
        [geometry], L[None, :], wrench=wrench, gravity=gravity, n_elements=n_elements,
        initial_poses=None if initial_pose is None else _check_pose(initial_pose, "initial_pose")[None],
        tolerance=tolerance, max_iterations=max_iterations, _return_legs=True,
    )
    res, F, M, _ = st
    return ModulePose(
        pose=res.poses[0], tip_forces=F[0], tip_moments=M[0], leg_positions=res.leg_positions[0],
        converged=res.converged, iterations=res.iterations, residual=res.residual, reason=res.reason,
        wall_time=res.wall_time,
    )


def _leg_solve(geometry, i, Li, T, gravity, n_el, tol, max_it, guess=None, guess_length=None):
    P0, R0 = hole_frames(geometry)
    A = attachment_points(geometry)
    Tt = np.eye(4)
    Tt[:3, :3] = T[:3, :3]
    Tt[:3, 3] = T[:3, :3] @ A[i] + T[:3, 3]
    kw = dict(tip_pose=Tt, free_base_twist=True, gravity=gravity, n_elements=n_el, tolerance=tol, max_iterations=max_it,
              continuation=False)  # the IK continues on the platform pose instead (cheaper)
    leg = leg_static(geometry, P0[i], R0[i], Li, initial_guess=guess, **kw)
    if not leg.converged and guess is not None and guess.converged and guess_length is not None:
        leg = _leg_homotopy(geometry, P0[i], R0[i], guess, float(guess_length), Li, Tt, kw)
    if not leg.converged and guess is not None:
        leg = leg_static(geometry, P0[i], R0[i], Li, **kw)
    return leg


def _leg_homotopy(geometry, p0, R0, guess, L_start, L_end, T_end, kw, min_step=1.0 / 64):
    """Walk one leg from a converged state (``guess`` at length ``L_start``) to (``L_end``, ``T_end``).

    Tip position, tip rotation (slerp) and length are interpolated together, every step
    warm-started from the last.  Needed where the legs are strongly S-bent (large platform
    rotations): one Newton solve from the neighbouring state then diverges although the leg
    problem is regular, because the change of the stress-free length enters through the stiff
    axial direction (``EA dL / L``).
    """
    Tg = np.eye(4)
    Tg[:3, :3] = guess.rotations[-1]
    Tg[:3, 3] = guess.positions[-1]
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Tg[:3, :3], T_end[:3, :3]])))
    cur, lam, step = guess, 0.0, 0.25
    kw = dict(kw)
    kw.pop("tip_pose")
    last = guess
    while lam < 1.0:
        lt = min(1.0, lam + step)
        Tt = np.eye(4)
        Tt[:3, :3] = slerp([lt]).as_matrix()[0]
        Tt[:3, 3] = (1.0 - lt) * Tg[:3, 3] + lt * T_end[:3, 3]
        last = leg_static(geometry, p0, R0, (1.0 - lt) * L_start + lt * L_end, tip_pose=Tt, initial_guess=cur, **kw)
        if last.converged:
            lam, cur = lt, last
            step = min(2.0 * step, 0.5)
        else:
            step *= 0.5
            if step < min_step:
                return last
    return cur


def module_inverse(
    geometry: ModuleGeometry,
    target_pose,
    wrench=None,
    gravity=None,
    *,
    n_elements: int = 8,
    initial_lengths=None,
    length_tolerance: float = 1e-10,
    max_iterations: int = 20,
    leg_tolerance: float = 1e-11,
    fd_step: float = 1e-7,
    path_steps: int | None = None,
    check_branch: bool = True,
    home_cache: dict | None = None,
) -> ModuleIK:
    """Inverse kinematics of one module: insertion lengths that hold the platform at a pose (Eq 25-28).

    With the platform pose prescribed, each leg is an independent two-point boundary-value
    problem (hole condition Eq 21 at the base, clamp Eq 25-26 at the platform), solved with
    Exudyn.  Newton over ``L`` drives the platform balance Eq 22 to zero; the Jacobian
    ``d(balance)/dL`` is built column by column by forward differences (leg i depends on L_i
    only, so a column costs one leg solve), reused (chord Newton) while the length updates
    contract by at least a factor 4, with a backtracking line search on the balance residual.
    Large motions fall back to continuation along the path from the home pose.

    Parameters
    ----------
    geometry : ModuleGeometry
    target_pose : array_like, shape (4, 4)
        Desired platform pose in the module base frame.
    wrench : array_like, shape (6,), optional
        External force and moment on the platform at its origin, base frame [N, N m].
    gravity : array_like, shape (3,), optional
        Gravitational acceleration, base frame [m/s^2].
    n_elements : int
        GE beam elements per leg.
    initial_lengths : array_like, shape (6,), optional
        Start (default: cubic-Hermite leg lengths of the target pose).
    length_tolerance : float
        Converged when the max length update is below this [m].
    max_iterations : int
        Newton iteration cap.
    leg_tolerance : float
        Newton tolerance of each leg solve.
    fd_step : float
        Finite-difference step on L_i [m].
    path_steps : int, optional
        If Newton from the start fails, continue along the SE(3) path from the home pose to the
        target in this many steps (adaptive halving; default: about one step per 40 mm and
        0.1 rad); 0 disables the fallback.
    check_branch : bool
        Accept only solutions on the IK solution branch connected to the home pose (under the same
        loads): the sign of ``det d(balance)/dL`` must equal its sign at home, at the solution and
        at every continuation step (one extra Jacobian, six leg solves, per check).  A sign change
        marks a fold or bifurcation of the branch (measured for the default module: rx 26.8 deg
        about the platform centre); beyond it the legs only close on other branches (buckled,
        looped legs), so the IK fails there with that reason instead of returning them.
    home_cache : dict, optional
        Caller-owned dict in which the home-pose reference of the branch check is kept, keyed by
        geometry, loads and solver settings; pass the same dict to repeated calls (a sweep, the
        modules of a stack) to solve the home pose once instead of per call.

    Returns
    -------
    ModuleIK
    """
    t_start = time.perf_counter()
    T = _check_pose(target_pose, "target_pose")
    w = _check_wrench(wrench)
    g = _check_gravity(gravity)
    n_el = _check_n_elements(n_elements)
    L0 = _hermite_lengths(geometry, T) if initial_lengths is None else _check_lengths(initial_lengths).copy()
    counter = [0]
    kw = dict(w=w, g=g, n_el=n_el, length_tolerance=length_tolerance, leg_tolerance=leg_tolerance, fd_step=fd_step,
              counter=counter)
    direct_cap = max_iterations if path_steps == 0 else min(max_iterations, 8)
    L, legs, ok, its, r, msg = _ik_newton(geometry, T, L0, None, max_iterations=direct_cap, **kw)
    total_its = its
    H = home_pose(geometry)
    home: list = []  # lazily: [L, legs, det sign] of the home pose

    cache_key = (geometry, None if w is None else w.tobytes(), None if g is None else g.tobytes(), n_el,
                 length_tolerance, leg_tolerance, fd_step)

    def home_state():
        if not home and home_cache is not None and cache_key in home_cache:
            home.extend(home_cache[cache_key])
        if not home:
            Lh, legs_h, okh, _, _, msgh = _ik_newton(geometry, H, _hermite_lengths(geometry, H), None,
                                                    max_iterations=max(max_iterations, 20), **kw)
            if not okh:
                raise _BranchCheckError(f"branch check: IK of the home pose failed: {msgh}")
            home.extend([Lh, legs_h, *_branch_sign(geometry, H, Lh, legs_h, kw, counter, with_smin=True)])
            if home_cache is not None:
                home_cache[cache_key] = tuple(home)
        return home

    at_home = bool(np.allclose(T, H, rtol=0.0, atol=1e-12))
    direct_off_branch = False
    try:
        if ok and check_branch and not at_home and _branch_sign(geometry, T, L, legs, kw, counter) != home_state()[2]:
            ok, msg, direct_off_branch = False, "", True
    except _BranchCheckError as e:
        ok, msg, path_steps = False, str(e), 0
    if not ok and path_steps != 0:
        # continuation along the SE(3) path home -> target, warm-starting L and the legs
        slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([H[:3, :3], T[:3, :3]])))
        n_steps = path_steps if path_steps else max(
            2, int(math.ceil(np.linalg.norm(T[:3, 3] - H[:3, 3]) / 0.04 + np.linalg.norm(rotation_vector(H[:3, :3].T @ T[:3, :3])) / 0.1))
        )
        lam, step = 0.0, 1.0 / n_steps
        try:
            Lc, legs_c, s_home, smin_home = home_state() if check_branch else (_hermite_lengths(geometry, H), None, 0.0, 0.0)
        except _BranchCheckError as e:
            lam, msg = -1.0, str(e)
        off_branch_seen = False  # a step from the current state converged on another branch
        while 0.0 <= lam < 1.0:
            lt = min(1.0, lam + step)
            Tt = np.eye(4)
            Tt[:3, :3] = slerp([lt]).as_matrix()[0]
            Tt[:3, 3] = (1 - lt) * H[:3, 3] + lt * T[:3, 3]
            # predictor: previous L shifted by the change of the Hermite lengths
            Lg = Lc + (_hermite_lengths(geometry, Tt) - _hermite_lengths(geometry, _interp_pose(H, T, slerp, lam)))
            Ln, legs_n, okn, itn, rn, msgn = _ik_newton(geometry, Tt, Lg, legs_c, legs0_L=Lc, max_iterations=max_iterations, **kw)
            total_its += itn
            if okn and check_branch:
                # a converged step on another branch is a failed step: a smaller one may stay on ours
                try:
                    if _branch_sign(geometry, Tt, Ln, legs_n, kw, counter) != s_home:
                        okn, msgn, off_branch_seen = False, "converged on another branch", True
                except _BranchCheckError as e:
                    msg = str(e)
                    break
            if okn:
                lam, Lc, legs_c, off_branch_seen = lt, Ln, legs_n, False
                step = min(1.5 * step, 2.0 / n_steps)
            else:
                step *= 0.5
                if step < 1.0 / (16 * n_steps):
                    where = (f"{lam:.3f} of the way from home to the target (rotation "
                             f"{math.degrees(lam * np.linalg.norm(rotation_vector(H[:3, :3].T @ T[:3, :3]))):.1f} deg, "
                             f"translation {1e3 * lam * np.linalg.norm(T[:3, 3] - H[:3, 3]):.0f} mm)")
                    if off_branch_seen:
                        msg = (f"the IK solution branch connected to home ends near {where}: det d(balance)/dL changes "
                               f"sign (fold or bifurcation), the target lies outside the workspace of that branch")
                    else:
                        msg = f"pose continuation stalled at {where}: {msgn}"
                        if check_branch and legs_c is not None:
                            try:
                                _, smin = _branch_sign(geometry, _interp_pose(H, T, slerp, lam), Lc, legs_c, kw, counter,
                                                       with_smin=True)
                                msg += (f"; smallest singular value of the IK Jacobian there {smin / smin_home:.2g} x its "
                                        f"home value" + (" (near a fold of the IK branch: workspace boundary)"
                                                         if smin < 1e-2 * smin_home else ""))
                            except _BranchCheckError:
                                pass
                    break
        if lam >= 1.0:
            L, legs, ok, r, msg = Lc, legs_c, True, rn, ""
    if not ok and direct_off_branch:
        msg = ((msg + "; ") if msg else "") + ("direct Newton converged on another IK solution branch (sign of det "
                                               "d(balance)/dL differs from home's: buckled or looped legs), rejected")
    if not ok or legs is None or any(lg is None or not lg.converged for lg in legs):
        nan = np.full((6, 3), np.nan)
        return ModuleIK(np.full(6, np.nan), False, total_its, float("nan") if r is None else _resnorm(geometry, r), msg or "IK failed",
                        nan, nan, nan, nan, np.full((6, n_el + 1, 3), np.nan), counter[0], time.perf_counter() - t_start)
    F = np.stack([lg.tip_force for lg in legs])
    M = np.stack([lg.tip_moment for lg in legs])
    base = [_base_reaction_lumped(geometry, i, legs[i], L[i], g) for i in range(6)]
    return ModuleIK(
        lengths=L, success=True, iterations=total_its, residual=_resnorm(geometry, r), reason="",
        tip_forces=F, tip_moments=M,
        base_forces=np.stack([b[0] for b in base]), base_moments=np.stack([b[1] for b in base]),
        leg_positions=np.stack([lg.positions for lg in legs]), leg_solves=counter[0],
        wall_time=time.perf_counter() - t_start,
    )


def rotation_vector(R) -> np.ndarray:
    """``(3,)`` rotation vector (log map) of a rotation matrix [rad] (Eq 27-28)."""
    return Rotation.from_matrix(np.asarray(R, dtype=float)).as_rotvec()


def _interp_pose(H, T, slerp, lam):
    Tt = np.eye(4)
    Tt[:3, :3] = slerp([lam]).as_matrix()[0]
    Tt[:3, 3] = (1 - lam) * H[:3, 3] + lam * T[:3, 3]
    return Tt


def _ik_newton(geometry, T, L, legs0, *, legs0_L=None, w, g, n_el, length_tolerance, leg_tolerance, fd_step, max_iterations, counter):
    """Newton over L for a fixed platform pose (Eq 22 with Eq 25-26), backtracking on the residual.

    Returns (L, legs, success, iterations, residual vector, message).
    """

    def evaluate(Lv, guess_legs, only=None, base_legs=None, guess_L=None):
        legs = list(base_legs) if base_legs is not None else [None] * 6
        for i in range(6) if only is None else only:
            gl = None if guess_legs is None else guess_legs[i]
            gL = None if guess_L is None else guess_L[i]
            legs[i] = _leg_solve(geometry, i, Lv[i], T, g, n_el, leg_tolerance, 50, guess=gl, guess_length=gL)
            counter[0] += 1
            if not legs[i].converged:
                return None, legs, f"leg {i} static solve failed at L = {Lv[i]:.6g} m: {legs[i].reason}"
        F = np.stack([lg.tip_force for lg in legs])
        M = np.stack([lg.tip_moment for lg in legs])
        return _balance(geometry, T, F, M, w, g), legs, ""

    r, legs, msg = evaluate(L, legs0, guess_L=legs0_L)
    if r is None:
        return L, None, False, 0, None, msg
    J = None
    last_step = np.inf
    for it in range(1, max_iterations + 1):
        fresh = J is None
        if J is None:
            J = np.empty((6, 6))
            for i in range(6):
                Lp = L.copy()
                Lp[i] += fd_step
                rp, _, msg = evaluate(Lp, legs, only=[i], base_legs=legs, guess_L=L)
                if rp is None:
                    return L, legs, False, it, r, "Jacobian: " + msg
                J[:, i] = (rp - r) / fd_step
        try:
            dL = -np.linalg.solve(J, r)
        except np.linalg.LinAlgError:
            return L, legs, False, it, r, "singular IK Jacobian d(balance)/dL (module at a singular pose)"
        # backtracking: accept the first fraction that lowers the scaled balance residual
        r0 = _resnorm(geometry, r)
        for frac in (1.0, 0.5, 0.25, 0.125):
            Ln = L + frac * dL
            if np.any(Ln <= 0):
                continue
            rn, legs_n, msg = evaluate(Ln, legs, guess_L=L)
            if rn is not None and (_resnorm(geometry, rn) < r0 or frac * np.max(np.abs(dL)) < length_tolerance):
                break
        else:
            if not fresh:  # the reused (chord) Jacobian is stale: rebuild it before giving up
                J = None
                continue
            return L, legs, False, it, r, msg or "line search failed to reduce the platform balance residual"
        L, r, legs = Ln, rn, legs_n
        step = float(np.max(np.abs(frac * dL)))
        if step < length_tolerance:
            return L, legs, True, it, r, ""
        if frac < 1.0 or step > 0.25 * last_step:
            J = None  # slow contraction or damped step: refresh the Jacobian
        last_step = step
    return L, legs, False, max_iterations, r, f"no convergence in {max_iterations} Newton iterations (last update {step:.3g} m)"


class _BranchCheckError(RuntimeError):
    pass


def _branch_sign(geometry, T, L, legs, kw, counter, with_smin=False):
    """Sign of ``det d(balance)/dL`` at a converged IK state (which IK solution branch it is on);
    with ``with_smin`` also the smallest singular value of ``diag(1, 1, 1, 1/r, 1/r, 1/r) J`` [N/m]."""
    try:
        J = _ik_jacobian(geometry, T, L, legs, wrench=kw["w"], gravity=kw["g"], n_elements=kw["n_el"],
                         leg_tolerance=kw["leg_tolerance"], fd_step=kw["fd_step"])
    except RuntimeError as e:
        raise _BranchCheckError(f"branch check: Jacobian at a converged state: {e}") from None
    counter[0] += 6
    sign, _ = np.linalg.slogdet(J)
    if not with_smin:
        return float(sign)
    S = np.diag([1.0, 1.0, 1.0] + [1.0 / geometry.platform_radius] * 3)
    return float(sign), float(np.linalg.svd(S @ J, compute_uv=False)[-1])


def _ik_jacobian(geometry, T, L, legs, *, wrench=None, gravity=None, n_elements=8, leg_tolerance=1e-11, fd_step=1e-7):
    """``(6, 6)`` Jacobian ``d(balance)/dL`` (Eq 22) at a converged IK state, by forward differences.

    ``legs`` are the converged :class:`LegSolution` of the six legs at pose ``T`` and lengths
    ``L``; column i re-solves leg i at ``L_i + fd_step`` warm-started from ``legs[i]``.  Used to
    locate folds (turning points) of the IK solution branch, where this matrix is singular.
    """
    F = np.stack([lg.tip_force for lg in legs])
    M = np.stack([lg.tip_moment for lg in legs])
    r = _balance(geometry, T, F, M, wrench, gravity)
    J = np.empty((6, 6))
    for i in range(6):
        lg = _leg_solve(geometry, i, L[i] + fd_step, T, gravity, n_elements, leg_tolerance, 50, guess=legs[i],
                        guess_length=L[i])
        if not lg.converged:
            raise RuntimeError(f"leg {i} solve failed at L = {L[i] + fd_step:.6g} m: {lg.reason}")
        F2, M2 = F.copy(), M.copy()
        F2[i], M2[i] = lg.tip_force, lg.tip_moment
        J[:, i] = (_balance(geometry, T, F2, M2, wrench, gravity) - r) / fd_step
    return J


def _base_reaction_lumped(geometry, i, leg: LegSolution, Li, gravity):
    """``n_i(0)``, ``m_i(0)`` (about the hole): force and moment rod i exerts on the base.

    Exact for the discrete model: equilibrium of the whole leg under the tip wrench and the rod
    weight lumped at the nodes (as in ``_series_parallel_exudyn._add_leg``).
    """
    P0, _ = hole_frames(geometry)
    p = leg.positions
    n0 = leg.tip_force.copy()
    m0 = leg.tip_moment + np.cross(p[-1] - P0[i], leg.tip_force)
    if gravity is not None:
        N = p.shape[0] - 1
        wts = np.full(N + 1, Li / N)
        wts[0] *= 0.5
        wts[-1] *= 0.5
        f = wts[:, None] * (geometry.rod_params().weight_per_length * gravity)[None, :]
        n0 = n0 + f.sum(axis=0)
        m0 = m0 + np.sum(np.cross(p - P0[i], f), axis=0)
    return n0, m0


# --------------------------------------------------------------------------- stacks


def _check_geometries(geometries) -> tuple:
    gs = tuple(geometries)
    if len(gs) < 1 or not all(isinstance(g, ModuleGeometry) for g in gs):
        raise ValueError("geometries must be a non-empty sequence of ModuleGeometry")
    return gs


def stack_forward(
    geometries: Sequence[ModuleGeometry],
    lengths_per_module,
    wrench=None,
    gravity=None,
    *,
    base_pose=None,
    n_elements: int = 8,
    initial_poses=None,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
    continuation: bool = True,
    _return_legs: bool = False,
):
    """Forward kinematics of n modules in series (Eq 29-30), one static equilibrium.

    All modules are solved together: module k's holes sit on platform k-1 (through the constant
    mount transform of module k-1), so the weight of the modules above and the tip wrench are
    carried exactly.  Without loads this equals the paper's recursion ``T_k = T_{k-1} M T'_k``
    with each ``T'_k = F(L_k)`` (Eq 29-30).

    Parameters
    ----------
    geometries : sequence of n ModuleGeometry
        Module 1 (at the base) first.
    lengths_per_module : array_like, shape (n, 6)
        Insertion lengths [m].
    wrench : array_like, shape (6,), optional
        External force/moment at the last platform's origin, stack base frame [N, N m].
    gravity : array_like, shape (3,), optional
        Gravitational acceleration, stack base frame [m/s^2].
    base_pose : array_like, shape (4, 4), optional
        Pose of module 1's base in the stack base frame (default identity).
    n_elements : int
        GE beam elements per leg.
    initial_poses : array_like, shape (n, 4, 4), optional
        Module-local starting guesses for the geometric predictor (default home poses).
    tolerance, max_iterations
        Newton settings.
    continuation : bool
        If the solve from the geometric predictor fails, start from the home poses (their
        insertion lengths by :func:`module_inverse`) and walk the lengths to the requested ones,
        warm-starting every step from the previous equilibrium and halving the step on failure.

    Returns
    -------
    StackPose
    """
    t_start = time.perf_counter()
    gs = _check_geometries(geometries)
    n = len(gs)
    Ls = np.asarray(lengths_per_module, dtype=float)
    if Ls.shape != (n, 6):
        raise ValueError(f"lengths_per_module must have shape ({n}, 6), got {Ls.shape}")
    for k in range(n):
        _check_lengths(Ls[k])
    w = _check_wrench(wrench)
    g = _check_gravity(gravity)
    n_el = _check_n_elements(n_elements)
    B = np.eye(4) if base_pose is None else _check_pose(base_pose, "base_pose")
    # geometric predictor, module by module (Eq 30 recursion)
    guesses = np.empty((n, 4, 4))
    shapes = []
    Tb = B.copy()
    for k, geo in enumerate(gs):
        Tk0 = home_pose(geo) if initial_poses is None else _check_pose(np.asarray(initial_poses)[k], "initial_poses[k]")
        Tloc = _pose_from_lengths_hermite(geo, Ls[k], Tk0)
        guesses[k] = Tb @ Tloc
        P0, R0 = hole_frames(geo)
        A = attachment_points(geo)
        legs = []
        for i in range(6):
            pb = Tb[:3, :3] @ P0[i] + Tb[:3, 3]
            Rb = Tb[:3, :3] @ R0[i]
            pt = guesses[k][:3, :3] @ A[i] + guesses[k][:3, 3]
            # start each leg from its own equilibrium with the platform held at the predicted
            # pose (the Hermite shape alone is too far off for Newton on the whole module)
            Tt = np.eye(4)
            Tt[:3, :3] = guesses[k][:3, :3]
            Tt[:3, 3] = pt
            leg = leg_static(geo, pb, Rb, Ls[k, i], tip_pose=Tt, gravity=g, n_elements=n_el)
            if leg.converged:
                legs.append(_ex.LegShape(positions=leg.positions, rotations=leg.rotations))
            else:
                legs.append(_leg_shape(pb, Rb, Ls[k, i], pt, guesses[k][:3, :3], n_el, True))
        shapes.append(legs)
        Tb = guesses[k] @ geo.mount_transform()
    specs = [_spec(geo, Ls[k]) for k, geo in enumerate(gs)]
    wr = None if w is None else (w[:3], w[3:])
    out, poses, F, M, (legpos, legrot) = _ex.solve_stack(specs, B, guesses, shapes, g, wr, tolerance, max_iterations, 1)
    if not out.converged and continuation:
        out, poses, F, M, (legpos, legrot) = _stack_continuation(gs, Ls, B, g, wr, n_el, tolerance, max_iterations, out)
    if not out.converged:
        nanT = np.full((n, 4, 4), np.nan)
        res = StackPose(nanT, nanT, np.full((n, 6, n_el + 1, 3), np.nan), False, out.iterations, float("nan"),
                        out.reason or "static solve failed", time.perf_counter() - t_start)
        return (res, np.full((n, 6, 3), np.nan), np.full((n, 6, 3), np.nan), None) if _return_legs else res
    # local poses (Eq 31) and the per-platform balance check in the stack base frame
    local = np.empty_like(poses)
    Tb = B.copy()
    worst = 0.0
    for k, geo in enumerate(gs):
        local[k] = np.linalg.solve(Tb, poses[k])
        Tb = poses[k] @ geo.mount_transform()
    for k, geo in enumerate(gs):
        # forces on platform k: its legs' tips, the next module's holes, gravity, tip wrench
        Tk = poses[k]
        A = attachment_points(geo)
        pa = (Tk[:3, :3] @ A.T).T + Tk[:3, 3]
        Fs = -F[k].sum(axis=0)
        Ms = -np.sum(np.cross(pa - Tk[:3, 3], F[k]) + M[k], axis=0)
        if g is not None:
            Fs = Fs + geo.platform_mass * g
        if k + 1 < n:
            geo_n = gs[k + 1]
            Tbn = Tk @ geo.mount_transform()
            P0, _ = hole_frames(geo_n)
            for i in range(6):
                leg = LegSolution(legpos[k + 1, i], np.empty((0, 3, 3)), F[k + 1, i], M[k + 1, i], True, 0)
                hole = Tbn[:3, :3] @ P0[i] + Tbn[:3, 3]
                n0 = leg.tip_force.copy()
                m0 = leg.tip_moment + np.cross(leg.positions[-1] - hole, leg.tip_force)
                if g is not None:
                    Nn = leg.positions.shape[0] - 1
                    wts = np.full(Nn + 1, Ls[k + 1, i] / Nn)
                    wts[[0, -1]] *= 0.5
                    f = wts[:, None] * (geo_n.rod_params().weight_per_length * g)[None, :]
                    n0 = n0 + f.sum(axis=0)
                    m0 = m0 + np.sum(np.cross(leg.positions - hole, f), axis=0)
                Fs = Fs + n0
                Ms = Ms + m0 + np.cross(hole - Tk[:3, 3], n0)
        elif w is not None:
            Fs = Fs + w[:3]
            Ms = Ms + w[3:]
        worst = max(worst, _resnorm(geo, np.concatenate([Fs, Ms])))
    res = StackPose(poses, local, legpos, True, out.iterations, worst, "", time.perf_counter() - t_start)
    return (res, F, M, legrot) if _return_legs else res


def _extrapolate_rot(R_prev, R_curr, c):
    """``R_curr exp(c log(R_prev^T R_curr))`` for stacks of rotations (..., 3, 3)."""
    shp = R_curr.shape
    a = Rotation.from_matrix(R_prev.reshape(-1, 3, 3))
    b = Rotation.from_matrix(R_curr.reshape(-1, 3, 3))
    d = (a.inv() * b).as_rotvec()
    return (b * Rotation.from_rotvec(c * d)).as_matrix().reshape(shp)


def _presolve_legs(gs, Ls, B, poses, g, n_el, guess_pos, guess_rot):
    """Leg shapes for a stack solve: each leg in equilibrium with its platform held at ``poses``."""
    shapes = []
    Tb = B.copy()
    for k, geo in enumerate(gs):
        P0, R0 = hole_frames(geo)
        A = attachment_points(geo)
        legs = []
        for i in range(6):
            pb = Tb[:3, :3] @ P0[i] + Tb[:3, 3]
            Rb = Tb[:3, :3] @ R0[i]
            Tt = np.eye(4)
            Tt[:3, :3] = poses[k][:3, :3]
            Tt[:3, 3] = poses[k][:3, :3] @ A[i] + poses[k][:3, 3]
            guess = LegSolution(guess_pos[k, i], guess_rot[k, i], np.zeros(3), np.zeros(3), True, 0)
            leg = leg_static(geo, pb, Rb, Ls[k, i], tip_pose=Tt, gravity=g, n_elements=n_el, initial_guess=guess,
                             continuation=False)
            if leg.converged:
                legs.append(_ex.LegShape(positions=leg.positions, rotations=leg.rotations))
            else:
                legs.append(_ex.LegShape(positions=guess_pos[k, i], rotations=guess_rot[k, i]))
        shapes.append(legs)
        Tb = poses[k] @ geo.mount_transform()
    return shapes


def _stack_continuation(gs, Ls, B, g, wr, n_el, tol, max_it, last_out, min_step=1.0 / 256):
    """Length continuation from the home configuration for :func:`stack_forward`."""
    n = len(gs)
    L_home = np.empty((n, 6))
    for k, geo in enumerate(gs):
        ik = module_inverse(geo, home_pose(geo), n_elements=n_el)
        if not ik.success:
            return last_out, None, None, None, (None, None)
        L_home[k] = ik.lengths
    # home configuration of the stack (no loads): predictor + leg equilibria
    res = stack_forward(gs, L_home, base_pose=B, n_elements=n_el, tolerance=tol, max_iterations=max_it,
                        continuation=False, _return_legs=True)
    if not res[0].converged:
        return last_out, None, None, None, (None, None)
    poses, legpos = res[0].poses, res[0].leg_positions
    legrot = res[3]
    lam, step = 0.0, 0.25
    out = last_out
    F = M = None
    prev = None  # (lam, poses, legpos, legrot) of the step before: secant predictor
    while lam < 1.0:
        lt = min(1.0, lam + step)
        Lt = L_home + lt * (Ls - L_home)
        specs = [_spec(geo, Lt[k]) for k, geo in enumerate(gs)]
        if prev is None:
            g_poses, g_pos, g_rot = poses, legpos, legrot
        else:
            c = (lt - lam) / (lam - prev[0])
            g_poses = poses.copy()
            g_poses[:, :3, 3] += c * (poses[:, :3, 3] - prev[1][:, :3, 3])
            g_poses[:, :3, :3] = _extrapolate_rot(prev[1][:, :3, :3], poses[:, :3, :3], c)
            g_pos = legpos + c * (legpos - prev[2])
            g_rot = _extrapolate_rot(prev[3], legrot, c)
        # every leg pre-solved with its new length at the predicted platform pose, warm-started from
        # the previous equilibrium: the old leg shapes with the new stress-free lengths carry an
        # axial misfit (EA dL / L, ~kN for 0.1 mm) that Newton on the whole module does not survive
        shapes = _presolve_legs(gs, Lt, B, g_poses, g if g is None else lt * g, n_el, g_pos, g_rot)
        out, P_, F_, M_, (lp, lr) = _ex.solve_stack(specs, B, g_poses, shapes, g if lt == 1.0 or g is None else lt * g,
                                                     None if wr is None else (lt * wr[0], lt * wr[1]), tol, max_it, 1)
        if out.converged:
            prev = (lam, poses, legpos, legrot)
            lam, poses, F, M, legpos, legrot = lt, P_, F_, M_, lp, lr
            step = min(2.0 * step, 0.5)
        else:
            step *= 0.5
            if step < min_step:
                reason = f"length continuation from home stalled at {lam:.3f}: {out.reason}"
                return _ex.StaticOutcome(False, out.iterations, out.residual, reason, out.wall_time), None, None, None, (None, None)
    return out, poses, F, M, (legpos, legrot)


def stack_inverse(
    geometries: Sequence[ModuleGeometry],
    platform_poses,
    wrench=None,
    gravity=None,
    *,
    base_pose=None,
    n_elements: int = 8,
    length_tolerance: float = 1e-10,
    max_iterations: int = 20,
) -> StackIK:
    """Inverse kinematics of n modules in series for given platform poses (Eq 31-32).

    The paper's "configuration planning" gives every platform pose; then each module's local
    target is ``T'_k = (T_{k-1} M_{k-1})^{-1} T_k`` (Eq 31) and ``L_k = f(T'_k)`` (Eq 32).  With
    loads, the modules are solved from the top down: the force and moment each rod of module k+1
    exerts on its hole (from its IK solution) are applied to platform k, which is exact because
    all platform poses are prescribed.

    Parameters
    ----------
    geometries : sequence of n ModuleGeometry
    platform_poses : array_like, shape (n, 4, 4)
        Desired platform poses in the stack base frame.
    wrench : array_like, shape (6,), optional
        External force/moment at the last platform origin, stack base frame.
    gravity : array_like, shape (3,), optional
        Stack base frame [m/s^2].
    base_pose : array_like, shape (4, 4), optional
        Module 1's base in the stack base frame (default identity).
    n_elements, length_tolerance, max_iterations
        Passed to :func:`module_inverse`.

    Returns
    -------
    StackIK
    """
    t_start = time.perf_counter()
    gs = _check_geometries(geometries)
    n = len(gs)
    Tp = np.asarray(platform_poses, dtype=float)
    if Tp.shape != (n, 4, 4):
        raise ValueError(f"platform_poses must have shape ({n}, 4, 4), got {Tp.shape}")
    for k in range(n):
        _check_pose(Tp[k], f"platform_poses[{k}]")
    w = _check_wrench(wrench)
    g = _check_gravity(gravity)
    B = np.eye(4) if base_pose is None else _check_pose(base_pose, "base_pose")
    bases = [B] + [Tp[k] @ gs[k].mount_transform() for k in range(n - 1)]
    results: list = [None] * n
    home_cache: dict = {}  # the branch check's home reference, shared by modules with equal geometry and loads
    # global wrench acting on the current platform from above, as (F, M about global origin)
    # the wrench is given about the last platform origin; M_above_o is about the stack origin
    F_above = np.zeros(3) if w is None else w[:3].copy()
    M_above_o = np.zeros(3) if w is None else w[3:] + np.cross(Tp[-1][:3, 3], w[:3])
    Bg = g
    for k in range(n - 1, -1, -1):
        Tb = bases[k]
        Rb = Tb[:3, :3]
        local = np.linalg.solve(Tb, Tp[k])
        # wrench at platform k origin, module-k base frame
        pk = Tp[k][:3, 3]
        M_pk = M_above_o - np.cross(pk, F_above)
        wk = np.concatenate([Rb.T @ F_above, Rb.T @ M_pk])
        gk = None if Bg is None else Rb.T @ Bg
        r = module_inverse(gs[k], local, wrench=wk if np.any(wk) else None, gravity=gk, n_elements=n_elements,
                           length_tolerance=length_tolerance, max_iterations=max_iterations, home_cache=home_cache)
        results[k] = r
        if not r.success:
            return StackIK(np.stack([x.lengths if x is not None else np.full(6, np.nan) for x in results]), False,
                           np.array([x.iterations if x is not None else 0 for x in results]), r.residual,
                           f"module {k + 1}: {r.reason}", tuple(results), time.perf_counter() - t_start)
        # module k's rods act on its base (platform k-1): forces n_i(0), moments m_i(0) about the holes
        P0, _ = hole_frames(gs[k])
        holes = (Rb @ P0.T).T + Tb[:3, 3]
        Fg = (Rb @ r.base_forces.T).T
        Mg = (Rb @ r.base_moments.T).T
        F_above = Fg.sum(axis=0)
        M_above_o = np.sum(Mg + np.cross(holes, Fg), axis=0)
    L = np.stack([x.lengths for x in results])
    return StackIK(L, True, np.array([x.iterations for x in results]), max(x.residual for x in results), "",
                   tuple(results), time.perf_counter() - t_start)


# --------------------------------------------------------------------------- constant curvature


@dataclass(frozen=True)
class ArcFit:
    """Constant-curvature arc fitted through platform poses.

    The arc starts at the stack base origin, tangent to the base z axis (the CC assumption for a
    single section): ``p(s) = ((1 - cos ks)/k cos phi, (1 - cos ks)/k sin phi, sin(ks)/k)``.

    Parameters
    ----------
    curvature : float
        k [1/m] (>= 0).
    phi : float
        Bending-plane angle from base x [rad].
    arc_lengths : ndarray, shape (n,)
        Arc-length parameter of each platform on the fitted arc [m].
    position_errors : ndarray, shape (n,)
        Distance of each platform origin from its arc point [m].
    tangent_errors : ndarray, shape (n,)
        Angle between each platform z axis and the arc tangent at its arc point [rad].
    rms_position_error, max_position_error : float
        [m].
    max_tangent_error : float
        [rad].
    """

    curvature: float
    phi: float
    arc_lengths: np.ndarray
    position_errors: np.ndarray
    tangent_errors: np.ndarray
    rms_position_error: float
    max_position_error: float
    max_tangent_error: float


def _arc_points(k, phi, s):
    """Arc points and tangents, stable for k -> 0; s shape (n,) -> (n, 3), (n, 3)."""
    x = k * s
    # (1 - cos x)/k = s * (1 - cos x)/x ; sin x / k = s * sin x / x
    small = np.abs(x) < 1e-6
    xs = np.where(small, 1.0, x)
    c1 = np.where(small, x / 2.0 - x**3 / 24.0, (1.0 - np.cos(xs)) / xs)
    c2 = np.where(small, 1.0 - x**2 / 6.0, np.sin(xs) / xs)
    P = np.stack([s * c1 * np.cos(phi), s * c1 * np.sin(phi), s * c2], axis=-1)
    t = np.stack([np.sin(x) * np.cos(phi), np.sin(x) * np.sin(phi), np.cos(x)], axis=-1)
    return P, t


def _segment_distances(P0, P1, Q0, Q1) -> np.ndarray:
    """Minimum distances between segments ``P0-P1`` and ``Q0-Q1``, broadcast over leading axes.

    Closest points of two segments: minimise ``|P(s) - Q(t)|`` over ``s, t in [0, 1]``.  The
    unconstrained optimum ``s`` is clamped, then ``t``, ``s`` and ``t`` are each re-optimised for
    the other one and clamped.  The first steps are the exact closest-point construction for
    segments (Ericson, Real-Time Collision Detection, 2005, sec 5.1.9), and each further step can
    only lower the distance, so the result is the minimum (parallel segments: ``s = 0`` first).
    """
    d1, d2, r = P1 - P0, Q1 - Q0, P0 - Q0
    a = np.einsum("...i,...i", d1, d1)
    e = np.einsum("...i,...i", d2, d2)
    b = np.einsum("...i,...i", d1, d2)
    c = np.einsum("...i,...i", d1, r)
    f = np.einsum("...i,...i", d2, r)
    den = a * e - b * b
    tiny = 1e-300
    s = np.where(den > 1e-14 * a * e, (b * f - c * e) / np.maximum(den, tiny), 0.0)
    s = np.clip(s, 0.0, 1.0)
    t = np.clip((b * s + f) / np.maximum(e, tiny), 0.0, 1.0)
    s = np.clip((b * t - c) / np.maximum(a, tiny), 0.0, 1.0)
    t = np.clip((b * s + f) / np.maximum(e, tiny), 0.0, 1.0)
    diff = r + s[..., None] * d1 - t[..., None] * d2
    return np.linalg.norm(diff, axis=-1)


def min_leg_gap(leg_positions, rod_diameter: float) -> tuple[float, tuple[int, int]]:
    """Smallest surface-to-surface gap between the legs of one module [m] (the paper's "no interference").

    Parameters
    ----------
    leg_positions : array_like, shape (6, N+1, 3)
        Leg node positions of one module [m] (e.g. ``ModulePose.leg_positions``).
    rod_diameter : float
        d [m].

    Returns
    -------
    gap : float
        ``min_{i<j} dist(centreline_i, centreline_j) - d`` with the centrelines taken as the polylines
        through the element nodes (chord error of a node interval of length ``l_e`` at curvature
        ``kappa``: at most ``kappa l_e^2 / 8``); negative means the rods intersect.
    pair : (int, int)
        The two legs (0-based) where it occurs.
    """
    X = np.asarray(leg_positions, dtype=float)
    if X.ndim != 3 or X.shape[0] != 6 or X.shape[1] < 2 or X.shape[2] != 3:
        raise ValueError(f"leg_positions must have shape (6, N+1, 3), got {X.shape}")
    if not np.all(np.isfinite(X)):
        raise ValueError("leg_positions must be finite")
    A0, A1 = X[:, :-1], X[:, 1:]  # (6, N, 3) segments
    best, pair = math.inf, (0, 1)
    for i in range(6):
        for j in range(i + 1, 6):
            dmin = float(np.min(_segment_distances(A0[i][:, None], A1[i][:, None], A0[j][None], A1[j][None])))
            if dmin < best:
                best, pair = dmin, (i, j)
    return best - float(rod_diameter), pair


def fit_constant_curvature(platform_poses, base_pose=None) -> ArcFit:
    """Least-squares constant-curvature arc through the platform origins of a stack.

    Unknowns: curvature k, plane angle phi and one arc-length parameter per platform; the
    objective is the sum of squared distances between the platform origins and their arc points
    (positions only; the platform-z vs arc-tangent angle is reported, not fitted).  A stack that
    bends like one CC section (e.g. the paper's Fig 10 "bending") fits closely; translation and
    S-shapes do not, which is the point of the comparison.

    Parameters
    ----------
    platform_poses : array_like, shape (n, 4, 4)
        Platform poses in the stack base frame.
    base_pose : array_like, shape (4, 4), optional
        Frame the arc starts in (default identity); poses are expressed in it first.

    Returns
    -------
    ArcFit
    """
    T = np.asarray(platform_poses, dtype=float)
    if T.ndim != 3 or T.shape[1:] != (4, 4) or T.shape[0] < 1:
        raise ValueError(f"platform_poses must have shape (n, 4, 4) with n >= 1, got {T.shape}")
    B = np.eye(4) if base_pose is None else _check_pose(base_pose, "base_pose")
    T = np.einsum("ij,njk->nik", np.linalg.inv(B), T)
    P = T[:, :3, 3]
    Z = T[:, :3, 2]
    tip = P[-1]
    phi0 = math.atan2(tip[1], tip[0]) if np.hypot(tip[0], tip[1]) > 1e-12 else 0.0
    s0 = np.cumsum(np.linalg.norm(np.diff(np.vstack([np.zeros(3), P]), axis=0), axis=1))
    r_xy = np.hypot(tip[0], tip[1])
    d2 = float(tip @ tip)
    k0 = 2.0 * r_xy / d2 if d2 > 0 else 0.0

    def res(x):
        Pa, _ = _arc_points(x[0], x[1], x[2:])
        return (Pa - P).ravel()

    best = None
    for kk in (k0, 0.0, 0.5 * k0, 2.0 * k0):
        sol = least_squares(res, np.concatenate([[kk, phi0], s0]), method="lm", xtol=1e-14, ftol=1e-14)
        if best is None or sol.cost < best.cost:
            best = sol
    k, phi, s = best.x[0], best.x[1], best.x[2:]
    if k < 0:  # same arc, opposite plane
        k, phi = -k, phi + math.pi
    phi = math.atan2(math.sin(phi), math.cos(phi))
    Pa, ta = _arc_points(k, phi, s)
    e = np.linalg.norm(Pa - P, axis=1)
    ang = np.arccos(np.clip(np.sum(ta * Z, axis=1), -1.0, 1.0))
    return ArcFit(float(k), float(phi), s, e, ang, float(np.sqrt(np.mean(e**2))), float(e.max()), float(ang.max()))
