"""A physics model calibrated on data it generated itself: the Cosserat rod recovers E and the registration.

Slow (the Cosserat kernel compiles in a fresh process, then every residual evaluation solves each
sample): marked ``slow``; run it on its own.
"""

from __future__ import annotations

import numpy as np
import pytest

from fit_support import PARAMETERS, split_rows, synthetic_study, true_values
from workbench.measure.rows import calibration_row
from workbench.study.params import flatten_params

ROD = {"preset": "steel_rod", "length": 0.2, "n_sections": 1, "diameter": 1.0e-3, "youngs_modulus": 54e9,
       "tendon_count": 3, "tendon_offset": 0.01, "base_orientation": "horizontal"}
NAMES = ("robot.youngs_modulus", "registration.translation[2]", "registration.rotation[0]")


@pytest.mark.slow
def test_cosserat_recovers_its_own_values():
    """10 samples (8 fitted), tension mode, gravity across the rod: E, a translation and a rotation
    come back within their intervals, and the held-out tips within a few noise levels."""
    solver = {"n_elements": 16}
    st = synthetic_study(10, NAMES, seed=11, noise=2e-5, model="cosserat", robot=ROD, solver=solver, high=1.5,
                         models=("cosserat",))
    rows = split_rows(10, 0.2, seed=11, physics=10)
    row = calibration_row("c", "cosserat", st, rows, flatten_params({"calibration": {"fold": 0}}))
    assert row["status"] == "ok", row["error"]
    assert row["calib.converged"], row["calib.message"]
    truth = true_values(NAMES)
    low, high = np.array(row["calib.ci_low"]), np.array(row["calib.ci_high"])
    assert np.all((low <= truth) & (truth <= high)), (row["calib.values"], truth)
    assert (high[0] - low[0]) / truth[0] < 0.005  # E to better than 0.5 % from 8 tips with 20 um noise
    assert row["err.test_rms"] < 5 * 2e-5 * np.sqrt(3)
    assert row["calib.seconds_per_evaluation"] > 0 and len(row["view.file_row"]) == 2
    assert PARAMETERS["robot.youngs_modulus"][0] == truth[0]
