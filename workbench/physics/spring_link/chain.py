"""What every spring-link chain shares: inputs, tendon commands, active set, tensions, result.

A chain object is the assembled Exudyn system of one solve (built from plain parameters, no
module state).  :class:`Chain` builds it in one fixed sequence -- bind the inputs and the tendon
routing, :meth:`Chain._check` the case, create the system, :meth:`Chain._build` every item,
``Assemble`` -- and drives it through the interface the static ramp and the dynamic pre-step use:
:meth:`Chain.set_external`, :meth:`Chain.set_tendons`, :meth:`Chain.update_active_set`,
:meth:`Chain.result`.  A variant (:mod:`.planar`, :mod:`.spatial`, :mod:`.tree`) provides the
hooks named in the class docstring and nothing else.  Checked through every chain by
``tests/physics/test_spring_link*.py`` and the layout by ``tests/physics/test_spring_link_layout.py``.
"""

from __future__ import annotations

import math

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .geometry import ChainGeometry
from .lengthmode import gap_sums
from .routing import add_eyelet_rope, TendonRoute, route_tendons
from .shape import planar_shape, spatial_shape, twist_vs_parallel_transport

__all__: list[str] = []


class Chain:
    """Base of the chain variants.

    Hooks a variant must provide (each raises ``NotImplementedError`` here):

    * ``_build(mbs)``: add every node, object, marker and load (in the variant's fixed order);
      it sets ``tip_force_load``/``tip_torque_load`` (via :meth:`_add_tip_loads`) and the tendon
      items (via :meth:`_add_tendons`);
    * ``_eyelet_marker(mbs, i, tendon, link, z, d)``: the marker of one eyelet of tendon ``i``;
    * ``_continuum_items(mbs, i, tendon)``: the items that carry continuum tendon ``i``;
    * ``_set_continuum()``: apply ``self._values`` (and ``self._L0``) to those items;
    * ``link_states()`` (planar chains: joint positions ``(N, 3)``, link angles ``(N,)``) or
      ``link_frames()`` (3-D chains: joint positions ``(N, 3)``, link rotations ``(N, 3, 3)``).

    Optional hooks: ``_check()`` (reject unsupported cases with :class:`ModelFailure`) and
    ``_set_gravity(lam)`` (default: the mass-proportional loads of ``gravity_loads``).

    Class attributes: ``planar`` (result in the base x-z plane), ``rigid_bodies`` (rigid bodies
    with joint constraints, as opposed to minimal coordinates), ``axial``, ``torsion`` and
    ``link_ropes`` (the rope forces come from the variant's own user function, so tendons get eyelet
    markers but no rope connectors; :mod:`.tree`).
    """

    planar: bool = True
    rigid_bodies: bool = True
    link_ropes: bool = False
    axial: bool = False
    torsion: str = "spring"

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry) -> None:
        import exudyn as exu
        import exudyn.itemInterface as eii

        check_model_inputs(robot, load, options)
        self.exu, self.eii = exu, eii
        self.robot, self.load, self.options, self.geo = robot, load, options, geo
        #: the LoadRampInfo of every static ramp of the current solve (``driver.static_ramp`` appends)
        self.ramps: list = []
        self.tendons: list[TendonRoute] = route_tendons(robot, geo, options.tendon_model)
        self.mode = None if load.actuation is None else load.actuation.mode
        self.model = options.tendon_model
        self.ropes = self.model == "eyelets" or self._continuum_ropes()
        # planar continuum length mode with axial springs (:mod:`.lengthmode`): lagged couplings
        self.lagged_length = self.axial and self.planar and self.mode == "length" and not self.ropes
        self.lag_gaps = np.zeros(len(self.tendons))
        self.lag_tensions = np.zeros(len(self.tendons))
        self._check()
        self.SC = exu.SystemContainer()
        self.mbs = self.SC.AddSystem()
        self.tendon_active = [True] * len(self.tendons)
        # side of each tendon in the bending plane (planar chains): +1 at sigma = 0, -1 at pi
        self.sign = [1.0 if math.cos(t.sigma) > 0 else -1.0 for t in self.tendons]
        self.gravity_loads: list[int] = []
        self._build(self.mbs)
        self.mbs.Assemble()

    # -- hooks ---------------------------------------------------------------------------------
    def _check(self) -> None:
        """Raise :class:`ModelFailure` for cases this variant cannot model (default: none)."""

    def _build(self, mbs) -> None:  # noqa: ANN001
        raise NotImplementedError

    def _eyelet_marker(self, mbs, i: int, tendon: TendonRoute, link: int, z: float, d: float) -> int:  # noqa: ANN001
        raise NotImplementedError

    def _continuum_items(self, mbs, i: int, tendon: TendonRoute) -> list:  # noqa: ANN001
        raise NotImplementedError

    def _set_continuum(self) -> None:
        raise NotImplementedError

    def link_states(self) -> tuple[np.ndarray, np.ndarray]:
        raise NotImplementedError(f"{type(self).__name__} is not a planar chain")

    def link_frames(self) -> tuple[np.ndarray, np.ndarray]:
        raise NotImplementedError(f"{type(self).__name__} is not a 3-D chain")

    def _set_gravity(self, lam: float) -> None:
        for ld in self.gravity_loads:
            self.mbs.SetLoadParameter(ld, "loadVector", (lam * self.g2).tolist())

    def _continuum_ropes(self) -> bool:
        """Whether continuum tendons are ropes through an eyelet at every link eyelet ``e_k``.

        3-D chains (tension or length) and planar length mode with axial springs or a tapered
        offset: the rope (constant-force segments in tension mode, a reeving rope in length mode)
        follows the deformed chain, so its forces are exact for the routed tendon under any
        external load, and the continuous routing is its limit as the links grow (the chord's
        lever-arm error is ``O(ds^2)``, ``test_spring_link_crossexam.py``).  Planar chains use the
        exact internal moment ``T d cos(alpha)`` (tension) or the terminating link's rotation
        (length, constant offset; with axial springs through :mod:`.lengthmode`), exact in the
        plane under any load; planar length mode with a tapered offset uses the ropes too.
        """
        if self.model != "continuum" or self.mode is None:
            return False
        return not self.planar or (self.mode == "length" and any(t.tapered for t in self.tendons))

    # -- shared build steps --------------------------------------------------------------------
    def _eyelet_marker_type(self):  # noqa: ANN202
        """Rigid markers for reeving ropes (Exudyn needs them), position markers otherwise."""
        eii = self.eii
        return eii.MarkerBodyRigid if (self.ropes and self.mode == "length") else eii.MarkerBodyPosition

    def _add_gravity(self, mbs) -> None:  # noqa: ANN001
        """Mass-proportional gravity loads on the rigid bodies (set by the load factor)."""
        eii = self.eii
        if np.any(self.g2 != 0):
            for b in self.bodies:
                mm = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=b))
                self.gravity_loads.append(mbs.AddLoad(eii.LoadMassProportional(markerNumber=mm, loadVector=[0.0, 0.0, 0.0])))

    def _add_tip_loads(self, mbs, marker: int, force: np.ndarray | None = None,  # noqa: ANN001
                       torque: np.ndarray | None = None) -> None:
        """Tip force and torque loads on ``marker``; ``force``/``torque`` are their full values in
        the system's frame (default: the load case's, base frame)."""
        eii = self.eii
        self.tip_force_full = np.asarray(self.load.tip_force, dtype=float) if force is None else force
        self.tip_torque_full = np.asarray(self.load.tip_torque, dtype=float) if torque is None else torque
        self.tip_force_load = mbs.AddLoad(eii.LoadForceVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0]))
        self.tip_torque_load = mbs.AddLoad(eii.LoadTorqueVector(markerNumber=marker, loadVector=[0.0, 0.0, 0.0]))

    def _add_tendons(self, mbs) -> None:  # noqa: ANN001
        """Eyelet markers and the items of every tendon (ropes or the variant's continuum items)."""
        self.eyelet_markers: list[list[int]] = []
        self.tendon_items: list[list[int]] = []
        for i, t in enumerate(self.tendons):
            marks = [self._eyelet_marker(mbs, i, t, lk, zk, dk) for lk, zk, dk in zip(t.eye_link, t.eye_z, t.eye_d)]
            self.eyelet_markers.append(marks)
            if self.mode is None or self.link_ropes:
                items = []
            elif self.ropes:
                items = add_eyelet_rope(mbs, marks, t, self.mode, self.options.damping)
            else:
                items = self._continuum_items(mbs, i, t)
            self.tendon_items.append(items)

    # -- load application ----------------------------------------------------------------------
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
        """Gravity and tip loads at load factor ``lam``."""
        mbs = self.mbs
        self._set_gravity(lam)
        mbs.SetLoadParameter(self.tip_force_load, "loadVector", (lam * self.tip_force_full).tolist())
        mbs.SetLoadParameter(self.tip_torque_load, "loadVector", (lam * self.tip_torque_full).tolist())

    def set_tendons(self, values: np.ndarray, pretension_factor: float) -> None:
        """Apply tendon commands (tensions [N] or length changes [m])."""
        if self.mode is None:
            return
        self._values = np.asarray(values, dtype=float)
        if self.mode == "length":
            self._L0 = self.rest_lengths(self._values, pretension_factor)
        if self.ropes:
            self._set_ropes()
        else:
            self._set_continuum()

    def _set_ropes(self) -> None:
        if self.link_ropes:  # the variant's user function reads self._values / self._L0
            return
        mbs = self.mbs
        for i, items in enumerate(self.tendon_items):
            if self.mode == "tension":
                v = float(self._values[i])
                for it in items:
                    mbs.SetObjectParameter(it, "force", v)
            else:
                mbs.SetObjectParameter(items[0], "referenceLength", float(self._L0[i]))
                mbs.SetObjectParameter(items[0], "activeConnector", bool(self.tendon_active[i]))

    def _set_compression(self, axis: int) -> None:
        """Continuum tendons with axial springs: compression sum(T) in every joint a tendon
        passes, as a rest-length offset of the joint spring's coordinate ``axis`` (length mode:
        the lagged tensions of :mod:`.lengthmode`)."""
        N = self.geo.n_links
        comp = np.zeros(N)
        for t, v in zip(self.tendons, self.lag_tensions if self.mode == "length" else self._values):
            comp[: t.end_eyelet] += v * t.cos_alpha
        for k in range(N):
            off = [0.0] * 6
            off[axis] = float(-comp[k] / self.geo.axial_stiffness[k])
            self.mbs.SetObjectParameter(self.joint_springs[k], "offset", off)

    # -- state access ----------------------------------------------------------------------------
    def save_state(self) -> tuple:
        """The state a failed load step returns to: initial coordinates and the active set."""
        q = self.mbs.systemData.GetODE2Coordinates(configuration=self.exu.ConfigurationType.Initial)
        return q, list(self.tendon_active)

    def restore_state(self, state: tuple) -> None:
        """Reset the initial and current coordinates and the active set to ``state``."""
        q, active = state
        cfg = self.exu.ConfigurationType
        self.mbs.systemData.SetODE2Coordinates(q, configuration=cfg.Initial)
        self.mbs.systemData.SetODE2Coordinates(q, configuration=cfg.Current)
        self.tendon_active = active

    def tendon_lengths(self) -> np.ndarray:
        """Current tendon path lengths [m]: continuum tendons of planar chains from the rotation
        of their terminating link, ropes (and 3-D chains) from the eyelet marker positions."""
        if not self.ropes and self.planar:
            _, beta = self.link_states()
            gaps = gap_sums(self) if self.axial else np.zeros(len(self.tendons))
            return np.asarray([t.reference_length - t.offsets[-1] * s * beta[t.end_eyelet - 1] + g
                               for t, s, g in zip(self.tendons, self.sign, gaps)])
        exu = self.exu
        out = []
        for marks in self.eyelet_markers:
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
        """The :class:`PhysicsResult` of the current state (see :mod:`.shape` for the outputs)."""
        geo = self.geo
        stations = np.linspace(0.0, self.robot.length, self.options.n_stations)
        if self.planar:
            P, beta = self.link_states()
            pos, T, joint, axes = planar_shape(geo, stations, P, beta)
            change = self._length_change(axes, lambda p: np.array([p[0], p[1]]))
            twist, dim = 0.0, 2.0
            link_axes = np.stack([np.sin(beta), np.zeros_like(beta), np.cos(beta)], axis=1)
        else:
            P, R = self.link_frames()
            pos, T, joint = spatial_shape(geo, stations, P, R, self.torsion)
            change = self._length_change(R[:, :, 2], lambda p: np.asarray(p, dtype=float))
            twist, dim = twist_vs_parallel_transport(R), 3.0
            link_axes = R[:, :, 2]
        tensions = self.tensions()
        return PhysicsResult(
            model="spring_link", stations=stations, positions=pos, tip_frame=T, length_change=change,
            tendon_tensions=tensions, tip_twist=twist, solver=solver, joint_angles=joint,
            time=time_, series=series or {},
            extras={"n_links": float(geo.n_links), "dimension": dim,
                    **self._stress(joint, tensions, link_axes)},
        )

    def _distal_weight(self) -> np.ndarray:
        """Weight of everything beyond each joint (backbone, disks, payload), base frame, ``(N, 3)`` [N]."""
        robot, s = self.robot, self.geo.joints
        if not np.any(robot.gravity_in_base()):  # weightless: nothing to integrate
            return np.zeros((s.size, 3))
        starts = np.concatenate([[0.0], robot.section_ends[:-1]])
        disks = robot.disk_stations()
        disk_m = np.concatenate([np.full(sec.n_disks, sec.disk_mass) for sec in robot.sections])
        mass = np.zeros(s.size)
        for a, sec in zip(starts, robot.sections):
            b = a + sec.length
            u = np.linspace(0.0, 1.0, 9)
            mu = np.array([sec.cross_section_at(float(x)).mass_per_length for x in u])
            for k, sk in enumerate(s):
                lo = min(max(sk, a), b)
                x = np.linspace((lo - a) / sec.length, 1.0, 9)
                mass[k] += (b - lo) * float(np.mean(np.interp(x, u, mu)))
        mass += np.array([disk_m[disks > sk].sum() for sk in s]) + robot.payload.mass
        return mass[:, None] * robot.gravity_in_base()[None, :]

    def _stress(self, joint: np.ndarray, tensions: np.ndarray, link_axes: np.ndarray) -> dict[str, float]:
        """Stress extras (:mod:`workbench.models.stress`) of the equivalent rod at every joint.

        Bending moment ``k_j |theta_j|`` of the joint spring (planar angle; 3-D: the bending part
        of the relative rotation, torsion excluded); axial force along the distal link: the tip
        force plus the distal weight, minus the summed tensions of the tendons passing the joint.
        """
        from ...models.stress import combined_stress, section_arrays, stress_extras
        from .geometry import section_of

        robot, geo = self.robot, self.geo
        idx, frac = section_of(robot, geo.joints)
        arrs = section_arrays([robot.sections[int(i)].cross_section_at(float(f)) for i, f in zip(idx, frac)])
        sigma = strength = None
        if arrs is not None:
            j = np.asarray(joint, dtype=float)
            bend = np.abs(j[:, 0]) if j.shape[1] == 1 else np.hypot(j[:, 0], j[:, 1])
            ends = robot.section_ends
            secs = np.array([sec for sec, _, _ in robot.tendon_table()], dtype=int)
            passing = (geo.joints[:, None] < np.asarray(ends)[secs][None, :]).astype(float).reshape(geo.n_links, -1)
            N = -(passing @ np.asarray(tensions, dtype=float)) if passing.size else np.zeros(geo.n_links)
            F_ext = np.asarray(self.load.tip_force, dtype=float)[None, :] + self._distal_weight()
            N = N + np.sum(F_ext * link_axes, axis=1)
            sigma, strength = combined_stress(N, geo.stiffness * bend, arrs[0], arrs[1]), arrs[2]
        return stress_extras(sigma, strength, robot, tensions)
