"""Cojocaru et al.'s wire-delay experiment on one tronconic 3-wire section, in physics.

Source: Cojocaru et al., "3D Kinematics Control for a Hyper Redundant Robot"
(``/work/shared/papers/001_*``), Sec. 3.1 (wire lengths, Eq 4-11), Eq 12 (virtual
compression of the central bone), Sec. 5.1 (constant wire speeds from
(theta, alpha) = (0, 0) to (45 deg, 45 deg); wire 1 starting 3 s late compresses the bone
"by approximately 2 %").

Here the section is the spatial geometrically exact beam of :mod:`workbench.physics.beam3d`
with three length-controlled tendons (eyelets at the disks, steel wires of stiffness EA_t).
The wire commands are the paper's kinematic wire lengths; the physics then shows how the
kinematic incompatibility of a delayed wire is really taken up: backbone compression,
tendon stretch (tension), twist and a tip error against the constant-curvature (CC) shape.

Conventions and errata
----------------------
* Bending direction: the paper's alpha puts wire 1 (``alpha_1 = -alpha``) on the outside
  of the bend (radius ``R + D/2 cos(alpha_1)``, Eq 9); the workbench's ``phi`` is the
  direction the section bends towards, so ``phi = alpha + pi`` and the radius of wire i
  is ``R - d cos(sigma_i - phi)``.
* Eq 6-8 treat each wire as a circular arc through its two end points at radii
  ``L_i1``, ``L_i2`` from the centre of curvature (the kinematics module evaluates them in
  a form regular at theta = 0, the straight slanted wire ``sqrt(H^2 + (d1 - d2)^2 c^2)``);
  checked against Eq 6-8 written out literally in the tests.  The physics tendon runs in
  straight chords between the disks, which is shorter than the paper's arc-wire by about
  ``theta^2 / (24 n^2)`` per unit length (n disks): with 5 disks and theta = 45 deg the
  commanded (arc) lengths are ~3e-4 m too long for all wires, a virtual *extension* an
  order larger than the pretension stretch, so the outer wire goes slack in the
  delay-free move.
* Eq 12 (``mean(L_w) = L``) holds exactly only for the cylindrical section (D1 = D2); for
  the tronconic section the mean of consistent wire lengths differs from H at second
  order.  The *kinematic virtual compression* reported here is therefore the common
  offset ``e`` in ``L_cmd,i = L_w,i(theta, phi) + e`` solved together with (theta, phi)
  (3 equations, 3 unknowns): ``e = 0`` exactly when the commanded lengths are a CC
  configuration; ``e < 0`` means the wires are collectively too short, i.e. the bone
  would have to be compressed.  The literal Eq 12 value ``mean(L_cmd) - H`` is reported
  as well.

Measured behaviour (defaults: ``cojocaru_tronconic(n_sections=1)`` = H 0.35 m, 4 mm
steel rod, D 100 -> 80 mm, 1 mm steel wires (EA_t 1.65e5 N), 5 disks, 20 N pretension;
8 elements, 5 ms steps, no material damping (Exudyn's GE beam has none); 4 s moves to
(45 deg, 45 deg), wire 1 (which must lengthen) 3 s late, 10 s simulated):

* kinematic virtual compression e reaches -6.23 mm (-1.78 % of H) at t = 3 s, the
  paper's "approximately 2 %";
* for t < ~2 s the physics splits e like springs in series: backbone length change =
  e * 3 k_t / (3 k_t + k_b) (k_t = EA_t/H, k_b = EA/H; 16 % of e here, within 1 %), all
  three wires tighten equally (~840 N at t = 1 s) and the tip stays on the CC arc
  (0.7 mm);
* at ~1.7 kN per wire (t ~ 2 s) the backbone compression saturates at -0.66 mm
  (-0.19 %) and the section snaps into a strongly bent shape that is not a CC arc
  (curvature up to ~9 1/m against the CC 2.2 1/m, tip 0.15 m off the CC tip, tip twist
  up to 2.5e-2 rad) until wire 1 has caught up (tip error 17 mm at t = 5 s, 3 mm at
  t = 6 s): "a wrong solution ... that cannot
  be described with only 2 DOF" (Sec. 5.1), rather than a 2 % compression of the bone;
* without delay e stays below 1.8e-6 m and the backbone shortens only by sum(T) H / EA
  of the bending tensions (about 2e-5 m); the outer wire goes slack (see the chord
  remark above) and the final tip is 2-3 mm off the CC tip.

The forward wire map and Eq 12 come from :mod:`workbench.kinematics` (merged from the
kinematics branch: ``wire_lengths_tronconic``, ``virtual_compression``); the inverse with a
common offset (:func:`arc_from_wire_lengths_tronconic`) is local.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass

import numpy as np

from ..models.result import SolverOptions
from ..robot import LoadCase, Robot, TendonActuation

__all__ = [
    "wire_lengths_tronconic",
    "arc_from_wire_lengths_tronconic",
    "WireDelayResult",
    "simulate_wire_delay",
]


def _sinc(x: np.ndarray) -> np.ndarray:
    return np.sinc(np.asarray(x) / np.pi)


def wire_lengths_tronconic(theta, phi, length: float, offset_base: float, offset_tip: float, sigma) -> np.ndarray:
    """Wire lengths of a tronconic section bent into a CC arc (Cojocaru Eq 4-11).

    Thin adapter to :func:`workbench.kinematics.wire_lengths_tronconic` (paper convention:
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
        Wire angles [rad]: ``first + (0, 2 pi/3, 4 pi/3)`` (the paper's layout, any
        ``first``).

    Returns
    -------
    ndarray, shape (..., 3)
        Wire lengths [m] in the order of ``sigma``.
    """
    from ..kinematics import wire_lengths_tronconic as _paper

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


def arc_from_wire_lengths_tronconic(
    wire_lengths, length: float, offset_base: float, offset_tip: float, sigma, iterations: int = 8
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inverse of :func:`wire_lengths_tronconic` with a common length offset.

    Solves ``L_cmd,i = L_w,i(theta, phi) + e`` for (theta, phi, e) by Newton's method on
    (theta cos phi, theta sin phi, e), started from the cylindrical closed form.

    Parameters
    ----------
    wire_lengths : array_like, shape (..., n), n >= 3
        Commanded wire lengths [m].
    length, offset_base, offset_tip, sigma
        As in :func:`wire_lengths_tronconic`.

    Returns
    -------
    theta, phi, e : ndarray, shape (...)
        Bending angle [rad], direction [rad] and the common offset ``e`` [m] (the kinematic
        virtual compression; 0 for CC-consistent lengths).
    """
    Lc = np.asarray(wire_lengths, dtype=float)
    sigma = np.asarray(sigma, dtype=float).reshape(-1)
    if Lc.shape[-1] != sigma.size or sigma.size < 3:
        raise ValueError(f"wire_lengths must have shape (..., {sigma.size}) with >= 3 wires, got {Lc.shape}")
    d = 0.5 * (offset_base + offset_tip)
    L0 = wire_lengths_tronconic(0.0, 0.0, length, offset_base, offset_tip, sigma)
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
        return wire_lengths_tronconic(th, ph, length, offset_base, offset_tip, sigma) + x[..., 2:3] - Lc

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


def _eq12(wire_lengths: np.ndarray, H: float) -> np.ndarray:
    from ..kinematics import virtual_compression

    return virtual_compression(wire_lengths, H)


def _cc_tip(theta: np.ndarray, phi: np.ndarray, length: float) -> np.ndarray:
    th = np.asarray(theta, dtype=float)
    sc = _sinc(th / 2.0)
    # r = L (1 - cos th) / th = L sin(th/2) sinc(th/2);  z = L sin(th)/th = L sinc(th)
    r = length * np.sin(th / 2.0) * sc
    z = length * _sinc(th)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=-1)


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
        see the module docstring).
    virtual_compression_eq12 : ndarray, shape (k,)
        Literal Eq 12: ``mean(L_cmd) - H`` [m] (``workbench.kinematics.virtual_compression``;
        non-zero, ~+7e-5 m, already for the straight tronconic section).
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
    """Options used when none are given: 8 elements, eyelets, 5 ms steps, no material damping
    (the 3-D beam has none, see :mod:`workbench.physics.beam3d`), spectral radius 0.8."""
    return SolverOptions(n_elements=8, tendon_model="eyelets", time_step=5e-3, damping=0.0, spectral_radius=0.8)


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
        One section with exactly three tendons (default:
        ``cojocaru_tronconic(n_sections=1)``).
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
    from .beam3d import run as beam3d_run

    if robot is None:
        from ..robot.presets.cojocaru import cojocaru_tronconic

        robot = cojocaru_tronconic(n_sections=1)
    if robot.n_sections != 1 or robot.n_tendons != 3:
        raise ValueError(
            f"wire delay needs a one-section robot with 3 tendons, got {robot.n_sections} sections, "
            f"{robot.n_tendons} tendons"
        )
    if not (move_time > 0 and delay >= 0 and theta_final >= 0):
        raise ValueError(f"need move_time > 0, delay >= 0, theta_final >= 0; got {move_time}, {delay}, {theta_final}")
    if delayed_wire not in (0, 1, 2):
        raise ValueError(f"delayed_wire must be 0, 1 or 2, got {delayed_wire!r}")
    options = default_options() if options is None else options
    if duration is None:
        duration = delay + move_time + 3.0
    sec = robot.sections[0]
    g = sec.tendons
    H = sec.length
    d1 = g.offset
    d2 = g.offset_tip if g.offset_tip is not None else g.offset
    sigma = np.asarray(g.angles)
    phi_final = alpha_final + math.pi
    L0 = wire_lengths_tronconic(0.0, 0.0, H, d1, d2, sigma)
    Lf = wire_lengths_tronconic(theta_final, phi_final, H, d1, d2, sigma)
    starts = tuple(delay if i == delayed_wire else 0.0 for i in range(3))
    act = TendonActuation(
        "length", tuple(Lf - L0), start_times=starts, ramp_durations=(move_time,) * 3, pretension=pretension
    )
    load = LoadCase(actuation=act, analysis="dynamic", duration=duration, ramp_time=move_time)
    t0 = _time.perf_counter()
    res = beam3d_run(robot, load, options)
    wall = _time.perf_counter() - t0
    t = res.time
    Lcmd = L0 + act.command_at(t, move_time)
    th, ph, e = arc_from_wire_lengths_tronconic(Lcmd, H, d1, d2, sigma)
    tip_cc = _cc_tip(th, ph, H)
    tip = res.series["tip_position"]
    return WireDelayResult(
        time=t,
        commanded_wire_lengths=Lcmd,
        virtual_compression=e,
        virtual_compression_eq12=_eq12(Lcmd, H),
        length_change=res.series["length_change"],
        tendon_tensions=res.series["tendon_tensions"],
        tendon_stretch=res.series["tendon_stretch"],
        tip_twist=res.series["tip_twist"],
        tip_position=tip,
        tip_position_cc=tip_cc,
        tip_error=np.linalg.norm(tip - tip_cc, axis=1),
        section_length=H,
        delay=float(delay),
        move_time=float(move_time),
        n_elements=int(res.extras["n_elements"]),
        n_steps=int(res.extras["n_steps"]),
        wall_time=wall,
    )
