"""What a calibration study is made of: measured samples, the parameters to calibrate, the split.

A *calibration study* (``[study] kind = "calibration"``, ``docs/measurements.md``) reads a robot's
measured data (``[measurements]``: a CSV or Parquet file and the meaning of its columns), calibrates
each listed model's unknown parameters on the training rows by nonlinear least squares
(``[calibration]``) and predicts the held-out rows.  This module holds the frozen values passed
between the layers of that pipeline; it imports nothing of the workbench, so every layer may use it.

Conventions
-----------
- Everything is SI after reading (m, N, rad); the units of the file's columns are converted once,
  by the reader, through the one units table.
- ``commands`` follow :class:`workbench.robot.TendonActuation`: one column per tendon of
  ``robot.tendon_table()``, tension [N] in ``"tension"`` mode, change of free length [m] in
  ``"length"`` mode (negative = reeled in).
- Positions are in the frame ``Measurements.frame`` names: ``"base"`` or ``"world"`` (the robot's
  frames, ``docs/architecture.md``) or ``"measurement"`` -- the tracker's own frame, related to the
  base frame by a rigid transform that is calibrated (``registration.*`` parameters):
  ``p_measurement = R(rotation) @ p_base + translation``, ``R`` from the rotation vector
  (axis times angle, rad).
- A calibrated parameter is named by a *key path* into the case parameters (``robot.youngs_modulus``,
  ``robot.sections[1].length``; :mod:`workbench.study.keypath`) or by one of the calibration's own
  names: ``command_zero[i]`` (a constant added to tendon ``i``'s command: tendon slack or an encoder
  zero, in the command's SI unit) and ``registration.translation[j]`` [m] /
  ``registration.rotation[j]`` [rad], ``j`` in 0..2.

Checked by ``tests/measure/``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["CalibrationSettings", "CalibrationStudy", "FitParameter", "FoldRows", "Measurements", "Split",
           "FRAMES", "MODES", "SPLIT_CODES"]

#: frames a measured position may be given in
FRAMES = ("measurement", "base", "world")
#: tendon command modes (as :class:`workbench.robot.TendonActuation`)
MODES = ("tension", "length")
#: ``sample.split`` codes of a result row: the role each evaluated sample played in one calibration
SPLIT_CODES = {"train": 0, "test": 1}


@dataclass(frozen=True, eq=False)
class Measurements:
    """Measured samples in SI units: what the robot was commanded and where its tip was seen.

    Attributes
    ----------
    source : str
        The data file as the study file names it (messages and provenance).
    mode : str
        ``"tension"`` or ``"length"``.
    commands : ndarray, shape (n, n_tendons)
        Tendon commands [N] or [m] in ``robot.tendon_table()`` order (module docstring).
    tip_position : ndarray, shape (n, 3)
        Measured tip position [m] in ``frame``.
    frame : str
        One of :data:`FRAMES`.
    file_rows : ndarray of int, shape (n,)
        The 1-based data row of each sample in the file (the header line not counted).
    tip_force : ndarray, shape (n, 3), optional
        Force applied at the tip [N] in the base frame.
    tip_orientation : ndarray, shape (n, 3, 3), optional
        Measured tip orientation: rotation matrices ``frame <- tip``.
    backbone_stations : ndarray, shape (k,), optional
        Reference arc length [m] of the measured backbone points.
    backbone : ndarray, shape (n, k, 3), optional
        Measured backbone points [m] in ``frame``.
    """

    source: str
    mode: str
    commands: np.ndarray
    tip_position: np.ndarray
    frame: str
    file_rows: np.ndarray
    tip_force: np.ndarray | None = None
    tip_orientation: np.ndarray | None = None
    backbone_stations: np.ndarray | None = None
    backbone: np.ndarray | None = None

    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.commands.shape[0])


@dataclass(frozen=True)
class FitParameter:
    """One calibrated parameter.

    Attributes
    ----------
    name : str
        A key path into the case parameters or a calibration name (module docstring).
    initial, lower, upper : float
        Start value and bounds, SI units; ``lower < initial < upper``.
    unit : str
        Its unit (from :mod:`workbench.units`).
    source : str
        Where the start value comes from (``"preset rao_2021"``, ``"set in the study file"``).
    """

    name: str
    initial: float
    lower: float
    upper: float
    unit: str
    source: str


@dataclass(frozen=True)
class Split:
    """How samples are split into training and held-out (test) rows; seeded, so it is reproducible.

    Attributes
    ----------
    seed : int
        Seed of the shuffle.
    test_fraction : float or None
        One split: this fraction of the rows is held out (fold 0 only).
    folds : int or None
        k-fold: fold ``f`` holds out the ``f``-th of ``folds`` parts.  Exactly one of
        ``test_fraction`` and ``folds`` is set.
    physics_rows : int
        Training rows a physics model is calibrated on (a seeded subsample of the training rows),
        and held-out rows it predicts (a seeded subsample of the test rows); CC uses every row.
    """

    seed: int
    test_fraction: float | None
    folds: int | None
    physics_rows: int


@dataclass(frozen=True, eq=False)
class FoldRows:
    """Sample indices (into :class:`Measurements`, sorted) of one fold.

    ``train`` and ``test`` are disjoint; ``physics_train`` is a subset of ``train``,
    ``physics_test`` a subset of ``test``.
    """

    fold: int
    train: np.ndarray
    test: np.ndarray
    physics_train: np.ndarray
    physics_test: np.ndarray


@dataclass(frozen=True)
class CalibrationSettings:
    """The ``[calibration]`` table, validated.

    Attributes
    ----------
    models : tuple of str
        Models to calibrate (registry names, ``cc`` included when listed).
    parameters : tuple of FitParameter
        The unknowns, in the order of the parameter vector.
    split : Split
    confidence : float
        Level of the reported confidence intervals (default 0.95).
    max_evaluations : int
        Residual evaluations allowed per calibration (scipy ``least_squares`` ``max_nfev``).
    """

    models: tuple[str, ...]
    parameters: tuple[FitParameter, ...]
    split: Split
    confidence: float = 0.95
    max_evaluations: int = 100


@dataclass(frozen=True, eq=False)
class CalibrationStudy:
    """A validated calibration study file (what ``CalibrationKind.load`` returns).

    Attributes
    ----------
    path, name, config_hash : str
        The study file, its name, the SHA-256 of its resolved content.
    robot : dict
        The ``[robot]`` table (preset or description form, ``docs/robot-format.md``): the nominal
        robot; calibrated robot keys replace its values.
    load : dict
        ``[load]`` fields every sample shares (e.g. ``pretension``); the commands and tip forces come
        from the data file.
    solver : dict
        ``[solver]`` settings, with ``by_model`` tables as in sweep studies.
    report : dict
        ``[report]`` settings.
    measurements : Measurements
    calibration : CalibrationSettings
    overrides, notes, warnings : tuple of str
        The study-kind contract (:class:`workbench.study.kinds.StudyKind`).
    """

    path: str
    name: str
    config_hash: str
    robot: dict[str, Any]
    load: dict[str, Any]
    solver: dict[str, Any]
    report: dict[str, Any]
    measurements: Measurements
    calibration: CalibrationSettings
    overrides: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    raw: dict[str, Any] = field(default_factory=dict)

    def resolved(self) -> dict[str, Any]:
        """The study as run (the manifest records it): the file's tables with overrides applied."""
        return dict(self.raw)
