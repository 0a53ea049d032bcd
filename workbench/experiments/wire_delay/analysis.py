"""Cojocaru's wire delay: the wire commands, their CC reading, and the physics driver.

Source: Cojocaru et al., "3D Kinematics Control for a Hyper Redundant Robot"
(``/work/shared/papers/001_*``), Sec. 3.1 (wire lengths, Eq 4-11), Eq 12 (virtual compression
of the central bone), Sec. 5.1 (constant wire speeds from (theta, alpha) = (0, 0) to
(45 deg, 45 deg), wire 1 starting late).

What is here, and who uses it:

- the wire map in the workbench convention (:func:`wire_lengths_tronconic_workbench`, direction
  ``phi = alpha + pi``, offsets, wire angles ``sigma``) and its inverse with a common length
  offset ``e`` (:func:`arc_from_wire_lengths_tronconic_workbench`), the *kinematic virtual compression*;
- the one computation of the wire-delay commands (:func:`wire_delay_commands`) used by the
  scenario (:mod:`.scenario`) and by the driver, and the commanded lengths over time
  (:func:`commanded_wire_lengths`) used by the driver and the report figures (:mod:`.figures`);
- the driver :func:`simulate_wire_delay` (a one-section :mod:`workbench.physics.beam3d` run)
  and its result :class:`WireDelayResult`.

Pure numpy at import (the driver imports the beam model when called).  Checked by
``tests/physics/test_wire_delay.py`` (paper Eq 4-11 written out, the inverse, the driver) and
``tests/study/test_scenarios.py`` (the scenario's commands).  Conventions, errata and the
measured behaviour: ``docs/models.md``, "Wire delay (Cojocaru)".
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass

import numpy as np

from ...models.result import SolverOptions
from ...robot import LoadCase, Robot, TendonActuation

__all__ = [
    "wire_lengths_tronconic_workbench",
    "arc_from_wire_lengths_tronconic_workbench",
    "cc_tip_positions",
    "eq12_compression",
    "WireGeometry",
    "wire_geometry",
    "WireDelayCommands",
    "wire_delay_commands",
    "commanded_wire_lengths",
    "CCReading",
    "cc_reading",
    "WireDelayResult",
    "default_options",
    "simulate_wire_delay",
]


def _sinc(x: np.ndarray) -> np.ndarray:
    return np.sinc(np.asarray(x) / np.pi)


def wire_lengths_tronconic_workbench(theta, phi, length: float, offset_base: float, offset_tip: float,
                                     sigma) -> np.ndarray:
    """Wire lengths of a tronconic section bent into a CC arc (Cojocaru Eq 4-11), workbench convention.

    Thin adapter to :func:`workbench.kinematics.wire_lengths_tronconic_paper` (paper convention:
    direction ``alpha``, disk diameters ``D1, D2``, wires at 0/120/240 deg) in the workbench
    convention (direction ``phi = alpha + pi``, offsets, wire angles ``sigma``).

    Parameters
    ----------
    theta : array_like, shape (...)
        Bending angle [rad] (>= 0).
    phi : array_like, shape (...)
        Bending direction [rad] (workbench convention).
    length : float
        Section (backbone) length H [m].
    offset_base, offset_tip : float
        Wire offsets D1/2 and D2/2 at the section's end disks [m].
    sigma : array_like, shape (3,)
        Wire angles [rad]: ``first + (0, 2 pi/3, 4 pi/3)`` (the paper's layout, any ``first``).

    Returns
    -------
    ndarray, shape (..., 3)
        Wire lengths [m] in the order of ``sigma``.
    """
    from ...kinematics import wire_lengths_tronconic_paper as _paper

    sigma = np.asarray(sigma, dtype=float).reshape(-1)
    rel = np.mod(sigma - sigma[0], 2 * np.pi)
    if sigma.size != 3 or not np.allclose(rel, [0.0, 2 * np.pi / 3, 4 * np.pi / 3], atol=1e-12):
        raise ValueError(f"sigma must hold 3 wire angles at first + (0, 120, 240) deg, got {sigma.tolist()}")
    theta = np.asarray(theta, dtype=float)
    if np.any(theta < 0):
        raise ValueError("theta must be >= 0 (use phi for the direction)")
    # wire n sits at azimuth sigma_n; the paper's wires sit at (0, 120, 240) deg from its x axis
    alpha = np.asarray(phi, dtype=float) - np.pi - sigma[0]
    return _paper(theta, alpha, length, 2.0 * offset_base, 2.0 * offset_tip)


def arc_from_wire_lengths_tronconic_workbench(
    wire_lengths, length: float, offset_base: float, offset_tip: float, sigma, iterations: int = 8
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inverse of :func:`wire_lengths_tronconic_workbench` with a common length offset.

    Solves ``L_cmd,i = L_w,i(theta, phi) + e`` for (theta, phi, e) by Newton's method on
    (theta cos phi, theta sin phi, e), started from the cylindrical closed form.

    Parameters
    ----------
    wire_lengths : array_like, shape (..., n), n >= 3
        Commanded wire lengths [m].
    length, offset_base, offset_tip, sigma
        As in :func:`wire_lengths_tronconic_workbench`.

    Returns
    -------
    theta, phi, e : ndarray, shape (...)
        Bending angle [rad], direction [rad] and the common offset ``e`` [m] (the kinematic
        virtual compression; 0 for CC-consistent lengths, < 0: the bone would be compressed).
    """
    Lc = np.asarray(wire_lengths, dtype=float)
    sigma = np.asarray(sigma, dtype=float).reshape(-1)
    if Lc.shape[-1] != sigma.size or sigma.size < 3:
        raise ValueError(f"wire_lengths must have shape (..., {sigma.size}) with >= 3 wires, got {Lc.shape}")
    d = 0.5 * (offset_base + offset_tip)
    L0 = wire_lengths_tronconic_workbench(0.0, 0.0, length, offset_base, offset_tip, sigma)
    dl = Lc - L0
    n = sigma.size
    x = np.stack(
        [
            -(2.0 / n) * np.sum(dl * np.cos(sigma), axis=-1) / d,
            -(2.0 / n) * np.sum(dl * np.sin(sigma), axis=-1) / d,
            np.mean(dl, axis=-1),
        ],
        axis=-1,
    )

    def F(x):
        th = np.hypot(x[..., 0], x[..., 1])
        ph = np.arctan2(x[..., 1], x[..., 0])
        return wire_lengths_tronconic_workbench(th, ph, length, offset_base, offset_tip, sigma) + x[..., 2:3] - Lc

    h = 1e-7
    for _ in range(iterations):
        r = F(x)
        J = np.empty(r.shape + (3,))
        for k in range(3):
            xp = x.copy()
            xp[..., k] += h
            J[..., k] = (F(xp) - r) / h
        if n == 3:
            step = np.linalg.solve(J, r[..., None])[..., 0]
        else:
            step = np.linalg.lstsq(J.reshape(-1, n, 3)[0], r.reshape(-1, n)[0], rcond=None)[0]
        x = x - step
    theta = np.hypot(x[..., 0], x[..., 1])
    phi = np.arctan2(x[..., 1], x[..., 0])
    return theta, phi, x[..., 2]


def eq12_compression(wire_lengths: np.ndarray, H: float) -> np.ndarray:
    """Literal Cojocaru Eq 12, ``mean(L_w) - H`` [m] (:func:`workbench.kinematics.virtual_compression`)."""
    from ...kinematics import virtual_compression

    return virtual_compression(wire_lengths, H)


def cc_tip_positions(theta: np.ndarray, phi: np.ndarray, length: float) -> np.ndarray:
    """Tip of a CC arc of length ``length`` [m] bent by ``theta`` towards ``phi`` [rad]: shape ``(..., 3)``.

    Base frame, backbone along +z; regular at ``theta = 0`` (written with ``sinc``).
    """
    th = np.asarray(theta, dtype=float)
    sc = _sinc(th / 2.0)
    # r = L (1 - cos th) / th = L sin(th/2) sinc(th/2);  z = L sin(th)/th = L sinc(th)
    r = length * np.sin(th / 2.0) * sc
    z = length * _sinc(th)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


@dataclass(frozen=True, eq=False)
class WireGeometry:
    """The wire layout of a one-section tronconic robot: H [m], offsets D1/2, D2/2 [m], ``sigma`` (3,) [rad]."""

    length: float
    offset_base: float
    offset_tip: float
    sigma: np.ndarray

    def lengths(self, theta, phi) -> np.ndarray:
        """:func:`wire_lengths_tronconic_workbench` of this section, shape ``(..., 3)`` [m]."""
        return wire_lengths_tronconic_workbench(theta, phi, self.length, self.offset_base, self.offset_tip,
                                               self.sigma)


def wire_geometry(robot: Robot) -> WireGeometry:
    """:class:`WireGeometry` of the first section (tip offset = base offset when not tapered)."""
    sec = robot.sections[0]
    g = sec.tendons
    d2 = g.offset_tip if g.offset_tip is not None else g.offset
    return WireGeometry(sec.length, g.offset, d2, np.asarray(g.angles, dtype=float))


@dataclass(frozen=True, eq=False)
class WireDelayCommands:
    """The motor commands of one wire-delay move (all shape (3,), wire order of ``sigma``).

    Attributes
    ----------
    rest_lengths, final_lengths : ndarray
        Wire lengths straight and at the target arc [m].
    start_delays, ramp_durations : tuple of float
        Start of each wire's constant-speed move and its duration [s].
    """

    rest_lengths: np.ndarray
    final_lengths: np.ndarray
    start_delays: tuple[float, ...]
    ramp_durations: tuple[float, ...]

    @property
    def length_changes(self) -> np.ndarray:
        """``final_lengths - rest_lengths`` [m]."""
        return self.final_lengths - self.rest_lengths


def wire_delay_commands(robot: Robot, *, theta: float, alpha: float, move_time: float, delay: float,
                        delayed_wire: int) -> WireDelayCommands:
    """Cojocaru's constant-speed move to ``(theta, alpha)`` with wire ``delayed_wire`` ``delay`` s late.

    Every wire moves from its straight length to its kinematic length at ``(theta, phi = alpha + pi)``
    in ``move_time``.  No checks here: the callers (scenario, driver) check their inputs with
    their own wording.

    Parameters
    ----------
    robot : Robot
        One section with three tendons (:func:`wire_geometry` reads the first section).
    theta, alpha : float
        Target bending angle and the paper's direction angle [rad].
    move_time, delay : float
        Duration of every wire's move and start delay of the late wire [s].
    delayed_wire : int
        Index of the late wire (0, 1 or 2).

    Returns
    -------
    WireDelayCommands
    """
    geo = wire_geometry(robot)
    L0 = geo.lengths(0.0, 0.0)
    Lf = geo.lengths(theta, alpha + math.pi)
    starts = tuple(float(delay) if i == delayed_wire else 0.0 for i in range(3))
    return WireDelayCommands(L0, Lf, starts, (float(move_time),) * 3)


def commanded_wire_lengths(robot: Robot, actuation: TendonActuation, t, ramp_time: float) -> np.ndarray:
    """Wire lengths the motors command at times ``t`` [s]: straight lengths + ``actuation.command_at``.

    Returns
    -------
    ndarray, shape (len(t), 3)
        [m].
    """
    return wire_geometry(robot).lengths(0.0, 0.0) + actuation.command_at(t, ramp_time)


@dataclass(frozen=True, eq=False)
class CCReading:
    """The CC configuration nearest to commanded wire lengths (arrays share the leading shape).

    Attributes
    ----------
    theta, phi : ndarray
        Bending angle and direction [rad].
    virtual_compression : ndarray
        The common offset ``e`` [m] (:func:`arc_from_wire_lengths_tronconic_workbench`).
    tip : ndarray, shape (..., 3)
        Tip of that CC arc [m] (:func:`cc_tip_positions`).
    """

    theta: np.ndarray
    phi: np.ndarray
    virtual_compression: np.ndarray
    tip: np.ndarray


def cc_reading(wire_lengths, geometry: WireGeometry) -> CCReading:
    """Read commanded wire lengths ``(..., 3)`` [m] as a CC arc plus a common offset (see :class:`CCReading`)."""
    g = geometry
    th, ph, e = arc_from_wire_lengths_tronconic_workbench(wire_lengths, g.length, g.offset_base, g.offset_tip, g.sigma)
    return CCReading(th, ph, e, cc_tip_positions(th, ph, g.length))


@dataclass(frozen=True)
class WireDelayResult:
    """Time series of one wire-delay simulation (all arrays share the first axis ``k``).

    Attributes
    ----------
    time : ndarray, shape (k,)
        [s].
    commanded_wire_lengths : ndarray, shape (k, 3)
        Paper wire lengths commanded by the motors [m].
    virtual_compression : ndarray, shape (k,)
        Kinematic virtual compression ``e`` [m] (negative = bone would be compressed;
        :func:`arc_from_wire_lengths_tronconic_workbench`).
    virtual_compression_eq12 : ndarray, shape (k,)
        Literal Eq 12: ``mean(L_cmd) - H`` [m] (:func:`eq12_compression`; non-zero, ~+7e-5 m,
        already for the straight tronconic section).
    length_change : ndarray, shape (k,)
        Real backbone length change from the physics model [m].
    tendon_tensions, tendon_stretch : ndarray, shape (k, 3)
        [N], [m] (current rope path length minus rest length).
    tip_twist : ndarray, shape (k,)
        [rad] (see :mod:`workbench.physics.beam3d`).
    tip_position, tip_position_cc : ndarray, shape (k, 3)
        Physics tip and the CC tip of the arc fitted to the commanded lengths [m].
    tip_error : ndarray, shape (k,)
        ``|tip_position - tip_position_cc|`` [m].
    section_length : float
        H [m].
    delay, move_time : float
        Delay of the late wire and duration of each wire's constant-speed move [s].
    n_elements, n_steps : int
        Discretisation.
    wall_time : float
        Seconds spent in the physics model.
    """

    time: np.ndarray
    commanded_wire_lengths: np.ndarray
    virtual_compression: np.ndarray
    virtual_compression_eq12: np.ndarray
    length_change: np.ndarray
    tendon_tensions: np.ndarray
    tendon_stretch: np.ndarray
    tip_twist: np.ndarray
    tip_position: np.ndarray
    tip_position_cc: np.ndarray
    tip_error: np.ndarray
    section_length: float
    delay: float
    move_time: float
    n_elements: int
    n_steps: int
    wall_time: float


def default_options() -> SolverOptions:
    """Options used when none are given: 8 elements, eyelets, 5 ms steps, no damping, spectral radius 0.8.

    A quick look only: with 5 disks inside 8 elements, undamped, the snapped state of a late wire
    depends on the mesh (``docs/models.md``, "Wire delay"); the committed study runs 40 elements at
    2.5 ms with stiffness-proportional damping ``damping = 2.7e-4`` s (zeta = 2 % on the first mode)."""
    return SolverOptions(n_elements=8, tendon_model="eyelets", time_step=5e-3, damping=0.0, spectral_radius=0.8)


def _check_driver_inputs(robot: Robot, move_time: float, delay: float, theta_final: float,
                         delayed_wire: int) -> None:
    if robot.n_sections != 1 or robot.n_tendons != 3:
        raise ValueError(
            f"wire delay needs a one-section robot with 3 tendons, got {robot.n_sections} sections, "
            f"{robot.n_tendons} tendons"
        )
    if not (move_time > 0 and delay >= 0 and theta_final >= 0):
        raise ValueError(f"need move_time > 0, delay >= 0, theta_final >= 0; got {move_time}, {delay}, {theta_final}")
    if delayed_wire not in (0, 1, 2):
        raise ValueError(f"delayed_wire must be 0, 1 or 2, got {delayed_wire!r}")


def simulate_wire_delay(
    robot: Robot | None = None,
    *,
    theta_final: float = math.pi / 4,
    alpha_final: float = math.pi / 4,
    move_time: float = 4.0,
    delay: float = 3.0,
    delayed_wire: int = 0,
    duration: float | None = None,
    pretension: float = 20.0,
    options: SolverOptions | None = None,
) -> WireDelayResult:
    """Run the wire-delay experiment on a one-section, three-wire robot.

    Each wire moves at constant speed from its straight length to its length at
    (theta_final, alpha_final) in ``move_time``; wire ``delayed_wire`` starts ``delay``
    seconds late (``delay = 0``: the paper's delay-free move, Fig 8).

    Parameters
    ----------
    robot : Robot, optional
        One section with exactly three tendons (default: ``build_preset("cojocaru_tronconic", n_sections=1)``).
    theta_final, alpha_final : float
        Target bending angle and the paper's direction alpha [rad] (phi = alpha + pi).
    move_time : float
        Duration of every wire's move [s] (default 4 s).
    delay : float
        Start delay of the late wire [s] (paper: 3 s).
    delayed_wire : int
        Index of the late wire (paper: wire 1 -> 0).
    duration : float, optional
        Simulated time [s]; default ``delay + move_time + 3`` (10 s with the defaults).
    pretension : float
        Tendon pretension in the straight reference [N].
    options : SolverOptions, optional
        Default :func:`default_options`.

    Returns
    -------
    WireDelayResult
    """
    from ...physics.beam3d import run as beam3d_run

    if robot is None:
        from ...robot.presets import build_preset

        robot = build_preset("cojocaru_tronconic", n_sections=1)
    _check_driver_inputs(robot, move_time, delay, theta_final, delayed_wire)
    options = default_options() if options is None else options
    if duration is None:
        duration = delay + move_time + 3.0
    cmd = wire_delay_commands(robot, theta=theta_final, alpha=alpha_final, move_time=move_time, delay=delay,
                              delayed_wire=delayed_wire)
    act = TendonActuation("length", tuple(cmd.length_changes), start_times=cmd.start_delays,
                          ramp_durations=cmd.ramp_durations, pretension=pretension)
    load = LoadCase(actuation=act, analysis="dynamic", duration=duration, ramp_time=move_time)
    t0 = _time.perf_counter()
    res = beam3d_run(robot, load, options)
    wall = _time.perf_counter() - t0
    t = res.time
    H = robot.sections[0].length
    Lcmd = commanded_wire_lengths(robot, act, t, move_time)
    cc = cc_reading(Lcmd, wire_geometry(robot))
    tip = res.series["tip_position"]
    return WireDelayResult(
        time=t,
        commanded_wire_lengths=Lcmd,
        virtual_compression=cc.virtual_compression,
        virtual_compression_eq12=eq12_compression(Lcmd, H),
        length_change=res.series["length_change"],
        tendon_tensions=res.series["tendon_tensions"],
        tendon_stretch=res.series["tendon_stretch"],
        tip_twist=res.series["tip_twist"],
        tip_position=tip,
        tip_position_cc=cc.tip,
        tip_error=np.linalg.norm(tip - cc.tip, axis=1),
        section_length=H,
        delay=float(delay),
        move_time=float(move_time),
        n_elements=int(res.extras["n_elements"]),
        n_steps=int(res.extras["n_steps"]),
        wall_time=wall,
    )
