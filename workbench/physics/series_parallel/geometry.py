"""Geometry of one flexible six-rod parallel module (Huang et al. Fig 5) and pose helpers.

:class:`ModuleGeometry` holds the plain parameters (assumed defaults: the paper gives no numbers);
the functions give the hole frames on the base (Eq 21), the attachment points on the platform
(Eq 24, 26), poses as homogeneous transforms (base <- platform) and the input checks shared by
the solvers.  Pure numpy/scipy, no Exudyn work.  Checked by ``tests/physics/test_series_parallel.py``
(``test_bad_inputs_are_rejected``, the round-trip tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ...robot.description import circular_section
from ._systems import RodParams


@dataclass(frozen=True)
class ModuleGeometry:
    """Plain parameters of one flexible six-rod parallel module (Huang et al. Fig 5).

    Huang et al. give no numbers for the prototype; every default below is our assumption,
    sized so that the module reaches the paper's Fig 6 translations (+-200 mm) and twists (+-30 deg),
    and +-45 deg about x / y as tilts about the module's mid-height point.  Rotations about x / y
    about the platform centre stop short of 45 deg: the IK branch connected to home ends at
    rx +-26.8 deg (fold), ry -21.6 deg (symmetry-breaking bifurcation) and ry ~+38 deg (see
    ``docs/models.md``, "Series-parallel").

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
    yield_strength : float
        Rod 0.2 % proof stress [Pa] for the leg stress ratio (default 1.2e9: hardened and tempered
        spring steel 52CrMoV4, EN 10089, Rp0.2 >= 1200 MPa, Saarstahl data sheet).
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
    yield_strength: float = 1.2e9

    def __post_init__(self) -> None:
        for name in ("base_radius", "platform_radius", "height", "rod_diameter", "youngs_modulus", "density",
                     "yield_strength"):
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

    def rod_params(self) -> RodParams:
        """Section stiffnesses and weight per length of the legs (solid circular rod, no shear factor)."""
        A, I, J = circular_section(self.rod_diameter)
        return RodParams(
            EA=self.youngs_modulus * A,
            GA=self.shear_modulus * A,
            EI=self.youngs_modulus * I,
            GJ=self.shear_modulus * J,
            weight_per_length=self.density * A,
        )

    def platform_inertia(self) -> np.ndarray:
        """``(3,)`` principal inertia of a thin disk [kg m^2]."""
        m, r = self.platform_mass, self.platform_radius
        return np.array([m * r**2 / 4.0, m * r**2 / 4.0, m * r**2 / 2.0])

    def mount_transform(self) -> np.ndarray:
        """``(4, 4)`` constant transform platform k <- base k+1 (Eq 29-32)."""
        T = np.eye(4)
        T[:3, :3] = rot_z(math.radians(self.mount_twist_deg))
        T[2, 3] = self.mount_offset
        return T


def rot_z(t: float) -> np.ndarray:
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
    R = np.stack([rot_z(t) for t in b])
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


def check_pose(T, name="pose") -> np.ndarray:
    T = np.asarray(T, dtype=float)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise ValueError(f"{name} must be a finite (4, 4) homogeneous transform, got shape {T.shape}")
    R = T[:3, :3]
    if not np.allclose(R.T @ R, np.eye(3), atol=1e-8) or np.linalg.det(R) < 0:
        raise ValueError(f"{name}[:3, :3] must be a proper rotation matrix")
    return T


def check_lengths(L) -> np.ndarray:
    L = np.asarray(L, dtype=float)
    if L.shape != (6,) or not np.all(np.isfinite(L)) or np.any(L <= 0):
        raise ValueError(f"insertion_lengths must be 6 finite positive lengths [m], shape (6,), got {np.asarray(L).shape}: {L!r}")
    return L


def check_gravity(g):
    if g is None:
        return None
    g = np.asarray(g, dtype=float)
    if g.shape != (3,) or not np.all(np.isfinite(g)):
        raise ValueError(f"gravity must be None or a finite (3,) vector [m/s^2] in the base frame, got shape {g.shape}")
    return g


def check_wrench(w):
    if w is None:
        return None
    w = np.asarray(w, dtype=float)
    if w.shape != (6,) or not np.all(np.isfinite(w)):
        raise ValueError(f"wrench must be None or a finite (6,) vector (Fx, Fy, Fz, Mx, My, Mz) [N, N m], got shape {w.shape}")
    return w


def check_n_elements(n):
    if int(n) != n or n < 1:
        raise ValueError(f"n_elements must be a positive integer, got {n!r}")
    return int(n)


def rotation_vector(R) -> np.ndarray:
    """``(3,)`` rotation vector (log map) of a rotation matrix [rad] (Eq 27-28)."""
    return Rotation.from_matrix(np.asarray(R, dtype=float)).as_rotvec()


def interp_pose(H, T, slerp, lam):
    Tt = np.eye(4)
    Tt[:3, :3] = slerp([lam]).as_matrix()[0]
    Tt[:3, 3] = (1 - lam) * H[:3, 3] + lam * T[:3, 3]
    return Tt


def check_geometries(geometries) -> tuple:
    gs = tuple(geometries)
    if len(gs) < 1 or not all(isinstance(g, ModuleGeometry) for g in gs):
        raise ValueError("geometries must be a non-empty sequence of ModuleGeometry")
    return gs
