"""A grasp plan through the planar contact physics: close, release, pull out or carry (one case).

:func:`cc_result` is the CC row of a plan (the arcs it commands; for a tendon plan the same as the
``cc`` model, ``tests/experiments/test_whole_arm_grasp.py``).  :func:`run_task` runs the physics on
:class:`~workbench.physics.contact.PlanarContactSystem`:

1. wrap: the object is held at its planned centre while tendon/chamber strains and gravity ramp
   in (``close_on_held_object``) -- the physical wrap of a held object;
2. hold (``release``): then released into the arm (spring homotopy): does the arm hold it, and
   where does it settle under its weight;
3. pull-out (``pull_distance > 0``): from the held state, pulled along a base axis (displacement
   control): force-displacement curve and holding force;
4. carry (``carry`` plans): from the held state again (restored after the pull), the plan's later
   samples (the grasp centre moved along a line) are ramped in one after another with the object
   free: where the object really goes.

Returns the contact row's :class:`~workbench.models.PhysicsResult`: positions of the held state (the
closed state without release or when the object slips out), extras and series documented in
``docs/models.md`` ("Whole-arm grasp").  Every step is a static solve; a solve that fails raises
``ModelFailure`` (the row is recorded failed with the reason); an object that slips out is a result
(``x.held = 0``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ...models.result import PhysicsResult, SolverInfo, SolverOptions
from ...physics.contact import (
    ContactLaw, PlanarContactSystem, chamber_strains, planar_setup, section_tendon_strains, tendon_strains,
    without_tendons,
)
from ...physics.contact.procedures import (
    close_on_held_object, contact_force_on_object, contact_summary, pull_out, release, surface_gap,
)
from .plan import GraspPlan, cc_backbone

__all__ = ["GraspTask", "GraspRun", "cc_result", "half_width_at", "run_task"]


@dataclass(frozen=True)
class GraspTask:
    """What the physics does with a plan.

    Attributes
    ----------
    release : bool
        Release the object into the arm after closing (else: the wrap of a held object only).
    law : ContactLaw
    pull_axis : {"x", "z"}
        Base axis of the pull; ``pull_sign`` its direction (+1 / -1).
    pull_distance, pull_step : float
        Largest pull displacement and step [m]; ``pull_distance = 0``: no pull-out.
    carry : tuple of GraspPlan
        The later samples of a carry (sample 0 is the plan itself); empty: no carry.
    control : callable, optional
        ``control(run: GraspRun) -> None``, run last from the held state (e.g. Shao's grasp-centre
        controller, ``workbench/experiments/fruit_harvester/centre_control.py``).
    escape_distance : float, optional
        Centre displacement [m] during the release beyond which the object counts as slipped out
        (default: its radius).
    """

    release: bool = True
    law: ContactLaw = field(default_factory=ContactLaw)
    pull_axis: str = "z"
    pull_sign: float = -1.0
    pull_distance: float = 0.0
    pull_step: float = 0.005
    carry: tuple = ()
    control: Callable | None = None
    escape_distance: float | None = None

    def __post_init__(self) -> None:
        if self.pull_axis not in ("x", "z") or self.pull_sign not in (1.0, -1.0):
            raise ValueError(f"pull direction must be +x, -x, +z or -z, got {self.pull_sign:+g}{self.pull_axis}")
        if not (self.pull_distance >= 0 and self.pull_step > 0):
            raise ValueError(f"need pull_distance >= 0 and pull_step > 0 [m], got {self.pull_distance}, {self.pull_step}")
        if (self.pull_distance > 0 or self.carry) and not self.release:
            raise ValueError("a pull-out or a carry needs the object released into the arm (release = true)")


def _stations_on_arcs(robot, ell, stations):
    ends0 = np.concatenate([[0.0], robot.section_ends])
    ends = np.concatenate([[0.0], np.cumsum(ell)])
    return np.interp(stations, ends0, ends)


def half_width_at(robot, s) -> np.ndarray:
    """Half the backbone diameter [m] at reference arc lengths ``s`` (0 where no diameter is given)."""
    ends = np.concatenate([[0.0], robot.section_ends])
    j = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, robot.n_sections - 1)
    f = np.clip((s - ends[j]) / robot.section_lengths[j], 0.0, 1.0)
    return np.array([0.5 * (robot.sections[a].cross_section_at(b).diameter or 0.0) for a, b in zip(j, f)])


def cc_result(robot, plan: GraspPlan, options: SolverOptions) -> PhysicsResult:
    """The CC row of a plan: its arcs at the reference stations, and where they penetrate or miss the object."""
    t0 = time.perf_counter()
    stations = np.linspace(0.0, robot.length, options.n_stations)
    s_cc = _stations_on_arcs(robot, plan.ell, stations)
    fine = np.linspace(0.0, robot.length, 40 * options.n_stations)
    pts = cc_backbone(plan.kappa, plan.ell, s_cc)
    pos = np.column_stack([pts[:, 0], np.zeros(len(pts)), pts[:, 1]])
    from ...kinematics import forward_kinematics
    from .plan import signed_arcs

    k, phi = signed_arcs(plan.kappa)
    tip = forward_kinematics(k, phi, plan.ell)
    extras = {"wrap_angle": plan.wrap_angle}
    for j, kj in enumerate(plan.kappa):
        extras[f"kappa_{j}"] = float(kj)
    if plan.circle is not None:
        g = surface_gap(cc_backbone(plan.kappa, plan.ell, _stations_on_arcs(robot, plan.ell, fine)),
                        half_width_at(robot, fine), plan.circle.centre, plan.circle.radius)
        ds = fine[1] - fine[0]
        extras.update({"object_x": plan.circle.centre[0], "object_z": plan.circle.centre[1],
                       "cc_max_penetration": float(max(0.0, -g.min())), "cc_penetration_arc": float(ds * np.sum(g < 0)),
                       "cc_tip_gap": float(g[-1])})
    T = plan.tensions if plan.tensions is not None else np.full(robot.n_tendons, np.nan)
    return PhysicsResult(model="cc", stations=stations, positions=pos, tip_frame=tip,
                         length_change=float(np.sum(plan.ell) - robot.length), tendon_tensions=T, tip_twist=0.0,
                         solver=SolverInfo(True, 0, time.perf_counter() - t0), extras=extras,
                         series={"half_width": half_width_at(robot, stations)})


def _in_plane_tendons(robot) -> bool:
    """Every tendon at sigma = 0 or pi (the planar mesh then carries them; else their moments are projected)."""
    return all(abs(math.remainder(sigma, math.pi)) <= 1e-9 for _, sigma, _ in robot.tendon_table())


def _strains(robot, pb, plan: GraspPlan):
    if plan.fluidic:
        return chamber_strains(robot, pb, plan.layouts, plan.pressures)
    if pb.tendons:
        return tendon_strains(pb, plan.tensions)
    return section_tendon_strains(robot, pb, plan.tensions)


def _summary_extras(prefix: str, summ: dict) -> dict[str, float]:
    return {f"{prefix}{k}": float(v) for k, v in summ.items() if math.isfinite(v)}


def _frame(pos: np.ndarray, tan: np.ndarray) -> np.ndarray:
    th = math.atan2(tan[-1, 0], tan[-1, 2])
    H = np.eye(4)
    H[:3, :3] = [[math.cos(th), 0.0, math.sin(th)], [0.0, 1.0, 0.0], [-math.sin(th), 0.0, math.cos(th)]]
    H[:3, 3] = pos[-1]
    return H


class GraspRun:
    """Bookkeeping of one physics task: the system, the strains of each plan, extras and series."""

    def __init__(self, robot, plan: GraspPlan, task: GraspTask, options: SolverOptions):
        self.robot_phys = robot if (not plan.fluidic and _in_plane_tendons(robot)) else without_tendons(robot)
        self.pb, hw = planar_setup(self.robot_phys, options)
        self.robot, self.plan, self.task, self.options = robot, plan, task, options
        self.sysm = PlanarContactSystem(self.pb, hw, plan.circle, task.law, tolerance=options.newton_tolerance)
        self.kap, self.eps = _strains(robot, self.pb, plan)
        self.stations = np.linspace(0.0, robot.length, options.n_stations)
        self.extras: dict[str, float] = {}
        self.series: dict[str, np.ndarray] = {}
        self.steps = 0
        #: notes for the row's solver message (e.g. a saturated controller)
        self.log: list[str] = []

    def snapshot(self):
        """``(positions, tangents, length change)`` of the current state (base frame)."""
        pos, tan = self.sysm.positions(self.stations)
        return pos, tan, self.sysm.arc_length() - self.pb.L

    def restart(self, state) -> None:
        """Back to a saved state (the held object free again)."""
        self.sysm.restore(state)
        if self.plan.circle is not None:
            self.sysm.free()

    def record_contact(self) -> None:
        seg = self.sysm.contact_segments()
        self.series.update({"contact_s": seg["s"], "contact_fn": seg["f_n"], "contact_ft": seg["f_t"]})

    def strains_of(self, plan: GraspPlan):
        """Prescribed strains ``(kappa0, eps0)`` per element of another plan of the same robot."""
        return _strains(self.robot, self.pb, plan)

    def close(self) -> None:
        sysm = self.sysm
        if self.plan.circle is None:  # no object: actuation and gravity only
            def apply(lam):
                sysm.set_strains(lam * self.kap, lam * self.eps)
                sysm.set_gravity(lam)

            self.steps += sysm.load_ramp(apply, self.options.max_load_steps)
            return
        self.steps += close_on_held_object(
            sysm, lambda lam: sysm.set_strains(lam * self.kap, lam * self.eps), self.options.max_load_steps)
        net = contact_force_on_object(sysm)
        self.extras.update(_summary_extras("closed_", contact_summary(sysm)))
        self.extras.update({"squeeze_out_x": float(net[0]), "squeeze_out_z": float(net[1])})

    def hold(self) -> bool:
        res = release(self.sysm, escape_distance=self.task.escape_distance)
        self.extras.update({"held": float(res.held), "settle_dx": float(res.displacement[0]),
                            "settle_dz": float(res.displacement[1]), "release_halvings": float(res.spring_steps),
                            "release_residual": res.residual_force})
        if res.held:
            self.extras.update(_summary_extras("", contact_summary(self.sysm)))
        return res.held

    def pull(self) -> None:
        t = self.task
        pr = pull_out(self.sysm, t.pull_axis, t.pull_sign, t.pull_distance, t.pull_step)
        i = int(np.argmax(pr.force))
        nb = [pr.force[j] for j in (i - 1, i + 1) if 0 <= j < pr.force.size]
        self.extras.update({"holding_force": pr.holding_force, "holding_displacement": float(pr.displacement[i]),
                            "holding_force_step_err": float(max(abs(pr.holding_force - f) for f in nb) if nb else 0.0),
                            "pull_peak_resolved": float(pr.peak_resolved),
                            "pull_end": float({"distance": 0, "contact lost": 1, "no equilibrium": 2, "snap": 3}[pr.end])})
        self.series.update({"pull_u": pr.displacement, "pull_force": pr.force, "pull_lateral": pr.lateral})

    def carry(self) -> None:
        sysm, prev = self.sysm, (self.kap, self.eps)
        planned, actual = [np.asarray(self.plan.circle.centre)], [sysm.object_centre()]
        for nxt in self.task.carry:
            k1, e1 = _strains(self.robot, self.pb, nxt)

            def apply(lam, k0=prev[0], e0=prev[1], k1=k1, e1=e1):
                sysm.set_strains(k0 + lam * (k1 - k0), e0 + lam * (e1 - e0))

            self.steps += sysm.load_ramp(apply, self.options.max_load_steps)
            prev = (k1, e1)
            planned.append(np.asarray(nxt.circle.centre))
            actual.append(sysm.object_centre())
            if np.linalg.norm(actual[-1] - planned[-1]) > 2.0 * self.plan.circle.radius:
                break
        P, A = np.array(planned), np.array(actual)
        err = np.linalg.norm(A - P, axis=1)
        move = np.linalg.norm((A - A[0]) - (P - P[0]), axis=1)  # tracking of the move, settling offset removed
        self.extras.update({"carry_max_error": float(err.max()), "carry_move_error": float(move.max()),
                            "carry_samples_held": float(len(A) - 1)})
        self.series.update({"carry_planned": P, "carry_actual": A})


def run_task(robot, plan: GraspPlan, task: GraspTask, options: SolverOptions) -> PhysicsResult:
    """The physics of one grasp case (module docstring); the contact row's result."""
    from ...models import quiet_if_loaded

    t0 = time.perf_counter()
    with quiet_if_loaded():
        r = GraspRun(robot, plan, task, options)
        r.close()
        shape = r.snapshot()
        r.record_contact()
        held_state = r.sysm.save() if plan.circle is None else None
        if task.release and plan.circle is not None and r.hold():
            shape = r.snapshot()
            r.record_contact()
            held_state = r.sysm.save()
            if task.pull_distance > 0:
                r.pull()
            if task.carry:
                r.restart(held_state)
                r.carry()
        if task.control is not None and held_state is not None:
            r.restart(held_state)
            task.control(r)
    pos, tan, length_change = shape
    r.extras["static_steps"] = float(r.steps)
    return PhysicsResult(model="contact", stations=r.stations, positions=pos, tip_frame=_frame(pos, tan),
                         length_change=length_change,
                         tendon_tensions=plan.tensions if plan.tensions is not None else np.zeros(0), tip_twist=0.0,
                         solver=SolverInfo(True, r.sysm.newton, time.perf_counter() - t0,
                                           "; ".join([f"{r.sysm.solves} static solves", *r.log])),
                         series=r.series, extras=r.extras)
