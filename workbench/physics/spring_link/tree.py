"""The spring-link chain as one Exudyn ``ObjectKinematicTree`` (minimal coordinates).

Same discretisation as the rigid-body chains (half-link layout, joint stiffness ``EI/ds`` as the
tree's ``jointPControlVector``, damping ``options.damping * k``).  Planar: one ``RevoluteY`` joint
per link (rotation about base +y, bending towards +x).  3-D (``spatial``): ``RevoluteX`` then
``RevoluteY`` at each joint (a Cardan joint, torsion locked, springs on both Cardan angles), the
intermediate link massless.  No joint constraints, so eyelet ropes (``MarkerKinematicTreeRigid``
eyelets) keep Newton quadratic; :mod:`.driver` uses it for every eyelet rope it can.  Planar
continuum tendons act as generalised joint forces (``jointForceVector``), in length mode as a
rotational spring to ground; 3-D ones (and planar tapered ones in length mode) are ropes through an
eyelet at every link (:meth:`.chain.Chain._continuum_ropes`).  In 3-D every tendon (continuum or
eyelets) and the tip force and torque are the generalised forces of one ``ObjectGenericODE2`` on the
tree's node with its own Jacobian (:mod:`.linkrope`); planar eyelet ropes are rope connectors on tree
markers.

:func:`tree_tip_position` is a stripped variant (continuum tendons at sigma in {0, pi}, tip moment
about base y and gravity, all as joint forces or the tree's own gravity) timed by
``benchmarks/bench_spring_link.py``.  Checked by ``tests/physics/test_spring_link.py``
(``test_kinematic_tree_*``, ``test_spatial_tree_backend_matches_cardan_bodies``).
"""

from __future__ import annotations

import math

import numpy as np

from ...models.result import ModelFailure, SolverOptions
from ...robot import LoadCase, Payload, Robot
from .chain import Chain
from .geometry import ChainGeometry, chain_geometry_from_robot
from .linkrope import axis_rotation, generalised_force_jacobian, generalised_forces, rope_layout, tree_kinematics
from .routing import TendonRoute
from .._stepping import PathPoint, RampExhausted, RampPolicy, load_ramp

__all__ = ["tree_tip_position"]

#: tree_tip_position's step rule: like the model's static ramp, but no smallest increment (only
#: ``options.max_load_steps`` stops it).
_TIP_RAMP = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="one", min_increment=None)


def _tree_link_masses(geo: ChainGeometry, payload: Payload | None) -> tuple[np.ndarray, list, list]:
    """Link masses (N,), centres of mass (N x (3,)) and inertias about the centre of mass
    (N x (3, 3)), payload (if any) folded into the last link."""
    mass, com = geo.mass.copy(), geo.com.copy()
    coms = [np.array([0.0, 0.0, c]) for c in com]
    inertias = [np.diag([geo.inertia_bending[k], geo.inertia_bending[k], geo.inertia_axial[k]])
                for k in range(geo.n_links)]
    pm = 0.0 if payload is None else payload.mass
    if pm > 0:
        pp = np.array(payload.offset) + np.array([0.0, 0.0, geo.link_lengths[-1]])
        c_new = (mass[-1] * coms[-1] + pm * pp) / (mass[-1] + pm)
        dc, dp = coms[-1] - c_new, pp - c_new
        inertias[-1] = (inertias[-1] + mass[-1] * (dc @ dc * np.eye(3) - np.outer(dc, dc))
                        + pm * (dp @ dp * np.eye(3) - np.outer(dp, dp)))
        mass[-1] += pm
        coms[-1] = c_new
    return mass, coms, inertias


#: Joint axes of the tree per chain joint: planar ``RevoluteY``; Cardan ``RevoluteX`` + ``RevoluteY``
#: (torsion locked); sprung torsion ``X, Y, Z`` at even and ``Z, Y, X`` at odd joints (see :func:`joint_axes`).
_AXES = {1: ("Y",), 2: ("X", "Y"), 3: ("X", "Y", "Z")}


def joint_axes(per: int, k: int) -> tuple[str, ...]:
    """Revolute axes (in order, proximal first) of chain joint ``k`` with ``per`` tree joints.

    ``per = 3`` (torsion spring): the relative rotation ``Rx(a) Ry(b) Rz(c)`` has rotation vector
    ``(a + bc/2, b - ac/2, c + ab/2) + O(3)``, so a torsion spring on ``c`` instead of on the
    rotation vector's axial component couples bending into twist at second order per joint
    (``ab/2``, a first-order twist error summed over ``N`` joints); the reversed order
    ``Rz Ry Rx`` has the opposite sign (``c - ab/2``), so alternating the two cancels the error
    pairwise (``tests/physics/test_spring_link.py``, ``test_sprung_torsion_tree_*``).
    """
    axes = _AXES[per]
    return axes[::-1] if per == 3 and k % 2 else axes


def _tree_links(exu, geo: ChainGeometry, mass: np.ndarray, coms: list, inertias: list, per: int) -> tuple:  # noqa: ANN001
    """Per tree link: joint types, offsets, masses, centres of mass, inertias, spring stiffness.

    ``per`` tree joints per chain joint (:func:`joint_axes`); the first carries the offset, all but
    the last are massless; bending axes (X, Y) get ``EI/ds``, the axial one (Z) ``GJ/ds``."""
    types, offs, ms, cs, Is, Ps = [], [], [], [], [], []
    for k in range(geo.n_links):
        off = float(geo.joints[0]) if k == 0 else float(geo.link_lengths[k - 1])
        axes = joint_axes(per, k)
        for i, ax in enumerate(axes):
            last = i == len(axes) - 1
            types.append(getattr(exu.JointType, "Revolute" + ax))
            offs.append([0.0, 0.0, off if i == 0 else 0.0])
            ms.append(float(mass[k]) if last else 0.0)
            cs.append(coms[k].tolist() if last else [0.0, 0.0, 0.0])
            Is.append(inertias[k] if last else np.zeros((3, 3)))
            Ps.append(float(geo.torsion_stiffness[k] if ax == "Z" else geo.stiffness[k]))
    return types, offs, ms, cs, Is, Ps


def _add_kinematic_tree(mbs, exu, eii, links: tuple, damping: float) -> tuple[int, int]:  # noqa: ANN001
    """The ``NodeGenericODE2`` and the serial ``ObjectKinematicTree`` of ``links`` (from
    :func:`_tree_links`), joint springs ``jointPControlVector``, damping ``damping * k``, no
    loads yet (gravity and joint forces are set by the load ramp)."""
    types, offs, ms, cs, Is, Ps = links
    n = len(types)
    node = mbs.AddNode(eii.NodeGenericODE2(
        referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n, initialCoordinates_t=[0.0] * n,
        numberOfODE2Coordinates=n))
    tree = mbs.AddObject(eii.ObjectKinematicTree(
        nodeNumber=node, jointTypes=types, linkParents=list(range(-1, n - 1)),
        jointTransformations=exu.Matrix3DList([np.eye(3)] * n), jointOffsets=exu.Vector3DList(offs),
        linkInertiasCOM=exu.Matrix3DList(Is), linkCOMs=exu.Vector3DList(cs),
        linkMasses=ms, baseOffset=[0.0, 0.0, 0.0], gravity=[0.0, 0.0, 0.0],
        jointForceVector=[0.0] * n, jointPositionOffsetVector=[0.0] * n, jointVelocityOffsetVector=[0.0] * n,
        jointPControlVector=Ps, jointDControlVector=[float(damping * k) for k in Ps]))
    return node, tree


class TreeChain(Chain):
    """Chain in minimal coordinates: planar (``RevoluteY``) or 3-D (``spatial=True``): Cardan joints
    with ``torsion="locked"``, three revolute joints with a torsion spring for ``"spring"``."""

    rigid_bodies = False

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 spatial: bool = False, torsion: str = "locked") -> None:
        self.spatial = bool(spatial)
        self.planar = not self.spatial
        self.torsion = torsion if self.spatial else "locked"
        self.per = (3 if torsion == "spring" else 2) if self.spatial else 1
        # 3-D tendons (continuum or eyelets) as rope forces of a generic object's user functions
        # (.linkrope): rope connectors on tree markers re-evaluate the tree kinematics per Jacobian entry
        self.link_ropes = self.spatial and load.actuation is not None
        super().__init__(robot, load, options, geo)

    def _continuum_ropes(self) -> bool:
        """3-D continuum tendons: rope forces through every link eyelet from the rope object's user
        functions (:mod:`.linkrope`), not rope connectors; otherwise as the base."""
        return False if self.link_ropes else super()._continuum_ropes()

    def _rope_tensions(self, length: np.ndarray) -> np.ndarray:
        """Tensions ``(..., n_tendons)`` of the link ropes at polygon lengths ``(..., n_tendons)``: the
        commands (tension mode) or ``EA_t (L - L_0) / L_0`` while taut, 0 when slack (length mode)."""
        if self.mode == "tension":
            return np.broadcast_to(self._values, np.shape(length))
        EA = np.array([t.axial_stiffness for t in self.tendons])
        L0 = np.asarray(self._L0, dtype=float)
        return np.where(np.asarray(self.tendon_active), EA * (length - L0) / L0, 0.0)

    def _rope_user_force(self, mbs, t, itemNumber, q, q_t):  # noqa: ANN001, ARG002 - Exudyn signature
        return generalised_forces(self._layout, q, self._rope_tensions, self._tip)

    def _rope_user_jacobian(self, mbs, t, itemNumber, q, q_t, fODE2, fODE2_t):  # noqa: ANN001, ARG002
        # the forces are on the right-hand side: the left-hand side's Jacobian is -fODE2 dQ/dq
        return -fODE2 * generalised_force_jacobian(self._layout, np.asarray(q), self._rope_tensions, self._tip)

    def set_external(self, lam: float) -> None:
        """Gravity and tip loads at load factor ``lam``; with link ropes the tip loads are the generic
        object's (:mod:`.linkrope`), the tree marker's loads stay zero."""
        super().set_external(lam)
        if self.link_ropes:
            self._tip = (lam * np.asarray(self.load.tip_force, dtype=float),
                         lam * np.asarray(self.load.tip_torque, dtype=float))

    def _build(self, mbs) -> None:  # noqa: ANN001
        exu, eii, geo = self.exu, self.eii, self.geo
        n = geo.n_links * self.per
        self.g2 = np.asarray(self.robot.gravity_in_base(), dtype=float)
        mass, coms, inertias = _tree_link_masses(geo, self.robot.payload)
        links = _tree_links(exu, geo, mass, coms, inertias, self.per)
        self.n_coords = n
        self.node, self.tree = _add_kinematic_tree(mbs, exu, eii, links, self.options.damping)
        # the joints and (for link ropes) the eyelets of the vectorised kinematics (.linkrope)
        self._layout = rope_layout(geo, [joint_axes(self.per, k) for k in range(geo.n_links)],
                                   self.tendons if self.link_ropes else [])
        if self.link_ropes:
            self._values = np.zeros(len(self.tendons))
            # the rope forces as a generic ODE2 object on the tree's coordinates, with its own
            # Jacobian (Exudyn would difference a tree user function one coordinate per call)
            self.rope_object = mbs.AddObject(eii.ObjectGenericODE2(
                nodeNumbers=[self.node], massMatrix=np.zeros((n, n)), forceUserFunction=self._rope_user_force,
                jacobianUserFunction=self._rope_user_jacobian))
        self.ground = mbs.AddObject(eii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        m_tip = mbs.AddMarker(eii.MarkerKinematicTreeRigid(objectNumber=self.tree, linkNumber=n - 1,
                                                           localPosition=[0.0, 0.0, float(geo.link_lengths[-1])]))
        if self.link_ropes:  # tip loads in the rope object's user function (with their Jacobian)
            self._tip = (np.zeros(3), np.zeros(3))
            self._add_tip_loads(mbs, m_tip, force=np.zeros(3), torque=np.zeros(3))
        else:
            self._add_tip_loads(mbs, m_tip)
        self._add_tendons(mbs)

    def _tree_marker(self, mbs, link: int, position: list[float]) -> int:  # noqa: ANN001
        return mbs.AddMarker(self.eii.MarkerKinematicTreeRigid(objectNumber=self.tree, linkNumber=link,
                                                               localPosition=position))

    def _eyelet_marker(self, mbs, i: int, tendon: TendonRoute, link: int, z: float, d: float) -> int:  # noqa: ANN001
        u = np.array([math.cos(tendon.sigma), math.sin(tendon.sigma)]) if self.spatial else np.array([self.sign[i], 0.0])
        x, y = (d * u).tolist()
        if link < 0:
            return mbs.AddMarker(self.eii.MarkerBodyRigid(bodyNumber=self.ground, localPosition=[x, y, float(z)]))
        return self._tree_marker(mbs, int(link + 1) * self.per - 1, [x, y, float(z)])

    def _continuum_items(self, mbs, i: int, tendon: TendonRoute) -> list:  # noqa: ANN001
        eii = self.eii
        if self.link_ropes:  # forces from the rope object's user function
            return []
        if self.mode == "length":  # planar: rotational spring on the terminating link's angle
            mg = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.ground, localPosition=[0.0, 0.0, 0.0]))
            mt = self._tree_marker(mbs, tendon.end_eyelet - 1, [0.0, 0.0, 0.0])
            return [mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(markerNumbers=[mg, mt],
                                                                           useIntrinsicFormulation=True))]
        return []  # planar tension: generalised joint forces (jointForceVector), no items

    def _set_gravity(self, lam: float) -> None:
        self.mbs.SetObjectParameter(self.tree, "gravity", (lam * self.g2).tolist())

    def _set_continuum(self) -> None:
        mbs = self.mbs
        if self.link_ropes:  # the user function reads self._values / self._L0
            return
        if self.mode == "tension":
            Q = np.zeros(self.geo.n_links)
            for i, (t, v) in enumerate(zip(self.tendons, self._values)):
                Q[: t.end_eyelet] += v * t.moment_arm * self.sign[i]
            mbs.SetObjectParameter(self.tree, "jointForceVector", Q.tolist())
            return
        for i, (t, items) in enumerate(zip(self.tendons, self.tendon_items)):
            d, c, L0 = t.offsets[-1], self.sign[i], float(self._L0[i])
            K = np.zeros((6, 6))
            K[4, 4] = t.axial_stiffness * d * d / L0 if self.tendon_active[i] else 0.0
            off = [0.0] * 6
            off[4] = float((t.reference_length - L0) / (d * c))
            mbs.SetObjectParameter(items[0], "stiffness", K.tolist())
            mbs.SetObjectParameter(items[0], "offset", off)

    def link_frames(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) and link rotations (N, 3, 3) from the tree coordinates
        (:func:`.linkrope.tree_kinematics`)."""
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(), dtype=float)
        P, R, _ = tree_kinematics(q, self._layout)
        return P, R

    def link_states(self) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions (N, 3) and link angles (N,) of the planar tree (angles add up)."""
        q = np.asarray(self.mbs.systemData.GetODE2Coordinates(), dtype=float)
        beta = np.cumsum(q)
        geo = self.geo
        P = np.zeros((geo.n_links, 3))
        P[0] = [0.0, 0.0, geo.joints[0]]
        for k in range(1, geo.n_links):
            P[k] = P[k - 1] + geo.link_lengths[k - 1] * np.array([math.sin(beta[k - 1]), 0.0, math.cos(beta[k - 1])])
        return P, beta


def _tip_joint_forces(robot: Robot, load: LoadCase, geo: ChainGeometry) -> np.ndarray:
    """Generalised joint moments (N,) about base y: the tip moment on every joint plus
    ``T d`` of every continuum tendon on the joints it passes (exact for bends in the x-z plane)."""
    Q = np.full(geo.n_links, float(load.tip_torque[1]))
    if load.actuation is not None:
        if load.actuation.mode != "tension":
            raise ValueError("tree_tip_position supports tension control only")
        m_end = geo.section_end_eyelet
        for (j, sigma, grp), T in zip(robot.tendon_table(), load.actuation.values):
            Q[: m_end[j]] += T * grp.offset * (1.0 if np.cos(sigma) > 0 else -1.0)
    return Q


def _tip_by_forward_kinematics(q: np.ndarray, geo: ChainGeometry, per: int) -> np.ndarray:
    """Tip position (3,) of the chain with tree coordinates ``q`` (``per`` per joint)."""
    R = np.eye(3)
    p = np.zeros(3)
    for k in range(geo.n_links):
        p = p + R @ np.array([0.0, 0.0, geo.joints[0] if k == 0 else geo.link_lengths[k - 1]])
        for ax, a in zip(joint_axes(per, k), q[k * per:(k + 1) * per]):
            R = R @ axis_rotation(ax, a)
    return p + R @ np.array([0.0, 0.0, geo.link_lengths[-1]])


def tree_tip_position(robot: Robot, load: LoadCase, options: SolverOptions, dimension: str = "2d") -> np.ndarray:
    """Static tip position of the stripped kinematic-tree chain (see the module docstring).

    Parameters
    ----------
    robot : Robot
        Tendons at sigma in {0, pi} only; the payload is not modelled.
    load : LoadCase
        Gravity, a tip moment about base y and tension-controlled continuum tendons.
    options : SolverOptions
        ``n_elements`` links, ``max_load_steps`` attempts of the load ramp.
    dimension : {"2d", "3d"}
        One ``RevoluteY`` per joint, or ``RevoluteX`` + ``RevoluteY`` (Cardan).

    Returns
    -------
    ndarray, shape (3,)
        Tip position [m], base frame.

    Raises
    ------
    ValueError
        Unsupported dimension, tendon angle, load or actuation mode.
    ModelFailure
        The load ramp needed more than ``options.max_load_steps`` attempts.
    """
    import exudyn as exu
    import exudyn.itemInterface as eii

    from .._exudyn import quiet_exudyn, static_settings

    if dimension not in ("2d", "3d"):
        raise ValueError(f"dimension must be '2d' or '3d', got {dimension!r}")
    if any(abs(np.sin(s)) > 1e-9 for _, s, _ in robot.tendon_table()):
        raise ValueError("tree_tip_position supports tendons at sigma in {0, pi} only")
    if np.any(np.abs(load.tip_force) > 0) or abs(load.tip_torque[0]) > 0 or abs(load.tip_torque[2]) > 0:
        raise ValueError("tree_tip_position supports a tip moment about base y only")
    geo = chain_geometry_from_robot(robot, options.n_elements)
    per = 1 if dimension == "2d" else 2
    Qfull = np.zeros(geo.n_links * per)
    Qfull[per - 1 :: per] = _tip_joint_forces(robot, load, geo)
    links = _tree_links(exu, geo, *_tree_link_masses(geo, None), per)
    g = np.asarray(robot.gravity_in_base(), dtype=float)
    with quiet_exudyn():
        SC = exu.SystemContainer()  # keep the container alive while its system is used
        mbs = SC.AddSystem()
        _, tree = _add_kinematic_tree(mbs, exu, eii, links, 0.0)
        mbs.Assemble()
        settings = static_settings(options, 1)
        settings.staticSolver.adaptiveStep = False
        initial = exu.ConfigurationType.Initial

        def point() -> PathPoint:  # the load-path measure: tip position / L
            q = np.asarray(mbs.systemData.GetODE2Coordinates())
            return PathPoint(tuple(_tip_by_forward_kinematics(q, geo, per) / robot.length))

        def attempt(lam: float) -> bool | PathPoint:
            mbs.SetObjectParameter(tree, "gravity", (lam * g).tolist())
            mbs.SetObjectParameter(tree, "jointForceVector", (lam * Qfull).tolist())
            solver = exu.MainSolverStatic()
            if not solver.SolveSystem(mbs, settings):
                return False
            mbs.systemData.SetODE2Coordinates(mbs.systemData.GetODE2Coordinates(), configuration=initial)
            return point()

        try:
            load_ramp(attempt, lambda: mbs.systemData.GetODE2Coordinates(configuration=initial),
                      lambda q: mbs.systemData.SetODE2Coordinates(q, configuration=initial),
                      max_attempts=options.max_load_steps, policy=_TIP_RAMP, failure=exu.SolverError, start=point())
        except RampExhausted:
            raise ModelFailure("kinematic tree: load ramp exceeded options.max_load_steps") from None
        q = np.asarray(mbs.systemData.GetODE2Coordinates())
    return _tip_by_forward_kinematics(q, geo, per)
