"""The ``whole_arm_wrap`` scenario: the CC wrap plan of one grasp case, and what the physics does with it.

Registered as ``registry.SCENARIOS["whole_arm_wrap"]`` (format: :mod:`workbench.study.scenarios`),
used by studies of the ``grasp`` kind (:mod:`.kind`).  The function returns the case's ``[load]``
fields -- the CC tendon tensions of the wrap (:func:`.plan.wrap_plan`), so that a study's load
records what the physics ran -- and validates every parameter when the study is loaded (a dry
run per case).  :func:`grasp_case` turns the same parameters into the plan and the
:class:`~.tasks.GraspTask` the worker runs.  Pure numpy.  Checked by
``tests/experiments/test_whole_arm_grasp.py``.
"""

from __future__ import annotations

import inspect
from typing import Any, Mapping

from ...physics.contact import ContactLaw
from .plan import carry_plans, wrap_plan
from .tasks import GraspTask

__all__ = ["whole_arm_wrap", "grasp_case", "PLAN_KEYS", "TASK_KEYS"]

#: Scenario parameters that shape the CC plan / the physics task.
PLAN_KEYS = ("object_radius", "object_mass", "friction", "wrap_sections", "approach_bend_angles", "squeeze")
TASK_KEYS = ("release", "pull_direction", "pull_distance", "pull_step", "carry_move", "carry_samples",
             "contact_stiffness", "friction_stiffness", "contact_segments", "error_estimate", "penalty_estimate")


def whole_arm_wrap(
    robot,
    *,
    object_radius: float = 0.05,
    object_mass: float = 0.2,
    friction: float = 0.3,
    wrap_sections: list | None = None,
    approach_bend_angles: list | None = None,
    squeeze: float = 1.2,
    release: bool = True,
    pull_direction: str = "-z",
    pull_distance: float = 0.45,
    pull_step: float = 0.005,
    carry_move: list | None = None,
    carry_samples: int = 4,
    contact_stiffness: float = 1.0e8,
    friction_stiffness: float = 1.0e6,
    contact_segments: int = 8,
    error_estimate: bool = True,
    penalty_estimate: bool = True,
) -> dict[str, Any]:
    """Tendon tensions of the CC wrap of an object (plan: :mod:`.plan`; physics: :mod:`.tasks`).

    Parameters
    ----------
    object_radius, object_mass, friction : float
        The cylinder [m], [kg] and the arm-object Coulomb coefficient.
    wrap_sections : list of int, optional
        The distal sections that wrap (default: the distal half of the robot).
    approach_bend_angles : list of float, optional
        Bend angles [rad] of the other sections (default 0.3 rad each).
    squeeze : float
        Commanded over touching curvature of the wrap sections (>= 1).
    release : bool
        Release the object into the arm after the wrap closed on it (else: the held wrap only).
    pull_direction : {"+x", "-x", "+z", "-z"}
        Base-frame direction of the pull-out; ``pull_distance`` [m] (0: no pull-out), ``pull_step`` [m].
    carry_move : list of 2 float, optional
        Straight-line move of the grasp centre [m, base (x, z)] in ``carry_samples`` samples
        (default ``[0, 0.05]``; ``carry_samples = 0``: no carry).
    contact_stiffness, friction_stiffness : float
        Normal and stick penalty per length [N/m^2] (:class:`~workbench.physics.contact.ContactLaw`).
    contact_segments : int
        Contact segments per element (1 ... 12).
    error_estimate, penalty_estimate : bool
        Re-run the physics at half the elements (``x.disc_*``) and at a tenth of the contact
        penalty (``x.pen_*``) for the error bars (:mod:`.worker`).

    Returns
    -------
    dict
        ``mode = "tension"``, ``tensions`` (n_tendons,) [N].
    """
    params = {k: v for k, v in locals().items() if k != "robot"}
    plan, _ = grasp_case(robot, params)
    return {"mode": "tension", "tensions": [float(t) for t in plan.tensions]}


def _plan_kwargs(robot, p: Mapping[str, Any]) -> dict[str, Any]:
    n = robot.n_sections
    wrap = p.get("wrap_sections")
    wrap = list(range(n - max(1, n // 2), n)) if wrap is None else [int(j) for j in wrap]
    approach = p.get("approach_bend_angles")
    approach = [0.3] * (n - len(wrap)) if approach is None else [float(a) for a in approach]
    return {"object_radius": float(p["object_radius"]), "object_mass": float(p["object_mass"]),
            "friction": float(p["friction"]), "wrap_sections": wrap, "approach_bend_angles": approach,
            "squeeze": float(p["squeeze"])}


def grasp_case(robot, params: Mapping[str, Any]):
    """``(GraspPlan, GraspTask)`` of one case from its resolved scenario parameters (``name`` ignored).

    Raises
    ------
    ValueError
        An infeasible plan (see :func:`.plan.wrap_plan`, :func:`.plan.carry_plans`) or a bad task parameter.
    """
    p = {k: v for k, v in params.items() if k != "name"}
    defaults = {k: v.default for k, v in inspect.signature(whole_arm_wrap).parameters.items() if k != "robot"}
    p = {**defaults, **p}
    direction = str(p["pull_direction"])
    if direction not in ("+x", "-x", "+z", "-z"):
        raise ValueError(f"pull_direction must be '+x', '-x', '+z' or '-z' (base frame), got {direction!r}")
    kw = _plan_kwargs(robot, p)
    plan = wrap_plan(robot, **kw)
    carry = ()
    if int(p["carry_samples"]) > 0:
        off = [0.0, 0.05] if p["carry_move"] is None else [float(v) for v in p["carry_move"]]
        if len(off) != 2:
            raise ValueError(f"carry_move must be [dx, dz] [m, base frame], got {p['carry_move']!r}")
        carry = tuple(carry_plans(robot, kw, off, int(p["carry_samples"]))[1:])
    law = ContactLaw(stiffness=float(p["contact_stiffness"]), friction_stiffness=float(p["friction_stiffness"]),
                     segments=int(p["contact_segments"]))
    task = GraspTask(release=bool(p["release"]), law=law, pull_axis=direction[1], pull_sign=1.0 if direction[0] == "+" else -1.0,
                     pull_distance=float(p["pull_distance"]), pull_step=float(p["pull_step"]), carry=carry)
    return plan, task
