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

from ...models.result import SolverInfo
from .chain import _Chain
from .planar import _Planar
from .spatial import _Spatial
from .tree import _Tree, tree_tip_position
from .geometry import ChainGeometry, chain_geometry_from_robot
from .params import SpringLinkParams, is_planar
from .routing import _add_eyelet_rope, _eyelet_placement, _Tendon, _tendons
from .solve import _static_ramp, _use_sparse, run, solve

_PlanarTree = _Tree  # deprecated name of the kinematic-tree chain (it is planar or 3-D)

__all__ = ["SpringLinkParams", "run", "solve", "is_planar", "chain_geometry_from_robot"]
