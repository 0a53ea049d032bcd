"""The ``wire_delay`` scenario: the tendon commands of one case of the wire-delay study.

Registered as ``registry.SCENARIOS["wire_delay"]``; a study selects it with
``[scenario] name = "wire_delay"`` (format: :mod:`workbench.study.scenarios`).  The commands come
from :func:`.analysis.wire_delay_commands`, the same function the driver
:func:`.analysis.simulate_wire_delay` uses.  Pure numpy.  Checked by
``tests/study/test_scenarios.py``.
"""

from __future__ import annotations

import math
from typing import Any

from ...assumptions import Assumption
from .analysis import wire_delay_commands

__all__ = ["wire_delay", "wire_delay_arm", "GIVEN", "ASSUMED"]

#: Scenario parameters the paper gives (Cojocaru et al. Sec. 5.1).
GIVEN: dict[str, str] = {
    "theta": "paper Sec. 5.1: final bending angle 45 deg",
    "alpha": "paper Sec. 5.1: final direction 45 deg",
    "delay": "paper Sec. 5.1: wire 1 starts 3 s late (the study sweeps 0-3 s)",
    "delayed_wire": "paper Sec. 5.1: wire 1",
}
#: Scenario parameters the paper does not give.
ASSUMED: tuple[Assumption, ...] = (
    Assumption("move_time", "4 s constant-speed wire moves (the paper gives no duration; with 4 s the 3 s delay "
                            "gives its 'approximately 2 %' virtual compression, 3 s -> 2.64 %, 6 s -> 1.32 %): see "
                            "Sensitivity"),
    Assumption("settle_time", "1 s simulated after the last wire stops (ours)"),
)


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
    :func:`.analysis.wire_lengths_tronconic_workbench`; the workbench bending plane is
    ``phi = alpha + pi``) in ``move_time``; wire ``delayed_wire`` starts ``delay`` seconds
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
    if robot.n_sections != 1 or robot.n_tendons != 3:
        raise ValueError(f"scenario wire_delay needs a one-section robot with 3 tendons, got "
                         f"{robot.n_sections} sections and {robot.n_tendons} tendons (set robot.n_sections = 1)")
    if not (move_time > 0 and delay >= 0 and settle_time >= 0 and 0 <= theta < math.pi):
        raise ValueError(f"scenario wire_delay needs move_time > 0, delay >= 0, settle_time >= 0, "
                         f"0 <= theta < pi; got {move_time}, {delay}, {settle_time}, {theta}")
    if delayed_wire not in (0, 1, 2):
        raise ValueError(f"scenario wire_delay: delayed_wire must be 0, 1 or 2, got {delayed_wire!r}")
    cmd = wire_delay_commands(robot, theta=theta, alpha=alpha, move_time=move_time, delay=delay,
                              delayed_wire=delayed_wire)
    return {
        "mode": "length",
        "length_changes": [float(v) for v in cmd.length_changes],
        "start_delays": list(cmd.start_delays),
        "ramp_durations": list(cmd.ramp_durations),
        "analysis": "dynamic",
        "duration": float(delay + move_time + settle_time),
        "ramp_time": float(move_time),
    }


def wire_delay_arm(
    robot,
    *,
    theta: float = math.pi / 4,
    alpha: float = math.pi / 4,
    move_time: float = 4.0,
    delay: float = 0.0,
    delayed_wire: int = 0,
    settle_time: float = 1.0,
    passive: str = "held",
    slack_margin: float = 2e-3,
) -> dict[str, Any]:
    """Cojocaru's wire-delay move of the first section of the whole arm, the upper sections passive.

    Section 1's three wires make the move of :func:`wire_delay` (constant speed to ``(theta,
    alpha)`` in ``move_time``, wire ``delayed_wire`` ``delay`` s late); the upper sections' wires
    follow ``passive`` (:mod:`.arm`: ``"held"`` at their length, the decoupled command;
    ``"compensated"`` by their path change through section 1; ``"slack"`` paid out by
    ``slack_margin`` [m] beyond it).  Simulated time ``delay + move_time + settle_time``.

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes``, ``start_delays``, ``ramp_durations`` (n_tendons,),
        ``analysis = "dynamic"``, ``duration`` [s], ``ramp_time`` [s].
    """
    from .arm import arm_commands

    if not (move_time > 0 and delay >= 0 and settle_time >= 0 and 0 <= theta < math.pi and slack_margin > 0):
        raise ValueError(f"scenario wire_delay_arm needs move_time > 0, delay >= 0, settle_time >= 0, "
                         f"0 <= theta < pi, slack_margin > 0; got {move_time}, {delay}, {settle_time}, {theta}, "
                         f"{slack_margin}")
    if delayed_wire not in (0, 1, 2):
        raise ValueError(f"scenario wire_delay_arm: delayed_wire must be 0, 1 or 2, got {delayed_wire!r}")
    try:
        cmd = arm_commands(robot, theta=theta, alpha=alpha, move_time=move_time, delay=delay,
                           delayed_wire=delayed_wire, passive=passive, slack_margin=slack_margin)
    except ValueError as e:
        raise ValueError(f"scenario wire_delay_arm: {e}") from None
    return {
        "mode": "length",
        "length_changes": [float(v) for v in cmd.length_changes],
        "start_delays": list(cmd.start_delays),
        "ramp_durations": list(cmd.ramp_durations),
        "analysis": "dynamic",
        "duration": float(delay + move_time + settle_time),
        "ramp_time": float(move_time),
    }
