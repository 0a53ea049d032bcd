"""The Exudyn system of a planar backbone (2-D ANCF cable) with prescribed strains and a rigid circle.

Built per call from plain data (:class:`~workbench.physics._ancf_problem.AncfProblem`: mesh, EI, EA,
mass per length, gravity and payload in Exudyn's plane, base (z, x) = Exudyn (X, Y)):

* backbone: ``ObjectANCFCable2D`` elements (``useReducedOrderIntegration=2``), clamp = node 0's x,
  y and y-slope (as in :mod:`workbench.physics.ancf`);
* actuation as **prescribed strains** per element: ``referenceCurvature`` (bending per reference
  length; > 0 bends towards base +x) and ``referenceAxialStrain`` -- a continuum tendon and a
  fluidic chamber line are both exactly this (``model.py``, :mod:`workbench.robot.fluidic`);
* gravity (mass-proportional loads on the rod's own mass), disks (each weight a point load at its station,
  :func:`~workbench.physics._exudyn.add_cable2d_disks`), payload (tip point mass and its weight), a dead tip force;
* optionally the object: a ``NodeRigidBody2D`` body, a fixture (coordinate constraints on x, z and
  rotation, each switchable, with offsets), release springs, its weight and an external force,
  and per element one ``ObjectContactFrictionCircleCable2D`` (circle radius = object radius + the
  element's half diameter, penalty per segment = ``ContactLaw`` per length x segment length).

Why that contact element (measured by ``benchmarks/measure_contact_elements.py``, ``docs/models.md``,
"Planar contact"): the frictionless ``ObjectContactCircleCable2D`` of Exudyn 1.13.6 applies a wrong
force to the circle as soon as adjacent segments touch (a cantilever pressed on a circle at a soft
penalty: +53 % on the circle, -1.5 % on the beam; a wrap always has adjacent touching segments), and
``GeneralContact`` (point penalty; 0.026 % off at 1e9 N/m, 0.06 % at 1e8) has friction regularised in
the relative velocity, so a static solve sees almost none (|F_t / F_n| = 0.011 for mu = 0.3 while
sliding, against 0.287 of the friction element, Coulomb's 0.3 less the beam's 0.0125 rad slope).  The
friction element with ``frictionCoefficient = 0`` is exact to the beam theory's own error (1.8e-4)
and action equals reaction.

Object modes: :meth:`hold` (fixture), :meth:`spring` (release springs), :meth:`free`,
:meth:`guide` (one coordinate prescribed, the other free).  A frictionless object's rotation is
always locked (frictionless contact exerts no torque; the lock only removes a zero-stiffness mode).
Static solves: :meth:`solve`, :meth:`load_ramp` (adaptive halving with the contact states saved and
restored).  Checked by ``tests/physics/test_contact.py``.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ...models.result import ModelFailure
from .._ancf_geometry import arc_length, centreline
from .description import ContactLaw, RigidCircle

__all__ = ["PlanarContactSystem", "to_exudyn", "to_base"]


def to_exudyn(xz) -> list[float]:
    """Base-frame ``(x, z)`` -> Exudyn plane ``[X, Y] = [z, x]``."""
    return [float(xz[1]), float(xz[0])]


def to_base(XY) -> np.ndarray:
    """Exudyn plane ``(X, Y)`` -> base-frame ``(x, z) = (Y, X)``."""
    return np.array([float(XY[1]), float(XY[0])])


class PlanarContactSystem:
    """One planar backbone system (module docstring); built per solve sequence, never shared.

    Parameters
    ----------
    pb : AncfProblem
        The planar problem (:func:`workbench.physics._ancf_problem.build_problem`); its tendons are
        ignored (actuation comes as prescribed strains).
    half_width : (n_el,) array
        Half the backbone diameter per element [m] (the surface that touches the object).
    circle : RigidCircle, optional
        The object (``None``: no object, no contact).
    law : ContactLaw
    tolerance : float
        Newton tolerance on the step size (``residualMode = 1``).
    """

    def __init__(self, pb, half_width, circle: RigidCircle | None = None, law: ContactLaw = ContactLaw(),
                 tolerance: float = 1e-9):
        import exudyn as exu

        from .._exudyn import settings

        self.exu, self.pb, self.circle, self.law = exu, pb, circle, law
        self.half_width = np.broadcast_to(np.asarray(half_width, float), (pb.s_nodes.size - 1,)).copy()
        self.SC = exu.SystemContainer()
        self.mbs = self.SC.AddSystem()
        self._add_backbone()
        self._add_loads()
        self.contacts: list[int] = []
        if circle is not None:
            self._add_object()
            self._add_contacts()
        self.mbs.Assemble()
        self.settings = settings(tolerance, 30)
        st = self.settings.staticSolver
        st.adaptiveStep = False
        st.discontinuous.maxIterations = 50
        st.discontinuous.iterationTolerance = 1e-6
        st.discontinuous.ignoreMaxIterations = False
        self.newton = 0
        self.solves = 0
        #: accepted share of the contact force on segments whose state disagrees with their gap
        self.active_set_tolerance = 0.0
        self.relaxed_solves = 0
        self.max_active_set_error = 0.0
        self._gravity = 0.0
        self._object_force = np.zeros(2)

    # -- building ---------------------------------------------------------------------------
    def _add_backbone(self) -> None:
        from exudyn.itemInterface import NodePoint2DSlope1, ObjectANCFCable2D

        from .._exudyn import clamp_coordinates

        pb, mbs = self.pb, self.mbs
        le = np.diff(pb.s_nodes)
        self.nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[float(s), 0.0, 1.0, 0.0])) for s in pb.s_nodes]
        self.elements = [mbs.AddObject(ObjectANCFCable2D(
            nodeNumbers=[self.nodes[e], self.nodes[e + 1]], length=float(le[e]), bendingStiffness=float(pb.EI[e]),
            axialStiffness=float(pb.EA[e]), massPerLength=float(pb.mu_rod[e]), useReducedOrderIntegration=2))
            for e in range(le.size)]
        clamp_coordinates(mbs, self.nodes[0], (0, 1, 3))

    def _add_loads(self) -> None:
        from exudyn.itemInterface import LoadForceVector, MarkerNodePosition, ObjectMassPoint2D

        from .._exudyn import add_cable2d_disks, add_gravity_loads

        pb, mbs = self.pb, self.mbs
        has_g = bool(np.any(pb.gravity != 0))
        self.grav_loads = add_gravity_loads(mbs, self.elements) if has_g else []
        self.disk_loads = add_cable2d_disks(mbs, pb.s_nodes, self.nodes, self.elements, pb.disk_s, pb.disk_m, has_g)
        tip = mbs.AddMarker(MarkerNodePosition(nodeNumber=self.nodes[-1]))
        self.tip_load = mbs.AddLoad(LoadForceVector(markerNumber=tip, loadVector=[0, 0, 0]))
        self.payload_load = None
        if pb.payload > 0:
            mbs.AddObject(ObjectMassPoint2D(nodeNumber=self.nodes[-1], mass=float(pb.payload)))
            self.payload_load = mbs.AddLoad(LoadForceVector(markerNumber=tip, loadVector=[0, 0, 0]))

    def _add_object(self) -> None:
        from exudyn.itemInterface import (
            CoordinateConstraint, CoordinateSpringDamper, LoadForceVector, MarkerBodyRigid, MarkerNodeCoordinate,
            MarkerNodePosition, NodePointGround, NodeRigidBody2D, ObjectRigidBody2D,
        )

        c, mbs = self.circle, self.mbs
        m = max(c.mass, 1e-6)  # statics: the mass only scales the weight, which is applied as a load
        self.obj_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[*to_exudyn(c.centre), 0.0]))
        body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=self.obj_node, mass=m, inertia=0.5 * m * c.radius**2))
        self.obj_marker = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
        ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
        coord = [mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=self.obj_node, coordinate=k)) for k in range(3)]
        self.fixture = [mbs.AddObject(CoordinateConstraint(markerNumbers=[ground, coord[k]])) for k in range(3)]
        self.springs = [mbs.AddObject(CoordinateSpringDamper(markerNumbers=[ground, coord[k]], stiffness=0.0))
                        for k in range(3)]
        self.obj_load = mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=self.obj_node)),
                                                    loadVector=[0, 0, 0]))
        self._spring_k = 0.0
        #: weak rotational spring [N m/rad] on a rubbing object, so that a rotation with every touching
        #: segment slipping (no stiffness) stays solvable; its torque is reported (``stabiliser_torque``)
        self.rotation_stabiliser = 1e-6 * self.law.stiffness * c.radius**3

    def stabiliser_torque(self) -> float:
        """Torque [N m] of the rotational stabiliser on the object now (0 when the rotation is locked)."""
        if self.circle is None or self.mbs.GetObjectParameter(self.fixture[2], "activeConnector"):
            return 0.0
        th = float(self.mbs.GetNodeOutput(self.obj_node, self.exu.OutputVariableType.Coordinates)[2])
        return float(self.mbs.GetObjectParameter(self.springs[2], "stiffness")) * abs(th)

    def _add_contacts(self) -> None:
        from exudyn.itemInterface import MarkerBodyCable2DShape, NodeGenericData, ObjectContactFrictionCircleCable2D

        mbs, law, c = self.mbs, self.law, self.circle
        n = law.segments
        le = np.diff(self.pb.s_nodes)
        self.data_nodes = []
        for e, elem in enumerate(self.elements):
            shape = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=elem, numberOfSegments=n))
            data = mbs.AddNode(NodeGenericData(initialCoordinates=[0.1] * n + [-2.0] * n + [0.0] * n,
                                               numberOfDataCoordinates=3 * n))
            self.data_nodes.append(data)
            self.contacts.append(mbs.AddObject(ObjectContactFrictionCircleCable2D(
                markerNumbers=[self.obj_marker, shape], nodeNumber=data, numberOfContactSegments=n,
                contactStiffness=float(law.stiffness * le[e] / n), frictionStiffness=0.0, frictionCoefficient=0.0,
                circleRadius=float(c.radius + self.half_width[e]))))
        self.set_friction(True)

    def set_friction(self, on: bool) -> None:
        """Friction on (the object's coefficient and the law's stick penalty) or off (both 0, exactly frictionless).

        Switching it on resets nothing: sticking starts where each touching segment is now.
        """
        mu = float(self.circle.friction) if on else 0.0
        le = np.diff(self.pb.s_nodes)
        for e, c in enumerate(self.contacts):
            kt = self.law.tangential * le[e] / self.law.segments if mu > 0 else 0.0
            self.mbs.SetObjectParameter(c, "frictionCoefficient", mu)
            self.mbs.SetObjectParameter(c, "frictionStiffness", float(kt))

    # -- loads and actuation --------------------------------------------------------------------
    def set_strains(self, kappa0, eps0) -> None:
        """Prescribed bending (per reference length, [1/m]; > 0 towards base +x) and axial strain per element."""
        k0 = np.broadcast_to(np.asarray(kappa0, float), (len(self.elements),))
        e0 = np.broadcast_to(np.asarray(eps0, float), (len(self.elements),))
        for elem, k, e in zip(self.elements, k0, e0):
            self.mbs.SetObjectParameter(elem, "referenceCurvature", float(k))
            self.mbs.SetObjectParameter(elem, "referenceAxialStrain", float(e))

    def set_gravity(self, lam: float) -> None:
        """Gravity on backbone, payload and (not held by the fixture) object at ``lam`` times its value."""
        pb, mbs = self.pb, self.mbs
        g = lam * pb.gravity
        for ld in self.grav_loads:
            mbs.SetLoadParameter(ld, "loadVector", [float(g[0]), float(g[1]), 0.0])
        for ld, m in zip(self.disk_loads, pb.disk_m):
            mbs.SetLoadParameter(ld, "loadVector", [float(m * g[0]), float(m * g[1]), 0.0])
        if self.payload_load is not None:
            mbs.SetLoadParameter(self.payload_load, "loadVector", [float(pb.payload * g[0]), float(pb.payload * g[1]), 0.0])
        self._gravity = float(lam)
        self._set_object_load()

    def set_tip_force(self, force_xz) -> None:
        """Dead force on the tip [N], base frame ``(x, z)`` (fixed direction)."""
        X, Y = to_exudyn(np.asarray(force_xz, dtype=float).reshape(2))
        self.mbs.SetLoadParameter(self.tip_load, "loadVector", [X, Y, 0.0])

    def set_object_force(self, force_xz) -> None:
        """External force on the object [N], base frame ``(x, z)`` (besides its weight)."""
        self._object_force = np.asarray(force_xz, dtype=float).reshape(2)
        self._set_object_load()

    def object_load(self) -> np.ndarray:
        """Weight plus external force ``(x, z)`` [N, base] acting on the object now."""
        if self.circle is None:
            return np.zeros(2)
        g = self._gravity * self.circle.mass * self.pb.gravity  # Exudyn plane
        return self._object_force + to_base(g)

    def _set_object_load(self) -> None:
        if self.circle is None:
            return
        w = self._gravity * self.circle.mass * self.pb.gravity  # Exudyn plane
        f = np.asarray(to_exudyn(self._object_force)) + w
        self.mbs.SetLoadParameter(self.obj_load, "loadVector", [float(f[0]), float(f[1]), 0.0])

    # -- object modes -----------------------------------------------------------------------------
    def _activate(self, fixture: tuple[bool, bool, bool], springs: float) -> None:
        mbs = self.mbs
        lock_rotation = fixture[2] or self.circle.friction == 0.0
        for k, on in enumerate((fixture[0], fixture[1], lock_rotation)):
            mbs.SetObjectParameter(self.fixture[k], "activeConnector", bool(on))
        kr = max(springs * self.circle.radius**2, self.rotation_stabiliser)
        for k, kk in enumerate((springs, springs, 0.0 if lock_rotation else kr)):
            mbs.SetObjectParameter(self.springs[k], "stiffness", float(kk))
        self._spring_k = float(springs)

    def hold(self, offset_xz=(0.0, 0.0)) -> None:
        """Fixture on: the centre held at reference + ``offset_xz`` [m, base], rotation locked."""
        X, Y = to_exudyn(offset_xz)
        self.mbs.SetObjectParameter(self.fixture[0], "offset", X)
        self.mbs.SetObjectParameter(self.fixture[1], "offset", Y)
        self._activate((True, True, True), 0.0)

    def spring(self, stiffness: float) -> None:
        """Fixture off; the centre tied to its reference position by springs [N/m] (a homotopy to free)."""
        self._activate((False, False, False), stiffness)

    def free(self) -> None:
        """Fixture and springs off: the object rests on the contact forces alone."""
        self._activate((False, False, False), 0.0)

    def guide(self, axis: str, displacement: float) -> None:
        """Prescribe the centre's displacement [m] along base ``axis`` (``"x"`` or ``"z"``); the other coordinate free."""
        k = {"z": 0, "x": 1}[axis]
        self.mbs.SetObjectParameter(self.fixture[k], "offset", float(displacement))
        self._activate((k == 0, k == 1, False), 0.0)

    # -- solving -------------------------------------------------------------------------------------
    def solve(self) -> None:
        """One static solve from the current state; :class:`ModelFailure` if it fails or is implausible.

        When only the contact active set does not settle (Exudyn's discontinuous iteration cycling
        between states that differ by segments at the contact boundary), the solve is repeated
        accepting the last iterate, and accepted only if the segments whose contact state
        disagrees with their gap carry less than ``active_set_tolerance`` of the contact force
        (:meth:`active_set_error`; the largest accepted value is kept in ``max_active_set_error``).
        """
        exu, mbs = self.exu, self.mbs
        start = self.save()
        try:
            self._solve_once(strict=True)
        except exu.SolverError as err:
            if not self.contacts:
                raise ModelFailure(f"static contact solve did not converge: {err}") from err
            self.restore(start)
            try:
                self._solve_once(strict=False)
            except exu.SolverError as err2:
                raise ModelFailure(f"static contact solve did not converge: {err2}") from err2
            bad, total = self.active_set_error()
            if bad > self.active_set_tolerance * max(total, 1e-12) or (bad > 0 and self.active_set_tolerance == 0):
                raise ModelFailure(f"contact active set did not settle: segments whose state disagrees with "
                                   f"their gap carry {bad:.3g} N of {total:.3g} N") from err
            self.relaxed_solves += 1
            self.max_active_set_error = max(self.max_active_set_error, bad / max(total, 1e-12))
        self._check()

    def _solve_once(self, strict: bool) -> None:
        """One static solve on Exudyn's solver object (``mbs.SolveStatic`` without its failure banner,
        which would announce every strict attempt that the relaxed one then settles), then the
        solution becomes the initial state (``updateInitialValues``)."""
        exu, mbs = self.exu, self.mbs
        self.settings.staticSolver.discontinuous.ignoreMaxIterations = not strict
        solver = exu.MainSolverStatic()
        try:
            ok = solver.SolveSystem(mbs, self.settings)
        finally:
            self.solves += 1
            self.newton += int(solver.it.newtonStepsCount)
        if not ok:
            raise exu.SolverError("SolveStatic terminated due to errors")
        sd = mbs.systemData
        sd.SetSystemState(systemStateList=sd.GetSystemState(), configuration=exu.ConfigurationType.Initial)

    def segment_gaps(self) -> np.ndarray:
        """Gap [m] of every contact segment from the current coordinates, exactly as Exudyn defines it:
        distance from the circle centre to the straight segment between the element's shape points,
        minus the contact radius (< 0: penetration)."""
        n = self.law.segments
        sn = self.pb.s_nodes
        pts_s = np.concatenate([sn[e] + np.arange(n + 1) * (sn[e + 1] - sn[e]) / n for e in range(sn.size - 1)])
        r, _ = centreline(self.node_coords(), sn, pts_s)
        r = r.reshape(sn.size - 1, n + 1, 2)
        c = np.asarray(self.mbs.GetNodeOutput(self.obj_node, self.exu.OutputVariableType.Position))[:2]
        p0, p1 = r[:, :-1], r[:, 1:]
        v = p1 - p0
        rho = np.clip(np.einsum("eij,eij->ei", c - p0, v) / np.einsum("eij,eij->ei", v, v), 0.0, 1.0)
        d = np.linalg.norm(c - (p0 + rho[..., None] * v), axis=-1)
        return (d - (self.circle.radius + self.half_width[:, None])).reshape(-1)

    def active_set_error(self) -> tuple[float, float]:
        """``(disagreeing, total)`` [N]: penalty force of the segments whose stored contact state
        disagrees with their current gap, and the total normal contact force."""
        n = self.law.segments
        state = np.concatenate([np.asarray(self.mbs.GetNodeOutput(d, self.exu.OutputVariableType.Coordinates))[:n]
                                for d in self.data_nodes])
        g = self.segment_gaps()
        k = np.repeat(self.law.stiffness * np.diff(self.pb.s_nodes) / n, n)
        wrong = (state <= 0) != (g <= 0)
        return float(np.sum(k[wrong] * np.abs(g[wrong]))), float(np.sum(k * np.maximum(-g, 0.0)))

    def _check(self) -> None:
        qn = self.node_coords()
        if not np.all(np.isfinite(qn)):
            raise ModelFailure("contact solve produced non-finite coordinates")
        slope = np.linalg.norm(qn[:, 2:], axis=-1)
        if np.any(slope < 0.5) or np.any(slope > 1.5):
            raise ModelFailure(f"contact solve produced implausible axial stretch |r'| in [{slope.min():.3g}, {slope.max():.3g}]")
        if qn[0, 2] <= 0.0:  # the clamp fixes y' only: x' = -1 is the reversed (point-mirrored) branch
            raise ModelFailure(f"contact solve reversed the clamped tangent (x-slope {qn[0, 2]:.3g}): Newton jumped "
                               f"to the mirrored branch")
        if np.max(np.linalg.norm(qn[:, :2], axis=-1)) > 2.0 * self.pb.L:
            raise ModelFailure("contact solve produced a backbone point further than 2 L from the base")

    def save(self):
        """The solver start state (ODE2, algebraic and contact data coordinates)."""
        sd, cfg = self.mbs.systemData, self.exu.ConfigurationType.Initial
        return (np.array(sd.GetODE2Coordinates(configuration=cfg)), np.array(sd.GetAECoordinates(configuration=cfg)),
                np.array(sd.GetDataCoordinates(configuration=cfg)))

    def restore(self, state) -> None:
        """Write a :meth:`save` state back as the initial and current configuration."""
        sd = self.mbs.systemData
        for cfg in (self.exu.ConfigurationType.Initial, self.exu.ConfigurationType.Current):
            sd.SetODE2Coordinates(state[0], configuration=cfg)
            sd.SetAECoordinates(state[1], configuration=cfg)
            sd.SetDataCoordinates(state[2], configuration=cfg)

    def load_ramp(self, apply: Callable[[float], None], max_steps: int, first_increment: float = 1.0) -> int:
        """Drive ``apply(lam)`` from 0 to 1: :func:`~workbench.physics._stepping.ancf_load_ramp` on this system.

        Returns the number of solve attempts; :class:`ModelFailure` (with the load factor reached)
        when the cap or the minimum increment is hit.
        """
        from .._stepping import ancf_load_ramp

        try:
            info = ancf_load_ramp(apply, self.solve, self.save, self.restore, max_steps=max_steps,
                                  first_increment=first_increment, failure=ModelFailure)
        except RuntimeError as err:
            raise ModelFailure(f"contact load ramp failed: {err}") from err
        return info.attempts

    # -- state -----------------------------------------------------------------------------------------
    def node_coords(self) -> np.ndarray:
        """Absolute node coordinates ``(n+1, 4)`` (x, y, x', y') in Exudyn's plane."""
        n = len(self.nodes)
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates())[: 4 * n].reshape(n, 4)
        ref = np.column_stack([self.pb.s_nodes, np.zeros(n), np.ones(n), np.zeros(n)])
        return ref + q

    def positions(self, stations) -> tuple[np.ndarray, np.ndarray]:
        """Backbone points ``(m, 3)`` and unit tangents ``(m, 3)`` in the base frame (``y = 0``) at reference ``stations``."""
        r, t = centreline(self.node_coords(), self.pb.s_nodes, np.asarray(stations, float))
        pos = np.zeros(r.shape[:-1] + (3,))
        tan = np.zeros_like(pos)
        pos[..., 0], pos[..., 2] = r[..., 1], r[..., 0]
        tan[..., 0], tan[..., 2] = t[..., 1], t[..., 0]
        return pos, tan

    def arc_length(self) -> float:
        """Deformed centreline length [m]."""
        return float(arc_length(self.node_coords(), self.pb.s_nodes))

    def object_centre(self) -> np.ndarray:
        """Centre ``(x, z)`` [m] of the object, base frame."""
        return to_base(self.mbs.GetNodeOutput(self.obj_node, self.exu.OutputVariableType.Position)[:2])

    def fixture_force(self) -> np.ndarray:
        """Force ``(x, z)`` [N, base] that the fixture and the release springs exert on the object."""
        exu, mbs = self.exu, self.mbs
        F = np.zeros(2)
        for k in range(2):
            if mbs.GetObjectParameter(self.fixture[k], "activeConnector"):
                F[k] += float(mbs.GetObjectOutput(self.fixture[k], exu.OutputVariableType.Force))
        d = np.asarray(mbs.GetNodeOutput(self.obj_node, exu.OutputVariableType.Displacement))[:2]
        F -= self._spring_k * d
        return to_base(F)

    def contact_segments(self) -> dict[str, np.ndarray]:
        """Per contact segment: reference arc length of its midpoint ``s`` [m], normal force ``f_n`` [N]
        (>= 0, pressing), tangential (friction) force ``f_t`` [N] and gap [m] (< 0: penetration).

        Empty arrays without an object.
        """
        if not self.contacts:
            z = np.zeros(0)
            return {"s": z, "f_n": z, "f_t": z, "gap": z}
        exu, mbs, n = self.exu, self.mbs, self.law.segments
        sn = self.pb.s_nodes
        s = np.concatenate([sn[e] + (np.arange(n) + 0.5) * (sn[e + 1] - sn[e]) / n for e in range(sn.size - 1)])
        f = np.concatenate([np.asarray(mbs.GetObjectOutput(c, exu.OutputVariableType.ForceLocal)).reshape(n, 2)
                            for c in self.contacts])
        g = np.concatenate([np.asarray(mbs.GetObjectOutput(c, exu.OutputVariableType.Coordinates)).reshape(n, 2)
                            for c in self.contacts])
        return {"s": s, "f_n": -f[:, 1], "f_t": f[:, 0], "gap": g[:, 1]}
