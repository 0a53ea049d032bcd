"""Cable geometry of the Hannan & Walker trunk (papers/000_, Eq. 1-3).

One joint of the robot connects two cylindrical segments; a cable runs through holes at
radius ``w`` (segment radius) whose exits are at axial distance ``h`` from the joint centre
on either side. The cable span across the joint is the chord between the two hole exits,
both at distance ``r = sqrt(w^2 + h^2)`` from the joint centre and separated by the angle
``psi = 2 atan(h/w) - theta`` when the joint bends by ``theta`` towards the cable. The span
is ``c = 2 r sin(psi/2)``, ``cos psi = (2 r^2 - c^2)/(2 r^2)`` and

``theta = pi - 2 atan(w/h) - atan2(c sqrt(4 r^2 - c^2), 2 r^2 - c^2)``   (Eq. 1)

with ``c = l - dl`` (evaluated in the equivalent half-angle form
``theta = 2 (atan2(h, w) - atan2(c/2, sqrt(r^2 - c^2/4)))``). Notes on Eq. 1 as printed:

* it uses a plain ``arctan`` of the ratio; that picks the wrong branch whenever
  ``psi > 90 deg`` (``2 r^2 < c^2``, e.g. always at ``dl = 0`` when ``h > w``). The
  quadrant-safe ``atan2`` form above is used (``sqrt(4 r^4 - (2 r^2 - c^2)^2)`` is written as
  ``c sqrt(4 r^2 - c^2)``, the same value without cancellation);
* ``theta(dl = 0) = 0`` requires the original span ``l = 2 h`` (straight joint), which is
  therefore not a free parameter here.

Eq. 2-3: a section of ``N = 4`` equal joints bends by ``4 theta`` in total; the angle of the
section's chord is ``phi = 2 theta`` (half the total bend, Eq. 3) and its curvature is
``k = 2 phi / s`` (Eq. 2) for arc length ``s``. For ``N`` joints: ``phi = N theta / 2``,
``k = N theta / s``.
"""

from __future__ import annotations

import numpy as np

from ._checks import as_float, broadcast_named, require_positive

__all__ = [
    "joint_angle_from_cable_change",
    "cable_change_from_joint_angle",
    "curvature_from_joint_angle",
    "joint_angle_from_curvature",
    "curvature_from_cable_change",
]


def _geom(w, h):
    w = as_float("w", w)
    h = as_float("h", h)
    require_positive("w", w)
    require_positive("h", h)
    return w, h


def joint_angle_from_cable_change(delta_l, w, h) -> np.ndarray:
    """Joint angle from the change of the cable span across one joint (Eq. 1, quadrant-safe).

    Parameters
    ----------
    delta_l : array_like, shape (...)
        Shortening of the cable span across the joint [m] (``> 0``: cable pulled, joint bends
        towards the cable; ``< 0``: bends away). For a section of ``N`` joints that share the
        cable equally, pass the section's cable change divided by ``N``.
    w : float or array_like
        Segment radius (cable hole radius) [m], ``> 0``.
    h : float or array_like
        Axial distance from the joint centre to the cable hole exit [m], ``> 0``; the
        original span is ``l = 2 h``.

    Returns
    -------
    theta : ndarray, shape (...)
        Joint angle [rad]; exactly 0 for ``delta_l = 0``.

    Raises
    ------
    ValueError
        If the new span ``2 h - delta_l`` is outside ``[0, 2 r]``, ``r = sqrt(w^2 + h^2)``.
    """
    dl = as_float("delta_l", delta_l)
    w, h = _geom(w, h)
    dl, w, h = broadcast_named(delta_l=dl, w=w, h=h)
    r2 = w * w + h * h
    c = 2.0 * h - dl
    if np.any(c < 0) or np.any(c * c > 4.0 * r2 * (1 + 1e-15)):
        raise ValueError("cable span 2h - delta_l must lie in [0, 2 sqrt(w^2 + h^2)] (joint limit exceeded)")
    # half-angle form of Eq. 1: sin(psi/2) = c/(2r), cos(psi/2) = sqrt(r^2 - c^2/4)/r with
    # r^2 - c^2/4 = w^2 + (dl/2)(2h - dl/2): psi/2 in [0, pi/2], no branch ambiguity, no
    # cancellation, and theta(dl = 0) = 0 exactly.
    cos_half = np.sqrt(np.maximum(w * w + 0.5 * dl * (2.0 * h - 0.5 * dl), 0.0))
    return 2.0 * (np.arctan2(h, w) - np.arctan2(0.5 * c, cos_half))


def cable_change_from_joint_angle(theta, w, h) -> np.ndarray:
    """Cable span shortening across one joint for a joint angle (inverse of Eq. 1).

    Parameters
    ----------
    theta : array_like, shape (...)
        Joint angle towards the cable [rad], within
        ``[2 atan(h/w) - pi, 2 atan(h/w)]`` (the hole exits may not cross).
    w, h : float or array_like
        See :func:`joint_angle_from_cable_change`.

    Returns
    -------
    delta_l : ndarray, shape (...)
        ``2 h - 2 r sin(psi/2)`` with ``psi = 2 atan(h/w) - theta`` [m].
    """
    th = as_float("theta", theta)
    w, h = _geom(w, h)
    th, w, h = broadcast_named(theta=th, w=w, h=h)
    psi = 2.0 * np.arctan2(h, w) - th
    if np.any(psi < -1e-15) or np.any(psi > np.pi + 1e-15):
        raise ValueError("theta outside the joint range [2 atan(h/w) - pi, 2 atan(h/w)]")
    r = np.sqrt(w * w + h * h)
    return 2.0 * h - 2.0 * r * np.sin(0.5 * psi)


def curvature_from_joint_angle(theta, s, joints_per_section: int = 4) -> np.ndarray:
    """Section curvature from the (equal) joint angle (Eq. 2-3).

    Parameters
    ----------
    theta : array_like, shape (...)
        Joint angle [rad].
    s : float or array_like
        Section arc length [m], ``> 0``.
    joints_per_section : int
        ``N`` (4 on the Hannan & Walker robot, giving Eq. 3 ``phi = 2 theta``).

    Returns
    -------
    k : ndarray, shape (...)
        ``k = 2 phi / s`` with ``phi = N theta / 2`` [1/m].
    """
    th = as_float("theta", theta)
    s = as_float("s", s)
    require_positive("s", s)
    if int(joints_per_section) < 1:
        raise ValueError("joints_per_section must be >= 1")
    phi = 0.5 * int(joints_per_section) * th
    return 2.0 * phi / s


def joint_angle_from_curvature(k, s, joints_per_section: int = 4) -> np.ndarray:
    """Joint angle from the section curvature (inverse of :func:`curvature_from_joint_angle`).

    Parameters
    ----------
    k : array_like, shape (...)
        Section curvature [1/m].
    s : float or array_like
        Section arc length [m], ``> 0``.
    joints_per_section : int
        ``N`` (4 on the Hannan & Walker robot).

    Returns
    -------
    theta : ndarray, shape (...)
        ``theta = k s / N`` [rad] (Eq. 2-3 solved for ``theta``).
    """
    k = as_float("k", k)
    s = as_float("s", s)
    require_positive("s", s)
    if int(joints_per_section) < 1:
        raise ValueError("joints_per_section must be >= 1")
    return k * s / int(joints_per_section)


def curvature_from_cable_change(delta_l_section, w, h, s, joints_per_section: int = 4) -> np.ndarray:
    """Section curvature from the section's cable length change (Eq. 1-3 chained).

    Parameters
    ----------
    delta_l_section : array_like, shape (...)
        Cable shortening over the whole section [m], shared equally by its joints.
    w, h : float or array_like
        Joint geometry [m] (see :func:`joint_angle_from_cable_change`).
    s : float or array_like
        Section arc length [m].
    joints_per_section : int

    Returns
    -------
    k : ndarray, shape (...)
        Curvature [1/m].
    """
    n = int(joints_per_section)
    if n < 1:
        raise ValueError("joints_per_section must be >= 1")
    theta = joint_angle_from_cable_change(as_float("delta_l_section", delta_l_section) / n, w, h)
    return curvature_from_joint_angle(theta, s, n)
