"""Case parameters -> the objects a model runs on: robot, load case, solver options.

Plain data in (the resolved ``{"robot": ..., "load": ..., "solver": ..., "derived": ...}`` of one
case, see :class:`~workbench.study.expand.Case`), frozen values out.  Used by the workers
(:func:`workbench.study.evaluate.evaluate_case`), by validation (every case is dry-built, so an
infeasible command is an input error before anything runs) and by the report (rebuilding a
stored row).  :func:`resolve_case` is the one rule for the parameters a case *runs with* (the
robot's derived gravity, a scenario's load fields): result rows record those, so a stored row
rebuilds exactly the robot and load that ran.  Imports no Exudyn; the preset registry and the CC
arc-to-tendon map are imported when first used.

Checked by ``tests/study/test_evaluate.py`` (gamma -> gravity, loads) and
``tests/study/test_build.py`` (rebuilding the robot and load of stored rows).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Mapping

import numpy as np

from .params import canonical_json
from .scenarios import load_with_scenario

__all__ = ["gravity_from_parameter", "resolve_robot", "build_robot", "resolve_case", "parameters_as_run",
           "build_load", "build_options", "build_pipeline_options", "PipelineOptions", "PIPELINE_KEYS"]


def gravity_from_parameter(gamma: float, EI: float, mass_per_length: float, length: float) -> float:
    """Gravity magnitude g [m/s^2] for the self-weight parameter ``gamma = q L^3 / EI``.

    ``q = m' g`` is the backbone weight per length, so ``g = gamma EI / (m' L^3)``.

    Raises
    ------
    ValueError
        ``mass_per_length`` is zero (gamma is then undefined) or inputs are not finite.
    """
    if not (math.isfinite(gamma) and gamma >= 0):
        raise ValueError(f"gravity_parameter must be finite and >= 0, got {gamma}")
    if not mass_per_length > 0:
        raise ValueError("gravity_parameter needs a backbone with mass (mass per length > 0)")
    return float(gamma) * float(EI) / (float(mass_per_length) * float(length) ** 3)


def resolve_robot(robot_params: Mapping[str, Any], derived: Mapping[str, Any] | None = None
                  ) -> tuple[Any, dict[str, Any]]:
    """The robot of a case and the robot parameters it was built with.

    ``robot_params`` is the case's ``[robot]`` table in either form of
    :func:`workbench.robot.spec.robot_from_params` (``{"preset": name, **preset parameters}`` or a
    description); ``derived["gravity_parameter"]`` (gamma) replaces the robot's ``gravity`` by
    :func:`gravity_from_parameter` of the backbone of a uniform robot (every section the same
    cross-section, no taper; disks and payload are not part of ``q``).  The returned parameters
    are those the robot ran with (gravity included), so ``build_robot(parameters)`` rebuilds the
    same robot without the derived parameters -- they are what a result row records as
    ``p.robot.*`` (``tests/study/test_build.py``).

    Raises
    ------
    ValueError
        gamma on a non-uniform robot, or invalid gamma (see :func:`gravity_from_parameter`).
    """
    from ..robot.spec import is_description, robot_from_params

    params = dict(robot_params)
    gamma = (derived or {}).get("gravity_parameter")
    robot = robot_from_params(params)
    if gamma is not None:
        cs = robot.sections[0].cross_section
        if any(s.cross_section != cs or s.cross_section_tip is not None for s in robot.sections):
            raise ValueError("derived.gravity_parameter needs a uniform robot (same cross-section, no taper)")
        g = gravity_from_parameter(gamma, cs.EI, cs.mass_per_length, robot.length)
        # the preset form's gravity is a magnitude along world -z, the description form's a world vector
        params["gravity"] = g if "preset" in params and not is_description(params) else [0.0, 0.0, -g]
        robot = robot_from_params(params)
    return robot, params


def build_robot(robot_params: Mapping[str, Any], derived: Mapping[str, Any] | None = None):
    """Robot from ``{"preset": name, **preset parameters}`` and the derived parameters (:func:`resolve_robot`)."""
    return resolve_robot(robot_params, derived)[0]


def resolve_case(params: Mapping[str, Any], robot_cache: dict[str, Any] | None = None
                 ) -> tuple[Any, dict[str, Any]]:
    """The robot of a case and the parameters the case runs with.

    The parameters are ``params`` with the robot's derived parameters applied
    (:func:`resolve_robot`: ``robot.gravity`` from ``derived.gravity_parameter``) and the
    scenario's load fields applied (``load_with_scenario``: e.g. ``length_changes``,
    ``start_delays``, ``duration`` computed per case), so ``build_robot(parameters["robot"])`` and
    ``build_load(robot, parameters["load"])`` rebuild exactly what ran.  These are the parameters
    a result row records; the case id stays the hash of ``params`` as configured.

    Parameters
    ----------
    params : dict
        The case's resolved parameters as configured (:class:`~workbench.study.expand.Case`).
    robot_cache : dict, optional
        Memo of :func:`resolve_robot` results keyed by the robot's parameters (robots are frozen).
    """
    key = canonical_json([params["robot"], params.get("derived")])
    if robot_cache is not None and key in robot_cache:
        robot, robot_params = robot_cache[key]
    else:
        robot, robot_params = resolve_robot(params["robot"], params.get("derived"))
        if robot_cache is not None:
            robot_cache[key] = (robot, robot_params)
    load = params["load"]
    if params.get("scenario"):
        load = load_with_scenario(robot, load, params["scenario"])
    return robot, {**params, "robot": robot_params, "load": load}


def parameters_as_run(params: Mapping[str, Any], robot_cache: dict[str, Any] | None = None) -> dict[str, Any]:
    """The parameters a case runs with (:func:`resolve_case`), or ``params`` if the case cannot be built.

    A case that cannot be built records its configured parameters (its rows are failed rows).
    ``robot_cache`` as in :func:`resolve_case` (a sweep over loads builds its robot once).
    """
    try:
        return resolve_case(params, robot_cache)[1]
    except Exception:  # noqa: BLE001 - the worker records the failure with its reason
        return dict(params)


def build_load(robot, load: Mapping[str, Any]):
    """LoadCase from the ``[load]`` parameters of one case.

    ``bend_angle`` (total angle per section, scalar or per section) and ``bend_plane`` become
    ``kappa_j = bend_angle_j / L_j`` and ``phi_j`` and are translated into tendon commands by
    ``workbench.models.cc.actuation_from_arc``.
    """
    from ..robot import LoadCase, TendonActuation

    mode = load["mode"]
    act = None
    if load.get("bend_angle") is not None:
        from ..models.cc import actuation_from_arc

        ns = robot.n_sections
        kappa = np.broadcast_to(np.asarray(load["bend_angle"], float), (ns,)) / robot.section_lengths
        phi = np.broadcast_to(np.asarray(load.get("bend_plane", 0.0), float), (ns,)).copy()
        act = actuation_from_arc(robot, kappa, phi, mode, pretension=load.get("pretension", 0.0))
    elif load.get("tensions") is not None:
        act = TendonActuation("tension", tuple(load["tensions"]), pretension=load.get("pretension", 0.0))
    elif load.get("length_changes") is not None:
        act = TendonActuation("length", tuple(load["length_changes"]), pretension=load.get("pretension", 0.0))
    if act is not None:
        st, rd = load.get("start_delays"), load.get("ramp_durations")
        if st is not None or rd is not None:
            act = replace(act, start_times=None if st is None else tuple(st),
                          ramp_durations=None if rd is None else tuple(rd))
        act.check_against(robot)
    return LoadCase(
        actuation=act,
        tip_force=tuple(load.get("tip_force", (0.0, 0.0, 0.0))),
        tip_torque=tuple(load.get("tip_torque", (0.0, 0.0, 0.0))),
        analysis=load.get("analysis", "static"),
        duration=load.get("duration", 0.0),
        ramp_time=load.get("ramp_time", 1.0),
    )


#: ``[solver]`` keys the study pipeline reads, not the models (:class:`PipelineOptions`, :mod:`.by_model`)
PIPELINE_KEYS = ("error_estimate", "error_estimate_exempt", "by_model", "warm_start")


def build_options(solver: Mapping[str, Any]):
    """:class:`~workbench.models.SolverOptions` from the ``[solver]`` parameters of one case.

    The pipeline's keys (:data:`PIPELINE_KEYS`) are left out (:func:`build_pipeline_options`; a
    model's own ``by_model`` table is applied before, by
    :func:`workbench.study.by_model.solver_for_model`); ``spring_link_backend``,
    ``spring_link_axial`` and ``spring_link_richardson`` (when not ``None``) become the spring-link
    model's own settings ``backend``, ``axial`` and ``richardson`` (``SolverOptions.model_settings``,
    read by ``workbench.physics.spring_link.run``).
    """
    from ..models.result import SolverOptions

    own = {"spring_link_backend": "backend", "spring_link_axial": "axial", "spring_link_richardson": "richardson"}
    fields = {k: v for k, v in solver.items() if k not in PIPELINE_KEYS and k not in own}
    spring = {name: solver[k] for k, name in own.items() if solver.get(k) is not None}
    if spring:
        fields["model_settings"] = {"spring_link": spring}
    return SolverOptions(**fields)


@dataclass(frozen=True)
class PipelineOptions:
    """The ``[solver]`` settings the study pipeline applies around the models (the models never see them).

    Attributes
    ----------
    error_estimate : {"richardson", "none"}
        ``"richardson"`` re-solves every physics case at 1/2 and 1/4 of the resolution and records
        its discretisation-error estimate (:mod:`workbench.study.estimate`); ``"none"`` turns that off.
    error_estimate_exempt : tuple of str
        Models whose discretisation *is* the hardware (e.g. a spring-link chain with one link per
        physical joint), so that coarsening them would change the robot, not the mesh; they get
        no estimate.
    warm_start : bool
        Start each model's solve from the nearest case of the same model and robot solved before in
        the same worker process (:mod:`workbench.models.warm`; the rows record the source case in
        ``warm_from``).  Off by default: results then do not depend on the execution order.

    Checked by ``tests/study/test_estimate.py`` and ``tests/models/test_warm.py``.
    """

    error_estimate: str = "richardson"
    error_estimate_exempt: tuple[str, ...] = ()
    warm_start: bool = False

    def __post_init__(self) -> None:
        if self.error_estimate not in ("richardson", "none"):
            raise ValueError(f"error_estimate must be 'richardson' or 'none', got {self.error_estimate!r}")
        if not isinstance(self.warm_start, bool):
            raise ValueError(f"warm_start must be true or false, got {self.warm_start!r}")
        object.__setattr__(self, "error_estimate_exempt", tuple(str(m) for m in self.error_estimate_exempt))


def build_pipeline_options(solver: Mapping[str, Any]) -> PipelineOptions:
    """:class:`PipelineOptions` from the ``[solver]`` parameters of one case."""
    return PipelineOptions(**{k: solver[k] for k in ("error_estimate", "error_estimate_exempt", "warm_start")
                              if k in solver})
