"""The assembled Exudyn system of one ``beam3d`` solve (private; see :mod:`workbench.physics.beam3d`).

:class:`Beam3DSystem` builds the geometrically exact beam in the model frame (beam axis = model x,
``R_BASE_MODEL``), its clamp, masses, loads and eyelet tendons, and offers the setters the load
ramp and the dynamics drive (tendon commands, load factor) and the readers of the results (base
frame).  Built per call from plain parameters; nothing is kept between calls.  Checked by
``tests/physics/test_beam3d*.py``.
"""

from __future__ import annotations

import math

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadForceVector,
    LoadTorqueVector,
    MarkerBodyPosition,
    MarkerBodyRigid,
    MarkerNodeRigid,
    NodeRigidBodyEP,
    NodeRigidBodyRotVecLG,
    ObjectBeamGeometricallyExact,
    MarkerNodePosition,
    ObjectConnectorReevingSystemSprings,
    ObjectConnectorRigidBodySpringDamper,
    ObjectConnectorSpringDamper,
    ObjectGround,
    ObjectRigidBody,
)

from ..models.result import ModelFailure, SolverOptions
from ..robot import LoadCase, Robot
from ._beam3d_layout import R_BASE_MODEL, element_layout, locate, tendon_routes
from ._exudyn import add_gravity_loads, add_point_masses, clamp_coordinates, lumped_disk_masses, set_load_factor

_SHEAR_FACTOR_IF_NONE = 100.0
_REGULARIZATION_FORCE = 1e-3
#: an eyelet within this fraction of the rod length from a node sits on the node (``Beam3DSystem._node_at``)
_ON_NODE = 1e-9
#: entries (eps, gamma_y, gamma_z) of Exudyn's StrainLocal Voigt 6-vector (xx, yy, zz, yz, xz, xy)
_STRAIN_ENTRIES = [0, 5, 4]


def beam_section(cs, damping: float, axial_shear_scale: float = 1.0) -> "exu.BeamSection":
    """``BeamSection`` of a cross-section: ``diag(EA, GA, GA, GJ, EI, EI)``, mass and rotary inertia per length.

    ``GA = CrossSection.GA`` or ``100 EA`` if None (shear-rigid limit); rotary inertia
    ``mu EI/EA diag(2, 1, 1)`` (solid homogeneous section).  The damping matrix is ignored by
    Exudyn 1.13.6 (``test_exudyn_ge_beam_ignores_section_damping``): beam3d's damping is added by
    :meth:`Beam3DSystem._add_section_dampers` instead.
    ``axial_shear_scale`` multiplies EA and GA in the stiffness (not in the inertia): < 1 only in
    the predictor stages of the static solve (:func:`workbench.physics.beam3d._ramp_static`).
    """
    GA = cs.GA if cs.GA is not None else _SHEAR_FACTOR_IF_NONE * cs.EA
    a = float(axial_shear_scale)
    K = np.diag([a * cs.EA, a * GA, a * GA, cs.GJ, cs.EI, cs.EI])
    bs = exu.BeamSection()
    bs.stiffnessMatrix = K
    bs.dampingMatrix = damping * K
    bs.massPerLength = cs.mass_per_length
    bs.inertia = cs.mass_per_length * (cs.EI / cs.EA) * np.diag([2.0, 1.0, 1.0])
    return bs


class Beam3DSystem:
    """The assembled Exudyn system of one beam3d solve, with its load setters and result readers.

    Parameters
    ----------
    robot, load, options
        The case; ``options.n_elements`` and ``options.damping`` are used here.
    tendon_mode : {"none", "tension", "length"}
        Which tendon objects to build (``"none"``: unloaded tendons are left out).
    node_type : {"EP", "LG"}
        Euler-parameter nodes (used) or Lie-group nodes (kept for measurements; they stall in
        static Newton for skewed bending planes).

    Attributes
    ----------
    loads : list of (load index, full vector)
        Every ramped load in the model frame, in the order added (gravity, then vector loads).
    tendon_objects, tendon_markers : list of lists
        Per tendon: its connector objects and its markers (anchor first).
    tendon_path0, tendon_rest0 : ndarray
        Per tendon: reference path length through the eyelets, and rest length at full pretension.
    """

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, tendon_mode: str,
                 node_type: str = "EP"):
        self.robot = robot
        self._damping = options.damping
        self.SC = exu.SystemContainer()
        self.mbs = self.SC.AddSystem()
        self.node_s, elem_sec = element_layout(robot, options.n_elements)
        self.elem_len = np.diff(self.node_s)
        clamped = self._add_beam(robot, elem_sec, options.damping, node_type)
        clamp_coordinates(self.mbs, self.nodes[0], clamped)
        g_m = R_BASE_MODEL.T @ robot.gravity_in_base()
        self.loads = self._add_masses(robot, g_m) + self._add_tip_loads(robot, load, g_m)
        self.tendon_mode = tendon_mode
        self.tendon_objects: list[list[int]] = []
        self.tendon_markers: list[list[int]] = []
        self.tendon_path0 = np.zeros(0)
        self.tendon_rest0 = np.zeros(0)
        self._node_bodies: dict[int, int] = {}
        # undamped dynamics keep the element markers: their answers depend on the last bit (the undamped
        # compensated arm's end tip moves by mm with the round-off; tests/regression golden wire_delay_arm)
        self._node_eyelets = not (load.analysis == "dynamic" and options.damping == 0)
        self._stress_cache = None
        if tendon_mode != "none":
            self._add_tendons(robot, load)
        self.dampers: list[int] = []
        if options.damping > 0 and load.analysis == "dynamic":
            self._add_section_dampers(float(options.damping))
        self.mbs.Assemble()

    # -- building -------------------------------------------------------------------------
    def _add_beam(self, robot: Robot, elem_sec: np.ndarray, damping: float, node_type: str) -> tuple[int, ...]:
        """Nodes and elements (cross-section at each element's midpoint); returns the clamped coordinates."""
        mbs, node_s = self.mbs, self.node_s
        if node_type == "EP":
            self.nodes = [mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=[float(s), 0, 0, 1, 0, 0, 0])) for s in node_s]
            clamped = (0, 1, 2, 4, 5, 6)  # position and Euler parameters e1..e3 (e0 follows from |e| = 1)
        else:
            self.nodes = [mbs.AddNode(NodeRigidBodyRotVecLG(referenceCoordinates=[float(s), 0, 0, 0, 0, 0])) for s in node_s]
            clamped = (0, 1, 2, 3, 4, 5)
        starts = np.concatenate([[0.0], robot.section_ends[:-1]])
        self.elements = []
        self.elem_cs = []  # CrossSection of every element (its midpoint), for stresses
        for e in range(elem_sec.size):
            j = int(elem_sec[e])
            sec = robot.sections[j]
            frac = (0.5 * (node_s[e] + node_s[e + 1]) - starts[j]) / sec.length
            self.elem_cs.append(sec.cross_section_at(frac))
            bs = beam_section(self.elem_cs[-1], damping)
            self.elements.append(mbs.AddObject(ObjectBeamGeometricallyExact(
                nodeNumbers=[self.nodes[e], self.nodes[e + 1]], length=float(self.elem_len[e]), sectionData=bs,
            )))
        return clamped

    def _add_section_dampers(self, beta: float) -> None:
        """Stiffness-proportional (Kelvin-Voigt) damping of every element, ``beta`` [s], added by connectors.

        Exudyn's GE beam ignores ``BeamSection.dampingMatrix``; the same dissipation is added per element
        between its two nodes: a ``ConnectorSpringDamper`` with damping ``beta EA / L_e`` on the rate of
        the node distance (axial) and a ``ConnectorRigidBodySpringDamper`` with no stiffness and damping
        ``beta diag(GJ, EI, EI) / L_e`` on the relative angular velocity in the node frames (torsion,
        bending; node x = beam axis).  Both rates vanish for rigid motions (objective); transverse shear
        is not damped.  Dynamics only (no velocities in statics).
        """
        mbs = self.mbs
        zero6 = np.zeros((6, 6))
        for e, cs in enumerate(self.elem_cs):
            a, b = self.nodes[e], self.nodes[e + 1]
            Le = float(self.elem_len[e])
            pa, pb = (mbs.AddMarker(MarkerNodePosition(nodeNumber=n)) for n in (a, b))
            self.dampers.append(mbs.AddObject(ObjectConnectorSpringDamper(
                markerNumbers=[pa, pb], referenceLength=Le, stiffness=0.0, damping=beta * cs.EA / Le)))
            ra, rb = (mbs.AddMarker(MarkerNodeRigid(nodeNumber=n)) for n in (a, b))
            D = zero6.copy()
            D[3:, 3:] = np.diag([cs.GJ, cs.EI, cs.EI]) * (beta / Le)
            self.dampers.append(mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
                markerNumbers=[ra, rb], stiffness=zero6, damping=D)))

    def _add_masses(self, robot: Robot, g_m: np.ndarray) -> list:
        """Disk masses and a zero-offset payload as node masses; gravity on them and on the beam."""
        lumped = lumped_disk_masses(robot, self.node_s, midpoint_weights=True)
        pay = robot.payload
        if pay.mass > 0 and not any(pay.offset):
            lumped[-1] += pay.mass
        points = add_point_masses(self.mbs, self.nodes, lumped)
        if not np.any(g_m != 0.0):
            return []
        return [(ld, g_m) for ld in add_gravity_loads(self.mbs, self.elements + points)]

    def _add_tip_loads(self, robot: Robot, load: LoadCase, g_m: np.ndarray) -> list:
        """Weight of an offset payload (a force at the offset point), tip force and tip torque."""
        mbs = self.mbs
        loads = []
        pay = robot.payload
        if pay.mass > 0 and any(pay.offset) and np.any(g_m != 0.0):
            off = np.asarray(pay.offset)  # tip frame (x, y, z) = local (y, z, x)
            loc = [0.5 * self.elem_len[-1] + off[2], off[0], off[1]]
            mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.elements[-1], localPosition=loc))
            loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=[0, 0, 0])), pay.mass * g_m))
        mtip = mbs.AddMarker(MarkerNodeRigid(nodeNumber=self.nodes[-1]))
        F = R_BASE_MODEL.T @ np.asarray(load.tip_force)
        M = R_BASE_MODEL.T @ np.asarray(load.tip_torque)
        if np.any(F != 0):
            loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mtip, loadVector=[0, 0, 0])), F))
        if np.any(M != 0):
            loads.append((mbs.AddLoad(LoadTorqueVector(markerNumber=mtip, loadVector=[0, 0, 0])), M))
        return loads

    def _add_eyelets(self, ground: int, route: list, sigma: float, rigid: bool) -> tuple[list[int], np.ndarray]:
        """Markers of one tendon route (anchor on ground, then eyelets); the straight segment lengths.

        ``rigid``: rigid markers (the reeving rope needs them); else position markers (same points;
        halves the numerically differentiated connector Jacobian, ``docs/models.md``).  An eyelet on a
        node (a disk on an element boundary) is a marker on that node's body (:meth:`_node_body`): it
        depends on the node's 7 coordinates instead of the element's 14, so the numerical connector
        Jacobian costs half as many rope evaluations, each cheaper (benchmarks/README.md, "wire delay");
        the point and frame are the element end's, so the physics is the same.
        """
        c, s_ = math.cos(sigma), math.sin(sigma)
        Marker = MarkerBodyRigid if rigid else MarkerBodyPosition
        markers, pts = [], []
        for k, (s, d) in enumerate(route):
            off = [d * c, d * s_]
            i = None if k == 0 else self._node_at(s)
            if k == 0:
                body, loc = ground, [0.0, *off]
            elif i is not None:
                body, loc = self._node_body(i), [0.0, *off]
            else:
                e, xl = locate(self.node_s, s)
                body, loc = self.elements[e], [xl, *off]
            markers.append(self.mbs.AddMarker(Marker(bodyNumber=body, localPosition=loc)))
            pts.append([s, *off])
        return markers, np.linalg.norm(np.diff(np.asarray(pts), axis=0), axis=1)

    def _node_at(self, s: float) -> int | None:
        """Index of the node at arc length ``s`` (to ``1e-9 L``), or None (the eyelet lies inside an element,
        or undamped dynamics, see ``__init__``)."""
        if not self._node_eyelets:
            return None
        i = int(np.argmin(np.abs(self.node_s - s)))
        return i if abs(self.node_s[i] - s) <= _ON_NODE * self.node_s[-1] else None

    def _node_body(self, i: int) -> int:
        """A massless ``ObjectRigidBody`` on node ``i`` that carries eyelet markers (one per node, made once;
        checked against element markers by ``tests/physics/test_beam3d_node_eyelets.py``).

        It adds no mass, inertia or stiffness; a marker on it is the node's frame, i.e. the element end's.
        """
        if i not in self._node_bodies:
            self._node_bodies[i] = self.mbs.AddObject(ObjectRigidBody(nodeNumber=self.nodes[i], mass=0.0,
                                                                      inertia=[0.0] * 6))
        return self._node_bodies[i]

    def _add_tendons(self, robot: Robot, load: LoadCase) -> None:
        """Tension mode: constant-force segments (position markers); length mode: one reeving rope per tendon (rigid markers)."""
        mbs, act = self.mbs, load.actuation
        ground = mbs.AddObject(ObjectGround())
        path0, rest0, rope_EA = [], [], []
        for (j, sigma, group), route in zip(robot.tendon_table(), tendon_routes(robot)):
            markers, seg = self._add_eyelets(ground, route, sigma, rigid=self.tendon_mode != "tension")
            L0 = float(seg.sum())
            path0.append(L0)
            self.tendon_markers.append(markers)
            if self.tendon_mode == "tension":
                objs = [
                    mbs.AddObject(ObjectConnectorSpringDamper(
                        markerNumbers=[markers[k], markers[k + 1]], referenceLength=float(seg[k]),
                        stiffness=0.0, damping=0.0, force=0.0
                    ))
                    for k in range(len(markers) - 1)
                ]
                rest0.append(L0)
            else:
                EAt = group.axial_stiffness
                rope_EA.append(EAt)
                rest0.append(L0 / (1.0 + act.pretension / EAt))
                objs = [mbs.AddObject(ObjectConnectorReevingSystemSprings(
                    markerNumbers=markers, stiffnessPerLength=EAt, dampingPerLength=0.0, referenceLength=L0,
                    regularizationForce=_REGULARIZATION_FORCE,
                    sheavesAxes=exu.Vector3DList([[0.0, 0.0, 1.0]] * len(markers)), sheavesRadii=[0.0] * len(markers),
                ))]
            self.tendon_objects.append(objs)
        self.tendon_path0 = np.asarray(path0)
        self.tendon_rest0 = np.asarray(rest0)
        self._rest = self.tendon_path0.copy()  # each rope's referenceLength as last set (built: the path length)
        self._rope_EA = np.asarray(rope_EA)

    # -- setters ----------------------------------------------------------------------------
    def set_tendons(self, values: np.ndarray, lam_pre: float) -> None:
        """Apply tendon commands ``values`` (tension [N] or length change [m]).

        ``lam_pre`` scales the pretension shortening (static ramp); 1 in dynamics.
        """
        mbs = self.mbs
        if self.tendon_mode == "tension":
            for objs, T in zip(self.tendon_objects, values):
                for o in objs:
                    mbs.SetObjectParameter(o, "force", float(T))
        elif self.tendon_mode == "length":
            for i, (objs, L0, r0, dl) in enumerate(zip(self.tendon_objects, self.tendon_path0, self.tendon_rest0, values)):
                rest = L0 + lam_pre * (r0 - L0) + float(dl)
                if rest <= 0:
                    raise ModelFailure(f"beam3d: tendon rest length {rest:.4g} m <= 0 (command too large)")
                if rest != self._rest[i]:  # unchanged commands (before or after a ramp) are not set again
                    mbs.SetObjectParameter(objs[0], "referenceLength", float(rest))
                    self._rest[i] = rest

    def set_axial_shear_scale(self, scale: float) -> None:
        """Scale EA and GA of every element by ``scale`` (1: the robot's own section); bending and torsion unchanged."""
        for e, cs in zip(self.elements, self.elem_cs):
            self.mbs.SetObjectParameter(e, "sectionData", beam_section(cs, self._damping, scale))

    def set_loads(self, lam: float) -> None:
        """Every ramped load at ``lam`` times its full value."""
        set_load_factor(self.mbs, self.loads, lam)

    # -- readers (base frame) ---------------------------------------------------------------
    def tendon_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Current tensions [N] and stretches (path length - rest length) [m] of every built tendon."""
        mbs = self.mbs
        n = len(self.tendon_objects)
        T = np.zeros(n)
        stretch = np.zeros(n)
        if self.tendon_mode == "tension":
            for i, objs in enumerate(self.tendon_objects):
                T[i] = float(mbs.GetObjectParameter(objs[0], "force"))
        elif self.tendon_mode == "length":
            for i, objs in enumerate(self.tendon_objects):
                # the rope's own path length through its markers (sheave radii 0: the polyline length)
                length = float(mbs.GetObjectOutput(objs[0], exu.OutputVariableType.Distance))
                rest = float(self._rest[i])
                stretch[i] = length - rest
                T[i] = max(0.0, float(self._rope_EA[i]) * stretch[i] / rest)
        return T, stretch

    def element_strains(self) -> tuple[np.ndarray, np.ndarray]:
        """Strain ``(eps, gamma_y, gamma_z)`` and curvature ``(kappa_1 torsion, kappa_2, kappa_3)`` of every element, ``(n_el, 3)`` each."""
        mbs = self.mbs
        # StrainLocal is a Voigt 6-vector (xx, yy, zz, yz, xz, xy): eps = [0], gamma_y = [5] (xy),
        # gamma_z = [4] (xz), engineering shear strains (Q / GA); checked against Timoshenko theory by
        # tests/physics/test_beam3d_shear_strain.py.  localPosition passed positionally (a keyword
        # argument costs more than the call: benchmarks/README.md, "wire delay")
        get, mid = mbs.GetObjectOutputBody, [0.0, 0.0, 0.0]
        strain, curv = exu.OutputVariableType.StrainLocal, exu.OutputVariableType.CurvatureLocal
        g = np.array([get(e, strain, mid) for e in self.elements], dtype=float)[:, _STRAIN_ENTRIES]
        k = np.array([get(e, curv, mid)[:3] for e in self.elements], dtype=float)
        return g, k

    def shape_scalars(self, strains: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[float, float]:
        """(length change [m], tip twist [rad]) from element strains and torsional curvature."""
        g, k = self.element_strains() if strains is None else strains
        stretch = np.sqrt((1.0 + g[:, 0]) ** 2 + g[:, 1] ** 2 + g[:, 2] ** 2)  # |Gamma| per element
        dl = float(np.sum(self.elem_len * (stretch - 1.0)))
        tw = float(np.sum(self.elem_len * k[:, 0]))
        return dl, tw

    def backbone_stress(self, strains: tuple[np.ndarray, np.ndarray] | None = None):
        """Largest normal stress of every element (:mod:`workbench.models.stress`: ``EA eps`` and
        ``EI |(kappa_2, kappa_3)|``) and its strength: ``(sigma (n_el,), strength (n_el,))``, or
        ``None`` without stress geometry."""
        from ..models.stress import combined_stress

        arrs, EA, EI = self._stress_sections()
        if arrs is None:
            return None
        g, k = self.element_strains() if strains is None else strains
        return combined_stress(EA * g[:, 0], EI * np.hypot(k[:, 1], k[:, 2]), arrs[0], arrs[1]), arrs[2]

    def _stress_sections(self):
        """``(section_arrays of the elements or None, EA (n_el,), EI (n_el,))``, computed once (dynamics reads them per sample)."""
        if self._stress_cache is None:
            from ..models.stress import section_arrays

            self._stress_cache = (section_arrays(self.elem_cs), np.array([cs.EA for cs in self.elem_cs]),
                                  np.array([cs.EI for cs in self.elem_cs]))
        return self._stress_cache

    def tip_position(self) -> np.ndarray:
        """Tip node position, base frame, ``(3,)`` [m]."""
        p = self.mbs.GetNodeOutput(self.nodes[-1], exu.OutputVariableType.Position)
        return R_BASE_MODEL @ np.asarray(p)

    def tip_frame(self) -> np.ndarray:
        """Base <- tip homogeneous transform ``(4, 4)``; columns = tip cross-section axes, z along the backbone."""
        mbs = self.mbs
        p = np.asarray(mbs.GetNodeOutput(self.nodes[-1], exu.OutputVariableType.Position))
        A = np.asarray(mbs.GetNodeOutput(self.nodes[-1], exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
        T = np.eye(4)
        T[:3, :3] = R_BASE_MODEL @ A @ R_BASE_MODEL.T
        T[:3, 3] = R_BASE_MODEL @ p
        return T

    def positions(self, stations: np.ndarray) -> np.ndarray:
        """Centreline points at reference stations, by the element's own interpolation, ``(m, 3)`` [m]."""
        out = np.empty((stations.size, 3))
        for i, s in enumerate(stations):
            e, xl = locate(self.node_s, float(s))
            p = self.mbs.GetObjectOutputBody(self.elements[e], exu.OutputVariableType.Position, localPosition=[xl, 0, 0])
            out[i] = R_BASE_MODEL @ np.asarray(p)
        return out
