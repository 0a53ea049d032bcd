"""The planar spring-link chain on rigid bodies (Exudyn ``RigidBody2D``).

One ``RigidBody2D`` per link, joined by ``RevoluteJoint2D`` and a ``CoordinateSpringDamper`` on the
relative rotation (stiffness ``k_k``, damping ``options.damping * k_k``); with ``axial=True`` each
joint is an intrinsic ``RigidBodySpringDamper`` with shear, axial and bending stiffness instead.
Exudyn's plane (X, Y) is base (x, z): the chain bends in the base x-z plane.  Continuum tendons:
tension mode applies torque pairs on the links they pass, length mode a rotational spring to
ground on the terminating link (``EA_t d^2 / L_0``, switched off when slack).  Checked by
``tests/physics/test_spring_link.py`` (arc, heavy elastica, CC limit, slack, 2-D = 3-D, axial).
"""

from __future__ import annotations

import numpy as np

from ...models.result import SolverOptions
from ...robot import LoadCase, Payload, Robot
from .chain import Chain
from .geometry import ChainGeometry
from .routing import TendonRoute

__all__: list[str] = []


def _planar_link_masses(geo: ChainGeometry, payload: Payload) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Link masses (N,), centres of mass along the links (N,), inertias about the centre (N,)
    and the last link's centre of mass in its plane frame (2,), with the payload folded into the
    last link (point mass at its offset in the tip frame)."""
    mass, com, inertia = geo.mass.copy(), geo.com.copy(), geo.inertia_bending.copy()
    pm = payload.mass
    if pm > 0:
        ox, _, oz = payload.offset
        px = np.array([0.0, com[-1]])
        pp = np.array([ox, geo.link_lengths[-1] + oz])
        mt = mass[-1] + pm
        c = (mass[-1] * px + pm * pp) / mt
        inertia[-1] = inertia[-1] + mass[-1] * np.sum((px - c) ** 2) + pm * np.sum((pp - c) ** 2)
        mass[-1] = mt
        return mass, com, inertia, c
    return mass, com, inertia, np.array([0.0, com[-1]])


class PlanarChain(Chain):
    """Planar chain on rigid bodies; ``axial=True``: rigid-body springs instead of pin joints."""

    planar = True

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 axial: bool = False) -> None:
        self.axial = bool(axial)
        super().__init__(robot, load, options, geo)

    def _build(self, mbs) -> None:  # noqa: ANN001
        eii, geo = self.eii, self.geo
        g = self.robot.gravity_in_base()
        self.g2 = np.array([g[0], g[2], 0.0])
        self.ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        ng = mbs.AddNode(eii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
        self.m_ground_coord = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=ng, coordinate=0))
        mass, com, inertia, self.com_last = _planar_link_masses(geo, self.robot.payload)
        self._add_links(mbs, mass, com, inertia)
        self._add_joints(mbs)
        self._add_gravity(mbs)
        m_tip = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[-1],
                                                  localPosition=[0.0, float(geo.link_lengths[-1]), 0.0]))
        f, tq = self.load.tip_force, self.load.tip_torque
        self._add_tip_loads(mbs, m_tip, np.array([f[0], f[2], 0.0]), np.array([0.0, 0.0, -tq[1]]))
        self._add_tendons(mbs)

    def _add_links(self, mbs, mass: np.ndarray, com: np.ndarray, inertia: np.ndarray) -> None:  # noqa: ANN001
        eii, geo = self.eii, self.geo
        N = geo.n_links
        self.nodes, self.bodies, self.coord_markers = [], [], []
        for k in range(N):
            n = mbs.AddNode(eii.NodeRigidBody2D(referenceCoordinates=[0.0, float(geo.joints[k]), 0.0]))
            c = self.com_last if k == N - 1 else np.array([0.0, com[k]])
            b = mbs.AddObject(
                eii.RigidBody2D(nodeNumber=n, mass=float(mass[k]), inertia=float(inertia[k]),
                                centerOfMass=[float(c[0]), float(c[1])])
            )
            self.nodes.append(n)
            self.bodies.append(b)
            self.coord_markers.append(mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=n, coordinate=2)))

    def _add_joints(self, mbs) -> None:  # noqa: ANN001
        """Pin joint + rotational spring per joint, or one rigid-body spring with ``axial``."""
        eii, geo, damping = self.eii, self.geo, self.options.damping
        self.joint_springs, self.joint_markers = [], []
        for k in range(geo.n_links):
            if k == 0:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.ground, localPosition=[0.0, float(geo.joints[0]), 0.0]))
                c0 = self.m_ground_coord
            else:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k - 1],
                                                       localPosition=[0.0, float(geo.link_lengths[k - 1]), 0.0]))
                c0 = self.coord_markers[k - 1]
            m1 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k], localPosition=[0.0, 0.0, 0.0]))
            self.joint_markers.append((m0, m1))
            if self.axial:
                K = np.zeros((6, 6))
                K[0, 0], K[1, 1], K[5, 5] = geo.shear_stiffness[k], geo.axial_stiffness[k], geo.stiffness[k]
                self.joint_springs.append(mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
                    markerNumbers=[m0, m1], stiffness=K.tolist(), damping=(damping * K).tolist(),
                    useIntrinsicFormulation=True)))
                continue
            mbs.AddObject(eii.RevoluteJoint2D(markerNumbers=[m0, m1]))
            self.joint_springs.append(mbs.AddObject(eii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[c0, self.coord_markers[k]], stiffness=float(geo.stiffness[k]),
                damping=float(damping * geo.stiffness[k]))))

    def _eyelet_marker(self, mbs, i: int, tendon: TendonRoute, link: int, z: float, d: float) -> int:  # noqa: ANN001
        body = self.ground if link < 0 else self.bodies[link]
        x, y = float(self.sign[i] * d), float(z)
        return mbs.AddMarker(self._eyelet_marker_type()(bodyNumber=body, localPosition=[x, y, 0.0]))

    def _continuum_items(self, mbs, i: int, tendon: TendonRoute) -> list:  # noqa: ANN001
        eii = self.eii
        if self.mode == "length":
            return [mbs.AddObject(eii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[self.m_ground_coord, self.coord_markers[tendon.end_eyelet - 1]],
                stiffness=0.0, offset=0.0))]
        # internal moment T a_k at joint k = torque pairs; link k carries T (a_k - a_{k+1})
        # (only the terminating link for a constant offset); the base reaction acts on ground
        items = []
        for k in (range(tendon.end_eyelet) if tendon.tapered else [tendon.end_eyelet - 1]):
            mt = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k]))
            items.append(mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mt, loadVector=[0.0, 0.0, 0.0])))
        return items

    def _set_continuum(self) -> None:
        mbs = self.mbs
        for i, (t, items) in enumerate(zip(self.tendons, self.tendon_items)):
            v = float(self._values[i])
            if self.mode == "tension":
                for it, tau in zip(items, self._continuum_torques(i, v)):
                    mbs.SetLoadParameter(it, "loadVector", tau)
                continue
            d, c, L0 = t.offsets[-1], self.sign[i], float(self._L0[i])
            K = t.axial_stiffness * d * d / L0
            phi_star = (L0 - self.lag_gaps[i] - t.reference_length) / (d * c)
            mbs.SetObjectParameter(items[0], "stiffness", K if self.tendon_active[i] else 0.0)
            mbs.SetObjectParameter(items[0], "offset", float(phi_star))
        if self.axial:
            self._set_compression(axis=1)

    def _continuum_torques(self, i: int, v: float) -> list[list[float]]:
        """Torques about Exudyn Z = -base y, one per loaded link (see :meth:`_continuum_items`)."""
        t = self.tendons[i]
        a = t.moment_arm
        w = (a - np.append(a[1:], 0.0)) if t.tapered else a[-1:]
        return [[0.0, 0.0, float(-v * wk * self.sign[i])] for wk in w]

    def link_states(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) in the base frame and link angles beta (N,) (towards +x)."""
        exu = self.exu
        P = np.zeros((len(self.nodes), 3))
        beta = np.zeros(len(self.nodes))
        for k, n in enumerate(self.nodes):
            q = self.mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates)
            P[k] = [q[0], 0.0, self.geo.joints[k] + q[1]]
            beta[k] = -q[2]
        return P, beta
