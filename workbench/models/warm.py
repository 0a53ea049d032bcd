"""Warm starts: solve a load from a neighbouring solve's state (``SolverOptions.warm_state``).

A model that supports warm starts returns :attr:`~workbench.models.result.PhysicsResult.warm_state`
(an opaque plain-numpy state) and starts from ``SolverOptions.warm_state`` when it fits; a model
without them ignores the option (``cosserat`` and ``spring_link`` have them under tension control,
see :mod:`workbench.physics.cosserat.warm` and ``workbench.physics.spring_link.driver``; ``beam3d``,
``ancf``, ``ancf3d``, ``contact`` and ``cc`` do not: a ``beam3d`` prototype was slower than its
cold solve, ``benchmarks/README.md``).  The model keeps the static
answer of the load path from the unloaded state: it uses a state only from a solve at a fraction
``0 < c <= 1`` of the same load and continues its ramp from there with its path checks, and solves cold
when the state does not fit or the ramp sees an event.

* :func:`solve_chain` -- a list of loads solved in order, each from the state of the nearest
  earlier one on its ray (the calibration of issue 30 can solve its measured loads this way; loads
  on no common ray are solved cold).
* :class:`WarmPool` -- the solved states of one process, by :func:`warm_key` (same model, robot,
  options and load kind), and the nearest one to a new load (Euclidean distance of
  :func:`load_vector`; ties go to the earliest stored) among the fractions of the load
  (:func:`on_ray`: the models' ramps follow ``lam`` x the load from the unloaded state, and a start
  on that path keeps the answer of the path; off it a model may reach another equilibrium).  The sweep runner
  (:mod:`workbench.study.evaluate`, ``[solver] warm_start = true``) records where a warm start came
  from (``warm_from``: the source's case id), so every result is reproducible.

Checked by ``tests/models/test_warm.py``.
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Hashable, Sequence

import numpy as np

from ..robot import LoadCase, Robot
from .result import PhysicsResult, SolverOptions

__all__ = ["WarmPool", "leaves_secant", "load_vector", "on_ray", "ray_fraction", "solve_chain", "warm_key"]


def solve_chain(run: Callable[[Robot, LoadCase, SolverOptions], PhysicsResult], robot: Robot,
                loads: Sequence[LoadCase], options: SolverOptions) -> list[PhysicsResult]:
    """Solve ``loads`` in order, each warm-started from the nearest earlier one at a fraction of it.

    The state comes from the earlier load of the list nearest to this one among its fractions
    ``c x load``, ``0 < c <= 1`` (:class:`WarmPool`; list the loads of a ray by growing magnitude);
    without one, from ``options.warm_state`` or cold.  A model's
    :class:`~workbench.models.result.ModelFailure` propagates.  The answers are the cold solves'
    within the solver tolerance wherever the cold ramp follows the load path
    (``tests/models/test_warm.py``); a model without warm starts solves every load cold.
    """
    pool = WarmPool(maxsize=len(loads) + 1)
    out: list[PhysicsResult] = []
    for i, load in enumerate(loads):
        key = warm_key("", robot, load, options)
        hit = pool.nearest(key, load)
        state = options.warm_state if hit is None else hit[1]
        res = run(robot, load, dataclasses.replace(options, warm_state=state))
        out.append(res)
        pool.add(key, load, str(i), res.warm_state)
    return out


def load_vector(load: LoadCase) -> np.ndarray:
    """The numbers a sweep varies in a load: actuation values, tip force, tip torque (SI units)."""
    values = () if load.actuation is None else load.actuation.values
    return np.concatenate([np.asarray(values, dtype=float), np.asarray(load.tip_force, dtype=float),
                           np.asarray(load.tip_torque, dtype=float)])


def ray_fraction(other: np.ndarray, v: np.ndarray, rtol: float = 1e-9) -> float | None:
    """``c`` where load vector ``other`` is ``c v`` with ``0 < c <= 1`` (a point of the straight load
    path ``lam v``, ``lam`` from 0 to 1, every model's ramp follows from the unloaded state), else ``None``."""
    other, v = np.asarray(other, dtype=float), np.asarray(v, dtype=float)
    vv = float(v @ v)
    if other.shape != v.shape or vv == 0.0:
        return None
    c = float(other @ v) / vv
    if not 0.0 < c <= 1.0 + rtol or float(np.linalg.norm(other - c * v)) > rtol * float(np.linalg.norm(other)):
        return None
    return min(c, 1.0)


def on_ray(other: np.ndarray, v: np.ndarray, rtol: float = 1e-9) -> bool:
    """Is ``other`` a fraction of ``v`` (:func:`ray_fraction`)?"""
    return ray_fraction(other, v, rtol) is not None


def leaves_secant(unloaded: np.ndarray, start: np.ndarray, c: float, lam: float, measure: np.ndarray,
                  ratio: float, floor: float) -> bool:
    """Does the first step of a warm ramp, from ``lam = c`` to ``lam``, leave the cold path?

    A ramp checks a step against the secant of its last two accepted points
    (:func:`workbench.physics._stepping.load_ramp`: farther than ``max(ratio |predicted move|, floor)``
    from it is a jump); a warm ramp has one, its start (path measure ``start`` at ``c``), and the
    cold path gives the second, the unloaded state (``unloaded`` at 0).  Used by the models' warm
    starts (``cosserat``, ``spring_link``); checked by ``tests/models/test_warm_cosserat.py``.
    """
    m0, mc, m = (np.asarray(a, dtype=float) for a in (unloaded, start, measure))
    move = (lam - c) / c * (mc - m0)
    return float(np.linalg.norm(m - mc - move)) > max(ratio * float(np.linalg.norm(move)), floor)


def warm_key(model: str, robot: Robot, load: LoadCase, options: SolverOptions) -> Hashable:
    """What two solves must share for one to start from the other: model, robot, options (without
    ``warm_state``) and everything in the load but :func:`load_vector` (mode, analysis, pretension, ...)."""
    act = load.actuation
    kind = dataclasses.replace(load, tip_force=(0.0, 0.0, 0.0), tip_torque=(0.0, 0.0, 0.0),
                               actuation=None if act is None else dataclasses.replace(
                                   act, values=(0.0,) * len(act.values)))
    return (str(model), repr(robot), repr(dataclasses.replace(options, warm_state=None)), repr(kind))


class WarmPool:
    """Solved states by :func:`warm_key`, at most ``maxsize`` per key (the oldest dropped first)."""

    def __init__(self, maxsize: int = 256) -> None:
        self.maxsize = int(maxsize)
        self._states: dict[Hashable, list[tuple[np.ndarray, str, np.ndarray]]] = {}

    def add(self, key: Hashable, load: LoadCase, tag: str, state: np.ndarray | None) -> None:
        """Keep ``state`` (ignored when ``None``) of the solve of ``load``, named ``tag`` (a case id)."""
        if state is None:
            return
        entries = self._states.setdefault(key, [])
        entries.append((load_vector(load), str(tag), np.asarray(state, dtype=float)))
        del entries[:-self.maxsize]

    def nearest(self, key: Hashable, load: LoadCase, ray: bool = True) -> tuple[str, np.ndarray] | None:
        """``(tag, state)`` of the stored solve nearest to ``load`` under ``key`` (``None``: none);
        with ``ray`` only solves of a fraction of ``load`` (:func:`on_ray`)."""
        entries = self._states.get(key)
        if not entries:
            return None
        v = load_vector(load)
        fits = [(float(np.linalg.norm(e[0] - v)), i) for i, e in enumerate(entries)
                if e[0].shape == v.shape and (not ray or on_ray(e[0], v))]
        if not fits:
            return None
        _, i = min(fits)
        return entries[i][1], entries[i][2]

    def __len__(self) -> int:
        """The number of states kept."""
        return sum(len(v) for v in self._states.values())

    def clear(self) -> None:
        """Forget every state."""
        self._states.clear()
