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

This module is the mechanism only: the scenarios themselves live with their experiment
(``workbench/experiments/<study>/scenario.py``) and are found through ``registry.table("scenarios")``.
Checked by ``tests/study/test_scenarios.py``.
"""

from __future__ import annotations

import inspect
from typing import Any, Callable, Iterator, Mapping

from .. import registry

__all__ = [
    "SCENARIOS",
    "SCENARIO_LOAD_FIELDS",
    "scenario_parameters",
    "load_with_scenario",
]

#: ``[load]`` fields a scenario may set.
SCENARIO_LOAD_FIELDS = frozenset(
    {"mode", "length_changes", "tensions", "start_delays", "ramp_durations", "analysis", "duration", "ramp_time",
     "pretension"}
)


class _Scenarios(Mapping[str, Callable[..., dict[str, Any]]]):
    """Read-only view of ``registry.table("scenarios")``: name -> scenario function, imported on lookup."""

    def __getitem__(self, name: str) -> Callable[..., dict[str, Any]]:
        return registry.resolve(registry.table("scenarios")[name])

    def __iter__(self) -> Iterator[str]:
        return iter(registry.table("scenarios"))

    def __len__(self) -> int:
        return len(registry.table("scenarios"))

    def __contains__(self, name: object) -> bool:
        return name in registry.table("scenarios")

    def __repr__(self) -> str:
        return f"SCENARIOS({list(registry.table('scenarios'))})"


#: ``[scenario] name`` -> scenario function (resolved from ``registry.table("scenarios")`` when looked up).
SCENARIOS: Mapping[str, Callable[..., dict[str, Any]]] = _Scenarios()

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
