"""Synthetic calibration studies for the calibration tests: data a model generated itself, with known values.

:func:`synthetic_study` builds a :class:`~workbench.measure.types.CalibrationStudy` directly (no
study file): random tendon commands, the tips a model predicts for them at the *true* parameter
vector (through :class:`~workbench.measure.predict.Predictor`, whose CC path
``tests/measure/test_measure_calibrate.py`` checks against ``cc.run`` and an independent rotation)
plus Gaussian noise; :func:`split_rows` a seeded split into training and test rows.
"""

from __future__ import annotations

import numpy as np

from workbench.measure.predict import Predictor
from workbench.measure.types import (CalibrationSettings, CalibrationStudy, FitParameter, FoldRows, Measurements,
                                     Split)

#: a small two-section NiTi rod with three tendons per section (the preset form of steel_rod)
ROBOT = {"preset": "steel_rod", "length": 0.4, "n_sections": 2, "diameter": 1.4e-3, "youngs_modulus": 54e9,
         "tendon_count": 3, "tendon_offset": 0.01}
#: name -> (true value, initial, lower, upper)
PARAMETERS = {
    "robot.youngs_modulus": (60e9, 54e9, 30e9, 80e9),
    "command_zero[1]": (0.2, 0.0, -0.5, 0.5),
    "registration.translation[0]": (0.01, 0.0, -0.1, 0.1),
    "registration.translation[1]": (-0.02, 0.0, -0.1, 0.1),
    "registration.translation[2]": (0.03, 0.0, -0.1, 0.1),
    "registration.rotation[0]": (0.05, 0.0, -0.5, 0.5),
    "registration.rotation[1]": (-0.1, 0.0, -0.5, 0.5),
    "registration.rotation[2]": (0.2, 0.0, -0.5, 0.5),
}


def fit_parameters(names, table=PARAMETERS) -> tuple[FitParameter, ...]:
    """The :class:`FitParameter` of ``names`` (start, bounds from ``table``)."""
    return tuple(FitParameter(n, table[n][1], table[n][2], table[n][3], "", "test") for n in names)


def split_rows(n: int, test_fraction: float, seed: int, physics: int | None = None) -> FoldRows:
    """A seeded split of ``n`` samples (``physics``: the size of the physics subsamples, default all)."""
    rng = np.random.default_rng(seed)
    perm = rng.permutation(n)
    k = int(round(test_fraction * n))
    test, train = np.sort(perm[:k]), np.sort(perm[k:])
    p = physics if physics is not None else n
    return FoldRows(0, train, test, np.sort(train[:p]), np.sort(test[:p]))


def synthetic_study(n: int, names, seed: int = 0, noise: float = 1e-4, model: str = "cc", robot=None,
                    truth=None, table=PARAMETERS, mode: str = "tension", high: float = 3.0, solver=None,
                    frame: str = "measurement", models=("cc",), tip_force=None) -> CalibrationStudy:
    """A calibration study whose tips ``model`` generated at the true values of ``names`` plus noise.

    ``truth``: overrides of the true values (name -> value); ``noise``: standard deviation per
    coordinate [m]; commands uniform in ``[0, high]`` (tension mode) or ``[-high, 0]`` (length).
    """
    robot = dict(ROBOT if robot is None else robot)
    rng = np.random.default_rng(seed)
    from workbench.study.build import build_robot

    n_t = build_robot(robot).n_tendons
    lo, hi = (0.0, high) if mode == "tension" else (-high, 0.0)
    cmd = rng.uniform(lo, hi, (n, n_t))
    rows = np.arange(1, n + 1)
    x_true = np.array([(truth or {}).get(k, table[k][0]) for k in names])
    blank = Measurements("synthetic.csv", mode, cmd, np.zeros((n, 3)), frame, rows, tip_force=tip_force)
    tables = {"robot": robot, "load": {}, "solver": dict(solver or {})}
    tips = Predictor(model, tables, tuple(names), blank).tips(x_true, np.arange(n))
    meas = Measurements("synthetic.csv", mode, cmd, tips + rng.normal(0.0, noise, tips.shape), frame, rows,
                        tip_force=tip_force)
    settings = CalibrationSettings(models=tuple(models), parameters=fit_parameters(names, table),
                                   split=Split(seed=seed, test_fraction=0.25, folds=None, physics_rows=n))
    return CalibrationStudy(path="synthetic.toml", name="synthetic", config_hash=f"synthetic-{seed}", robot=robot,
                            load={}, solver=dict(solver or {}), report={}, measurements=meas, calibration=settings)


def true_values(names, truth=None, table=PARAMETERS) -> np.ndarray:
    """The true parameter vector of :func:`synthetic_study`."""
    return np.array([(truth or {}).get(k, table[k][0]) for k in names])


#: the calibration study tests/study/test_kind_contract.py runs (its data: :func:`write_contract_data`)
CONTRACT_STUDY = "fixtures/fit_contract.toml"


def write_contract_data(path) -> None:
    """Write ``fixtures/fit_contract.csv``: 24 samples, tips CC predicts for :data:`ROBOT` at E = 60 GPa
    and the registration of :data:`PARAMETERS`, plus 0.1 mm noise, in mm (``python -c "import fit_support;
    fit_support.write_contract_data('fixtures/fit_contract.csv')"`` in ``tests/measure``)."""
    names = ("robot.youngs_modulus", "registration.translation[0]", "registration.translation[1]",
             "registration.translation[2]", "registration.rotation[0]", "registration.rotation[1]",
             "registration.rotation[2]")
    st = synthetic_study(24, names, seed=21, noise=1e-4)
    m = st.measurements
    lines = ["T1,T2,T3,T4,T5,T6,x,y,z"]
    for c, p in zip(m.commands, m.tip_position * 1e3):
        lines.append(",".join(f"{v:.6f}" for v in (*c, *p)))
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
