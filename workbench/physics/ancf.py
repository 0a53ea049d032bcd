"""Planar tendon-driven backbone as a chain of 2-D ANCF cable elements (Exudyn).

Model ``"ancf"``: ``run(robot, load, options) -> PhysicsResult``.  Description -> system ->
drivers: :func:`build_problem` (``_ancf_problem``, pure numpy: the robot in Exudyn's plane, base
(z, x) = Exudyn (X, Y)), :class:`_System` (the assembled Exudyn system), :class:`_StaticDriver`
and :func:`_dynamic`.

* Plane: the robot bends in its base x-z plane; results are reported as ``(x, 0, z)``.  Tendons
  only at sigma = 0 or pi, tip forces in the x-z plane, tip torques along base y, no payload
  offset (else :class:`PlanarModelError`); gravity out of that plane raises :class:`ModelFailure`.
* Backbone: ``options.n_elements`` ``ObjectANCFCable2D`` elements (extensible Euler-Bernoulli,
  ``useReducedOrderIntegration=2``), every section end a node; clamp = node 0's x, y and y-slope
  (the x-slope stays free); payload = tip point mass; disks: :func:`~workbench.physics._exudyn.add_cable2d_disks`.
* Tendons, ``"continuum"``: the exact load of a frictionless tendon at offset ``y(s)`` (moment
  ``T y cos(alpha)``, compression ``T cos(alpha)``, ``tan alpha = y'``) as per-element reference
  curvature ``sum T y cos(alpha) / EI`` and reference axial strain ``-sum T cos(alpha) / EA``;
  ``"eyelets"``: a rope anchored at ``(0, y)`` through rigid-marker eyelets at every disk of its
  path, each straight segment a zero-stiffness spring-damper with constant ``force = T``.
* Length control (``mode == "length"``): ``T = EA_t max(0, (l - l0) / l0)``, ``l0`` by
  :func:`~workbench.physics.tendon_loads.tendon_rest_lengths`, ``l`` the deformed path length.
  Static: semismooth quasi-Newton on the tensions around tension-controlled equilibria
  (:func:`~workbench.physics.tendon_loads.solve_length_controlled`, compliance from
  :func:`~workbench.physics.tendon_loads.tendon_path_compliance`).  Dynamic: tensions from the
  state at the step start and the rest length at its end (explicit, in a ``PreStepUserFunction``);
  divergence or a chattering tension history raises :class:`ModelFailure`.
* Static solution: loads and tensions ramped by :func:`~workbench.physics._stepping.ancf_load_ramp`
  (at most ``options.max_load_steps`` ``SolveStatic`` attempts per ramp); non-convergence or an implausible state (non-finite, ``|r'|`` outside
  (0.5, 1.5), a point beyond 2 L) raises :class:`ModelFailure`.
* Dynamics: generalised-alpha from the static equilibrium at t = 0 (``initial_state="static"``)
  or from the straight rod with all loads applied at once (``"reference"``); commands
  ``command_at(t, load.ramp_time)``; Rayleigh damping ``bendingDamping = beta EI``,
  ``axialDamping = beta EA`` with ``beta = options.damping`` [s].
* Outputs: positions at ``options.n_stations`` stations (Hermite centreline), tip frame (rotation
  about base y), ``length_change = int |r'| ds - L``, tensions, ``tip_twist = 0``; series
  ``tip_position`` (k, 3), ``tendon_tensions`` (k, n), ``length_change`` (k,); extras
  ``static_steps``, ``failed_steps``, ``tendon_iterations``, ``gravity_out_of_plane`` (always 0), stresses
  (:func:`~workbench.physics._ancf_stress.ancf_stress_extras`; dynamics: the largest over time).
Checked by ``tests/physics/test_ancf.py``, ``test_ancf_reeving.py`` (eyelet chain = reeving rope),
``test_ancf_geometry.py``, ``tests/models/test_stress.py``; accuracy: ``docs/models.md``.
"""

from __future__ import annotations

import math
import time as _time
from typing import Literal

import numpy as np

from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from ._ancf_geometry import (arc_length, centreline, element_lengths, gauss_points, locate,
                             offset_curve_length, offset_points)
from ..models.backbone_frames import backbone_series, frame_stride
from ._ancf_problem import AncfProblem, PlanarModelError, build_problem
from ._ancf_stress import ancf_stress_extras
from ._stepping import PathPoint, ancf_load_ramp, path_fields
from .tendon_loads import solve_length_controlled, tendon_path_compliance, tendon_rest_lengths, tension_from_stretch

__all__ = ["run", "PlanarModelError"]


# ----------------------------------------------------------------------------------------
# Exudyn system
# ----------------------------------------------------------------------------------------
class _System:
    """The assembled Exudyn system of one ANCF solve, with setters for the ramped loads (built per call).

    Parameters
    ----------
    pb : AncfProblem
        The planar problem (:func:`build_problem`).
    options : SolverOptions
        Unused here (kept for the callers' signature).
    tendon_model : {"continuum", "eyelets"}
    damping : float
        Rayleigh ``beta`` [s] of the elements.
    """

    def __init__(self, pb: AncfProblem, options: SolverOptions, tendon_model: str, damping: float):
        import exudyn as exu

        self.exu = exu
        self.pb = pb
        self.tendon_model = tendon_model
        self.SC = exu.SystemContainer()
        self.mbs = self.SC.AddSystem()
        ground = self._add_backbone(damping)
        self._add_loads()
        self._add_tendons(ground)
        self.quad = gauss_points(pb.s_nodes, 6)
        self._T = np.full(len(pb.tendons), np.nan)
        self._ext = np.nan
        self.mbs.Assemble()

    # -- building ---------------------------------------------------------------------------
    def _add_backbone(self, damping: float) -> int:
        """Build the backbone: ANCF nodes, ``ANCFCable2D`` beam elements (Exudyn's name for the planar
        ANCF beam; not a tendon) and the clamp (node 0's x, y and y-slope); returns the ground object."""
        from exudyn.itemInterface import NodePoint2DSlope1, ObjectANCFCable2D, ObjectGround

        from ._exudyn import clamp_coordinates

        pb, mbs = self.pb, self.mbs
        le = np.diff(pb.s_nodes)
        self.nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[float(s), 0.0, 1.0, 0.0])) for s in pb.s_nodes]
        self.elements = []
        for e in range(le.size):
            self.elements.append(mbs.AddObject(ObjectANCFCable2D(
                nodeNumbers=[self.nodes[e], self.nodes[e + 1]], length=float(le[e]),
                bendingStiffness=float(pb.EI[e]), axialStiffness=float(pb.EA[e]),
                massPerLength=float(pb.mu_rod[e]), bendingDamping=float(damping * pb.EI[e]),
                axialDamping=float(damping * pb.EA[e]), useReducedOrderIntegration=2,
            )))
        ground = mbs.AddObject(ObjectGround())
        clamp_coordinates(mbs, self.nodes[0], (0, 1, 3))
        return ground

    def _add_loads(self) -> None:
        """Gravity, payload (mass point and weight), tip force and torque; values set by :meth:`set_external`."""
        from exudyn.itemInterface import (
            LoadForceVector, LoadTorqueVector, MarkerBodyRigid, MarkerNodePosition, ObjectMassPoint2D,
        )

        from ._exudyn import add_cable2d_disks, add_gravity_loads

        pb, mbs = self.pb, self.mbs
        has_g = bool(np.any(pb.gravity != 0))
        self.grav_loads = add_gravity_loads(mbs, self.elements) if has_g else []
        tipm = mbs.AddMarker(MarkerNodePosition(nodeNumber=self.nodes[-1]))
        self.disk_loads = add_cable2d_disks(mbs, pb.s_nodes, self.nodes, self.elements, pb.disk_s, pb.disk_m, has_g)
        self.payload_load = None
        if pb.payload > 0:
            mbs.AddObject(ObjectMassPoint2D(nodeNumber=self.nodes[-1], mass=pb.payload))
            if has_g:
                self.payload_load = mbs.AddLoad(LoadForceVector(markerNumber=tipm, loadVector=[0, 0, 0]))
        self.force_load = None
        if np.any(pb.tip_force != 0):
            self.force_load = mbs.AddLoad(LoadForceVector(markerNumber=tipm, loadVector=[0, 0, 0]))
        self.torque_load = None
        if pb.tip_torque != 0:
            tip_x = float(pb.s_nodes[-1] - pb.s_nodes[-2])
            mr = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.elements[-1], localPosition=[tip_x, 0, 0]))
            self.torque_load = mbs.AddLoad(LoadTorqueVector(markerNumber=mr, loadVector=[0, 0, 0]))

    def _add_tendons(self, ground: int) -> None:
        """Per-unit-tension reference curvature / axial strain (continuum) or the eyelet rope segments."""
        from exudyn.itemInterface import MarkerBodyPosition, MarkerBodyRigid, ObjectConnectorSpringDamper

        pb, mbs, sn = self.pb, self.mbs, self.pb.s_nodes
        nt, n_el = len(pb.tendons), sn.size - 1
        smid = 0.5 * (sn[1:] + sn[:-1])
        self.kap_per_T = np.zeros((n_el, nt))
        self.eps_per_T = np.zeros((n_el, nt))
        self.segments: list[list[int]] = []
        for i, td in enumerate(pb.tendons):
            on = smid < td.end
            cosa = 1.0 / np.sqrt(1.0 + td.dy(smid) ** 2)
            self.kap_per_T[:, i] = np.where(on, td.y(smid) * cosa / pb.EI, 0.0)
            self.eps_per_T[:, i] = np.where(on, -cosa / pb.EA, 0.0)
            if self.tendon_model == "eyelets":
                prev = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, float(td.y(0.0)), 0.0]))
                segs = []
                elem, x = locate(sn, np.array(td.eyelets))
                for s_e, e_i, x_i in zip(td.eyelets, elem, x):
                    m = mbs.AddMarker(MarkerBodyRigid(bodyNumber=self.elements[int(e_i)],
                                                      localPosition=[float(x_i), float(td.y(s_e)), 0.0]))
                    segs.append(mbs.AddObject(ObjectConnectorSpringDamper(
                        markerNumbers=[prev, m], stiffness=0.0, damping=0.0, force=0.0, referenceLength=0.0)))
                    prev = m
                self.segments.append(segs)

    # -- load setters -----------------------------------------------------------------------
    def set_external(self, lam: float) -> None:
        if lam == self._ext:
            return
        pb, mbs = self.pb, self.mbs
        g = lam * pb.gravity
        for ld in self.grav_loads:
            mbs.SetLoadParameter(ld, "loadVector", [float(g[0]), float(g[1]), 0.0])
        for ld, m in zip(self.disk_loads, pb.disk_m):
            mbs.SetLoadParameter(ld, "loadVector", [float(m * g[0]), float(m * g[1]), 0.0])
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
                    el_len = element_lengths(qn, pb.s_nodes, quad=self.quad)
                    th = np.unwrap(np.arctan2(qn[..., 3], qn[..., 2]), axis=-1)
                k = int(np.argmin(np.abs(pb.s_nodes - td.end)))
                arc = el_len[..., :k].sum(axis=-1)
                out.append(arc - float(td.y(0.0)) * (th[..., k] - th[..., 0]))
            elif self.tendon_model == "continuum":
                out.append(offset_curve_length(qn, pb.s_nodes, td.end, td.y, td.dy, quad=self.quad))
            else:
                st = np.array(td.eyelets)
                pts = offset_points(qn, pb.s_nodes, st, td.y(st))
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
        self.newton = 0
        self.ext = 0.0
        self.T = np.zeros(len(sysm.pb.tendons))
        self.ramps: list = []  # the LoadRampInfo of every go_to

    def _solve(self) -> PathPoint:
        mbs = self.sysm.mbs
        mbs.SolveStatic(self.settings, updateInitialValues=True, storeSolver=True)
        self.newton += int(mbs.sys["staticSolver"].it.newtonStepsCount)
        return _check_state(self.sysm, self.sysm.coords())

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
            info = ancf_load_ramp(apply, self._solve, save, restore, max_steps=self.options.max_load_steps,
                                  failure=(exu.SolverError, ModelFailure),
                                  start=_check_state(self.sysm, self.sysm.coords()))
        except RuntimeError as err:
            raise ModelFailure(f"ANCF static solve failed: {err}") from err
        self.ramps.append(info)
        self.ext, self.T = ext, T.copy()


def _check_state(sysm: _System, q: np.ndarray) -> PathPoint:
    """Reject an implausible state; returns its load-path measure (tip position / L, unit tip tangent)."""
    qn = sysm.node_coords(q)
    if not np.all(np.isfinite(qn)):
        raise ModelFailure("ANCF solve produced non-finite coordinates")
    slope = np.linalg.norm(qn[:, 2:], axis=-1)
    if np.any(slope < 0.5) or np.any(slope > 1.5):
        raise ModelFailure(f"ANCF solve produced implausible axial stretch |r'| in [{slope.min():.3g}, {slope.max():.3g}]")
    if np.max(np.linalg.norm(qn[:, :2], axis=-1)) > 2.0 * sysm.pb.L:
        raise ModelFailure("ANCF solve produced a point further than 2 L from the base")
    return PathPoint((*(qn[-1, :2] / sysm.pb.L), *(qn[-1, 2:] / slope[-1])))


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
    elem, _ = locate(sn, s)
    y = np.array([t.y(s) for t in pb.tendons])
    return tendon_path_compliance(s, pb.EI[elem], pb.EA[elem], y, [t.end for t in pb.tendons])


def _frame_and_positions(sysm: _System, qn: np.ndarray, stations: np.ndarray):
    r, t = centreline(qn, sysm.pb.s_nodes, stations)
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
        Gravity out of the base x-z plane, no convergence or an implausible state.
    """
    from ._exudyn import quiet_exudyn

    t_wall = _time.perf_counter()
    pb = build_problem(robot, load, options)
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
            stress = ancf_stress_extras(pb, robot, sysm.node_coords(q), T)
        else:
            T, tendon_it, q, times, series, stress = _dynamic(sysm, drv, load, options, initial_state, robot)
    qn = sysm.node_coords(q)
    pos, tang = _frame_and_positions(sysm, qn, stations)
    length_change = float(arc_length(qn, pb.s_nodes, quad=sysm.quad)) - pb.L
    wall = _time.perf_counter() - t_wall
    steps, failed = (sum(getattr(r, k) for r in drv.ramps) for k in ("attempts", "failed"))
    return PhysicsResult(
        model="ancf",
        stations=stations,
        positions=pos,
        tip_frame=_tip_frame(pos[-1], tang[-1]),
        length_change=length_change,
        tendon_tensions=T,
        tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=drv.newton, wall_time=wall,
                          message=f"{steps} load steps ({failed} halved), {tendon_it} tendon iterations",
                          **path_fields(*drv.ramps)),
        time=times,
        series=series,
        extras={"static_steps": float(steps), "failed_steps": float(failed),
                "tendon_iterations": float(tendon_it), "gravity_out_of_plane": pb.g_out, **stress},
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


class _Commands:
    """Tendon commands of a dynamic run (``command_at``) and, in length mode, the rest lengths they give."""

    def __init__(self, sysm: _System, load: LoadCase):
        self.act = load.actuation
        self.ramp_time = load.ramp_time
        self.nt = len(sysm.pb.tendons)
        self.length_mode = self.act is not None and self.act.mode == "length" and self.nt > 0
        self.EAt = np.array([t.EAt for t in sysm.pb.tendons])
        self.lref = sysm.reference_path_lengths()

    def at(self, t) -> np.ndarray:
        return np.zeros(self.nt) if self.act is None else self.act.command_at(float(t), self.ramp_time)

    def rest(self, t) -> np.ndarray:
        return tendon_rest_lengths(self.lref, self.at(t), self.act.pretension, self.EAt)


def _dynamic_start(sysm: _System, drv: _StaticDriver, cmd: _Commands, initial_state: str) -> int:
    """Set the state and tensions at t = 0; returns the tendon iterations of a static start."""
    if initial_state == "static":
        _, tendon_it = _static_tensions(sysm, drv, cmd.act, cmd.at(0.0))
        return tendon_it
    sysm.set_external(1.0)
    sysm.set_tensions(tension_from_stretch(cmd.lref, cmd.rest(0.0), cmd.EAt) if cmd.length_mode else cmd.at(0.0))
    return 0


def _dynamic_series(sysm: _System, cmd: _Commands, Q: np.ndarray, times: np.ndarray, h: float,
                    stations: np.ndarray):
    """Checked states ``Q`` (k, n_ode2) -> (final tensions, series; backbone frames at ``stations``)."""
    for q in (Q[0], Q[len(Q) // 2], Q[-1]):
        _check_state(sysm, q)
    pb = sysm.pb
    qn = sysm.node_coords(Q)
    tip, _ = _frame_and_positions(sysm, qn, np.array([pb.L]))
    if cmd.nt:
        if cmd.length_mode:
            Ts = tension_from_stretch(sysm.path_lengths(qn), np.array([cmd.rest(t) for t in times]), cmd.EAt)
            _check_tension_history(Ts, cmd.EAt, h)
        else:
            Ts = np.array([cmd.at(t) for t in times])
        T_final = Ts[-1]
    else:
        Ts = np.zeros((times.size, 0))
        T_final = np.zeros(0)
    series = {
        "tip_position": tip[:, 0, :],
        "tendon_tensions": Ts,
        "length_change": arc_length(qn, pb.s_nodes, quad=sysm.quad) - pb.L,
    }
    keep = np.unique(np.r_[np.arange(0, times.size - 1, frame_stride(times.size - 1)), times.size - 1])
    series.update(backbone_series(times[keep], _frame_and_positions(sysm, qn[keep], stations)[0]))
    return T_final, series


def _dynamic(sysm: _System, drv: _StaticDriver, load: LoadCase, options: SolverOptions, initial_state: str,
             robot: Robot | None = None):
    """Generalised-alpha run; returns (final tensions, tendon iterations, final ODE2 state, times, series, stress extras)."""
    from ._exudyn import dynamic_settings

    exu, mbs = sysm.exu, sysm.mbs
    cmd = _Commands(sysm, load)
    tendon_it = _dynamic_start(sysm, drv, cmd, initial_state)
    h = options.time_step
    settings = dynamic_settings(options, load.duration)
    settings.timeIntegration.numberOfSteps = max(1, int(round(load.duration / h)))
    settings.timeIntegration.adaptiveStep = False
    rec_t, rec_q = [], []

    def pre_step(mbs_, t):
        # Exudyn passes the time at the END of the coming step; the state is the one at its start
        q = np.asarray(mbs_.systemData.GetODE2Coordinates())
        rec_t.append(float(t) - h)
        rec_q.append(q.copy())
        if cmd.nt:
            t_end = float(t)
            if cmd.length_mode:
                T = tension_from_stretch(sysm.path_lengths(sysm.node_coords(q)), cmd.rest(t_end), cmd.EAt)
            else:
                T = cmd.at(t_end)
            sysm.set_tensions(T)
        return True

    mbs.SetPreStepUserFunction(pre_step)
    try:
        mbs.SolveDynamic(settings, solverType=exu.DynamicSolverType.GeneralizedAlpha, storeSolver=True)
        drv.newton += int(mbs.sys["dynamicSolver"].it.newtonStepsCount)
    except exu.SolverError as err:
        hint = (" (length-controlled tendons are coupled explicitly: stiff tendons need a smaller "
                "options.time_step)") if cmd.length_mode else ""
        raise ModelFailure(f"ANCF dynamic solve failed: {err}{hint}") from err
    finally:
        mbs.SetPreStepUserFunction(0)
    q_end = sysm.coords()
    rec_t.append(float(load.duration))
    rec_q.append(q_end.copy())
    times = np.array(rec_t)
    Q = np.array(rec_q)
    T_final, series = _dynamic_series(sysm, cmd, Q, times, h, np.linspace(0.0, sysm.pb.L, options.n_stations))
    stress = ancf_stress_extras(sysm.pb, robot, sysm.node_coords(Q), series["tendon_tensions"]) if robot is not None else {}
    # stored on the shared output grid (workbench.models.result.series_times), every step checked above;
    # the backbone frames keep their own (decimated) time axis
    from ..models.result import series_times

    keep = np.searchsorted(times, series_times(load.duration, h) - 1e-9 * h)
    keep = np.unique(np.clip(keep, 0, times.size - 1))
    stored = {k: (v if k.startswith("backbone") else v[keep]) for k, v in series.items()}
    return T_final, tendon_it, q_end, times[keep], stored, stress
