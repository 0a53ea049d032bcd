"""Predicted tip positions of measured samples for one calibration parameter vector.

A calibration (:mod:`workbench.measure.calibrate`) asks, again and again, "where would model *m*
put the tip of these samples if the parameters were *x*?".  :class:`Predictor` answers it:

1. ``x`` is split into its parts (:func:`split_vector`, the order of ``docs/measurements.md``): key
   paths into the case parameters (``robot.youngs_modulus``, ``robot.sections[1].length``, ...),
   ``command_zero[i]`` and ``registration.translation[j]`` / ``registration.rotation[j]``.
2. The key-path values replace the nominal ones (:func:`workbench.study.keypath.with_value` on
   ``{"robot", "load", "solver"}``) and the robot is built once per vector
   (:func:`workbench.study.build.build_robot`), not once per sample.
3. ``command_zero`` is added to every measured command; in tension mode a tendon cannot push, so
   the sum is clipped at 0 N (a slack tendon carries no force).
4. The model predicts the tips in the base frame: CC for all samples at once (:func:`_cc_tips`), a
   physics model (``workbench.models.get_model(name)``, static analysis, the sample's tip force)
   sample by sample in one function (:func:`solve_samples`), along a nearest-neighbour chain in
   command space (:func:`chain_order`); every solve starts cold from the straight rod, so the order
   changes no result (the models' warm starts, ``workbench.models.warm``, apply only along one load
   ray -- measured commands rarely share one -- and are not used here).
5. The tips are moved into the measurement frame: ``p = R(rotation) p_base + translation``
   (registration, ``R`` from the rotation vector, :func:`to_frame`), the world frame of the robot's
   base pose, or left in the base frame.

A model that raises (``ModelFailure``, ``exudyn.SolverError``, a robot it refuses), does not
converge or returns a non-finite tip on any sample raises :class:`PredictionFailure` with one line
naming the model, the file row and the reason; the calibration records it and fails.

Checked by ``tests/measure/test_measure_calibrate.py`` (CC tips equal ``cc.run`` row by row,
registration, command zero, failures) and ``tests/measure/test_measure_calibrate_physics.py``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from ..study.build import build_load, build_options, build_robot
from ..study.by_model import solver_for_model
from ..study.keypath import KeyPathError, with_value
from ..study.schema import LIMIT_KEYS
from .types import Measurements

__all__ = ["PredictionFailure", "Predictor", "Timing", "VectorParts", "chain_order", "model_options",
           "rotation_matrix", "solve_samples", "split_vector", "to_frame"]

_ZERO = "command_zero["
_TRANSLATION = "registration.translation["
_ROTATION = "registration.rotation["


class PredictionFailure(RuntimeError):
    """A model could not predict a sample (message: one line, model, file row and reason)."""


@dataclass(frozen=True)
class VectorParts:
    """A parameter vector split into its parts (:func:`split_vector`).

    Attributes
    ----------
    keys : dict
        Key path -> value (SI) of the calibrated case parameters.
    command_zero : ndarray, shape (n_tendons,)
        Added to every sample's commands (0 where not calibrated).
    translation, rotation : ndarray, shape (3,)
        Registration base -> measurement frame (0 where not calibrated).
    """

    keys: dict[str, float]
    command_zero: np.ndarray
    translation: np.ndarray
    rotation: np.ndarray


def _index(name: str, prefix: str) -> int:
    return int(name[len(prefix):].rstrip("]"))


def split_vector(names: Sequence[str], x: Sequence[float], n_tendons: int) -> VectorParts:
    """Split the parameter vector ``x`` (names ``names``, module docstring) into its parts."""
    keys: dict[str, float] = {}
    zero, t, r = np.zeros(n_tendons), np.zeros(3), np.zeros(3)
    for name, v in zip(names, x):
        if name.startswith(_ZERO):
            zero[_index(name, _ZERO)] = v
        elif name.startswith(_TRANSLATION):
            t[_index(name, _TRANSLATION)] = v
        elif name.startswith(_ROTATION):
            r[_index(name, _ROTATION)] = v
        else:
            keys[name] = float(v)
    return VectorParts(keys, zero, t, r)


def to_frame(points: np.ndarray, frame: str, robot, parts: VectorParts) -> np.ndarray:
    """Base-frame points ``(..., 3)`` in the measurement frame ``frame`` (module docstring, step 5)."""
    p = np.asarray(points, dtype=float)
    if frame == "base":
        return p
    if frame == "world":
        from ..robot.frames import base_points_to_world

        return base_points_to_world(p, robot.base_rotation, robot.base_position)
    return p @ rotation_matrix(parts.rotation).T + parts.translation


def rotation_matrix(rotvec: Sequence[float]) -> np.ndarray:
    """``R`` (3, 3) of the rotation vector ``rotvec`` (axis times angle [rad]): Rodrigues' formula
    ``I + sin(a) K + (1 - cos(a)) K^2``, ``K`` the cross-product matrix of the unit axis (Taylor
    terms below 1e-8 rad).  Equal to ``scipy.spatial.transform.Rotation.from_rotvec`` (tested)."""
    r = np.asarray(rotvec, dtype=float)
    a = float(np.linalg.norm(r))
    K = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    if a < 1e-8:
        return np.eye(3) + K + 0.5 * K @ K
    return np.eye(3) + (math.sin(a) / a) * K + ((1.0 - math.cos(a)) / a**2) * (K @ K)


def chain_order(commands: np.ndarray) -> np.ndarray:
    """A nearest-neighbour chain through the samples in command space (greedy, from the smallest command).

    Commands are scaled per column by their spread so tendons of different ranges weigh alike.
    Deterministic (ties: the lower index).  O(n^2): meant for the physics subsample (hundreds).
    """
    c = np.asarray(commands, dtype=float)
    n = c.shape[0]
    if n == 0:
        return np.zeros(0, dtype=int)
    span = np.ptp(c, axis=0)
    c = c / np.where(span > 0, span, 1.0)
    left = np.ones(n, dtype=bool)
    order = [int(np.argmin(np.linalg.norm(c, axis=1)))]
    left[order[0]] = False
    for _ in range(n - 1):
        d = np.linalg.norm(c - c[order[-1]], axis=1)
        d[~left] = np.inf
        k = int(np.argmin(d))
        order.append(k)
        left[k] = False
    return np.asarray(order, dtype=int)


def model_options(solver: Mapping[str, Any], model: str):
    """:class:`~workbench.models.SolverOptions` of ``model``: its ``[solver.by_model]`` table over
    ``[solver]`` (:func:`~workbench.study.by_model.solver_for_model`), the per-case limits left out."""
    own = {k: v for k, v in solver_for_model(solver, model).items() if k not in LIMIT_KEYS}
    return build_options(own)


def _cc_tips(robot, mode: str, commands: np.ndarray) -> np.ndarray:
    """CC tip positions ``(n, 3)`` in the base frame for ``commands`` ``(n, n_tendons)`` (vectorised,
    :func:`workbench.models.cc_batch.cc_tip_positions`)."""
    from ..models.cc_batch import cc_tip_positions

    return np.asarray(cc_tip_positions(robot, mode, commands), dtype=float)


def _cc_backbones(robot, mode: str, commands: np.ndarray, n_stations: int) -> np.ndarray:
    """CC backbones ``(k, n_stations, 3)`` in the base frame (:func:`workbench.models.cc_batch.cc_backbones`)."""
    from ..models.cc_batch import cc_backbones

    return np.asarray(cc_backbones(robot, mode, commands, n_stations), dtype=float)


def _reason(e: BaseException) -> str:
    return f"{type(e).__name__}: {' '.join(str(e).split())[:300]}"


def solve_samples(model: str, robot, load: Mapping[str, Any], options, mode: str, commands: np.ndarray,
                  tip_force: np.ndarray | None, file_rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solve physics model ``model`` for every sample (the one per-sample loop; warm starts go here).

    Parameters
    ----------
    model : str
        Registry name.
    robot, load, options
        The robot, the ``[load]`` fields every sample shares and the model's solver options.
    mode : str
        ``"tension"`` or ``"length"``.
    commands : ndarray, shape (n, n_tendons)
        SI commands with the command zero applied.
    tip_force : ndarray, shape (n, 3), or None
        Tip force of each sample, base frame [N].
    file_rows : ndarray, shape (n,)
        File rows (messages).

    Returns
    -------
    tips : ndarray, shape (n, 3)
        Base frame [m].
    backbones : ndarray, shape (n, n_stations, 3)
        The solved backbones, base frame [m].

    Raises
    ------
    PredictionFailure
        The model raised, did not converge or returned a non-finite tip on a sample.
    """
    from ..models import get_model, quiet_if_loaded

    fn = get_model(model)
    key = "tensions" if mode == "tension" else "length_changes"
    tips = np.empty((commands.shape[0], 3))
    backbones: list[np.ndarray] = [np.zeros(0)] * commands.shape[0]
    for i in chain_order(commands):
        where = f"model {model}, file row {int(file_rows[i])}"
        fields = {**load, "mode": mode, "analysis": "static", key: [float(v) for v in commands[i]]}
        if tip_force is not None:
            fields["tip_force"] = [float(v) for v in tip_force[i]]
        try:
            case = build_load(robot, fields)
            with quiet_if_loaded():
                res = fn(robot, case, options)
        except Exception as e:  # noqa: BLE001 - ModelFailure, exudyn.SolverError, a refused input: the reason
            raise PredictionFailure(f"{where}: {_reason(e)}") from None
        if not res.solver.converged:
            raise PredictionFailure(f"{where}: not converged: {res.solver.message}".rstrip(": "))
        tip = np.asarray(res.tip_frame, dtype=float)[:3, 3]
        if not np.isfinite(tip).all():
            raise PredictionFailure(f"{where}: non-finite tip position")
        tips[i] = tip
        backbones[i] = np.asarray(res.positions, dtype=float)
    return tips, np.stack(backbones) if backbones else np.zeros((0, options.n_stations, 3))


@dataclass
class Timing:
    """Model evaluations counted by a :class:`Predictor`: ``calls`` predictions that ran the model,
    ``samples`` model evaluations of one sample, ``seconds`` spent in the model, ``reused``
    predictions that only moved the last one (a registration change)."""

    calls: int = 0
    samples: int = 0
    seconds: float = 0.0
    reused: int = 0


@dataclass
class Predictor:
    """Tip predictions of one model for the samples of one calibration (module docstring).

    Attributes
    ----------
    model : str
        Registry name (``"cc"``: all samples at once).
    tables : dict
        ``{"robot", "load", "solver"}``: the nominal case parameters.
    names : tuple of str
        Parameter names in vector order.
    measurements : Measurements
    timing : Timing
        Counts of the evaluations so far.
    robots : dict
        Memo of the robots built (:meth:`robot_for`).
    recent : dict
        The last four base-frame predictions, by what they were made for (:meth:`predict`).
    """

    model: str
    tables: dict[str, dict[str, Any]]
    names: tuple[str, ...]
    measurements: Measurements
    timing: Timing = field(default_factory=Timing)
    robots: dict = field(default_factory=dict, repr=False)
    recent: dict = field(default_factory=dict, repr=False)

    def robot_for(self, parts: VectorParts):
        """The robot with the calibrated key-path values and the case parameters (memoised by those
        values: the Jacobian's steps in command zero or registration reuse the robot)."""
        key = tuple(parts.keys.items())
        if key not in self.robots:
            if len(self.robots) >= 8:
                self.robots.clear()
            self.robots[key] = self._build(parts)
        return self.robots[key]

    def _build(self, parts: VectorParts):
        params = dict(self.tables)
        try:
            for path, v in parts.keys.items():
                params = with_value(params, path, v, create=True)
            return build_robot(params["robot"]), params
        except (KeyPathError, TypeError, ValueError) as e:
            shown = ", ".join(f"{k} = {v:.6g}" for k, v in parts.keys.items())
            raise PredictionFailure(f"model {self.model}: the robot with {shown} cannot be built: {_reason(e)}"
                                    ) from None

    def commands(self, parts: VectorParts, idx: np.ndarray) -> np.ndarray:
        """SI commands of samples ``idx`` with the command zero added (tension clipped at 0 N)."""
        c = self.measurements.commands[idx] + parts.command_zero
        return np.maximum(c, 0.0) if self.measurements.mode == "tension" else c

    def predict(self, x: Sequence[float], idx: np.ndarray, backbones: bool = False
                ) -> tuple[np.ndarray, np.ndarray | None]:
        """Tips ``(len(idx), 3)`` of samples ``idx`` in the measurement frame, and their backbones
        ``(len(idx), n_stations, 3)`` when ``backbones`` (else ``None``).

        A recent base-frame prediction is reused when only the registration changed (the
        Jacobian's registration columns: no model evaluation).
        """
        idx = np.asarray(idx, dtype=int)
        m = self.measurements
        parts = split_vector(self.names, x, m.commands.shape[1])
        robot, params = self.robot_for(parts)
        key = (tuple(parts.keys.items()), parts.command_zero.tobytes(), idx.tobytes(), backbones)
        if key in self.recent:
            tips, bb = self.recent[key]
            self.timing.reused += 1
        else:
            tips, bb = self._base_frame(robot, params, parts, idx, backbones)
            if len(self.recent) >= 4:
                del self.recent[next(iter(self.recent))]
            self.recent[key] = (tips, bb)
        return to_frame(tips, m.frame, robot, parts), (None if bb is None else to_frame(bb, m.frame, robot, parts))

    def _base_frame(self, robot, params, parts: VectorParts, idx: np.ndarray, backbones: bool
                    ) -> tuple[np.ndarray, np.ndarray | None]:
        """The model's tips (and backbones) of samples ``idx`` in the base frame (timed)."""
        t0 = time.perf_counter()
        m = self.measurements
        cmd = self.commands(parts, idx)
        options = model_options(params["solver"], self.model)
        if self.model == "cc":
            tips = _cc_tips(robot, m.mode, cmd)
            bb = _cc_backbones(robot, m.mode, cmd, options.n_stations) if backbones else None
        else:
            force = None if m.tip_force is None else m.tip_force[idx]
            load = {k: v for k, v in params["load"].items() if k not in ("tensions", "length_changes")}
            tips, bb = solve_samples(self.model, robot, load, options, m.mode, cmd, force, m.file_rows[idx])
            bb = bb if backbones else None
        self.timing.calls += 1
        self.timing.samples += len(idx)
        self.timing.seconds += time.perf_counter() - t0
        if not np.isfinite(tips).all():
            raise PredictionFailure(f"model {self.model}: non-finite tip position")
        return tips, bb

    def tips(self, x: Sequence[float], idx: np.ndarray) -> np.ndarray:
        """Tips ``(len(idx), 3)`` of samples ``idx`` in the measurement frame (:meth:`predict`)."""
        return self.predict(x, idx)[0]
