"""The 32-DOF Hannan & Walker trunk: the spatial CC plan of a line and its cables, Eq. 1 per plane.

The robot (papers/000_, Sec. 3) has 16 two-DOF joints and 16 cables: per section two antagonistic
pairs, one in the base x-z plane (sigma = 0, pi) and one in the y-z plane (sigma = pi/2, 3pi/2).
The paper's cable geometry (Eq. 1-3) is planar; on the spatial robot it is applied **per plane**:

1. the spatial CC resolved-rate controller (Eq. 10-11 with the spatial CC Jacobian,
   :func:`workbench.kinematics.follow_path` on a 3-column path) tracks a straight tip line in the
   base frame, giving per section a curvature ``kappa_i`` in a bending plane ``phi_i``;
2. the curvature splits into its plane components ``kappa_i cos(phi_i)`` (towards base +x) and
   ``kappa_i sin(phi_i)`` (towards +y), each giving equal joint angles per section by Eq. 2-3;
3. every joint is a Cardan joint ``R_rel = Rx(a) Ry(b)`` (:mod:`workbench.physics.spring_link.cardan`):
   bending towards +x is ``b``, towards +y is ``-a``; a cable at ``sigma`` sees the joint angle
   ``theta_sigma = cos(sigma) b - sin(sigma) a`` of its own plane, and its length change is Eq. 1
   of that angle summed over the joints it passes (:func:`cable_changes_from_cardan_angles`).

For a bend in one cable plane this is the exact rope geometry of the cables in that plane (it
reduces to the planar map, :func:`.replay.cable_changes_from_joint_angles`); the cables of the other
plane then lie on the bend's neutral line and shorten at second order in the joint angles (the chord
``2 h cos(theta/2)`` per joint), and oblique bends couple the planes at second order too -- both
ignored by Eq. 1 per plane (measured in ``tests/experiments/test_hannan_walker_3d.py``, and in
``docs/models.md``).  Checked there too: planar plans on this robot equal the planar 16-DOF chain to 1e-9.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...kinematics import follow_path, line_path
from ...kinematics.hannan_walker import cable_change_from_joint_angle, joint_angle_from_curvature
from ...physics.spring_link import chain_geometry_from_robot
from ...robot import Robot

#: resolved-rate iterations per path sample of the spatial plan
_MAX_ITER = 600

__all__ = [
    "cable_changes_from_cardan_angles",
    "cardan_angles_from_arcs",
    "CCSpatialPlan",
    "cc_spatial_cable_plan",
]


def _plane_signs(sigma: float) -> tuple[float, float]:
    """``(cos sigma, sin sigma)`` rounded to -1/0/1; a cable must lie in the x-z or the y-z plane."""
    c, s = np.cos(sigma), np.sin(sigma)
    rc, rs = round(float(c)), round(float(s))
    if abs(c - rc) > 1e-9 or abs(s - rs) > 1e-9:
        raise ValueError(f"Eq. (1) per plane needs cables in the base x-z or y-z plane (sigma a multiple of pi/2), "
                         f"got sigma = {sigma:.6g} rad")
    return float(rc), float(rs)


def cable_changes_from_cardan_angles(cardan, robot: Robot, n_links: int | None = None) -> np.ndarray:
    """Cable length changes of the two-DOF-joint robot from its Cardan angles (Eq. 1 per plane).

    Parameters
    ----------
    cardan : array_like, shape (..., N, 2)
        Cardan angles ``(a, b)`` of every joint, ``R_rel = Rx(a) Ry(b)`` [rad] (the
        ``joint_angles`` of ``spring_link_cardan``).
    robot : Robot
        Cables at sigma in {0, pi/2, pi, 3pi/2}, constant offsets (the ``hannan_walker_3d`` preset).
    n_links : int, optional
        Number of joints ``N`` (default: from ``cardan``).

    Returns
    -------
    dl : ndarray, shape (..., n_tendons)
        Change of each cable's length from the straight reference [m] (negative = shorter), in
        :meth:`Robot.tendon_table` order.
    """
    q = np.asarray(cardan, dtype=float)
    if q.ndim < 2 or q.shape[-1] != 2:
        raise ValueError(f"cardan must have shape (..., N, 2), got {q.shape}")
    N = q.shape[-2] if n_links is None else int(n_links)
    if q.shape[-2] != N:
        raise ValueError(f"cardan must have shape (..., {N}, 2), got {q.shape}")
    geo = chain_geometry_from_robot(robot, N)
    h = 0.5 * np.diff(geo.eyelets)
    out = []
    for j, sigma, grp in robot.tendon_table():
        if grp.offset_tip is not None:
            raise ValueError("tapered tendon offsets are not supported by the Eq. (1) cable map")
        c, s = _plane_signs(sigma)
        m = int(geo.section_end_eyelet[j])
        theta = c * q[..., :m, 1] - s * q[..., :m, 0]
        out.append(np.sum(-cable_change_from_joint_angle(theta, grp.offset, h[:m]), axis=-1))
    return np.stack(out, axis=-1)


def cardan_angles_from_arcs(kappa, phi, ell, joints_per_section: int) -> np.ndarray:
    """Equal Cardan angles per section from CC arcs, per plane (Eq. 2-3 in each cable plane).

    Parameters
    ----------
    kappa, phi : array_like, shape (..., n)
        Section curvatures [1/m] and bending planes from base x [rad].
    ell : array_like, shape (n,)
        Section lengths [m].
    joints_per_section : int

    Returns
    -------
    cardan : ndarray, shape (..., n * joints_per_section, 2)
        ``(a, b) = (-theta_y, theta_x)`` with ``theta_x = kappa cos(phi) l / n_j`` (towards +x) and
        ``theta_y = kappa sin(phi) l / n_j`` (towards +y) [rad].
    """
    k = np.asarray(kappa, dtype=float)
    f = np.asarray(phi, dtype=float)
    per = int(joints_per_section)
    tx = joint_angle_from_curvature(k * np.cos(f), ell, per)
    ty = joint_angle_from_curvature(k * np.sin(f), ell, per)
    return np.stack([np.repeat(-ty, per, axis=-1), np.repeat(tx, per, axis=-1)], axis=-1)


@dataclass(frozen=True, eq=False)
class CCSpatialPlan:
    """The spatial CC plan of a straight line and its cable commands (:func:`cc_spatial_cable_plan`).

    Attributes
    ----------
    path : ndarray, shape (m, 3)
        Line samples, base frame [m].
    kappa, phi : ndarray, shape (m, n_sections)
        Section curvatures [1/m] and bending planes [rad] of the resolved-rate controller.
    success : bool
        The controller tracked the line to its tolerance.
    tracking_error : ndarray, shape (m,)
        Its tip error per sample [m].
    cardan : ndarray, shape (m, N, 2) or (N, 2), or None
        Per-plane equal joint angles of all samples, or of the one requested sample; ``None`` when
        the controller failed.
    cable_changes : ndarray, shape (m, n_tendons) or (n_tendons,), or None
        Cable commands (Eq. 1 per plane) [m].
    """

    path: np.ndarray
    kappa: np.ndarray
    phi: np.ndarray
    success: bool
    tracking_error: np.ndarray
    cardan: np.ndarray | None
    cable_changes: np.ndarray | None


def cc_spatial_cable_plan(robot: Robot, start, end, n_samples: int, *, kappa0=None, phi0=None, kappa_d=None,
                          n_links: int = 16, sample: int | None = None) -> CCSpatialPlan:
    """Spatial CC resolved-rate plan of the line ``start -> end`` and its cables (Eq. 1 per plane).

    Parameters
    ----------
    robot : Robot
        Cables in the two planes (see :func:`cable_changes_from_cardan_angles`).
    start, end : sequence of 3 numbers
        Line end points, base frame ``(x, y, z)`` [m].
    n_samples : int
        Path samples, both ends included.
    kappa0, phi0 : array_like, shape (n_sections,), optional
        Initial curvatures [1/m] (default ``0.1 / L``) and bending planes [rad] (default: the
        direction of ``start`` from the base axis, ``atan2(y, x)``, in every section).
    kappa_d : array_like, shape (n_sections,), optional
        Null-space target curvatures of Eq. 11 (``None``: no null-space task).
    n_links : int
        Joints of the robot (16).
    sample : int, optional
        Cable commands of this sample only (0-based); default all.

    Returns
    -------
    CCSpatialPlan
        Without commands when the controller did not track the line.
    """
    a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    if a.shape != (3,) or b.shape != (3,):
        raise ValueError(f"start and end must have shape (3,) = (x, y, z), got {a.shape} and {b.shape}")
    ell = np.asarray(robot.section_lengths, dtype=float)
    ns = robot.n_sections
    k0 = np.full(ns, 0.1 / robot.length) if kappa0 is None else np.asarray(kappa0, dtype=float)
    p0 = np.full(ns, np.arctan2(a[1], a[0])) if phi0 is None else np.asarray(phi0, dtype=float)
    path = line_path(a, b, n_samples)
    # the spatial null-space task needs more iterations per sample than the planar one (measured:
    # up to ~410 at null_gain 0.2 on the study's lines, against 100 for the planar plan)
    pr = follow_path(path, k0, ell, phi0=p0, kappa_d=kappa_d, max_iter_per_sample=_MAX_ITER)
    kappa, phi = np.asarray(pr.q[:, 0]), np.asarray(pr.q[:, 1])
    if not pr.success:
        return CCSpatialPlan(path, kappa, phi, False, np.asarray(pr.error), None, None)
    sel = slice(None) if sample is None else sample
    q = cardan_angles_from_arcs(kappa[sel], phi[sel], ell, n_links // ns)
    return CCSpatialPlan(path, kappa, phi, True, np.asarray(pr.error), q,
                         cable_changes_from_cardan_angles(q, robot, n_links))
