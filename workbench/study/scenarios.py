"""Scenarios: named pure functions that compute a case's tendon commands from a few parameters.

Some studies cannot be written as "bend angle -> CC tendon map": the command of each case
comes from a controller or an experiment protocol (a path sample of a resolved-rate
trajectory, a delayed wire).  A study names such a scenario in an optional ``[scenario]``
section; its other keys are the scenario's parameters (typed by the function's keyword
defaults, exactly like robot parameters are typed by the preset's) and can be swept as
``"scenario.<key>"`` axes::

    [scenario]
    name = "wire_delay"     # a key of SCENARIOS
    delay = 0.0             # keyword parameters of the function (others keep their defaults)

    [sweep]
    product = { "scenario.delay" = [0.0, 1.0, 2.0, 3.0] }

Each scenario is ``fn(robot, **params) -> dict`` of ``[load]`` fields (``mode``,
``length_changes``, ``start_delays``, ``ramp_durations``, ``analysis``, ``duration``,
``ramp_time``); these replace the ``[load]`` values of the case before the
:class:`~workbench.robot.LoadCase` is built, so models stay ``run(robot, load, options)``.
Unknown scenarios or parameters are reported when the study is loaded, and every case's
scenario is evaluated (dry run) during validation, so infeasible commands fail up front.
The resolved scenario parameters are part of the case parameters and hence of ``case_id``.
Scenario functions are pure (numpy only, no Exudyn).
"""

from __future__ import annotations

import inspect
import math
from typing import Any, Callable, Mapping

import numpy as np

__all__ = [
    "SCENARIOS",
    "SCENARIO_LOAD_FIELDS",
    "scenario_parameters",
    "load_with_scenario",
    "wire_delay",
    "hannan_walker_line",
]

#: ``[load]`` fields a scenario may set.
SCENARIO_LOAD_FIELDS = frozenset(
    {"mode", "length_changes", "tensions", "start_delays", "ramp_durations", "analysis", "duration", "ramp_time",
     "pretension"}
)


# ---------------------------------------------------------------------------------------
# wire delay (Cojocaru et al., papers/001_, Sec. 5.1)
# ---------------------------------------------------------------------------------------
def wire_delay(
    robot,
    *,
    theta: float = math.pi / 4,
    alpha: float = math.pi / 4,
    move_time: float = 4.0,
    delay: float = 0.0,
    delayed_wire: int = 0,
    settle_time: float = 1.0,
) -> dict[str, Any]:
    """Cojocaru's constant-speed wire move with one wire started late.

    Every wire of the (one-section, three-wire, tronconic) robot moves at constant speed from
    its straight length to its kinematic length at ``(theta, alpha)`` (paper Eq 5-11, via
    :func:`workbench.physics.wire_delay.wire_lengths_tronconic`; the workbench bending plane
    is ``phi = alpha + pi``) in ``move_time``; wire ``delayed_wire`` starts ``delay`` seconds
    late.  The simulated time is ``delay + move_time + settle_time``.

    Parameters
    ----------
    robot : Robot
        One section with exactly three tendons.
    theta, alpha : float
        Target bending angle and the paper's direction angle [rad] (paper: 45 deg, 45 deg).
    move_time : float
        Duration of each wire's ramp [s].
    delay : float
        Start delay of the late wire [s] (paper: 3 s), >= 0.
    delayed_wire : int
        Index of the late wire (paper's wire 1 -> 0).
    settle_time : float
        Simulated time after the last wire stops [s], >= 0.

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes`` (3,) [m], ``start_delays`` (3,) [s],
        ``ramp_durations`` (3,) [s], ``analysis = "dynamic"``, ``duration`` [s],
        ``ramp_time`` [s].
    """
    from ..physics.wire_delay import wire_lengths_tronconic  # pure numpy (imports no Exudyn)

    if robot.n_sections != 1 or robot.n_tendons != 3:
        raise ValueError(f"scenario wire_delay needs a one-section robot with 3 tendons, got "
                         f"{robot.n_sections} sections and {robot.n_tendons} tendons (set robot.n_sections = 1)")
    if not (move_time > 0 and delay >= 0 and settle_time >= 0 and 0 <= theta < math.pi):
        raise ValueError(f"scenario wire_delay needs move_time > 0, delay >= 0, settle_time >= 0, "
                         f"0 <= theta < pi; got {move_time}, {delay}, {settle_time}, {theta}")
    if delayed_wire not in (0, 1, 2):
        raise ValueError(f"scenario wire_delay: delayed_wire must be 0, 1 or 2, got {delayed_wire!r}")
    sec = robot.sections[0]
    g = sec.tendons
    d1 = g.offset
    d2 = g.offset_tip if g.offset_tip is not None else g.offset
    sigma = np.asarray(g.angles, dtype=float)
    L0 = wire_lengths_tronconic(0.0, 0.0, sec.length, d1, d2, sigma)
    Lf = wire_lengths_tronconic(theta, alpha + math.pi, sec.length, d1, d2, sigma)
    return {
        "mode": "length",
        "length_changes": [float(v) for v in (Lf - L0)],
        "start_delays": [float(delay) if i == delayed_wire else 0.0 for i in range(3)],
        "ramp_durations": [float(move_time)] * 3,
        "analysis": "dynamic",
        "duration": float(delay + move_time + settle_time),
        "ramp_time": float(move_time),
    }


# ---------------------------------------------------------------------------------------
# Hannan & Walker (papers/000_): resolved-rate straight line and a grasp configuration
# ---------------------------------------------------------------------------------------
def hannan_walker_line(
    robot,
    *,
    shape: str = "line",
    start_x: float = 0.25,
    start_z: float = 0.70,
    end_x: float = 0.35,
    end_z: float = 0.60,
    n_samples: int = 9,
    sample: int = 0,
    grasp_bend_angles: list | None = None,
) -> dict[str, Any]:
    """Cable commands of the Hannan & Walker trunk for one sample of a CC plan.

    The planar CC resolved-rate controller (paper Eq 10-11, :func:`workbench.kinematics.follow_path`,
    start curvatures ``0.1 / L``) tracks the straight end-point line from ``(start_x, start_z)``
    to ``(end_x, end_z)`` (base x-z plane) in ``n_samples`` samples; the case is sample
    ``sample`` (0-based).  ``shape = "line"``: no null-space task (paper's first example,
    q_0 = 0).  ``shape = "grasp"``: the null-space term of Eq 11 pulls the configuration
    towards the grasp configuration ``q_d`` given as section bend angles
    ``grasp_bend_angles`` (kappa_i l_i [rad], planar sign: > 0 bends towards base +x) while the
    tip stays on the line (paper's second example: approach with the grasp configuration).

    Either way the section curvatures become equal joint angles per section (paper Eq 2-3) and
    cable length changes from the jointed geometry of Eq 1
    (:func:`workbench.physics.hannan_walker_trajectory.cable_changes_from_joint_angles`), the
    exact cable geometry of the spring-link chain.

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes`` (n_tendons,) [m].
    """
    from ..kinematics import follow_path, line_path
    from ..kinematics.hannan_walker import joint_angle_from_curvature
    from ..physics.hannan_walker_trajectory import cable_changes_from_joint_angles  # numpy only at import

    ell = np.asarray(robot.section_lengths, dtype=float)
    ns = robot.n_sections
    if shape not in ("line", "grasp"):
        raise ValueError(f"scenario hannan_walker_line: shape must be 'line' or 'grasp', got {shape!r}")
    if n_samples < 2 or not 0 <= sample < n_samples:
        raise ValueError(f"scenario hannan_walker_line needs n_samples >= 2 and 0 <= sample < n_samples, "
                         f"got n_samples = {n_samples}, sample = {sample}")
    kappa_d = None
    if shape == "grasp":
        if grasp_bend_angles is None or len(grasp_bend_angles) != ns:
            raise ValueError(f"scenario hannan_walker_line: shape = 'grasp' needs grasp_bend_angles with {ns} "
                             f"entries (one bend angle per section) [rad], got {grasp_bend_angles!r}")
        kappa_d = np.asarray(grasp_bend_angles, dtype=float) / ell
    # base (x, z) -> planar (-x, z)
    path = line_path(np.array([-start_x, start_z]), np.array([-end_x, end_z]), n_samples)
    pr = follow_path(path, np.full(ns, 0.1 / robot.length), ell, kappa_d=kappa_d)
    if not pr.success:
        raise ValueError(f"scenario hannan_walker_line: the CC resolved-rate controller did not track the "
                         f"line (max error {np.max(pr.error):.3g} m); the line is out of reach")
    kappa = np.asarray(pr.q, dtype=float)[sample]
    n_links = 16
    per = n_links // ns
    q = np.repeat(joint_angle_from_curvature(kappa, ell, per), per, axis=-1)
    dl = cable_changes_from_joint_angles(q, robot, n_links)
    return {"mode": "length", "length_changes": [float(v) for v in np.asarray(dl).reshape(-1)]}


SCENARIOS: dict[str, Callable[..., dict[str, Any]]] = {
    "wire_delay": wire_delay,
    "hannan_walker_line": hannan_walker_line,
}


def scenario_parameters(name: str) -> dict[str, Any]:
    """Keyword parameters of scenario ``name`` with their defaults.

    Raises
    ------
    KeyError
        Unknown scenario (message lists the known ones).
    """
    if name not in SCENARIOS:
        raise KeyError(f"unknown scenario {name!r} (known: {', '.join(sorted(SCENARIOS))})")
    sig = inspect.signature(SCENARIOS[name])
    return {p.name: p.default for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY}


def load_with_scenario(robot, load: Mapping[str, Any], scenario: Mapping[str, Any] | None) -> dict[str, Any]:
    """The ``[load]`` parameters of a case with the scenario's fields applied.

    Parameters
    ----------
    robot : Robot
    load : mapping
        Resolved ``[load]`` parameters.
    scenario : mapping or None
        ``{"name": ..., **parameters}`` (resolved ``[scenario]``); ``None`` returns ``load``.

    Returns
    -------
    dict
        A new load dict; the scenario's fields replace ``load``'s and clear the other command
        fields (``bend_angle``, ``tensions``, ``length_changes``) it does not set.
    """
    out = dict(load)
    if not scenario:
        return out
    params = dict(scenario)
    name = params.pop("name")
    fields = SCENARIOS[name](robot, **params)
    bad = sorted(set(fields) - SCENARIO_LOAD_FIELDS)
    if bad:  # a programming error in the scenario, not user input
        raise RuntimeError(f"scenario {name!r} returned unknown load fields {bad}")
    for k in ("bend_angle", "tensions", "length_changes"):
        out[k] = None
    out.update(fields)
    return out
