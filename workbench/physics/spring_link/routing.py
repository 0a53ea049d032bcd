"""Tendon routing along the chain (pure numpy) and the Exudyn items of one eyelet rope.

Eyelet ropes pass the robot's disks (``robot.disk_stations()`` up to their section end; the
section-end station is the terminating eyelet) at the tendon's offset ``d`` (``offset_at`` the
fraction of its own path, for tapered groups), as in the ANCF model; a disk sits on the link
whose span contains its station (links may be finer than disks).  Continuum tendons use the link
eyelets.  Tension control: one constant-force spring-damper (stiffness 0) per straight rope
segment, exactly a frictionless rope with uniform tension ``T``.  Length control: one
``ObjectConnectorReevingSystemSprings`` rope, ``T = EA_t (L - L_0) / L_0``.  Checked by
``tests/physics/test_spring_link_eyelets.py`` (eyelets at the disk stations) and
``test_reeving_length_control_equals_constant_force_rope``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...robot import Robot
from .geometry import ChainGeometry

__all__: list[str] = []


@dataclass(frozen=True)
class TendonRoute:
    """Routing of one tendon along the chain (reference configuration, lengths in m)."""

    section: int
    sigma: float
    end_eyelet: int          # index m of the terminating link eyelet (section end)
    offsets: np.ndarray      # (m + 1,) offset d at link eyelets 0..m
    axial_stiffness: float
    reference_length: float  # straight reference path length (eyelet 0 to m; eyelet ropes: disk path)
    tapered: bool
    moment_arm: np.ndarray   # (m,) d cos(alpha) at joints 1..m (continuum: internal moment / T)
    cos_alpha: np.ndarray    # (m,) cos of the tendon's reference slope angle at joints 1..m
    eye_link: np.ndarray     # (n_eye,) int, link carrying each rope eyelet (-1: base plate)
    eye_z: np.ndarray        # (n_eye,) axial position of the eyelet past that link's joint [m]
    eye_d: np.ndarray        # (n_eye,) tendon offset at the eyelet [m]


def _eyelet_placement(geo: ChainGeometry, stations: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Link index (-1 = base plate) and axial position past its joint for arc-length ``stations``.

    Link ``k`` spans ``[s_k, s_{k+1})`` (the last one up to the tip); a station below the first
    joint lies on the base plate, at axial position equal to the station.
    """
    k = np.searchsorted(geo.joints, stations, side="right") - 1
    z = np.where(k < 0, stations, stations - geo.joints[np.maximum(k, 0)])
    return k.astype(int), z



def add_eyelet_rope(mbs, marks: list, tendon: "TendonRoute", mode: str, damping: float) -> list:
    """Exudyn items of one frictionless eyelet rope through ``marks`` (base anchor first).

    Tension mode: one constant-force spring-damper per straight segment (stiffness 0, the force is
    set by the load ramp), i.e. the same tension in every segment.  Length mode: one
    ``ObjectConnectorReevingSystemSprings`` rope with the tendon's EA_t and rest length.
    """
    import exudyn as exu
    import exudyn.itemInterface as eii

    if mode == "tension":
        return [mbs.AddObject(eii.ObjectConnectorSpringDamper(
            markerNumbers=[a, b], referenceLength=0.0, stiffness=0.0, force=0.0))
            for a, b in zip(marks[:-1], marks[1:])]
    n = len(marks)
    return [mbs.AddObject(eii.ObjectConnectorReevingSystemSprings(
        markerNumbers=marks, stiffnessPerLength=float(tendon.axial_stiffness),
        dampingPerLength=float(damping * tendon.axial_stiffness),
        referenceLength=float(tendon.reference_length), regularizationForce=-1.0,
        sheavesRadii=[0.0] * n, sheavesAxes=exu.Vector3DList([[0.0, 0.0, 1.0]] * n)))]

def route_tendons(robot: Robot, geo: ChainGeometry, tendon_model: str = "continuum") -> list[TendonRoute]:
    """Tendon routing.  Eyelet ropes pass the robot's disks (``robot.disk_stations()``) of the
    sections they cross and end at their section end (as in the ANCF model); the links may be
    finer than the disks.  Continuum tendons use the link eyelets."""
    out = []
    disks = robot.disk_stations()
    for j, sigma, grp in robot.tendon_table():
        m = int(geo.section_end_eyelet[j])
        e = geo.eyelets[: m + 1]
        d = np.array([grp.offset_at(x / e[-1]) for x in e])
        # straight reference: eyelets on a straight line, offsets may vary (taper)
        L_ref = float(np.sum(np.hypot(np.diff(e), np.diff(d))))
        cos_a = 1.0 / np.hypot(1.0, np.diff(d) / np.diff(e))
        arm = 0.5 * (d[:-1] + d[1:]) * cos_a
        if tendon_model == "eyelets":
            end = float(e[-1])
            tol = 1e-9 * robot.length
            st = disks[(disks > tol) & (disks < end - tol)]
            st = np.concatenate([[0.0], st, [end]])
            dd = np.array([grp.offset_at(x / end) for x in st])
            L_ref = float(np.sum(np.hypot(np.diff(st), np.diff(dd))))
            link, z = _eyelet_placement(geo, st)
            link[-1] = m - 1                        # the terminating eyelet sits on link m - 1
            z[-1] = float(e[-1] - geo.joints[m - 1])
            link[0], z[0] = -1, 0.0
        else:
            dd = d
            link = np.arange(-1, m)
            z = np.concatenate([[0.0], e[1:] - geo.joints[:m]])
        out.append(TendonRoute(j, float(sigma), m, d, grp.axial_stiffness, L_ref, grp.offset_tip is not None, arm,
                           cos_a, link, z, dd))
    return out
