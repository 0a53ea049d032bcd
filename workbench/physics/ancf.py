"""Planar tendon-driven backbone as a chain of 2-D ANCF cable elements (Exudyn).

Model ``"ancf"``: ``run(robot, load, options) -> PhysicsResult``.

Planar mapping
--------------
The robot bends in its base x-z plane.  Exudyn's plane ``(X, Y)`` is (base z, base x): the
backbone starts along Exudyn +X, a rotation about Exudyn +Z is a rotation about base +y.
Results are reported in the base frame as ``(x, 0, z)``.  Only tendons at
``sigma = 0`` (lateral offset ``+d`` along base x) or ``sigma = pi`` (``-d``), within 1e-9
rad, fit the planar model; anything else raises :class:`PlanarModelError`.  Tip forces
must lie in the x-z plane and tip torques along base y.  Gravity: the in-plane component
of ``robot.gravity_in_base()`` (the out-of-plane component is reported in
``extras["gravity_out_of_plane"]`` and ignored).

Discretisation
--------------
``options.n_elements`` ``ObjectANCFCable2D`` elements (Euler-Bernoulli, extensible;
Lobatto reduced integration ``useReducedOrderIntegration=2`` against axial locking),
distributed over the sections in proportion to their lengths (at least one each), so every
section end (tendon termination) is a node.  Per element: ``EI``, ``EA`` and mass per
length from ``Section.cross_section_at`` at the element midpoint (piecewise-constant taper,
O(h^2)); disk masses are smeared over their section's length (``n_disks * disk_mass /
length``).  Clamp: node 0's x, y and y-slope are fixed, the x-slope stays free (facts note:
fixing it forbids axial strain at the clamp).  The tip payload is a point mass on the tip
node (gravity and inertia); a payload offset is not supported (error).

Tendons (``options.tendon_model``)
----------------------------------
``"continuum"``: frictionless tendon with continuous routing at offset ``y_i(s)``.  Cutting
rod and tendon at ``s`` shows that the tendon adds the moment ``T y cos(alpha)`` and the
compression ``T cos(alpha)`` to the rod's cross-section (``tan alpha = y'``, the tendon's
slope; 1 for constant offsets), which is applied exactly by a per-element reference
curvature ``kappa_0 = sum_i T_i y_i cos(alpha_i) / EI`` and reference axial strain
``eps_0 = -sum_i T_i cos(alpha_i) / EA`` over the elements the tendon passes (elastic
moment ``EI (kappa - kappa_0)``, axial force ``EA (eps - eps_0)``).  Exact for constant
offsets; a tapered offset is sampled at element midpoints (O(h^2)) and ``alpha`` is
taken in the reference configuration.  A tendon's offset varies linearly along its whole
routed length ``[0, end]`` from ``TendonGroup.offset`` (base plate) to
``TendonGroup.offset_tip`` (terminating disk) -- for a single section this is
``TendonGroup.offset_at``; for tendons of later sections it is this model's reading of the
description (which only defines the offset over the group's own section).

``"eyelets"``: one frictionless rope per tendon, anchored on the base plate at ``(0, y)``
and passing through eyelets at every disk of the sections it crosses (rigid markers at
``[x_disk, y]`` on the element, i.e. at ``r + y n``), terminating on its own section's last
disk.  Every straight segment carries the common rope tension (an
``ObjectConnectorSpringDamper`` with zero stiffness and constant ``force = T``): equal
tensions on both sides of each eyelet is exactly frictionless sliding.  Chosen over
``ObjectConnectorReevingSystemSprings`` for speed (facts note: 26 ms vs 0.4-1.8 s per
static solve at 64 elements); the rope law of length control is applied outside (below).
``tests/physics/test_ancf_reeving.py`` checks that both give the same length-controlled
equilibrium (tip within 1e-6 L, tensions within 1e-5).

Length control (``TendonActuation.mode == "length"``)
------------------------------------------------------
``T_i = EA_t max(0, (l_i - l0_i) / l0_i)`` with ``l0 = l_ref / (1 + p/EA_t) + delta_l``
(:func:`workbench.physics.tendon_loads.tendon_rest_lengths`) and ``l_i`` the tendon path
length of the deformed configuration (continuum: the length of the curve ``r + y n`` on
``[0, end]``, equal to ``int (1 - y kappa)(1 + eps) ds`` for constant ``y``; eyelets: the sum
of the straight segments).  Static: the tensions are the unknowns of the outer problem
``T = EA_t max(0, stretch(l(T)))`` around tension-controlled equilibria, solved by a
semismooth quasi-Newton method whose Jacobian comes from the exact small-deflection
compliance (:func:`workbench.physics.tendon_loads.tendon_path_compliance`) and is improved
by Broyden updates; slack tendons drop out (complementarity).  Without external loads the
first step is already exact; gravity / tip loads need a few iterations.  Dynamic: the
tension applied over a step is evaluated from the state at the step start and the rest
length at the step end (one-step lag, ``PreStepUserFunction``).  This explicit coupling is
stable for moderate ``EA_t h^2`` (measured on the 0.8 m, 6 mm steel rod with d = 20 mm:
stable for EA_t = 4e4, 1e5, 3e5 N at h = 2 ms and 1e6 N at 0.5 ms; 1e6 N at 1 or 2 ms
diverges or chatters -- the boundary is near EA_t h^2 ~ 1 N s^2 but not sharp and depends on
the rod).  Divergence raises ``ModelFailure``, and so does a chattering tension history
(second differences above 25 % of the peak tension).  (A linearly implicit update with the
quasi-static compliance was tried and rejected: it does not diverge but chatters.)

Static solution
---------------
Tip loads, gravity, tendon tensions (reference curvature / connector forces) are ramped by
own adaptive load stepping (:func:`workbench.physics.tendon_loads.ramp_load`): repeated
``SolveStatic(updateInitialValues=True)`` with one internal load step and no internal
adaptivity, halving the increment on failure, at most ``options.max_load_steps`` attempts
per ramp.  Newton converges on the step size (``residualMode = 1``).  Non-convergence or an
implausible state (non-finite coordinates, slopes with |r'| outside (0.5, 1.5), points
further than 2 L from the base) raises :class:`~workbench.models.result.ModelFailure`.

Dynamics
--------
Implicit generalised-alpha (``options.time_step``, ``options.spectral_radius``), starting
from the static equilibrium of the loads and commands at ``t = 0`` (``initial_state=
"static"``) or from the undeformed straight rod with all loads applied at once
(``"reference"``).  Tendon commands follow ``TendonActuation.command_at(t,
load.ramp_time)``; the tension parameters are updated in a ``PreStepUserFunction`` only when
they change.  Damping: stiffness-proportional (Rayleigh ``beta = options.damping`` [s]) via
the element's ``bendingDamping = beta EI`` and ``axialDamping = beta EA``.

Measured accuracy (``tests/physics/test_ancf.py``, EA = 1e4 x steel vs the inextensible elastica)
-----------------------------------------------------------------------------------------------
Tip error [m] at 4 / 8 / 16 / 32 elements (L = 0.8 m; observed order ~4 throughout):

* tip load alpha = 1: 3.1e-5 / 2.0e-6 / 1.2e-7 / 7.7e-9; alpha = 3: 3.6e-4 / 2.5e-5 / 1.6e-6 /
  9.9e-8; alpha = 10: 2.1e-3 / 1.7e-4 / 1.2e-5 / 7.4e-7
* self-weight gamma = 1: 6.7e-6 / 4.4e-7 / 2.8e-8 / 1.7e-9; gamma = 4: 3.0e-4 / 2.1e-5 / 1.3e-6 /
  8.3e-8; gamma = 8: 1.3e-3 / 9.6e-5 / 6.4e-6 / 4.0e-7
* pure end moment (theta = pi/2): 1.2e-4 / 7.4e-6 / 4.6e-7 / 2.9e-8
* continuum tendon, single tendon: the exact arc (curvature ``T d / EI`` per reference
  length, length ``L (1 - T/EA)``) to ~1e-10 m at any mesh
* eyelet tendon vs continuum (64 el., T = 300 N, d = 20 mm), 4 / 8 / 16 / 32 / 64 disks:
  1.2e-2 / 2.7e-3 / 6.6e-4 / 1.7e-4 / 4.1e-5 m (order 2); mean curvature above ``T d / EI``
  by 1.9e-2 / 4.6e-3 / 1.2e-3 / 2.9e-4 at 8 / 16 / 32 / 64 disks (discrete-eyelet physics:
  the chord's lever arm, not a numerical error)

Outputs
-------
Positions at ``options.n_stations`` equally spaced reference stations (Hermite
centreline inside the elements), tip frame (rotation about base y by the tip tangent
angle), ``length_change = int |r'| ds - L``, tendon tensions, ``tip_twist = 0``.  Dynamic
series: ``tip_position`` (k, 3), ``tendon_tensions`` (k, n), ``length_change`` (k,).
Extras: ``static_steps``, ``failed_steps``, ``tendon_iterations``, ``gravity_out_of_plane``.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from . import _ancf_geometry as geo
from .tendon_loads import (
    ramp_load,
    solve_length_controlled,
    tendon_path_compliance,
    tendon_rest_lengths,
    tension_from_stretch,
)

__all__ = ["run", "PlanarModelError"]

_SIGMA_TOL = 1e-9


class PlanarModelError(ValueError):
    """The robot or load does not fit the planar (base x-z) model."""


# ----------------------------------------------------------------------------------------
# plain description of the planar problem
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Tendon:
    sign: float  # +1: sigma = 0 (base +x, Exudyn +Y); -1: sigma = pi
    end: float  # arc length of the terminating disk [m]
    d0: float  # offset at s = 0 [m]
    d1: float  # offset at s = end [m]
    EAt: float
    eyelets: tuple[float, ...]  # disk stations along the path [m], last = end

    def y(self, s):
        s = np.asarray(s, dtype=float)
        return self.sign * (self.d0 + (self.d1 - self.d0) * s / self.end)

    def dy(self, s):
        return np.full_like(np.asarray(s, dtype=float), self.sign * (self.d1 - self.d0) / self.end)


@dataclass(frozen=True)
class _Problem:
    L: float
    s_nodes: np.ndarray  # (n+1,)
    EI: np.ndarray  # (n,)
    EA: np.ndarray
    mu: np.ndarray
    gravity: np.ndarray  # (2,) Exudyn plane
    tip_force: np.ndarray  # (2,)
    tip_torque: float
    payload: float
    tendons: tuple[_Tendon, ...]
    g_out: float


def _tendon_sign(sigma: float, index: int) -> float:
    w = math.remainder(sigma, 2.0 * math.pi)
    if abs(w) <= _SIGMA_TOL:
        return 1.0
    if abs(abs(w) - math.pi) <= _SIGMA_TOL:
        return -1.0
    raise PlanarModelError(
        f"tendon {index} sits at sigma = {sigma!r} rad; the planar ANCF model only accepts tendons at "
        f"sigma = 0 or pi (within {_SIGMA_TOL} rad): use a spatial model (beam3d) instead"
    )


def _problem(robot: Robot, load: LoadCase, options: SolverOptions) -> _Problem:
    check_model_inputs(robot, load, options)
    L = robot.length
    F = np.asarray(load.tip_force)
    M = np.asarray(load.tip_torque)
    scale_f = max(1.0, float(np.linalg.norm(F)))
    if abs(F[1]) > 1e-12 * scale_f:
        raise PlanarModelError(f"tip_force must lie in the base x-z plane (y component 0), got {F.tolist()}")
    scale_m = max(1.0, float(np.linalg.norm(M)))
    if abs(M[0]) > 1e-12 * scale_m or abs(M[2]) > 1e-12 * scale_m:
        raise PlanarModelError(f"tip_torque must be along base y (x, z components 0), got {M.tolist()}")
    if np.any(np.asarray(robot.payload.offset) != 0.0):
        raise PlanarModelError(f"payload offset {robot.payload.offset} is not supported by the planar ANCF model")
    # mesh: elements per section proportional to length, at least one each
    lengths = robot.section_lengths
    n_sec = len(lengths)
    if options.n_elements < n_sec:
        raise ValueError(f"n_elements={options.n_elements} must be >= the number of sections ({n_sec})")
    raw = options.n_elements * lengths / L
    counts = np.maximum(1, np.floor(raw).astype(int))
    while counts.sum() < options.n_elements:
        counts[np.argmax(raw - counts)] += 1
    while counts.sum() > options.n_elements:
        k = np.argmax(np.where(counts > 1, counts - raw, -np.inf))
        counts[k] -= 1
    s_nodes = [0.0]
    EI, EA, mu = [], [], []
    s0 = 0.0
    for sec, n in zip(robot.sections, counts):
        for k in range(n):
            frac = (k + 0.5) / n
            cs = sec.cross_section_at(frac)
            EI.append(cs.EI)
            EA.append(cs.EA)
            mu.append(cs.mass_per_length + sec.n_disks * sec.disk_mass / sec.length)
            s_nodes.append(s0 + sec.length * (k + 1) / n)
        s0 += sec.length
    s_nodes = np.array(s_nodes)
    s_nodes[-1] = L
    g = robot.gravity_in_base()
    ends = robot.section_ends
    disks = robot.disk_stations()
    tendons = []
    for i, (j, sigma, grp) in enumerate(robot.tendon_table()):
        sign = _tendon_sign(sigma, i)
        end = float(s_nodes[np.argmin(np.abs(s_nodes - ends[j]))])
        d1 = grp.offset if grp.offset_tip is None else grp.offset_tip
        eyes = tuple(float(x) for x in disks[disks <= ends[j] * (1 + 1e-12)])
        tendons.append(_Tendon(sign, end, grp.offset, d1, grp.axial_stiffness, eyes))
    return _Problem(
        L=L, s_nodes=s_nodes, EI=np.array(EI), EA=np.array(EA), mu=np.array(mu),
        gravity=np.array([g[2], g[0]]), tip_force=np.array([F[2], F[0]]), tip_torque=float(M[1]),
        payload=robot.payload.mass, tendons=tuple(tendons), g_out=float(g[1]),
    )


# ----------------------------------------------------------------------------------------
# Exudyn system
# ----------------------------------------------------------------------------------------
class _System:
    """An assembled Exudyn system with setters for the ramped loads (built per call)."""

    def __init__(self, pb: _Problem, options: SolverOptions, tendon_model: str, damping: float):
        import exudyn as exu
        from exudyn.itemInterface import (
            CoordinateConstraint, LoadForceVector, LoadMassProportional, LoadTorqueVector,
            MarkerBodyMass, MarkerBodyPosition, MarkerBodyRigid, MarkerNodeCoordinate,
            MarkerNodePosition, NodePoint2DSlope1, NodePointGround, ObjectANCFCable2D,
            ObjectConnectorSpringDamper, ObjectGround, ObjectMassPoint2D,
        )

        self.exu = exu
        self.pb = pb
        self.tendon_model = tendon_model
        self.SC = exu.SystemContainer()
        mbs = self.mbs = self.SC.AddSystem()
        sn = pb.s_nodes
        le = np.diff(sn)
        self.nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[float(s), 0.0, 1.0, 0.0])) for s in sn]
        self.elements = []
        for e in range(le.size):
            self.elements.append(mbs.AddObject(ObjectANCFCable2D(
                nodeNumbers=[self.nodes[e], self.nodes[e + 1]], length=float(le[e]),
                bendingStiffness=float(pb.EI[e]), axialStiffness=float(pb.EA[e]),
                massPerLength=float(pb.mu[e]), bendingDamping=float(damping * pb.EI[e]),
                axialDamping=float(damping * pb.EA[e]), useReducedOrderIntegration=2,
            )))
        ground = mbs.AddObject(ObjectGround())
        gnode = mbs.AddNode(NodePointGround())
        mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=gnode, coordinate=0))
        for c in (0, 1, 3):
            mc = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=self.nodes[0], coordinate=c))
            mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mc]))
        # loads (values set by set_loads)
        self.grav_loads = []
        if np.any(pb.gravity != 0):
            for e in self.elements:
                m = mbs.AddMarker(MarkerBodyMass(bodyNumber=e))
                self.grav_loads.append(mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[0, 0, 0])))
        tipm = mbs.AddMarker(MarkerNodePosition(nodeNumber=self.nodes[-1]))
        self.payload_load = None
        if pb.payload > 0:
            mbs.AddObject(ObjectMassPoint2D(nodeNumber=self.nodes[-1], mass=pb.payload))
            if np.any(pb.gravity != 0):
                self.payload_load = mbs.AddLoad(LoadForceVector(markerNumber=tipm, loadVector=[0, 0, 0]))
        self.force_load = None
        if np.any(pb.tip_force != 0):
            self.force_load = mbs.AddLoad(LoadForceVector(markerNumber=tipm, loadVector=[0, 0, 0]))
        self.torque_load = None
        if pb.tip_torque != 0:
            mr = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.elements[-1], localPosition=[float(le[-1]), 0, 0]))
            self.torque_load = mbs.AddLoad(LoadTorqueVector(markerNumber=mr, loadVector=[0, 0, 0]))
        # tendons
        nt = len(pb.tendons)
        smid = 0.5 * (sn[1:] + sn[:-1])
        self.kap_per_T = np.zeros((le.size, nt))
        self.eps_per_T = np.zeros((le.size, nt))
        self.segments: list[list[int]] = []
        for i, td in enumerate(pb.tendons):
            on = smid < td.end
            cosa = 1.0 / np.sqrt(1.0 + td.dy(smid) ** 2)
            self.kap_per_T[:, i] = np.where(on, td.y(smid) * cosa / pb.EI, 0.0)
            self.eps_per_T[:, i] = np.where(on, -cosa / pb.EA, 0.0)
            if tendon_model == "eyelets":
                prev = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, float(td.y(0.0)), 0.0]))
                segs = []
                elem, x = geo.locate(sn, np.array(td.eyelets))
                for s_e, e_i, x_i in zip(td.eyelets, elem, x):
                    m = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.elements[int(e_i)],
                                                      localPosition=[float(x_i), float(td.y(s_e)), 0.0]))
                    segs.append(mbs.AddObject(ObjectConnectorSpringDamper(
                        markerNumbers=[prev, m], stiffness=0.0, damping=0.0, force=0.0, referenceLength=0.0)))
                    prev = m
                self.segments.append(segs)
        self.quad = geo.gauss_points(sn, 6)
        self._T = np.full(nt, np.nan)
        self._ext = np.nan
        mbs.Assemble()

    # -- load setters -----------------------------------------------------------------------
    def set_external(self, lam: float) -> None:
        if lam == self._ext:
            return
        pb, mbs = self.pb, self.mbs
        g = lam * pb.gravity
        for ld in self.grav_loads:
            mbs.SetLoadParameter(ld, "loadVector", [float(g[0]), float(g[1]), 0.0])
        if self.payload_load is not None:
            f = pb.payload * g
            mbs.SetLoadParameter(self.payload_load, "loadVector", [float(f[0]), float(f[1]), 0.0])
        if self.force_load is not None:
            f = lam * pb.tip_force
            mbs.SetLoadParameter(self.force_load, "loadVector", [float(f[0]), float(f[1]), 0.0])
        if self.torque_load is not None:
            mbs.SetLoadParameter(self.torque_load, "loadVector", [0.0, 0.0, float(lam * pb.tip_torque)])
        self._ext = lam

    def set_tensions(self, T: np.ndarray) -> None:
        T = np.asarray(T, dtype=float)
        if T.size == 0 or np.array_equal(T, self._T):
            return
        mbs = self.mbs
        if self.tendon_model == "continuum":
            kap = self.kap_per_T @ T
            eps = self.eps_per_T @ T
            for e, k0, e0 in zip(self.elements, kap, eps):
                mbs.SetObjectParameter(e, "referenceCurvature", float(k0))
                mbs.SetObjectParameter(e, "referenceAxialStrain", float(e0))
        else:
            for segs, Ti in zip(self.segments, T):
                for c in segs:
                    mbs.SetObjectParameter(c, "force", float(Ti))
        self._T = T.copy()

    # -- state ------------------------------------------------------------------------------
    def coords(self, configuration=None) -> np.ndarray:
        cfg = self.exu.ConfigurationType.Current if configuration is None else configuration
        return np.asarray(self.mbs.systemData.GetODE2Coordinates(configuration=cfg))

    def node_coords(self, q_ode2: np.ndarray) -> np.ndarray:
        """Absolute node coordinates ``(..., n+1, 4)`` from ODE2 coordinates (reference + displacement)."""
        n = len(self.nodes)
        ref = np.column_stack([self.pb.s_nodes, np.zeros(n), np.ones(n), np.zeros(n)])
        return ref + np.asarray(q_ode2)[..., : 4 * n].reshape(q_ode2.shape[:-1] + (n, 4))

    def path_lengths(self, qn: np.ndarray) -> np.ndarray:
        """Tendon path lengths ``(..., n_tendons)`` for absolute node coordinates ``qn``."""
        pb = self.pb
        out = []
        el_len = th = None
        for td in pb.tendons:
            if self.tendon_model == "continuum" and td.d0 == td.d1:
                # constant offset: (r + y n)' = (|r'| - y theta') t, so l = int |r'| - y (theta_e - theta_0)
                if el_len is None:
                    el_len = geo.element_lengths(qn, pb.s_nodes, quad=self.quad)
                    th = np.unwrap(np.arctan2(qn[..., 3], qn[..., 2]), axis=-1)
                k = int(np.argmin(np.abs(pb.s_nodes - td.end)))
                arc = el_len[..., :k].sum(axis=-1)
                out.append(arc - float(td.y(0.0)) * (th[..., k] - th[..., 0]))
            elif self.tendon_model == "continuum":
                out.append(geo.offset_curve_length(qn, pb.s_nodes, td.end, td.y, td.dy, quad=self.quad))
            else:
                st = np.array(td.eyelets)
                pts = geo.offset_points(qn, pb.s_nodes, st, td.y(st))
                anchor = np.array([0.0, float(td.y(0.0))])
                pts = np.concatenate([np.broadcast_to(anchor, pts.shape[:-2] + (1, 2)), pts], axis=-2)
                out.append(np.sum(np.linalg.norm(np.diff(pts, axis=-2), axis=-1), axis=-1))
        return np.stack(out, axis=-1) if out else np.zeros(qn.shape[:-2] + (0,))

    def reference_path_lengths(self) -> np.ndarray:
        n = len(self.nodes)
        qn = np.column_stack([self.pb.s_nodes, np.zeros(n), np.ones(n), np.zeros(n)])
        return self.path_lengths(qn)


# ----------------------------------------------------------------------------------------
# solves
# ----------------------------------------------------------------------------------------
class _StaticDriver:
    def __init__(self, sysm: _System, options: SolverOptions):
        from ._exudyn import static_settings

        self.sysm = sysm
        self.options = options
        self.settings = static_settings(options, 1)
        self.settings.staticSolver.adaptiveStep = False
        self.steps = 0
        self.failed = 0
        self.newton = 0
        self.ext = 0.0
        self.T = np.zeros(len(sysm.pb.tendons))

    def _solve(self) -> None:
        mbs = self.sysm.mbs
        mbs.SolveStatic(self.settings, updateInitialValues=True, storeSolver=True)
        self.newton += int(mbs.sys["staticSolver"].it.newtonStepsCount)
        _check_state(self.sysm, self.sysm.coords())

    def go_to(self, ext: float, T: np.ndarray) -> None:
        """Ramp from the current (ext, T) to the given ones."""
        exu = self.sysm.exu
        ext0, T0 = self.ext, self.T.copy()
        T = np.asarray(T, dtype=float)

        def apply(lam):
            self.sysm.set_external(ext0 + lam * (ext - ext0))
            self.sysm.set_tensions(T0 + lam * (T - T0))

        def save():
            return self.sysm.coords(exu.ConfigurationType.Initial).copy()

        def restore(q):
            self.sysm.mbs.systemData.SetODE2Coordinates(q.tolist(), configuration=exu.ConfigurationType.Initial)

        try:
            info = ramp_load(apply, self._solve, save, restore, max_steps=self.options.max_load_steps,
                             failure=(exu.SolverError, ModelFailure))
        except RuntimeError as err:
            raise ModelFailure(f"ANCF static solve failed: {err}") from err
        self.steps += info.steps
        self.failed += info.failed_steps
        self.ext, self.T = ext, T.copy()


def _check_state(sysm: _System, q: np.ndarray) -> None:
    qn = sysm.node_coords(q)
    if not np.all(np.isfinite(qn)):
        raise ModelFailure("ANCF solve produced non-finite coordinates")
    slope = np.linalg.norm(qn[:, 2:], axis=-1)
    if np.any(slope < 0.5) or np.any(slope > 1.5):
        raise ModelFailure(f"ANCF solve produced implausible axial stretch |r'| in [{slope.min():.3g}, {slope.max():.3g}]")
    if np.max(np.linalg.norm(qn[:, :2], axis=-1)) > 2.0 * sysm.pb.L:
        raise ModelFailure("ANCF solve produced a point further than 2 L from the base")


def _static_tensions(sysm: _System, drv: _StaticDriver, actuation, commands, T_start=None) -> tuple[np.ndarray, int]:
    """Bring the system to equilibrium for the given tendon commands; returns (T, tendon iterations)."""
    nt = len(sysm.pb.tendons)
    if nt == 0 or actuation is None:
        drv.go_to(1.0, np.zeros(nt))
        return np.zeros(nt), 0
    if actuation.mode == "tension":
        drv.go_to(1.0, np.asarray(commands, dtype=float))
        return np.asarray(commands, dtype=float), 0
    pb = sysm.pb
    lref = sysm.reference_path_lengths()
    EAt = np.array([t.EAt for t in pb.tendons])
    l0 = tendon_rest_lengths(lref, commands, actuation.pretension, EAt)
    C = _compliance(sysm)

    def equilibrium(T):
        drv.go_to(1.0, T)
        return sysm.path_lengths(sysm.node_coords(sysm.coords()))

    try:
        info = solve_length_controlled(equilibrium, l0, EAt, C, initial_tensions=T_start,
                                       tol=max(1e-10, drv.options.newton_tolerance),
                                       length_tol=10.0 * drv.options.newton_tolerance)
    except RuntimeError as err:
        raise ModelFailure(f"ANCF length-controlled tendon solve failed: {err}") from err
    return info.tensions, info.iterations


def _compliance(sysm: _System) -> np.ndarray:
    pb = sysm.pb
    sn = pb.s_nodes
    s = np.linspace(0.0, pb.L, 40 * (sn.size - 1) + 1)
    elem, _ = geo.locate(sn, s)
    y = np.array([t.y(s) for t in pb.tendons])
    return tendon_path_compliance(s, pb.EI[elem], pb.EA[elem], y, [t.end for t in pb.tendons])


def _frame_and_positions(sysm: _System, qn: np.ndarray, stations: np.ndarray):
    r, t = geo.centreline(qn, sysm.pb.s_nodes, stations)
    pos = np.zeros(r.shape[:-1] + (3,))
    pos[..., 0] = r[..., 1]
    pos[..., 2] = r[..., 0]
    return pos, t


def _tip_frame(tip: np.ndarray, t_tip: np.ndarray) -> np.ndarray:
    th = math.atan2(float(t_tip[1]), float(t_tip[0]))
    c, s = math.cos(th), math.sin(th)
    H = np.eye(4)
    H[:3, :3] = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    H[:3, 3] = tip
    return H


def run(
    robot: Robot,
    load: LoadCase,
    options: SolverOptions,
    *,
    initial_state: Literal["static", "reference"] = "static",
) -> PhysicsResult:
    """Planar ANCF model of a tendon-driven continuum robot (see the module docstring).

    Parameters
    ----------
    robot : Robot
        Robot description; tendons only at sigma = 0 or pi.
    load : LoadCase
        Tendon commands, tip force (x-z plane) and torque (about y), static or dynamic.
    options : SolverOptions
        ``n_elements``, ``tendon_model``, ``n_stations``, ``newton_tolerance``,
        ``max_load_steps``, ``time_step``, ``damping`` (Rayleigh beta [s]),
        ``spectral_radius``.
    initial_state : {"static", "reference"}
        Dynamic analyses: start from the static equilibrium at ``t = 0`` or from the
        undeformed straight rod with loads applied as a step.

    Returns
    -------
    PhysicsResult
        Base-frame results; ``series`` for dynamic analyses.

    Raises
    ------
    PlanarModelError
        Tendons off the x-z plane, out-of-plane tip loads, payload offsets.
    ModelFailure
        No convergence or an implausible state.
    """
    from ._exudyn import quiet_exudyn

    t_wall = _time.perf_counter()
    pb = _problem(robot, load, options)
    if initial_state not in ("static", "reference"):
        raise ValueError(f"initial_state must be 'static' or 'reference', got {initial_state!r}")
    act = load.actuation
    nt = len(pb.tendons)
    stations = np.linspace(0.0, pb.L, options.n_stations)
    with quiet_exudyn():
        sysm = _System(pb, options, options.tendon_model, options.damping)
        drv = _StaticDriver(sysm, options)
        if load.analysis == "static":
            cmd = np.zeros(nt) if act is None else np.asarray(act.values)
            T, tendon_it = _static_tensions(sysm, drv, act, cmd)
            q = sysm.coords()
            series, times = {}, None
        else:
            T, tendon_it, q, times, series = _dynamic(sysm, drv, load, options, initial_state)
    qn = sysm.node_coords(q)
    pos, tang = _frame_and_positions(sysm, qn, stations)
    length_change = float(geo.arc_length(qn, pb.s_nodes, quad=sysm.quad)) - pb.L
    wall = _time.perf_counter() - t_wall
    return PhysicsResult(
        model="ancf",
        stations=stations,
        positions=pos,
        tip_frame=_tip_frame(pos[-1], tang[-1]),
        length_change=length_change,
        tendon_tensions=T,
        tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=drv.newton, wall_time=wall,
                          message=f"{drv.steps} load steps ({drv.failed} halved), {tendon_it} tendon iterations"),
        time=times,
        series=series,
        extras={"static_steps": float(drv.steps), "failed_steps": float(drv.failed),
                "tendon_iterations": float(tendon_it), "gravity_out_of_plane": pb.g_out},
    )


def _check_tension_history(Ts: np.ndarray, EAt: np.ndarray, h: float) -> None:
    """Reject step-to-step chattering of explicitly coupled rope tensions (an unstable loop).

    A physical tension history is smooth on the time-step scale (second differences ~
    ``T (omega h)^2``); the unstable explicit coupling alternates between slack and taut.
    """
    if Ts.shape[0] < 3:
        return
    d2 = np.abs(Ts[2:] - 2.0 * Ts[1:-1] + Ts[:-2]).max(axis=0)
    scale = np.abs(Ts).max(axis=0) + 1e-9
    bad = d2 > 0.25 * scale
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ModelFailure(
            f"length-controlled tendon {i} chatters (step-to-step tension jumps up to {d2[i]:.3g} N of "
            f"{scale[i]:.3g} N): the explicit rope coupling is unstable for EA_t = {EAt[i]:.3g} N at "
            f"time_step = {h:g} s; reduce options.time_step (the boundary is near EA_t h^2 ~ 1 N s^2)"
        )


def _dynamic(sysm: _System, drv: _StaticDriver, load: LoadCase, options: SolverOptions, initial_state: str):
    from ._exudyn import dynamic_settings

    exu = sysm.exu
    mbs = sysm.mbs
    pb = sysm.pb
    act = load.actuation
    nt = len(pb.tendons)
    length_mode = act is not None and act.mode == "length" and nt > 0
    EAt = np.array([t.EAt for t in pb.tendons])
    lref = sysm.reference_path_lengths()

    def commands(t):
        return np.zeros(nt) if act is None else act.command_at(float(t), load.ramp_time)

    def rest(t):
        return tendon_rest_lengths(lref, commands(t), act.pretension, EAt)

    tendon_it = 0
    if initial_state == "static":
        T0, tendon_it = _static_tensions(sysm, drv, act, commands(0.0))
    else:
        sysm.set_external(1.0)
        if length_mode:
            T0 = tension_from_stretch(lref, rest(0.0), EAt)
        else:
            T0 = commands(0.0)
        sysm.set_tensions(T0)
    h = options.time_step
    n_steps = max(1, int(round(load.duration / h)))
    settings = dynamic_settings(options, load.duration)
    settings.timeIntegration.numberOfSteps = n_steps
    settings.timeIntegration.adaptiveStep = False
    rec_t, rec_q = [], []

    def pre_step(mbs_, t):
        # Exudyn passes the time at the END of the coming step; the state is the one at its start
        q = np.asarray(mbs_.systemData.GetODE2Coordinates())
        rec_t.append(float(t) - h)
        rec_q.append(q.copy())
        if nt:
            t_end = float(t)
            if length_mode:
                T = tension_from_stretch(sysm.path_lengths(sysm.node_coords(q)), rest(t_end), EAt)
            else:
                T = commands(t_end)
            sysm.set_tensions(T)
        return True

    mbs.SetPreStepUserFunction(pre_step)
    try:
        mbs.SolveDynamic(settings, solverType=exu.DynamicSolverType.GeneralizedAlpha, storeSolver=True)
        drv.newton += int(mbs.sys["dynamicSolver"].it.newtonStepsCount)
    except exu.SolverError as err:
        hint = (" (length-controlled tendons are coupled explicitly: stiff tendons need a smaller "
                "options.time_step)") if length_mode else ""
        raise ModelFailure(f"ANCF dynamic solve failed: {err}{hint}") from err
    finally:
        mbs.SetPreStepUserFunction(0)
    q_end = sysm.coords()
    rec_t.append(float(load.duration))
    rec_q.append(q_end.copy())
    Q = np.array(rec_q)
    for q in (Q[0], Q[len(Q) // 2], Q[-1]):
        _check_state(sysm, q)
    qn = sysm.node_coords(Q)
    times = np.array(rec_t)
    tip, _ = _frame_and_positions(sysm, qn, np.array([pb.L]))
    if nt:
        if length_mode:
            Ts = tension_from_stretch(sysm.path_lengths(qn), np.array([rest(t) for t in times]), EAt)
            _check_tension_history(Ts, EAt, h)
        else:
            Ts = np.array([commands(t) for t in times])
        T_final = Ts[-1]
    else:
        Ts = np.zeros((times.size, 0))
        T_final = np.zeros(0)
    series = {
        "tip_position": tip[:, 0, :],
        "tendon_tensions": Ts,
        "length_change": geo.arc_length(qn, pb.s_nodes, quad=sysm.quad) - pb.L,
    }
    return T_final, tendon_it, q_end, times, series
