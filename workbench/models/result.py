"""The one result type every model returns (CC kinematics included), and the solver options.

Importing this module does not import Exudyn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, Mapping

import numpy as np

__all__ = ["SolverInfo", "PhysicsResult", "SolverOptions", "ModelFailure", "series_times"]


def series_times(duration: float, time_step: float) -> np.ndarray:
    """Output times [s] of a dynamic analysis: every model's stored series use this grid.

    ``n = max(1, round(duration / time_step))`` steps of ``h = duration / n``, recorded every
    ``max(h, duration / 1000)`` rounded to a whole number of steps, from 0 to ``duration``
    (at most ~1000 samples, so one study's series share one time resolution).
    """
    n = max(1, int(round(float(duration) / float(time_step))))
    h = float(duration) / n
    k = max(1, int(round(max(h, float(duration) / 1000.0) / h)))
    return np.append(np.arange(0, n, k) * h, float(duration)) if n % k else np.arange(0, n + 1, k) * h


class ModelFailure(RuntimeError):
    """A model could not produce a trustworthy result (no convergence, nonsense state, ...).

    Models raise it (or let ``exudyn.SolverError`` propagate); the study runner records the
    case as failed with ``str(error)`` as the reason.
    """


@dataclass(frozen=True)
class SolverOptions:
    """Discretisation and solver settings common to the models.

    Parameters
    ----------
    n_elements : int
        Number of beam elements (ANCF / geometrically exact) or rigid links (spring-link).
    tendon_model : {"continuum", "eyelets"}
        ``"continuum"``: frictionless tendon with continuous routing, applied as its exact
        distributed load (uniform moment T d plus compression T).  ``"eyelets"``: one
        frictionless rope per tendon through eyelets at the disks.
    n_stations : int
        Number of equally spaced arc-length stations (0..L) at which backbones are reported.
    newton_tolerance : float
        Relative Newton tolerance on the step size (Exudyn ``residualMode = 1``).
    max_load_steps : int
        Cap on (adaptive) static load steps; exceeding it is a failure, not a silent success.
    time_step : float
        Implicit (generalised-alpha) time step [s] for dynamic analyses.
    damping : float
        Model-specific viscous damping parameter (see each model's docstring).
    spectral_radius : float
        Generalised-alpha numerical damping (spectral radius at infinity), in [0, 1].
    model_settings : mapping of str to mapping
        Settings of one model's own solver, by model name (a tuple of ``(name, ((key, value),
        ...))`` pairs is accepted); the model reads its entry with :meth:`settings`, e.g.
        ``{"spring_link": {"backend": "tree"}}`` (the study key ``[solver] spring_link_backend``,
        :func:`workbench.study.build.build_options`).
    warm_state : ndarray, optional
        An opaque state of an earlier solve of the same model and robot
        (:attr:`PhysicsResult.warm_state`) the model may start from (:mod:`workbench.models.warm`);
        a model without warm starts, or one that finds it incompatible, ignores it.  Not part of
        equality, hashing or ``repr``.

    The study pipeline's own ``[solver]`` keys (``error_estimate``, ``error_estimate_exempt``) are not
    here (:class:`workbench.study.build.PipelineOptions`), nor ``by_model``: a model's options are built
    with its ``[solver.by_model.<model>]`` table applied (:mod:`workbench.study.by_model`).
    """

    n_elements: int = 16
    tendon_model: Literal["continuum", "eyelets"] = "continuum"
    n_stations: int = 33
    newton_tolerance: float = 1e-9
    max_load_steps: int = 200
    time_step: float = 2e-3
    damping: float = 0.0
    spectral_radius: float = 0.8
    model_settings: tuple[tuple[str, tuple[tuple[str, object], ...]], ...] = ()
    warm_state: np.ndarray | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.warm_state is not None:
            object.__setattr__(self, "warm_state", np.asarray(self.warm_state, dtype=float).reshape(-1))
        for name in ("n_elements", "n_stations", "max_load_steps"):
            v = getattr(self, name)
            if int(v) != v or v < (2 if name == "n_stations" else 1):
                raise ValueError(f"SolverOptions.{name} must be a positive integer, got {v!r}")
            object.__setattr__(self, name, int(v))
        if self.tendon_model not in ("continuum", "eyelets"):
            raise ValueError(f"SolverOptions.tendon_model must be 'continuum' or 'eyelets', got {self.tendon_model!r}")
        for name in ("newton_tolerance", "time_step"):
            v = float(getattr(self, name))
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"SolverOptions.{name} must be finite and > 0, got {v}")
            object.__setattr__(self, name, v)
        if not (math.isfinite(self.damping) and self.damping >= 0):
            raise ValueError(f"SolverOptions.damping must be finite and >= 0, got {self.damping}")
        if not (0.0 <= self.spectral_radius <= 1.0):
            raise ValueError(f"SolverOptions.spectral_radius must be in [0, 1], got {self.spectral_radius}")
        ms = self.model_settings
        object.__setattr__(self, "model_settings", tuple(sorted(
            (str(m), tuple(sorted((str(k), v) for k, v in (kv.items() if isinstance(kv, Mapping) else kv))))
            for m, kv in (ms.items() if isinstance(ms, Mapping) else ms))))

    def settings(self, model: str) -> dict[str, object]:
        """The own settings of model ``model`` (``{}`` when none are given)."""
        return dict(dict(self.model_settings).get(str(model), ()))


@dataclass(frozen=True)
class SolverInfo:
    """How a solve went.

    ``path_steps``: accepted steps of the static load path (0: not a ramped static solve);
    ``path_event``: ``""`` when the path from the unloaded state was followed without an event,
    ``"jump"`` when the state jumped at a step that could not be refined (a limit point or snap:
    the answer may lie on another equilibrium branch than the one loaded from the start),
    ``"bifurcation"`` when the tangent stiffness changed sign on the path;
    ``path_event_fraction``: the load fraction of the first event (NaN without one).  Set by the
    load ramp (:func:`workbench.physics._stepping.load_ramp`); checked by ``tests/physics/test_load_path.py``.
    """

    converged: bool
    iterations: int = 0
    wall_time: float = 0.0
    message: str = ""
    path_steps: int = 0
    path_event: str = ""
    path_event_fraction: float = math.nan


@dataclass(frozen=True)
class PhysicsResult:
    """Outcome of one model evaluation; all quantities in the robot's base frame, SI units.

    Parameters
    ----------
    model : str
        Model name (``"cc"``, ``"ancf"``, ``"beam3d"``, ``"spring_link"``, ...).
    stations : ndarray, shape (m,)
        Reference (undeformed) arc-length stations [m], 0..L.
    positions : ndarray, shape (m, 3)
        Backbone centreline points at the stations (final state for dynamics) [m].
    tip_frame : ndarray, shape (4, 4)
        Homogeneous transform base <- tip (z axis along the backbone tangent).
    length_change : float
        Deformed minus reference backbone centreline length [m] (negative = compressed).
    tendon_tensions : ndarray, shape (n_tendons,)
        Final tendon tensions [N] (global tendon order; 0 for slack tendons).
    tip_twist : float
        Rotation of the tip cross-section about the backbone tangent [rad], relative to the
        torsion-free (parallel-transport) frame; 0 for models without torsion.
    solver : SolverInfo
        Convergence, iterations, wall time.
    joint_angles : ndarray, optional
        Spring-link models: joint angles [rad], shape (n_joints, dofs_per_joint).
    time : ndarray, optional, shape (k,)
        Output times [s] of a dynamic analysis.
    series : mapping of str to ndarray, optional
        Time series, each shape (k, ...) (e.g. ``"tip_position"`` (k, 3),
        ``"tendon_tensions"`` (k, n_tendons), ``"length_change"`` (k,)).
    extras : mapping of str to float
        Model-specific scalar outputs (documented by each model).
    warm_state : ndarray, optional
        An opaque plain-numpy state a later solve of the same model and robot may start from
        (``SolverOptions.warm_state``, :mod:`workbench.models.warm`); ``None`` when the model has
        no warm starts or the state is not a safe start (a load-path event).  Not stored in the
        result rows; not part of equality or ``repr``.
    """

    model: str
    stations: np.ndarray
    positions: np.ndarray
    tip_frame: np.ndarray
    length_change: float
    tendon_tensions: np.ndarray
    tip_twist: float
    solver: SolverInfo
    joint_angles: np.ndarray | None = None
    time: np.ndarray | None = None
    series: Mapping[str, np.ndarray] = field(default_factory=dict)
    extras: Mapping[str, float] = field(default_factory=dict)
    warm_state: np.ndarray | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        st = np.asarray(self.stations, dtype=float)
        pos = np.asarray(self.positions, dtype=float)
        if st.ndim != 1 or pos.shape != (st.size, 3):
            raise ValueError(f"positions must have shape ({st.size}, 3) to match stations, got {pos.shape}")
        T = np.asarray(self.tip_frame, dtype=float)
        if T.shape != (4, 4):
            raise ValueError(f"tip_frame must have shape (4, 4), got {T.shape}")
        object.__setattr__(self, "stations", st)
        object.__setattr__(self, "positions", pos)
        object.__setattr__(self, "tip_frame", T)
        object.__setattr__(self, "tendon_tensions", np.asarray(self.tendon_tensions, dtype=float).reshape(-1))
        object.__setattr__(self, "length_change", float(self.length_change))
        object.__setattr__(self, "tip_twist", float(self.tip_twist))

    @property
    def tip_position(self) -> np.ndarray:
        """``(3,)`` tip position [m]."""
        return self.tip_frame[:3, 3]
