"""Hannan & Walker's resolved-rate and null-space controller (Eq. 10-11), open loop or in the loop.

The controller (papers/000_, Sec. 5) holds a CC configuration ``q`` (the planar section curvatures
``kappa_i``, the commanded shape) and, every control step, moves it by Eq. 11 with unit time step:

``dq = J^#(q) H1 (x_d - y) + (I - J^+ J)(-H2 k (q - q_d))``,

``J`` the planar CC Jacobian (App. B, errata fixed), ``J^#`` its damped pseudo-inverse
(:func:`workbench.kinematics.resolved_rate_step`), ``H1 = gain``, ``H2 k = null_gain``, each
section's bend change limited to ``max_step``; the cables follow ``q`` through the robot's cable map
(Eq. 1-3).  The two loops differ only in ``y``, what the controller believes the tip to be:

* **open loop** (:func:`cc_plan`): ``y = f_CC(q)``, the controller's own CC model -- the plan that
  is then pushed through the physics (the hannan_walker study's replay);
* **closed loop** (:func:`run_closed_loop`): ``y`` = the tip the physics plant reaches under the
  current cables (plus an optional Gaussian measurement noise), re-read after every step.

Both start from the converged CC solution of the line's first point and take ``steps_per_sample``
steps per path sample.  With a plant that *is* the controller's CC model the closed loop is the
open loop, exactly (``tests/experiments/test_closed_loop.py``).  Frames: the planar model works in
``(x_p, y_p) = (-x_base, z_base)`` (:mod:`workbench.kinematics.planar`); paths, tips and errors are
stored in the base frame.  Pure numpy; the plant is any callable.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ...kinematics import planar_forward_kinematics, planar_inverse_kinematics, planar_jacobian, resolved_rate_step

__all__ = ["ControllerSettings", "LoopTrace", "PlantFailure", "planar_from_base", "base_from_planar", "control_step",
           "start_configuration", "cc_plan", "run_open_loop", "run_closed_loop"]


class PlantFailure(RuntimeError):
    """A plant solve failed at a control step; the message names the sample and the step."""


@dataclass(frozen=True)
class ControllerSettings:
    """Gains and rates of the controller (Eq. 11) and its sensor.

    Attributes
    ----------
    steps_per_sample : int
        Control steps (one plant solve each, in the loop) per path sample, >= 1.
    gain : float
        ``H1`` of Eq. 11 (1: a full resolved-rate step towards the target), in (0, 2).
    null_gain : float
        ``H2 k`` of Eq. 11, >= 0 (only used with a null-space target).
    singular_threshold : float
        Damping switch of ``J^#`` (relative to the largest singular value).
    max_step : float
        Largest change of a section bend angle ``kappa_i l_i`` per step [rad].
    noise : float
        Standard deviation of the tip measurement per coordinate [m] (closed loop only), >= 0.
    noise_seed : int
        Seed of the measurement noise (``numpy.random.default_rng``).
    """

    steps_per_sample: int = 3
    gain: float = 1.0
    null_gain: float = 0.2
    singular_threshold: float = 1e-2
    max_step: float = 0.5
    noise: float = 0.0
    noise_seed: int = 0

    def __post_init__(self) -> None:
        if int(self.steps_per_sample) != self.steps_per_sample or self.steps_per_sample < 1:
            raise ValueError(f"steps_per_sample must be an integer >= 1, got {self.steps_per_sample!r}")
        if not 0.0 < self.gain < 2.0:
            raise ValueError(f"gain must lie in (0, 2) (H1 of Eq 11; 1 = full step), got {self.gain}")
        for name in ("null_gain", "noise"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"{name} must be finite and >= 0, got {v}")
        if not (self.singular_threshold > 0 and self.max_step > 0):
            raise ValueError("singular_threshold and max_step must be > 0")


def planar_from_base(x) -> np.ndarray:
    """Base-frame points ``(..., 3)`` -> planar CC frame ``(..., 2) = (-x, z)``."""
    x = np.asarray(x, dtype=float)
    return np.stack([-x[..., 0], x[..., 2]], axis=-1)


def base_from_planar(p) -> np.ndarray:
    """Planar CC frame ``(..., 2)`` -> base-frame points ``(..., 3) = (-x_p, 0, y_p)``."""
    p = np.asarray(p, dtype=float)
    return np.stack([-p[..., 0], np.zeros(p.shape[:-1]), p[..., 1]], axis=-1)


def control_step(kappa, measured, target, ell, settings: ControllerSettings, kappa_d=None) -> np.ndarray:
    """One Eq. 11 step: new curvatures ``(n,)`` from the measured and target tips (planar frame, m)."""
    q = np.asarray(kappa, dtype=float)
    ell = np.asarray(ell, dtype=float)
    null = None if kappa_d is None else -settings.null_gain * (q - np.asarray(kappa_d, dtype=float))
    dq_task, dq_null = resolved_rate_step(planar_jacobian(q, ell), settings.gain * (np.asarray(target) - measured),
                                          null, settings.singular_threshold)
    dq = dq_task + dq_null
    big = float(np.max(np.abs(dq * ell)))
    if big > settings.max_step:
        dq = dq * (settings.max_step / big)
    return q + dq


def start_configuration(start_base, ell, kappa_d=None) -> np.ndarray:
    """The converged CC configuration with the tip at ``start_base`` (start curvatures ``0.1 / L``).

    Raises
    ------
    ValueError
        The point is out of the CC model's reach.
    """
    ell = np.asarray(ell, dtype=float)
    res = planar_inverse_kinematics(planar_from_base(start_base), np.full(ell.size, 0.1 / ell.sum()), ell,
                                    kappa_d=kappa_d, max_iter=2000)
    if not res.success:
        raise ValueError(f"the point {np.round(np.asarray(start_base, dtype=float), 4).tolist()} m is out of the CC "
                         f"model's reach (residual {res.residual:.3g} m)")
    return res.q


def _cc_tip(q, ell) -> np.ndarray:
    return planar_forward_kinematics(q, ell)[:2, 3]


def cc_plan(path_base, ell, settings: ControllerSettings, kappa_d=None) -> tuple[np.ndarray, np.ndarray]:
    """The open-loop plan: the controller on its own CC model.

    Parameters
    ----------
    path_base : array_like, shape (m, 3)
        Tip targets, base frame [m] (in the base x-z plane).
    ell : array_like, shape (n,)
        Section lengths [m].
    settings : ControllerSettings
    kappa_d : array_like, shape (n,), optional
        Null-space target curvatures (Eq. 11), planar sign [1/m].

    Returns
    -------
    kappa : ndarray, shape (m, n)
        Commanded curvatures at the end of every sample [1/m].
    step_error : ndarray, shape (m * steps_per_sample,)
        ``|f_CC(q) - x_d|`` after every step [m].
    """
    P = planar_from_base(path_base)
    q = start_configuration(path_base[0], ell, kappa_d)
    ks, errs = [], []
    for target in P:
        for _ in range(settings.steps_per_sample):
            q = control_step(q, _cc_tip(q, ell), target, ell, settings, kappa_d)
            errs.append(float(np.linalg.norm(_cc_tip(q, ell) - target)))
        ks.append(q.copy())
    return np.asarray(ks), np.asarray(errs)


@dataclass(frozen=True, eq=False)
class LoopTrace:
    """What one loop did along the path (``m`` samples, ``K = m * steps_per_sample`` steps).

    Attributes
    ----------
    kappa : ndarray, shape (m, n)
        Commanded curvatures at the end of every sample [1/m] (planar sign).
    tip : ndarray, shape (m, 3)
        True plant tip at the end of every sample, base frame [m].
    error : ndarray, shape (m,)
        ``|tip - target|`` per sample [m].
    step_error : ndarray, shape (K,)
        ``|true plant tip - current target|`` after every control step [m] (open loop: NaN, the
        plant is solved once per sample).
    results : list
        The plant's result at the end of every sample.
    plant_solves : int
    plant_time : float
        Wall time inside the plant [s].
    """

    kappa: np.ndarray
    tip: np.ndarray
    error: np.ndarray
    step_error: np.ndarray
    results: list
    plant_solves: int
    plant_time: float


def _solve(plant: Callable, cables: np.ndarray, where: str, clock: list):
    t0 = time.perf_counter()
    try:
        res = plant(cables)
    except Exception as e:  # noqa: BLE001 - the loop stops; the row records why and where
        raise PlantFailure(f"{where}: {type(e).__name__}: {e}") from e
    finally:
        clock[0] += time.perf_counter() - t0
        clock[1] += 1
    return res


def run_open_loop(plant: Callable, cable_map: Callable, path_base, ell, settings: ControllerSettings,
                  kappa_d=None) -> LoopTrace:
    """The CC plan (:func:`cc_plan`) pushed through ``plant`` once per sample.

    ``plant(cable_changes) -> result`` with ``result.tip_position`` (base frame); ``cable_map(kappa)``
    the cable commands of a configuration.  Raises :class:`PlantFailure` (sample named).
    """
    path_base = np.asarray(path_base, dtype=float)
    kappa, _ = cc_plan(path_base, ell, settings, kappa_d)
    clock = [0.0, 0]
    results = [_solve(plant, cable_map(k), f"open loop, sample {j}", clock) for j, k in enumerate(kappa)]
    tip = np.array([r.tip_position for r in results])
    return LoopTrace(kappa, tip, np.linalg.norm(tip - path_base, axis=1),
                     np.full(len(kappa) * settings.steps_per_sample, np.nan), results, clock[1], clock[0])


def run_closed_loop(plant: Callable, cable_map: Callable, path_base, ell, settings: ControllerSettings,
                    kappa_d=None) -> LoopTrace:
    """The controller in the loop: every step reads the plant's tip (plus noise) and commands cables.

    The plant is first solved at the start configuration; then, for every sample, each of the
    ``steps_per_sample`` steps updates ``q`` from the last measurement (:func:`control_step`) and
    solves the plant under the new cables.  Raises :class:`PlantFailure` (sample and step named).
    """
    path_base = np.asarray(path_base, dtype=float)
    P = planar_from_base(path_base)
    rng = np.random.default_rng(settings.noise_seed)
    q = start_configuration(path_base[0], ell, kappa_d)
    clock = [0.0, 0]
    res = _solve(plant, cable_map(q), "closed loop, start configuration", clock)
    ks, results, step_err = [], [], []
    for j, target in enumerate(P):
        for s in range(settings.steps_per_sample):
            y = planar_from_base(res.tip_position)
            if settings.noise > 0:
                y = y + rng.normal(0.0, settings.noise, 2)
            q = control_step(q, y, target, ell, settings, kappa_d)
            res = _solve(plant, cable_map(q), f"closed loop, sample {j}, step {s + 1}", clock)
            step_err.append(float(np.linalg.norm(res.tip_position - path_base[j])))
        ks.append(q.copy())
        results.append(res)
    tip = np.array([r.tip_position for r in results])
    return LoopTrace(np.asarray(ks), tip, np.linalg.norm(tip - path_base, axis=1), np.asarray(step_err), results,
                     clock[1], clock[0])
