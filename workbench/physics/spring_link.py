"""Spring-link model: a chain of rigid links joined by rotational springs (Exudyn).

A segmented backbone (Hannan & Walker's trunk, OpenCR-MuJoCo's "N links with springs of
stiffness N EI / L") or the lumped equivalent of a continuous rod.

Discretisation
--------------
``options.n_elements = N`` rigid links ("half-link"/tangent-polygon layout, see
:mod:`workbench.physics._spring_link_geometry`): eyelet stations ``e_k`` equally spaced within
every section (``N`` must be a multiple of the number of sections), joint ``k`` half-way between
``e_{k-1}`` and ``e_k`` with bending stiffness ``k_k = EI(s_k) / (e_k - e_{k-1})`` (equivalent rod;
a robot with explicit joint springs ``k`` is described by ``EI = k * ds``, which is what the
Hannan & Walker preset does).  Link masses and inertias are integrated from the cross-section's
mass per length (plus the sections' disk masses, spread over the link eyelets); the base plate
carries the rod piece below the first joint.  Under a pure moment all joints turn by ``kappa ds``:
the tip orientation is exact, positions converge as ``O(1/N^2)`` (measured: order 2.00 for the
arc and the heavy elastica).  Kinematic limit: with equal joint angles ``theta`` in a section the
disks (link midpoints, every ``ds``) lie exactly on a constant-curvature arc of curvature
``2 tan(theta/2) / ds`` and the tip frame is that arc's end frame (tested to 1e-12).

Dimension
---------
``SpringLinkParams.dimension = "auto"`` (default) builds the planar model (Exudyn ``RigidBody2D`` +
``RevoluteJoint2D`` + ``CoordinateSpringDamper`` on the relative rotation) when every tendon lies at
``sigma in {0, pi}`` and gravity, tip force and payload offset lie in the base x-z plane and the tip
torque is about base y; otherwise the spatial model: Euler-parameter rigid bodies
(``NodeRigidBodyEP``; Lie-group nodes fail in statics), ``GenericJoint`` with the translations
constrained (spherical joint, or Cardan joint with ``torsion="locked"``) and
``RigidBodySpringDamper`` with ``useIntrinsicFormulation=True`` carrying ``diag(k, k, GJ/ds)``.  The
planar model bends in the base x-z plane; Exudyn's plane (X, Y) is mapped to base (x, z).  On a
planar case both give the same result to ~1e-11 (tested); the planar one is about 1.5-3x faster
(``benchmarks/bench_spring_link.py``).

Backend choice (measured, ``benchmarks/bench_spring_link.py``)
-------------------------------------------------------------
The inextensible chain also exists as one ``ObjectKinematicTree`` (minimal coordinates,
``RevoluteY`` joints, or ``RevoluteX`` + ``RevoluteY`` Cardan joints in 3-D with
``torsion="locked"``; springs as ``jointPControlVector``, eyelets as ``MarkerKinematicTreeRigid``;
``SpringLinkParams.backend``).  Both give the same statics to ~1e-10 (tested).  With eyelet ropes
(reeving in length mode, or constant-force segments in tension mode) the tree keeps Newton
quadratic (3-4 iterations) while the rigid-body chain converges only linearly (Newton
contraction 0.5-0.8 per iteration, see *Limitations*) and its static ramp stalls: in the bending
study (steel rod, 32 links, tension from the CC command up to kappa L = 2 pi, up to 10.5 kN) it
failed 14 of 15 eight-disk cases within 40 load steps (3-10 s each, 2 cores shared); the tree
solves all 60 eyelet cases in one load step (0.07-0.8 s; mean 0.27 s).  So ``backend="auto"`` uses the tree
for every eyelet rope; with continuum tendons / gravity the two are within a factor ~2 either
way on this machine, so the rigid bodies stay the default there.  The benchmark also times a
stripped tree chain (:mod:`._spring_link_tree`).

Tendons
-------
* ``tendon_model = "eyelets"``: one frictionless rope per tendon from the base plate through the
  robot's disks (``robot.disk_stations()`` up to its section end; the section-end station is the
  terminating eyelet), at offset ``d`` (``offset_at`` the fraction of the tendon's own path, for
  tapered groups), as in the ANCF model.  A disk sits on the link whose span contains its
  station (links may be finer than disks; several disks on one link are allowed).  The chain
  converges to the ANCF rope model (same disks) as ``O(1/N^2)`` (measured tip errors
  1.85e-2 / 4.5e-3 / 1.1e-3 m at N = 32 / 64 / 128, kappa L = pi, d/L = 0.025, 8 disks), and the
  eyelet effect (eyelets vs continuum tendon) falls with order ~2 in the disk count and equals
  ANCF's to the chain's discretisation error (tested).  Tension control: one constant-force
  ``ObjectConnectorSpringDamper`` (stiffness 0, ``force = T``) per straight rope segment, which is
  *exactly* a frictionless rope with uniform tension ``T``.  Length control:
  ``ObjectConnectorReevingSystemSprings`` (one rope, uniform tension ``T = EA_t (L - L_0) / L_0``)
  through rigid eyelet markers, ``L_0 = L_ref + dl - pretension L_ref / EA_t``; a tendon in
  compression is switched off (slack) and re-activated once taut again (active-set loop in
  statics, per time step in dynamics).  The equivalence of both (reeving tension fed back as a
  tension command gives the same shape) is a test.
* ``tendon_model = "continuum"``: the tendon follows the centreline at offset ``d``, so the
  internal moment at every joint it passes is ``T d cos(alpha)`` (``alpha`` its reference slope):
  a torque ``T d`` on its terminating link (reaction on the base) for a constant offset, torque
  differences on every link it passes for a tapered one (planar only).  Its compression ``T``
  matters only with axial springs (see *Axial compliance*).  Tension control applies the torque;
  length control uses that the tendon length is ``L_ref - d cos(sigma) beta_m`` with ``beta_m``
  the rotation of the terminating link: a rotational spring ``EA_t d^2 / L_0`` to ground on that
  link, switched off when slack.  Tapered offsets are not supported in continuum length mode.

Statics and dynamics
--------------------
Static: own load ramp (``SolveStatic`` repeatedly with ``updateInitialValues=True``): a load factor
scales gravity, tip loads and tendon commands together; the increment halves on failure; more
than ``options.max_load_steps`` attempted steps raise :class:`ModelFailure`.  Dynamic:
static equilibrium under gravity and tip loads with the tendon commands at ``t = 0``, then
implicit generalised-alpha with the commands of :meth:`TendonActuation.command_at` updated every
step; joint damping ``options.damping * k_k`` (``options.damping`` in seconds).

Axial compliance
----------------
``SpringLinkParams(axial=True)`` replaces every pin/spherical joint by a rigid-body spring with
axial ``EA/ds`` and shear ``GA/ds`` stiffness (a discrete Timoshenko rod), so tendon compression
shortens the backbone: equal continuum or eyelet tensions ``T`` on a straight rod give exactly
``length_change = -sum(T) L / EA`` (tested).  A continuum tendon's compression enters as a
rest-length offset ``-T / (EA/ds)`` of the axial springs it passes (the exact internal force of a
continuously routed tendon); eyelet ropes compress the chain through their eyelet forces.

Results
-------
Positions at ``options.n_stations`` reference stations interpolated along the straight links, tip
frame at the end of the last link, ``length_change`` (0 for inextensible joints), tensions,
``joint_angles`` [rad]: planar ``(N, 1)``, the bending angle of each joint towards base +x
(rotation about base +y); 3-D with sprung torsion ``(N, 3)``, the relative rotation vector of each
joint in the proximal link's frame; 3-D with locked torsion ``(N, 2)``, the Cardan angles
``(a, b)`` of ``R_rel = Rx(a) Ry(b)``.  ``tip_twist``: 3-D only, rotation of the tip frame about
the tangent relative to the frame parallel-transported along the links.

Limitations
-----------
Without ``SpringLinkParams(axial=True)`` the joints are inextensible and ``length_change`` is 0.
With it, ``length_change`` is the sum of the axial joint gaps (shear gaps are not counted).
Continuum tendons in length mode exist only in the planar inextensible chain (their length is
taken as ``L_ref - d cos(sigma) beta_m``, which ignores backbone strain).  Eyelet tendons on the
rigid-body chains converge only linearly in Newton (contraction ~0.47 per iteration at N = 16,
~0.83 at N = 32, 8 disks, 250 N; ~100-125 iterations per static solve at N = 16 against 3-6 for
continuum tendons, measured), so their load ramp stalls at large rope forces.  Neither
``numericalDifferentiation.forODE2Connectors`` nor system-wide numerical differentiation (dense
solver, incl. AEs) changes that (measured on the kappa L = pi bending case: same stall at load
factor 0.23), and ``axial=True`` stalls too (load factor 0.67).  With a rope eyelet at every link
the rigid-body ramp stalled at a rope tension of 630-640 N in 14 bending cases regardless of the
offset d (0.01-0.04 m) and of kappa L: the trouble scales with the backbone compression T carried
by the joint reactions, not with the bending moment T d (a plausible reading: the constraint term
d(C_q^T lambda)/dq, the compressed chain's geometric stiffness, is missing from the iteration
matrix; not proven); the same ropes on the kinematic
tree (minimal coordinates) need 4 iterations.  The failure is numerical, not physical: the tree
solves the same cases up to 10.5 kN (kappa L = 2 pi, d = 0.01 m) and converges to ANCF under
refinement.  Hence ``backend="auto"`` uses the tree for eyelet ropes; the 3-D chain with
``torsion="spring"`` (no tree variant) still uses rigid bodies and is slow with eyelets
(0.1-0.4 s at N = 16; ``axial=True`` makes them 6-10x faster).  Link masses come from the robot
description (mass per length, disk masses, payload); per-link masses cannot be given directly.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from ._spring_link_geometry import ChainGeometry, chain_geometry_from_robot

__all__ = ["SpringLinkParams", "run", "solve", "is_planar", "chain_geometry_from_robot"]

_PLANE_TOL = 1e-12
_SPARSE_FROM = 16


@dataclass(frozen=True)
class SpringLinkParams:
    """Model-specific settings of the spring-link chain.

    Parameters
    ----------
    dimension : {"auto", "2d", "3d"}
        ``"auto"``: planar chain when the robot and load are planar (see :func:`is_planar`),
        spatial chain otherwise.  ``"2d"`` forces the planar chain (raises if the case is not
        planar), ``"3d"`` the spatial chain.
    max_active_set_iterations : int
        Cap on slack/taut switching passes in a static length-controlled solve.
    torsion : {"spring", "locked"}
        3-D chain only.  ``"spring"`` (default): spherical joints with a rotational spring
        ``diag(k, k, GJ/ds)`` on the intrinsic relative rotation vector (the equivalent rod: a
        bend in any fixed plane is twist-free).  ``"locked"``: Cardan (universal) joints, the
        relative rotation about the link axis in the joint's x-y-z Tait-Bryan sequence is
        constrained (Hannan & Walker's 2-DOF joints; an oblique bend then carries the Cardan
        twist, reported as ``tip_twist``).
    axial : bool
        ``False`` (default): inextensible pin (2-D) / spherical or Cardan (3-D) joints.  ``True``:
        every joint becomes a rigid-body spring (``RigidBodySpringDamper``, intrinsic) with axial
        stiffness ``EA/ds`` and shear stiffness ``GA/ds`` (``CrossSection.GA``, or ``EA`` when it
        is ``None``) besides the bending (and torsion) springs, so the backbone can compress
        (wire-delay compression, continuum-tendon compression ``T``) and ``length_change`` is
        reported.  Not combined with ``torsion="locked"`` or with continuum tendons in length mode.
    backend : {"auto", "bodies", "tree"}
        Exudyn representation of the planar inextensible chain.  ``"tree"``: one
        ``ObjectKinematicTree`` (minimal coordinates, no joint constraints); ``"bodies"``: rigid
        bodies + revolute joints.  Both give the same statics (tested to ~1e-10).  Measured at
        N = 16 / 64 (steel rod): with length-controlled eyelet ropes (reeving) the tree needs 3-4
        Newton iterations instead of ~100 and is 2-4x faster (36 vs 155 ms, 1.1 vs 2.4 s), and it
        solved a heavily loaded Hannan & Walker case on which the bodies' ramp gave up; with
        constant-force rope chains (eyelets, tension control) it was 5-70x slower than the bodies
        when a rope passed every link (every rope segment on tree markers evaluates the tree's
        kinematics), but the bodies' ramp stalls under large rope forces (bending study, 8 disks: 1 of
        15 solved within 40 steps) while the tree solves them in one load step; with continuum
        tendons both are within noise.  In 3-D the tree is a chain of Cardan joints
        (``RevoluteX`` + ``RevoluteY``, springs on both Cardan angles), so it needs
        ``torsion="locked"``; it agrees with the rigid-body Cardan chain up to the spring law
        (rotation vector vs Cardan angles, second order in the joint angles: 2.8e-7 m at N = 16) and solved a 16-cable Hannan & Walker
        reeving case in 0.8 s where the bodies took 76 s (3330 Newton iterations).  ``"auto"``
        (default) uses the tree for eyelet tendons (length or tension mode; planar, or 3-D with
        ``torsion="locked"``) and bodies otherwise; ``axial=True`` always uses bodies.
    """

    dimension: Literal["auto", "2d", "3d"] = "auto"
    max_active_set_iterations: int = 20
    torsion: Literal["spring", "locked"] = "spring"
    axial: bool = False
    backend: Literal["auto", "bodies", "tree"] = "auto"

    def __post_init__(self) -> None:
        if self.dimension not in ("auto", "2d", "3d"):
            raise ValueError(f"SpringLinkParams.dimension must be 'auto', '2d' or '3d', got {self.dimension!r}")
        if self.backend not in ("auto", "bodies", "tree"):
            raise ValueError(f"SpringLinkParams.backend must be 'auto', 'bodies' or 'tree', got {self.backend!r}")
        if self.axial and self.torsion == "locked":
            raise ValueError("SpringLinkParams: axial=True needs torsion='spring'")
        if self.torsion not in ("spring", "locked"):
            raise ValueError(f"SpringLinkParams.torsion must be 'spring' or 'locked', got {self.torsion!r}")
        if int(self.max_active_set_iterations) < 1:
            raise ValueError("SpringLinkParams.max_active_set_iterations must be >= 1")


def is_planar(robot: Robot, load: LoadCase) -> tuple[bool, str]:
    """Whether ``robot`` under ``load`` stays in the base x-z plane.

    Returns
    -------
    planar : bool
    reason : str
        Why not (empty when planar).
    """
    for j, sigma, _ in robot.tendon_table():
        if abs(math.sin(sigma)) > 1e-9:
            return False, f"tendon of section {j} at sigma = {sigma:.6g} rad is not in the x-z plane (sigma in {{0, pi}})"
    g = robot.gravity_in_base()
    if abs(g[1]) > _PLANE_TOL * max(1.0, np.linalg.norm(g)):
        return False, f"gravity in the base frame {g.tolist()} has a y component"
    if abs(load.tip_force[1]) > _PLANE_TOL:
        return False, f"tip force {list(load.tip_force)} has a y component"
    if abs(load.tip_torque[0]) > _PLANE_TOL or abs(load.tip_torque[2]) > _PLANE_TOL:
        return False, f"tip torque {list(load.tip_torque)} is not about base y"
    if robot.payload.mass > 0 and abs(robot.payload.offset[1]) > _PLANE_TOL:
        return False, "payload offset has a y component"
    return True, ""


# ---------------------------------------------------------------------------------------------
# tendon routing (pure numpy)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Tendon:
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



def _add_eyelet_rope(mbs, marks: list, tendon: "_Tendon", mode: str, damping: float) -> list:
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

def _tendons(robot: Robot, geo: ChainGeometry, tendon_model: str = "continuum") -> list[_Tendon]:
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
        out.append(_Tendon(j, float(sigma), m, d, grp.axial_stiffness, L_ref, grp.offset_tip is not None, arm,
                           cos_a, link, z, dd))
    return out


# ---------------------------------------------------------------------------------------------
# planar Exudyn model
# ---------------------------------------------------------------------------------------------
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



def _points_on_links(geo: ChainGeometry, stations: np.ndarray, P: np.ndarray, link_axes: np.ndarray) -> np.ndarray:
    """Backbone points ``(m, 3)`` at reference arc lengths ``stations`` on a chain of straight links.

    ``P[k]`` is the position of joint ``k`` (at reference arc length ``geo.joints[k]``) and
    ``link_axes[k]`` the unit axis of the link after it; before the first joint the backbone is
    the clamped base segment along +z.
    """
    pos = np.zeros((stations.size, 3))
    for i, s in enumerate(stations):
        if s < geo.joints[0]:
            pos[i] = [0.0, 0.0, s]
            continue
        k = int(np.searchsorted(geo.joints, s, side="right") - 1)
        pos[i] = P[k] + (s - geo.joints[k]) * link_axes[k]
    return pos

def _rotation_vectors(R: np.ndarray) -> np.ndarray:
    """Rotation vectors (k, 3) of rotation matrices (k, 3, 3) (angles below pi)."""
    c = np.clip((np.trace(R, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    ang = np.arccos(c)
    w = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.sin(ang)
    f = np.where(s > 1e-12, ang / np.where(s > 1e-12, 2.0 * s, 1.0), 0.5)
    return w * f[:, None]


def _twist_vs_parallel_transport(R: np.ndarray) -> float:
    """Rotation of the last link frame about its axis relative to the frame parallel-transported
    (minimal rotations between successive link axes) from the base."""
    F = np.eye(3)
    t_prev = np.array([0.0, 0.0, 1.0])
    for Rk in R:
        t = Rk[:, 2]
        v = np.cross(t_prev, t)
        c = float(np.dot(t_prev, t))
        s = float(np.linalg.norm(v))
        if s > 1e-15:
            K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]]) / s
            Q = np.eye(3) + s * K + (1 - c) * K @ K
            F = Q @ F
        t_prev = t
    x_pt, x = F[:, 0], R[-1][:, 0]
    return float(math.atan2(np.dot(np.cross(x_pt, x), R[-1][:, 2]), np.dot(x_pt, x)))


# ---------------------------------------------------------------------------------------------
# solvers
# ---------------------------------------------------------------------------------------------
def _use_sparse(settings, model) -> None:  # noqa: ANN001
    """Sparse LU for larger chains (dense LU dominated the 3-D solve time from N ~ 32)."""
    import exudyn as exu

    if model.geo.n_links >= _SPARSE_FROM:
        settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse


def _static_ramp(model: "_Planar", options: SolverOptions, params: SpringLinkParams,
                 apply: Callable[[float], None]) -> tuple[int, int]:
    """Ramp ``apply(lam)`` from 0 to 1 with repeated static solves; returns (steps, newton its)."""
    from ._exudyn import static_settings

    exu = model.exu
    mbs = model.mbs
    settings = static_settings(options, 1)
    _use_sparse(settings, model)
    settings.staticSolver.adaptiveStep = False
    # eyelet ropes loading the joint constraints make Newton converge only linearly (measured
    # ~100-125 iterations at N = 16 vs 3-6 for continuum tendons; see Limitations): allow more.
    eyelet_ropes = model.model == "eyelets" and model.mode is not None
    settings.staticSolver.newton.maxIterations = 250 if eyelet_ropes else 40
    lam, inc = 0.0, 1.0
    attempts, newton_its = 0, 0
    while lam < 1.0:
        target = min(1.0, lam + inc)
        attempts += 1
        if attempts > options.max_load_steps:
            hint = ""
            if model.model == "eyelets" and model.mode is not None and not isinstance(model, _PlanarTree):
                hint = ("; eyelet ropes on the rigid-body chain converge only linearly in Newton (numerical, "
                        "not a physical instability): use SpringLinkParams(backend='tree') where possible")
            raise ModelFailure(
                f"spring_link: static load ramp exceeded options.max_load_steps={options.max_load_steps} "
                f"(reached load factor {lam:.4g}){hint}"
            )
        q_save = mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Initial)
        active_save = list(model.tendon_active)
        ok = True
        try:
            apply(target)
            for _ in range(params.max_active_set_iterations):
                solver = exu.MainSolverStatic()
                if not solver.SolveSystem(mbs, settings):
                    raise exu.SolverError("static Newton did not converge")
                newton_its += int(solver.it.newtonStepsCount)
                q = mbs.systemData.GetODE2Coordinates()
                if not np.all(np.isfinite(q)):
                    raise exu.SolverError("non-finite state")
                mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Initial)
                if not model.update_active_set():
                    break
                apply(target)
            else:
                raise ModelFailure("spring_link: tendon slack/taut switching did not settle")
        except (exu.SolverError, RuntimeError) as err:  # ModelFailure is a RuntimeError too
            if isinstance(err, ModelFailure) and "rest length" in str(err):
                raise
            ok = False
        if ok:
            lam = target
            inc = min(1.0, inc * 2.0)
        else:
            mbs.systemData.SetODE2Coordinates(q_save, configuration=exu.ConfigurationType.Initial)
            mbs.systemData.SetODE2Coordinates(q_save, configuration=exu.ConfigurationType.Current)
            model.tendon_active = active_save
            inc *= 0.5
            if inc < 1e-6:
                raise ModelFailure(f"spring_link: static solve failed near load factor {lam:.4g}")
    return attempts, newton_its


def solve(robot: Robot, load: LoadCase, options: SolverOptions,
          params: SpringLinkParams = SpringLinkParams()) -> PhysicsResult:
    """Static or dynamic solve of the spring-link chain (see the module docstring).

    Parameters
    ----------
    robot : Robot
    load : LoadCase
    options : SolverOptions
        ``n_elements`` is the number of links ``N`` (multiple of the number of sections).
    params : SpringLinkParams
        Model-specific settings.

    Returns
    -------
    PhysicsResult
        ``joint_angles`` shape ``(N, 1)``; for dynamics ``time`` (k,) and series
        ``tip_position`` (k, 3), ``tendon_tensions`` (k, n_tendons).

    Raises
    ------
    ModelFailure
        Non-planar case, failed load ramp, non-positive tendon rest length.
    ValueError
        ``n_elements`` not a multiple of the number of sections.
    """
    from ._exudyn import dynamic_settings, quiet_exudyn

    check_model_inputs(robot, load, options)
    planar, why = is_planar(robot, load)
    if params.dimension == "2d" and not planar:
        raise ModelFailure(f"spring_link: dimension='2d' requested but the case is not planar: {why}")
    use_2d = params.dimension == "2d" or (params.dimension == "auto" and planar)
    act_mode = None if load.actuation is None else load.actuation.mode
    geo = chain_geometry_from_robot(robot, options.n_elements)
    t0 = time.perf_counter()
    with quiet_exudyn():
        tree_ok = not params.axial and (use_2d or params.torsion == "locked")
        if params.backend == "tree" and not tree_ok:
            raise ModelFailure("spring_link: backend='tree' supports inextensible chains that are planar or have "
                               "torsion='locked' (Cardan joints) only")
        # eyelet ropes (reeving or constant-force segments) on the rigid-body chain stall the static
        # ramp (see Limitations); the constraint-free tree solves them in a few Newton iterations
        ropes = options.tendon_model == "eyelets" and act_mode is not None
        auto_tree = params.backend == "auto" and ropes
        if tree_ok and (params.backend == "tree" or auto_tree):
            model = _PlanarTree(robot, load, options, geo, spatial=not use_2d)
        elif use_2d:
            model = _Planar(robot, load, options, geo, params.axial)
        else:
            model = _Spatial(robot, load, options, geo, params.torsion, params.axial)
        act = load.actuation
        n_t = len(model.tendons)
        final = np.zeros(n_t) if act is None else np.asarray(act.values)
        if load.analysis == "static":

            def apply(lam: float) -> None:
                model.set_external(lam)
                model.set_tendons(lam * final, lam)

            steps, its = _static_ramp(model, options, params, apply)
            info = SolverInfo(converged=True, iterations=its, wall_time=time.perf_counter() - t0,
                              message=f"{steps} load steps")
            return model.result(info)

        # dynamic: equilibrium under external loads with commands at t = 0, then integrate
        start = np.zeros(n_t) if act is None else act.command_at(0.0, load.ramp_time)

        def apply0(lam: float) -> None:
            model.set_external(lam)
            model.set_tendons(lam * start, lam)

        steps, its = _static_ramp(model, options, params, apply0)
        exu = model.exu
        rec_t, rec_tip, rec_T = [], [], []

        def pre_step(mbs, t):  # noqa: ANN001 - Exudyn callback signature
            cmd = start if act is None else act.command_at(t, load.ramp_time)
            if model.mode == "length":
                model._L0 = model.rest_lengths(np.asarray(cmd), 1.0)
                model.update_active_set()
            model.set_tendons(np.asarray(cmd), 1.0)
            r = model.result(SolverInfo(True))
            rec_t.append(t)
            rec_tip.append(r.tip_position.copy())
            rec_T.append(r.tendon_tensions.copy())
            return True

        model.mbs.SetPreStepUserFunction(pre_step)
        settings = dynamic_settings(options, load.duration)
        _use_sparse(settings, model)
        solver = exu.MainSolverImplicitSecondOrder()
        try:
            solver.SolveSystem(model.mbs, settings)
        except exu.SolverError as err:
            raise ModelFailure(f"spring_link: dynamic solve failed: {err}") from err
        res = model.result(SolverInfo(True))
        rec_t.append(load.duration)
        rec_tip.append(res.tip_position.copy())
        rec_T.append(res.tendon_tensions.copy())
        info = SolverInfo(converged=True, iterations=int(solver.it.newtonStepsCount),
                          wall_time=time.perf_counter() - t0, message=f"{len(rec_t) - 1} time steps")
        return model.result(
            info, time_=np.asarray(rec_t),
            series={"tip_position": np.asarray(rec_tip), "tendon_tensions": np.asarray(rec_T)},
        )


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Registered model ``"spring_link"``: :func:`solve` with default :class:`SpringLinkParams`."""
    return solve(robot, load, options, SpringLinkParams())
