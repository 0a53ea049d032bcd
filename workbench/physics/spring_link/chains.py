"""The Exudyn chain builders (verbatim move; split into one file per chain next)."""

from __future__ import annotations

import math

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .geometry import ChainGeometry
from .routing import _add_eyelet_rope, _tendons
from .shape import _points_on_links, _rotation_vectors, _twist_vs_parallel_transport

__all__: list[str] = []


class _Planar:
    """Builds and drives the planar chain; holds Exudyn handles for one solve (not module state)."""

    def _bind(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry) -> None:
        """Store the inputs and the tendon routing shared by every chain variant."""
        import exudyn as exu

        check_model_inputs(robot, load, options)
        self.exu = exu
        self.robot, self.load, self.options, self.geo = robot, load, options, geo
        self.tendons = _tendons(robot, geo, options.tendon_model)
        self.mode = None if load.actuation is None else load.actuation.mode
        self.model = options.tendon_model

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 axial: bool = False) -> None:
        import exudyn as exu
        import exudyn.itemInterface as eii

        self._bind(robot, load, options, geo)
        self.axial = bool(axial)
        if self.axial and self.mode == "length" and self.model == "continuum":
            raise ModelFailure("spring_link: axial=True with continuum tendons in length mode is not supported; "
                               "use tendon_model='eyelets'")
        if self.mode == "length" and self.model == "continuum" and any(t.tapered for t in self.tendons):
            raise ModelFailure(
                "spring_link: continuum tendons with tapered offsets (offset_tip) are not supported in "
                "length mode; use tendon_model='eyelets'"
            )
        N = geo.n_links
        self.SC = exu.SystemContainer()
        mbs = self.SC.AddSystem()
        self.mbs = mbs
        g = robot.gravity_in_base()
        self.g2 = np.array([g[0], g[2], 0.0])

        ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        self.ground = ground
        ng = mbs.AddNode(eii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0]))
        self.m_ground_coord = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=ng, coordinate=0))

        # payload folded into the last link (point mass at its offset in the tip frame)
        mass, com, inertia = geo.mass.copy(), geo.com.copy(), geo.inertia_bending.copy()
        pm = robot.payload.mass
        if pm > 0:
            ox, _, oz = robot.payload.offset
            px = np.array([0.0, com[-1]])
            pp = np.array([ox, geo.link_lengths[-1] + oz])
            mt = mass[-1] + pm
            c = (mass[-1] * px + pm * pp) / mt
            inertia[-1] = inertia[-1] + mass[-1] * np.sum((px - c) ** 2) + pm * np.sum((pp - c) ** 2)
            mass[-1] = mt
            self.com_last = c
        else:
            self.com_last = np.array([0.0, com[-1]])

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

        # joints and rotational springs
        self.joint_springs, self.joint_markers = [], []
        for k in range(N):
            if k == 0:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, float(geo.joints[0]), 0.0]))
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
                    markerNumbers=[m0, m1], stiffness=K.tolist(), damping=(options.damping * K).tolist(),
                    useIntrinsicFormulation=True)))
                continue
            mbs.AddObject(eii.RevoluteJoint2D(markerNumbers=[m0, m1]))
            self.joint_springs.append(mbs.AddObject(eii.ObjectConnectorCoordinateSpringDamper(
                markerNumbers=[c0, self.coord_markers[k]], stiffness=float(geo.stiffness[k]),
                damping=float(options.damping * geo.stiffness[k]))))

        # gravity
        self.gravity_loads = []
        if np.any(self.g2 != 0):
            for b in self.bodies:
                mm = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=b))
                self.gravity_loads.append(mbs.AddLoad(eii.LoadMassProportional(markerNumber=mm, loadVector=[0.0, 0.0, 0.0])))
        # tip loads
        m_tip = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[-1],
                                                  localPosition=[0.0, float(geo.link_lengths[-1]), 0.0]))
        f, tq = load.tip_force, load.tip_torque
        self.tip_force_full = np.array([f[0], f[2], 0.0])
        self.tip_torque_full = np.array([0.0, 0.0, -tq[1]])
        self.tip_force_load = mbs.AddLoad(eii.LoadForceVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        self.tip_torque_load = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))

        # tendons
        self.eyelet_markers: list[list[int]] = []
        self.tendon_items: list[list[int]] = []
        self.tendon_active = [True] * len(self.tendons)
        for t in self.tendons:
            c = math.cos(t.sigma)
            c = 1.0 if c > 0 else -1.0
            marks = []
            _MK = eii.MarkerBodyRigid if (self.model == "eyelets" and self.mode == "length") else eii.MarkerBodyPosition
            for lk, zk, dk in zip(t.eye_link, t.eye_z, t.eye_d):
                x, y = float(c * dk), float(zk)
                body = ground if lk < 0 else self.bodies[lk]
                marks.append(mbs.AddMarker(_MK(bodyNumber=body, localPosition=[x, y, 0.0])))
            self.eyelet_markers.append(marks)
            items = []
            if self.mode is None:
                pass
            elif self.model == "eyelets" and self.mode == "tension":
                for a, b in zip(marks[:-1], marks[1:]):
                    items.append(mbs.AddObject(eii.ObjectConnectorSpringDamper(
                        markerNumbers=[a, b], referenceLength=0.0, stiffness=0.0, force=0.0)))
            elif self.model == "eyelets" and self.mode == "length":
                n = len(marks)
                items.append(mbs.AddObject(eii.ObjectConnectorReevingSystemSprings(
                    markerNumbers=marks, stiffnessPerLength=float(t.axial_stiffness),
                    dampingPerLength=float(options.damping * t.axial_stiffness),
                    referenceLength=float(t.reference_length), regularizationForce=-1.0,
                    sheavesRadii=[0.0] * n, sheavesAxes=exu.Vector3DList([[0.0, 0.0, 1.0]] * n))))
            elif self.model == "continuum" and self.mode == "tension":
                # internal moment T a_k at joint k = torque pairs; link k carries T (a_k - a_{k+1})
                # (only the terminating link for a constant offset); the base reaction acts on ground
                links = range(t.end_eyelet) if t.tapered else [t.end_eyelet - 1]
                for k in links:
                    mt = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k]))
                    items.append(mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mt, loadVector=[0.0, 0.0, 0.0])))
            else:  # continuum, length
                items.append(mbs.AddObject(eii.ObjectConnectorCoordinateSpringDamper(
                    markerNumbers=[self.m_ground_coord, self.coord_markers[t.end_eyelet - 1]],
                    stiffness=0.0, offset=0.0)))
            self.tendon_items.append(items)
        mbs.Assemble()
        self.sign = [1.0 if math.cos(t.sigma) > 0 else -1.0 for t in self.tendons]

    # -- load application ----------------------------------------------------------------
    def rest_lengths(self, values: np.ndarray, pretension_factor: float) -> np.ndarray:
        """Rope rest lengths L_0 for length commands ``values``."""
        p = 0.0 if self.load.actuation is None else self.load.actuation.pretension
        out = []
        for t, v in zip(self.tendons, values):
            L0 = t.reference_length + v - pretension_factor * p * t.reference_length / t.axial_stiffness
            if L0 <= 0:
                raise ModelFailure(f"spring_link: tendon rest length {L0:.4g} m <= 0 (command {v:.4g} m too short)")
            out.append(L0)
        return np.asarray(out)

    def set_external(self, lam: float) -> None:
        mbs = self.mbs
        for ld in self.gravity_loads:
            mbs.SetLoadParameter(ld, "loadVector", (lam * self.g2).tolist())
        mbs.SetLoadParameter(self.tip_force_load, "loadVector", (lam * self.tip_force_full).tolist())
        mbs.SetLoadParameter(self.tip_torque_load, "loadVector", (lam * self.tip_torque_full).tolist())

    def set_tendons(self, values: np.ndarray, pretension_factor: float) -> None:
        """Apply tendon commands (tensions [N] or length changes [m])."""
        mbs = self.mbs
        if self.mode is None:
            return
        self._values = np.asarray(values, dtype=float)
        if self.mode == "length":
            self._L0 = self.rest_lengths(self._values, pretension_factor)
        for i, (t, items) in enumerate(zip(self.tendons, self.tendon_items)):
            v = float(self._values[i])
            if self.model == "eyelets" and self.mode == "tension":
                for it in items:
                    mbs.SetObjectParameter(it, "force", v)
            elif self.model == "eyelets":
                mbs.SetObjectParameter(items[0], "referenceLength", float(self._L0[i]))
                mbs.SetObjectParameter(items[0], "activeConnector", bool(self.tendon_active[i]))
            elif self.mode == "tension":
                for it, tau in zip(items, self._continuum_torques(i, v)):
                    mbs.SetLoadParameter(it, "loadVector", tau)
            else:
                d, c, L0 = t.offsets[-1], self.sign[i], float(self._L0[i])
                K = t.axial_stiffness * d * d / L0
                phi_star = (L0 - t.reference_length) / (d * c)
                mbs.SetObjectParameter(items[0], "stiffness", K if self.tendon_active[i] else 0.0)
                mbs.SetObjectParameter(items[0], "offset", float(phi_star))
        if self.axial and self.model == "continuum" and self.mode == "tension":
            # continuum tendon: axial compression sum(T) in every joint it passes (rest-length offset)
            N = self.geo.n_links
            comp = np.zeros(N)
            for t, v in zip(self.tendons, self._values):
                comp[: t.end_eyelet] += v * t.cos_alpha
            ax = 1 if isinstance(self, _Planar) and not isinstance(self, _Spatial) else 2
            for k in range(N):
                off = [0.0] * 6
                off[ax] = float(-comp[k] / self.geo.axial_stiffness[k])
                mbs.SetObjectParameter(self.joint_springs[k], "offset", off)

    def _continuum_torques(self, i: int, v: float) -> list[list[float]]:
        # planar: torques about Exudyn Z = -base y, one per loaded link
        t = self.tendons[i]
        a = t.moment_arm
        w = (a - np.append(a[1:], 0.0)) if t.tapered else a[-1:]
        return [[0.0, 0.0, float(-v * wk * self.sign[i])] for wk in w]

    # -- state access ----------------------------------------------------------------------
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

    def tendon_lengths(self) -> np.ndarray:
        exu = self.exu
        out = []
        for t, marks in zip(self.tendons, self.eyelet_markers):
            if self.model == "continuum":
                _, beta = self.link_states()
                out.append(t.reference_length - t.offsets[-1] * self.sign[len(out)] * beta[t.end_eyelet - 1])
            else:
                pts = np.array([self.mbs.GetMarkerOutput(m, exu.OutputVariableType.Position) for m in marks])
                out.append(float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
        return np.asarray(out)

    def tensions(self) -> np.ndarray:
        if self.mode is None:
            return np.zeros(len(self.tendons))
        if self.mode == "tension":
            return self._values.copy()
        L = self.tendon_lengths()
        EA = np.array([t.axial_stiffness for t in self.tendons])
        T = EA * (L - self._L0) / self._L0
        return np.where(np.asarray(self.tendon_active), np.maximum(T, 0.0), 0.0)

    def _length_change(self, axes: np.ndarray, conv) -> float:  # noqa: ANN001
        """Sum of the axial joint gaps (projected on each distal link axis); 0 without axial springs."""
        if not self.axial:
            return 0.0
        exu = self.exu
        total = 0.0
        for k, (m0, m1) in enumerate(self.joint_markers):
            p0 = conv(self.mbs.GetMarkerOutput(m0, exu.OutputVariableType.Position))
            p1 = conv(self.mbs.GetMarkerOutput(m1, exu.OutputVariableType.Position))
            total += float(np.dot(p1 - p0, axes[k]))
        return total

    def update_active_set(self) -> bool:
        """Switch tendons slack/taut from the current state; True if anything changed."""
        if self.mode != "length":
            return False
        L = self.tendon_lengths()
        changed = False
        for i in range(len(self.tendons)):
            taut = bool(L[i] > self._L0[i])
            if taut != self.tendon_active[i]:
                self.tendon_active[i] = taut
                changed = True
        return changed

    def result(self, solver: SolverInfo, time_: np.ndarray | None = None,
               series: dict | None = None) -> PhysicsResult:
        geo, robot = self.geo, self.robot
        P, beta = self.link_states()
        stations = np.linspace(0.0, robot.length, self.options.n_stations)
        link_axes = np.stack([np.sin(beta), np.zeros_like(beta), np.cos(beta)], axis=1)
        pos = _points_on_links(geo, stations, np.asarray(P, dtype=float), link_axes)
        b = beta[-1]
        T = np.eye(4)
        T[:3, 0] = [math.cos(b), 0.0, -math.sin(b)]
        T[:3, 1] = [0.0, 1.0, 0.0]
        T[:3, 2] = [math.sin(b), 0.0, math.cos(b)]
        T[:3, 3] = P[-1] + geo.link_lengths[-1] * T[:3, 2]
        pos[-1] = T[:3, 3]
        joint = np.diff(np.concatenate([[0.0], beta]))[:, None]
        axes = np.stack([np.sin(beta), np.cos(beta)], axis=1)
        return PhysicsResult(
            model="spring_link", stations=stations, positions=pos, tip_frame=T,
            length_change=self._length_change(axes, lambda p: np.array([p[0], p[1]])),
            tendon_tensions=self.tensions(), tip_twist=0.0, solver=solver, joint_angles=joint,
            time=time_, series=series or {},
            extras={"n_links": float(geo.n_links), "dimension": 2.0},
        )


class _PlanarTree(_Planar):
    """Chain in minimal coordinates: one ``ObjectKinematicTree`` with a ``RevoluteY`` joint per
    link (planar: rotation about base +y = bending towards +x) or ``RevoluteX`` + ``RevoluteY``
    (``spatial``: a Cardan joint, torsion locked, springs ``k`` on both Cardan angles), joint
    springs as the tree's ``jointPControlVector``; eyelets are ``MarkerKinematicTreeRigid``
    markers.  Works directly in the base frame (no 2-D mapping)."""

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 spatial: bool = False) -> None:  # noqa: D107
        import exudyn as exu
        import exudyn.itemInterface as eii

        self._bind(robot, load, options, geo)
        self.axial = False
        self.spatial = bool(spatial)
        self.torsion = "locked"
        per = 2 if self.spatial else 1
        self.per = per
        if self.spatial and self.model == "continuum" and self.mode == "length":
            raise ModelFailure("spring_link: continuum tendons in length mode are only implemented for the planar chain")
        if self.spatial and self.model == "continuum" and self.mode is not None and any(t.tapered for t in self.tendons):
            raise ModelFailure("spring_link: continuum tendons with tapered offsets are only implemented for the planar chain")
        if self.mode == "length" and self.model == "continuum" and any(t.tapered for t in self.tendons):
            raise ModelFailure(
                "spring_link: continuum tendons with tapered offsets (offset_tip) are not supported in "
                "length mode; use tendon_model='eyelets'"
            )
        N = geo.n_links
        self.SC = exu.SystemContainer()
        mbs = self.SC.AddSystem()
        self.mbs = mbs
        self.g2 = np.asarray(robot.gravity_in_base(), dtype=float)
        mass, com = geo.mass.copy(), geo.com.copy()
        coms = [np.array([0.0, 0.0, c]) for c in com]
        inertias = [np.diag([geo.inertia_bending[k], geo.inertia_bending[k], geo.inertia_axial[k]]) for k in range(N)]
        pm = robot.payload.mass
        if pm > 0:
            pp = np.array(robot.payload.offset) + np.array([0.0, 0.0, geo.link_lengths[-1]])
            c_new = (mass[-1] * coms[-1] + pm * pp) / (mass[-1] + pm)
            dc, dp = coms[-1] - c_new, pp - c_new
            inertias[-1] = (inertias[-1] + mass[-1] * (dc @ dc * np.eye(3) - np.outer(dc, dc))
                            + pm * (dp @ dp * np.eye(3) - np.outer(dp, dp)))
            mass[-1] += pm
            coms[-1] = c_new
        # per joint: RevoluteY (planar) or RevoluteX + RevoluteY (Cardan; massless middle link)
        n = N * per
        types, offs, ms, cs, Is, Ps = [], [], [], [], [], []
        for k in range(N):
            off = float(geo.joints[0]) if k == 0 else float(geo.link_lengths[k - 1])
            if per == 2:
                types.append(exu.JointType.RevoluteX)
                offs.append([0.0, 0.0, off])
                ms.append(0.0)
                cs.append([0.0, 0.0, 0.0])
                Is.append(np.zeros((3, 3)))
                Ps.append(float(geo.stiffness[k]))
                off = 0.0
            types.append(exu.JointType.RevoluteY)
            offs.append([0.0, 0.0, off])
            ms.append(float(mass[k]))
            cs.append(coms[k].tolist())
            Is.append(inertias[k])
            Ps.append(float(geo.stiffness[k]))
        self.n_coords = n
        self.node = mbs.AddNode(eii.NodeGenericODE2(
            referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n, initialCoordinates_t=[0.0] * n,
            numberOfODE2Coordinates=n))
        self.tree = mbs.AddObject(eii.ObjectKinematicTree(
            nodeNumber=self.node, jointTypes=types, linkParents=list(range(-1, n - 1)),
            jointTransformations=exu.Matrix3DList([np.eye(3)] * n), jointOffsets=exu.Vector3DList(offs),
            linkInertiasCOM=exu.Matrix3DList(Is), linkCOMs=exu.Vector3DList(cs),
            linkMasses=ms, baseOffset=[0.0, 0.0, 0.0], gravity=[0.0, 0.0, 0.0],
            jointForceVector=[0.0] * n, jointPositionOffsetVector=[0.0] * n, jointVelocityOffsetVector=[0.0] * n,
            jointPControlVector=Ps, jointDControlVector=[float(options.damping * k) for k in Ps]))
        ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        self.ground = ground
        m_tip = mbs.AddMarker(eii.MarkerKinematicTreeRigid(objectNumber=self.tree, linkNumber=n - 1,
                                                           localPosition=[0.0, 0.0, float(geo.link_lengths[-1])]))
        self.tip_force_full = np.asarray(load.tip_force, dtype=float)
        self.tip_torque_full = np.asarray(load.tip_torque, dtype=float)
        self.tip_force_load = mbs.AddLoad(eii.LoadForceVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        self.tip_torque_load = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        self.gravity_loads = []

        self.eyelet_markers, self.tendon_items = [], []
        self.tendon_active = [True] * len(self.tendons)
        self.sign = [1.0 if math.cos(t.sigma) > 0 else -1.0 for t in self.tendons]
        for i, t in enumerate(self.tendons):
            u = np.array([math.cos(t.sigma), math.sin(t.sigma)]) if self.spatial else np.array([self.sign[i], 0.0])
            marks = []
            for lk, zk, dk in zip(t.eye_link, t.eye_z, t.eye_d):
                x, y = (dk * u).tolist()
                if lk < 0:
                    marks.append(mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[x, y, float(zk)])))
                else:
                    marks.append(mbs.AddMarker(eii.MarkerKinematicTreeRigid(
                        objectNumber=self.tree, linkNumber=int(lk + 1) * per - 1, localPosition=[x, y, float(zk)])))
            self.eyelet_markers.append(marks)
            items = []
            if self.mode is None:
                pass
            elif self.model == "eyelets":
                items += _add_eyelet_rope(mbs, marks, t, self.mode, options.damping)
            elif self.mode == "length":  # continuum: rotational spring on the terminating link's angle
                mg = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
                mt = mbs.AddMarker(eii.MarkerKinematicTreeRigid(objectNumber=self.tree, linkNumber=t.end_eyelet - 1,
                                                                localPosition=[0.0, 0.0, 0.0]))
                items.append(mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
                    markerNumbers=[mg, mt], useIntrinsicFormulation=True)))
            elif self.spatial:  # continuum tension: body-fixed torque on the terminating link
                mt = mbs.AddMarker(eii.MarkerKinematicTreeRigid(objectNumber=self.tree, linkNumber=t.end_eyelet * per - 1,
                                                                localPosition=[0.0, 0.0, 0.0]))
                items.append(mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mt, loadVector=[0.0, 0.0, 0.0], bodyFixed=True)))
            # planar continuum tension: generalised joint forces (jointForceVector), no items
            self.tendon_items.append(items)
        mbs.Assemble()

    def set_external(self, lam: float) -> None:
        mbs = self.mbs
        mbs.SetObjectParameter(self.tree, "gravity", (lam * self.g2).tolist())
        mbs.SetLoadParameter(self.tip_force_load, "loadVector", (lam * self.tip_force_full).tolist())
        mbs.SetLoadParameter(self.tip_torque_load, "loadVector", (lam * self.tip_torque_full).tolist())

    def set_tendons(self, values: np.ndarray, pretension_factor: float) -> None:
        """Apply tendon commands; continuum tendons act as generalised joint moments."""
        if self.mode is None:
            return
        if self.model == "eyelets":
            _Planar.set_tendons(self, values, pretension_factor)
            return
        mbs = self.mbs
        self._values = np.asarray(values, dtype=float)
        if self.mode == "tension" and self.spatial:
            for i, (t, items, v) in enumerate(zip(self.tendons, self.tendon_items, self._values)):
                d = float(t.moment_arm[-1])
                mbs.SetLoadParameter(items[0], "loadVector", [-v * d * math.sin(t.sigma), v * d * math.cos(t.sigma), 0.0])
            return
        if self.mode == "tension":
            Q = np.zeros(self.geo.n_links)
            for i, (t, v) in enumerate(zip(self.tendons, self._values)):
                Q[: t.end_eyelet] += v * t.moment_arm * self.sign[i]
            mbs.SetObjectParameter(self.tree, "jointForceVector", Q.tolist())
            return
        self._L0 = self.rest_lengths(self._values, pretension_factor)
        for i, (t, items) in enumerate(zip(self.tendons, self.tendon_items)):
            d, c, L0 = t.offsets[-1], self.sign[i], float(self._L0[i])
            K = np.zeros((6, 6))
            K[4, 4] = t.axial_stiffness * d * d / L0 if self.tendon_active[i] else 0.0
            off = [0.0] * 6
            off[4] = float((t.reference_length - L0) / (d * c))
            mbs.SetObjectParameter(items[0], "stiffness", K.tolist())
            mbs.SetObjectParameter(items[0], "offset", off)

    def link_frames(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) and link rotations (N, 3, 3) from the tree coordinates."""
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(), dtype=float).reshape(-1, self.per)
        geo = self.geo
        P = np.zeros((geo.n_links, 3))
        R = np.zeros((geo.n_links, 3, 3))
        Rk, pk = np.eye(3), np.array([0.0, 0.0, geo.joints[0]])
        for k in range(geo.n_links):
            if k > 0:
                pk = pk + geo.link_lengths[k - 1] * Rk[:, 2]
            if self.per == 2:
                c, s = math.cos(q[k, 0]), math.sin(q[k, 0])
                Rk = Rk @ np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
            c, s = math.cos(q[k, -1]), math.sin(q[k, -1])
            Rk = Rk @ np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
            P[k], R[k] = pk, Rk
        return P, R

    def result(self, solver: SolverInfo, time_: np.ndarray | None = None,
               series: dict | None = None) -> PhysicsResult:
        if self.spatial:
            return _Spatial.result(self, solver, time_, series)  # type: ignore[arg-type]
        return _Planar.result(self, solver, time_, series)

    def link_states(self) -> tuple[np.ndarray, np.ndarray]:
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(), dtype=float)
        beta = np.cumsum(q)
        geo = self.geo
        P = np.zeros((geo.n_links, 3))
        P[0] = [0.0, 0.0, geo.joints[0]]
        for k in range(1, geo.n_links):
            P[k] = P[k - 1] + geo.link_lengths[k - 1] * np.array([math.sin(beta[k - 1]), 0.0, math.cos(beta[k - 1])])
        return P, beta


class _Spatial(_Planar):
    """3-D chain: Euler-parameter rigid bodies, Cardan joints (``GenericJoint``, torsion locked),
    rotational springs (``RigidBodySpringDamper``, ``useIntrinsicFormulation=True``)."""

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 torsion: str = "spring", axial: bool = False) -> None:  # noqa: D107
        import exudyn as exu
        import exudyn.itemInterface as eii

        self._bind(robot, load, options, geo)
        self.axial = bool(axial)
        if self.mode == "length" and self.model == "continuum":
            raise ModelFailure(
                "spring_link: continuum tendons in length mode are only implemented for the planar chain; "
                "use tendon_model='eyelets' (or a planar case)"
            )
        if self.model == "continuum" and self.mode is not None and any(t.tapered for t in self.tendons):
            raise ModelFailure(
                "spring_link: continuum tendons with tapered offsets are only implemented for the planar "
                "chain; use tendon_model='eyelets'"
            )
        N = geo.n_links
        self.SC = exu.SystemContainer()
        mbs = self.SC.AddSystem()
        self.mbs = mbs
        self.g2 = np.asarray(robot.gravity_in_base(), dtype=float)
        ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        self.ground = ground

        mass, com = geo.mass.copy(), geo.com.copy()
        # inertia about the joint (reference point), body axes: x, y transverse, z along the link
        Ib = geo.inertia_bending + mass * com**2
        Ia = geo.inertia_axial.copy()
        coms = [np.array([0.0, 0.0, c]) for c in com]
        inertias = [np.diag([Ib[k], Ib[k], Ia[k]]) for k in range(N)]
        pm = robot.payload.mass
        if pm > 0:
            pp = np.array(robot.payload.offset) + np.array([0.0, 0.0, geo.link_lengths[-1]])
            c_new = (mass[-1] * coms[-1] + pm * pp) / (mass[-1] + pm)
            inertias[-1] = inertias[-1] + pm * (np.dot(pp, pp) * np.eye(3) - np.outer(pp, pp))
            mass[-1] += pm
            coms[-1] = c_new

        self.nodes, self.bodies = [], []
        for k in range(N):
            n = mbs.AddNode(eii.NodeRigidBodyEP(referenceCoordinates=[0.0, 0.0, float(geo.joints[k]), 1.0, 0.0, 0.0, 0.0]))
            J = inertias[k]
            b = mbs.AddObject(eii.ObjectRigidBody(
                nodeNumber=n, mass=float(mass[k]),
                inertia=[J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]],
                centerOfMass=[float(x) for x in coms[k]]))
            self.nodes.append(n)
            self.bodies.append(b)

        self.joint_springs, self.joint_markers = [], []
        for k in range(N):
            if k == 0:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, 0.0, float(geo.joints[0])]))
            else:
                m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k - 1],
                                                       localPosition=[0.0, 0.0, float(geo.link_lengths[k - 1])]))
            m1 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[k], localPosition=[0.0, 0.0, 0.0]))
            self.joint_markers.append((m0, m1))
            locked = 1 if torsion == "locked" else 0
            if not self.axial:
                mbs.AddObject(eii.GenericJoint(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 0, 0, locked]))
            kk = float(geo.stiffness[k])
            K = np.zeros((6, 6))
            K[3, 3] = K[4, 4] = kk
            K[5, 5] = 0.0 if locked else float(geo.torsion_stiffness[k])
            if self.axial:
                K[0, 0] = K[1, 1] = geo.shear_stiffness[k]
                K[2, 2] = geo.axial_stiffness[k]
            D = options.damping * K
            self.joint_springs.append(mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
                markerNumbers=[m0, m1], stiffness=K.tolist(), damping=D.tolist(), useIntrinsicFormulation=True)))

        self.gravity_loads = []
        if np.any(self.g2 != 0):
            for b in self.bodies:
                mm = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=b))
                self.gravity_loads.append(mbs.AddLoad(eii.LoadMassProportional(markerNumber=mm, loadVector=[0.0, 0.0, 0.0])))
        m_tip = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[-1],
                                                  localPosition=[0.0, 0.0, float(geo.link_lengths[-1])]))
        self.tip_force_full = np.asarray(load.tip_force, dtype=float)
        self.tip_torque_full = np.asarray(load.tip_torque, dtype=float)
        self.tip_force_load = mbs.AddLoad(eii.LoadForceVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))
        self.tip_torque_load = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m_tip, loadVector=[0.0, 0.0, 0.0]))

        self.eyelet_markers, self.tendon_items = [], []
        self.tendon_active = [True] * len(self.tendons)
        for t in self.tendons:
            u = np.array([math.cos(t.sigma), math.sin(t.sigma)])
            marks = []
            MK = eii.MarkerBodyRigid if (self.model == "eyelets" and self.mode == "length") else eii.MarkerBodyPosition
            for lk, zk, dk in zip(t.eye_link, t.eye_z, t.eye_d):
                x, y = (dk * u).tolist()
                body = ground if lk < 0 else self.bodies[lk]
                marks.append(mbs.AddMarker(MK(bodyNumber=body, localPosition=[x, y, float(zk)])))
            self.eyelet_markers.append(marks)
            items = []
            if self.mode is None:
                pass
            elif self.model == "eyelets":
                items += _add_eyelet_rope(mbs, marks, t, self.mode, options.damping)
            else:  # continuum, tension: body-fixed torque T d (-sin s, cos s, 0) on the end link
                mt = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.bodies[t.end_eyelet - 1]))
                items.append(mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mt, loadVector=[0.0, 0.0, 0.0], bodyFixed=True)))
            self.tendon_items.append(items)
        mbs.Assemble()
        self.sign = [1.0] * len(self.tendons)
        self.torsion = torsion

    def _continuum_torques(self, i: int, v: float) -> list[list[float]]:
        t = self.tendons[i]
        d = float(t.moment_arm[-1])
        return [[-v * d * math.sin(t.sigma), v * d * math.cos(t.sigma), 0.0]]

    def link_frames(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) and link rotation matrices (N, 3, 3), base frame."""
        exu = self.exu
        P = np.array([self.mbs.GetNodeOutput(n, exu.OutputVariableType.Position) for n in self.nodes])
        R = np.array([np.asarray(self.mbs.GetNodeOutput(n, exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
                      for n in self.nodes])
        return P, R

    def tendon_lengths(self) -> np.ndarray:
        exu = self.exu
        out = []
        for marks in self.eyelet_markers:
            pts = np.array([self.mbs.GetMarkerOutput(m, exu.OutputVariableType.Position) for m in marks])
            out.append(float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
        return np.asarray(out)

    def result(self, solver: SolverInfo, time_: np.ndarray | None = None,
               series: dict | None = None) -> PhysicsResult:
        geo, robot = self.geo, self.robot
        P, R = self.link_frames()
        stations = np.linspace(0.0, robot.length, self.options.n_stations)
        pos = _points_on_links(geo, stations, np.asarray(P, dtype=float), R[:, :, 2])
        T = np.eye(4)
        T[:3, :3] = R[-1]
        T[:3, 3] = P[-1] + geo.link_lengths[-1] * R[-1][:, 2]
        pos[-1] = T[:3, 3]
        Rprev = np.concatenate([np.eye(3)[None], R[:-1]])
        Rrel = np.einsum("kji,kjl->kil", Rprev, R)
        if self.torsion == "locked":
            # Cardan joint: relative rotation Rx(a) Ry(b) -> (a, b)
            b = np.arcsin(np.clip(Rrel[:, 0, 2], -1.0, 1.0))
            a = np.arctan2(-Rrel[:, 1, 2], Rrel[:, 2, 2])
            joint = np.stack([a, b], axis=1)
        else:
            joint = _rotation_vectors(Rrel)
        return PhysicsResult(
            model="spring_link", stations=stations, positions=pos, tip_frame=T,
            length_change=self._length_change(R[:, :, 2], lambda p: np.asarray(p, dtype=float)),
            tendon_tensions=self.tensions(), tip_twist=_twist_vs_parallel_transport(R), solver=solver,
            joint_angles=joint, time=time_, series=series or {},
            extras={"n_links": float(geo.n_links), "dimension": 3.0},
        )
