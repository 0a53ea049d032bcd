"""Fake models for the runner tests (importable by worker processes: module-level functions).

``arc`` bends the robot into a planar constant-curvature arc with ``kappa = T0 d / EI`` from
the first tendon tension (an exact pure-moment solution, cheap).  Magic first-tendon tensions
trigger failure modes:

- 13.0 -> raises ``RuntimeError``
- 7.0  -> returns NaN positions
- 66.0 -> ``os._exit(3)`` (kills the worker process)
- 5.0  -> result with ``converged = False``
- 99.0 -> sleeps for an hour (a hanging case)
- 98.0 -> asks for 64 GB (a case that eats memory)

``lookup_ancf_exits`` maps ``cc`` to the arc and ``ancf`` to a model that kills its process.
"""

from __future__ import annotations

import os
import textwrap
import time

import numpy as np

from workbench.models.result import PhysicsResult, SolverInfo
from workbench.study.evaluate import iter_case_rows
from workbench.study.kinds import SweepKind

RAISE, NAN, EXIT, NOCONV, HANG, HOG = 13.0, 7.0, 66.0, 5.0, 99.0, 98.0

#: a valid study (no sweep) the tests extend
GOOD = textwrap.dedent("""\
    [study]
    name = "good"
    seed = 3
    models = ["cc", "ancf"]

    [robot]
    preset = "steel_rod"
    length = 0.8

    [load]
    mode = "tension"
    tensions = [1.0, 0.0]

    [solver]
    n_elements = 8
    n_stations = 9
    """)



def _arc(robot, load, options, *, spin: float = 0.0):
    if spin:
        t_end = time.perf_counter() + spin
        while time.perf_counter() < t_end:
            pass
    T = load.actuation.values if load.actuation is not None else (0.0,)
    t0 = float(T[0])
    if t0 == RAISE:
        raise RuntimeError("fake model exploded")
    if t0 == EXIT:
        os._exit(3)
    if t0 == HANG:
        time.sleep(3600)
    if t0 == HOG:
        np.empty(8 * 10**9).fill(1.0)
    L = robot.length
    g = robot.sections[0].tendons
    EI = robot.sections[0].cross_section.EI
    kappa = t0 * g.offset / EI
    s = np.linspace(0.0, L, options.n_stations)
    if abs(kappa) < 1e-12:
        pos = np.column_stack([0 * s, 0 * s, s])
    else:
        pos = np.column_stack([(1 - np.cos(kappa * s)) / kappa, 0 * s, np.sin(kappa * s) / kappa])
    th = kappa * L
    R = np.array([[np.cos(th), 0, np.sin(th)], [0, 1, 0], [-np.sin(th), 0, np.cos(th)]])
    F = np.eye(4)
    F[:3, :3] = R
    F[:3, 3] = pos[-1]
    if t0 == NAN:
        pos = pos * np.nan
    return PhysicsResult(
        model="fake", stations=s, positions=pos, tip_frame=F, length_change=0.0,
        tendon_tensions=np.asarray(T, float), tip_twist=0.0,
        solver=SolverInfo(converged=(t0 != NOCONV), iterations=1, message="fake"),
        extras={"kappa": kappa},
        series={"tip_position": np.tile(pos[-1], (3, 1))},
    )


def arc(robot, load, options):
    return _arc(robot, load, options)


def arc_spin_1p5ms(robot, load, options):
    return _arc(robot, load, options, spin=1.5e-3)


def arc_spin_20ms(robot, load, options):
    return _arc(robot, load, options, spin=20e-3)


_MODELS = {"cc": arc, "ancf": arc, "spring_link": arc}


def lookup(name):
    """Model lookup: every model name maps to the fake arc."""
    return _MODELS[name]


def lookup_spin_1p5ms(name):
    return arc_spin_1p5ms


def lookup_spin_20ms(name):
    return arc_spin_20ms


def arc_sleep_1s(robot, load, options):
    """The fake arc after a 1 s sleep (a slow model for the progress timer)."""
    time.sleep(1.0)
    return _arc(robot, load, options)


def lookup_sleep_1s(name):
    return arc_sleep_1s


def fake_arc_actuation(robot, kappa, phi, mode, pretension=0.0):
    """Stand-in for workbench.models.cc.actuation_from_arc: T0 = kappa EI / d (planar)."""
    from workbench.robot import TendonActuation

    g = robot.sections[0].tendons
    EI = robot.sections[0].cross_section.EI
    vals = [0.0] * robot.n_tendons
    vals[0] = float(kappa[0]) * EI / g.offset
    return TendonActuation(mode, tuple(vals), pretension=pretension)


def exiting_model(robot, load, options):
    os._exit(4)


def lookup_ancf_exits(name):
    """``cc``: the arc; ``ancf``: kills its process (exit status 4)."""
    return arc if name == "cc" else exiting_model


def killed_once_model(robot, load, options):
    """The arc, but the first call with T0 = 2 N SIGKILLs its process (marker file: $WB_KILL_ONCE)."""
    marker = os.environ.get("WB_KILL_ONCE")
    if marker and float(load.actuation.values[0]) == 2.0 and not os.path.exists(marker):
        open(marker, "w").close()
        os.kill(os.getpid(), 9)
    return arc(robot, load, options)


def lookup_kill_once(name):
    """``cc``: :func:`killed_once_model` (an outside kill, the first time only); ``ancf``: the arc."""
    return killed_once_model if name == "cc" else arc


def _kill_worker_model(robot, load, options, once: bool):
    """The arc, but the 2 N case SIGKILLs the *Dask worker* (the sandbox's parent): a lost machine."""
    marker = os.environ.get("WB_KILL_ONCE")
    if float(load.actuation.values[0]) == 2.0 and (not once or (marker and not os.path.exists(marker))):
        if marker:
            open(marker, "w").close()
        os.kill(os.getppid(), 9)
        time.sleep(60)
    return arc(robot, load, options)


def lookup_kills_worker_once(name):
    return lambda robot, load, options: _kill_worker_model(robot, load, options, once=True)


def lookup_kills_worker_always(name):
    return lambda robot, load, options: _kill_worker_model(robot, load, options, once=False)


def die_on_one(x):
    """Task for executor tests: yields x, then SIGKILLs its own process on payload 1, else yields x * x."""
    yield x
    if x == 1:
        os.kill(os.getpid(), 9)
    yield x * x


def lengths(x):
    """Task for executor tests: yields ``len(x)``."""
    yield len(x)


def sleepy(x):
    """Task for executor tests: yields x, then sleeps x seconds, then yields -x."""
    yield x
    time.sleep(x)
    yield -x


# -- the fake models on the real pipeline: a sweep kind whose task uses a lookup of this module ------------


def fake_sweep_rows(payload):
    """:func:`workbench.study.evaluate.evaluate_rows` with the payload's ``lookup``."""
    case_id, params, models, lookup = payload
    return iter_case_rows(case_id, params, models, lookup)


class FakeSweepKind(SweepKind):
    """The sweep kind with its models looked up by ``lookup`` (a module-level function, so the payload
    pickles to worker processes); the tests' way to run the real runner and executors on fake models."""

    task = staticmethod(fake_sweep_rows)

    def __init__(self, lookup):
        self.lookup = lookup

    def payload(self, spec, case, models):
        return case.case_id, case.params, tuple(models), self.lookup



def sweep_kind(lookup=None) -> FakeSweepKind:
    """The sweep kind on the models of ``lookup`` (default :func:`lookup`: every model is the fake arc)."""
    return FakeSweepKind(lookup or globals()["lookup"])
