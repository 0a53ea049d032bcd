"""The 3-D spring-link chain on rigid bodies (Exudyn ``ObjectRigidBody``, Euler parameters).

One Euler-parameter rigid body per link (``NodeRigidBodyEP``: Lie-group nodes fail in statics).
Each joint: a ``GenericJoint`` with the translations constrained (spherical joint, or Cardan joint
with ``torsion="locked"``) and an intrinsic ``RigidBodySpringDamper`` carrying ``diag(k, k, GJ/ds)``
(``axial=True``: no joint constraint, shear ``GA/ds`` and axial ``EA/ds`` springs too).  Continuum
tendons are ropes through an eyelet at every link (:meth:`.chain.Chain._continuum_ropes`).
Checked by ``tests/physics/test_spring_link.py`` (2-D = 3-D, oblique and rotated bends, torsion,
Cardan twist, axial compression) and ``test_hannan_walker.py`` (spatial preset).
"""

from __future__ import annotations

import math

import numpy as np

from ...models.result import SolverOptions
from ...robot import LoadCase, Payload, Robot
from .chain import Chain
from .geometry import ChainGeometry
from .routing import TendonRoute

__all__: list[str] = []


def _spatial_link_masses(geo: ChainGeometry, payload: Payload) -> tuple[np.ndarray, list, list]:
    """Link masses (N,), centres of mass (N x (3,)) and inertias about the joint (N x (3, 3)) in
    the body axes (x, y transverse, z along the link), payload folded into the last link."""
    mass, com = geo.mass.copy(), geo.com.copy()
    Ib = geo.inertia_bending + mass * com**2
    Ia = geo.inertia_axial.copy()
    coms = [np.array([0.0, 0.0, c]) for c in com]
    inertias = [np.diag([Ib[k], Ib[k], Ia[k]]) for k in range(geo.n_links)]
    pm = payload.mass
    if pm > 0:
        pp = np.array(payload.offset) + np.array([0.0, 0.0, geo.link_lengths[-1]])
        c_new = (mass[-1] * coms[-1] + pm * pp) / (mass[-1] + pm)
        inertias[-1] = inertias[-1] + pm * (np.dot(pp, pp) * np.eye(3) - np.outer(pp, pp))
        mass[-1] += pm
        coms[-1] = c_new
    return mass, coms, inertias


class SpatialChain(Chain):
    """3-D chain on rigid bodies; ``torsion`` ``"spring"`` (spherical joints) or ``"locked"``
    (Cardan joints); ``axial=True``: rigid-body springs instead of joint constraints."""

    planar = False

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 torsion: str = "spring", axial: bool = False) -> None:
        self.torsion = torsion
        self.axial = bool(axial)
        super().__init__(robot, load, options, geo)

    def _build(self, mbs) -> None:  # noqa: ANN001
        eii, geo = self.eii, self.geo
        self.g2 = np.asarray(self.robot.gravity_in_base(), dtype=float)
        self.ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        mass, coms, inertias = _spatial_link_masses(geo, self.robot.payload)
        self.nodes, self.bodies = [], []
        for k in range(geo.n_links):
            n = mbs.AddNode(eii.NodeRigidBodyEP(referenceCoordinates=[0.0, 0.0, float(geo.joints[k]), 1.0, 0.0, 0.0, 0.0]))
            J = inertias[k]
            b = mbs.AddObject(eii.ObjectRigidBody(
                nodeNumber=n, mass=float(mass[k]),
                inertia=[J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]],
                centerOfMass=[float(x) for x in coms[k]]))
            self.nodes.append(n)
            self.bodies.append(b)
        self._add_joints(mbs)
        self._add_gravity(mbs)
        m_tip = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[-1],
                                                  localPosition=[0.0, 0.0, float(geo.link_lengths[-1])]))
        self._add_tip_loads(mbs, m_tip)
        self._add_tendons(mbs)

    def _add_joints(self, mbs) -> None:  # noqa: ANN001
        eii, geo = self.eii, self.geo
        locked = 1 if self.torsion == "locked" else 0
        self.joint_springs, self.joint_markers = [], []
        for k in range(geo.n_links):
            if k == 0:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.ground, localPosition=[0.0, 0.0, float(geo.joints[0])]))
            else:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k - 1],
                                                       localPosition=[0.0, 0.0, float(geo.link_lengths[k - 1])]))
            m1 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k], localPosition=[0.0, 0.0, 0.0]))
            self.joint_markers.append((m0, m1))
            if not self.axial:
                mbs.AddObject(eii.GenericJoint(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 0, 0, locked]))
            kk = float(geo.stiffness[k])
            K = np.zeros((6, 6))
            K[3, 3] = K[4, 4] = kk
            K[5, 5] = 0.0 if locked else float(geo.torsion_stiffness[k])
            if self.axial:
                K[0, 0] = K[1, 1] = geo.shear_stiffness[k]
                K[2, 2] = geo.axial_stiffness[k]
            D = self.options.damping * K
            self.joint_springs.append(mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
                markerNumbers=[m0, m1], stiffness=K.tolist(), damping=D.tolist(), useIntrinsicFormulation=True)))

    def _eyelet_marker(self, mbs, i: int, tendon: TendonRoute, link: int, z: float, d: float) -> int:  # noqa: ANN001
        u = np.array([math.cos(tendon.sigma), math.sin(tendon.sigma)])
        x, y = (d * u).tolist()
        body = self.ground if link < 0 else self.bodies[link]
        return mbs.AddMarker(self._eyelet_marker_type()(bodyNumber=body, localPosition=[x, y, float(z)]))

    def link_frames(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) and link rotation matrices (N, 3, 3), base frame."""
        exu = self.exu
        P = np.array([self.mbs.GetNodeOutput(n, exu.OutputVariableType.Position) for n in self.nodes])
        R = np.array([np.asarray(self.mbs.GetNodeOutput(n, exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
                      for n in self.nodes])
        return P, R
