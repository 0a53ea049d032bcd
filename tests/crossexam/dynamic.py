"""Dynamic pairs of the cross-examination: tip trajectories of a tendon step, ancf vs beam3d vs spring_link.

A dynamic run starts from the static equilibrium of its commands at t = 0 (gravity included),
so a "free swing" is made by a tendon step: the tendon is pulled at ``t = 5 ms`` within one
step (``ramp_durations = 0``) and the rod swings for 0.15 s -- once in a horizontal Rao NiTi
rod under gravity (the swing includes the sag and its release), once in a vertical steel rod
without gravity.  Each model runs at ``(n / 2, 2 h)``, ``(n, h)`` and ``(2 n, h / 2)``; the error bar
is the Richardson estimate of the largest tip difference over time between the two finest runs with
order 2 (generalised-alpha, :data:`workbench.models.discretization.DYNAMIC_ORDER`, below the models'
spatial orders), lowered to the order observed over the three runs where that is lower
(:func:`~workbench.models.discretization.effective_order`), as the study pipeline does.
Two models agree when the largest distance of their fine trajectories over time is below the
sum of the bars plus the static strain floor (:mod:`tests.crossexam.pairs`).  Checked by
``tests/crossexam/test_dynamic.py``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from workbench.models import SolverOptions, get_model
from workbench.models.discretization import DYNAMIC_ORDER, effective_order, observed_order, richardson_error
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset

from tests.crossexam.cases import MATERIALS

__all__ = ["DYNAMIC_CASES", "DynSide", "amplitude", "dynamic_pair", "dynamic_side", "dynamic_study"]

STEP_AT, RAMP, DURATION = 5e-3, 10e-3, 0.15


def _robot(material: str, gravity: bool):
    mat, sec = MATERIALS[material]
    return build_preset("steel_rod", **mat, length=sec, n_sections=1, tendon_count=2, disks_per_section=10,
                        tendon_stiffness=1e7, gravity=9.81 if gravity else 0.0,
                        base_orientation="horizontal" if gravity else "vertical")


def _load(robot, theta: float) -> LoadCase:
    cs = robot.sections[0].cross_section
    T = theta * cs.EI / (robot.length * robot.sections[0].tendons.offset)
    act = TendonActuation("tension", (T, 0.0), start_times=(STEP_AT, STEP_AT), ramp_durations=(RAMP, RAMP))
    return LoadCase(actuation=act, analysis="dynamic", duration=DURATION)


#: name -> (material, gravity, bending angle of the step [rad])
DYNAMIC_CASES = {"niti swing under gravity": ("niti", True, 0.6), "steel step": ("steel", False, 0.5)}


@dataclass(frozen=True)
class DynSide:
    """A model's fine tip trajectory ``tips`` (k, 3) at ``times``, its bar [m] and wall time [s]."""

    model: str
    tendon_model: str
    times: np.ndarray
    tips: np.ndarray
    bar: float
    seconds: float


@functools.lru_cache(maxsize=None)
def dynamic_side(case: str, model: str, tendon_model: str, n: int, h: float) -> DynSide:
    """``model`` on dynamic case ``case`` at ``(n / 2, 2 h)``, ``(n, h)`` and ``(2 n, h / 2)`` (see the module docstring)."""
    import time

    material, gravity, theta = DYNAMIC_CASES[case]
    robot = _robot(material, gravity)
    load = _load(robot, theta)
    runs, t0 = [], time.perf_counter()
    for k in (0.5, 1, 2):
        res = get_model(model)(robot, load, SolverOptions(n_elements=int(k * n), time_step=h / k,
                                                         tendon_model=tendon_model, newton_tolerance=1e-10))
        runs.append((np.asarray(res.time, float), np.asarray(res.series["tip_position"], float)))
    (t0_, x0_), (tc, xc), (tf, xf) = runs
    diff = max(float(np.linalg.norm(_at(tf, xf, t) - x)) for t, x in zip(tc, xc))
    coarse = max(float(np.linalg.norm(_at(tc, xc, t) - x)) for t, x in zip(t0_, x0_))
    order = effective_order(DYNAMIC_ORDER, observed_order(diff, coarse))
    return DynSide(model, tendon_model, tf, xf, richardson_error(diff, 2.0, order), time.perf_counter() - t0)


def _at(times: np.ndarray, tips: np.ndarray, t: float) -> np.ndarray:
    return np.array([np.interp(t, times, tips[:, i]) for i in range(3)])


def dynamic_pair(case: str, a: DynSide, b: DynSide) -> tuple[float, float]:
    """``(distance, tolerance)`` [m]: the largest tip distance over the coarser output times, and
    ``bar_a + bar_b + floor`` with the strain floor ``L ((T + W) / EA + W / GA + 1e-6)``."""
    material, gravity, theta = DYNAMIC_CASES[case]
    robot = _robot(material, gravity)
    cs = robot.sections[0].cross_section
    T = theta * cs.EI / (robot.length * robot.sections[0].tendons.offset)
    W = 9.81 * cs.mass_per_length * robot.length if gravity else 0.0
    floor = robot.length * ((T + W) / cs.EA + W / cs.GA + 1e-6)
    times = a.times if len(a.times) <= len(b.times) else b.times
    dist = max(float(np.linalg.norm(_at(a.times, a.tips, t) - _at(b.times, b.tips, t))) for t in times)
    return dist, a.bar + b.bar + floor


def amplitude(side: DynSide) -> float:
    """Largest tip excursion from its position at t = 0 [m] (what the trajectories are compared against)."""
    return float(np.max(np.linalg.norm(side.tips - side.tips[0], axis=1))) if len(side.tips) else math.nan


def dynamic_study(case: str, model: str, tendon_model: str, n: int, h: float) -> str:
    """A study file (``workbench run``) of ``model`` on dynamic case ``case`` at the fine resolution."""
    material, gravity, theta = DYNAMIC_CASES[case]
    robot = _robot(material, gravity)
    mat, sec = MATERIALS[material]
    act = _load(robot, theta).actuation
    rows = {**mat, "length": sec, "n_sections": 1, "tendon_count": 2, "disks_per_section": 10,
            "tendon_stiffness": 1e7, "gravity": 9.81 if gravity else 0.0,
            "base_orientation": "horizontal" if gravity else "vertical"}
    lines = ["[study]", f'name = "crossexam_dynamic"', f'models = ["{model}"]', "", "[robot]", 'preset = "steel_rod"']
    lines += [f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"' for k, v in rows.items()]
    lines += ["", "[load]", 'mode = "tension"', 'analysis = "dynamic"', f"duration = {DURATION!r}",
              f"tensions = {list(act.values)!r}", f"start_delays = {list(act.start_times)!r}",
              f"ramp_durations = {list(act.ramp_durations)!r}", "", "[solver]", f"n_elements = {2 * n}",
              f"time_step = {h / 2!r}", f'tendon_model = "{tendon_model}"', "newton_tolerance = 1e-10"]
    return "\n".join(lines) + "\n"
