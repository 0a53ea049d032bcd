"""The Hannan & Walker scenarios: cable commands of one sample of a CC line plan.

``hannan_walker_line`` (``registry.SCENARIOS["hannan_walker_line"]``, format:
:mod:`workbench.study.scenarios`): the planar plan :func:`.replay.cc_cable_plan`, the same pipeline
the driver :func:`.replay.replay_hannan_walker` replays.  ``hannan_walker_spatial``: the spatial plan
of the 32-DOF, 16-cable trunk, :func:`.spatial.cc_spatial_cable_plan` (Eq 1 per plane).  Pure numpy
(imports the spring-link module, which imports Exudyn only when it solves).  Checked by
``tests/study/test_scenarios.py``, ``tests/experiments/test_hannan_walker_plan.py`` and
``tests/experiments/test_hannan_walker_3d.py``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...assumptions import Assumption
from .replay import cc_cable_plan

__all__ = ["hannan_walker_line", "hannan_walker_spatial", "GIVEN", "ASSUMED"]

#: Scenario parameters the paper gives (Hannan & Walker Sec. 5, Figs 7-12).
GIVEN: dict[str, str] = {
    "shape": "paper Sec. 5: the straight-line example without (line) and with the null-space task (grasp)",
    "n_samples": "paper Figs 7-12: six snapshots",
}
#: Scenario parameters the paper does not give (its photos carry no numbers).
ASSUMED: tuple[Assumption, ...] = (
    Assumption("start_x", "line start (0.25, 0.70) m, read off the paper's figures (no numbers given)"),
    Assumption("start_z", "see start_x"),
    Assumption("end_x", "line end (0.35, 0.60) m (no numbers given)"),
    Assumption("end_z", "see end_x"),
    Assumption("grasp_bend_angles", "q_d = (-0.3, 0.3, 1.0, 1.6) rad per section, a curled tip (not given)"),
)


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
    (:func:`.replay.cable_changes_from_joint_angles`), the exact cable geometry of the
    spring-link chain.

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes`` (n_tendons,) [m].
    """
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
    plan = cc_cable_plan(robot, (start_x, start_z), (end_x, end_z), n_samples, kappa_d=kappa_d, n_links=16,
                         sample=sample)
    if not plan.success:
        raise ValueError(f"scenario hannan_walker_line: the CC resolved-rate controller did not track the "
                         f"line (max error {np.max(plan.tracking_error):.3g} m); the line is out of reach")
    return {"mode": "length", "length_changes": [float(v) for v in np.asarray(plan.cable_changes).reshape(-1)]}


def hannan_walker_spatial(
    robot,
    *,
    shape: str = "line",
    start_x: float = 0.25,
    start_y: float = -0.10,
    start_z: float = 0.70,
    end_x: float = 0.15,
    end_y: float = 0.25,
    end_z: float = 0.60,
    n_samples: int = 6,
    sample: int = 0,
    grasp_bend_angles: list | None = None,
) -> dict[str, Any]:
    """Cable commands of the 32-DOF trunk (16 cables) for one sample of a spatial CC plan.

    The spatial CC resolved-rate controller (Eq 10-11 with the spatial Jacobian) tracks the
    straight tip line ``(start_x, start_y, start_z) -> (end_x, end_y, end_z)`` (base frame, m) in
    ``n_samples`` samples; the case is sample ``sample`` (0-based).  ``shape = "grasp"``: the
    null-space term pulls the section bend angles towards ``grasp_bend_angles``
    (``kappa_i l_i`` [rad]; the bending planes stay free for the task).  The curvatures become
    per-plane equal joint angles and cable changes by Eq 1 per plane
    (:func:`.spatial.cc_spatial_cable_plan`).

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes`` (n_tendons,) [m].
    """
    from .spatial import cc_spatial_cable_plan

    ns = robot.n_sections
    if shape not in ("line", "grasp"):
        raise ValueError(f"scenario hannan_walker_spatial: shape must be 'line' or 'grasp', got {shape!r}")
    if n_samples < 2 or not 0 <= sample < n_samples:
        raise ValueError(f"scenario hannan_walker_spatial needs n_samples >= 2 and 0 <= sample < n_samples, "
                         f"got n_samples = {n_samples}, sample = {sample}")
    kappa_d = None
    if shape == "grasp":
        if grasp_bend_angles is None or len(grasp_bend_angles) != ns:
            raise ValueError(f"scenario hannan_walker_spatial: shape = 'grasp' needs grasp_bend_angles with {ns} "
                             f"entries (one bend angle per section) [rad], got {grasp_bend_angles!r}")
        kappa_d = np.asarray(grasp_bend_angles, dtype=float) / np.asarray(robot.section_lengths, dtype=float)
    plan = cc_spatial_cable_plan(robot, (start_x, start_y, start_z), (end_x, end_y, end_z), n_samples,
                                 kappa_d=kappa_d, n_links=16, sample=sample)
    if not plan.success:
        raise ValueError(f"scenario hannan_walker_spatial: the CC resolved-rate controller did not track the "
                         f"line (max error {np.max(plan.tracking_error):.3g} m); the line is out of reach")
    return {"mode": "length", "length_changes": [float(v) for v in np.asarray(plan.cable_changes).reshape(-1)]}
