"""The calibration engine on CC data with known values: predictions, recovery, intervals, flags, the split.

Synthetic data (:mod:`fit_support`): tips CC predicts at known values (Young's modulus, a tendon's
command zero, the registration) plus Gaussian noise.  The prediction path itself is checked
against ``cc.run`` row by row and against scipy's rotation (independent code), so recovering the
values is not the predictor agreeing with itself.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.special import stdtrit

from fit_support import PARAMETERS, ROBOT, fit_parameters, split_rows, synthetic_study, true_values
from workbench.measure.calibrate import calibrate_on, fit_parameters as fit
from workbench.measure.predict import Predictor, chain_order, rotation_matrix
from workbench.measure.types import Measurements
from workbench.models import SolverOptions
from workbench.models.cc import run as cc_run
from workbench.robot import LoadCase, TendonActuation
from workbench.study.build import build_robot

ALL = tuple(PARAMETERS)


def test_rotation_matrix_equals_scipy():
    for r in ([0.3, -0.2, 1.1], [1e-10, 2e-9, 0.0], [0.0, 0.0, 3.0]):
        assert np.allclose(rotation_matrix(r), Rotation.from_rotvec(r).as_matrix(), atol=1e-15)


def test_cc_tips_equal_cc_run_with_zero_and_registration():
    """Predicted tips = R (cc.run tip of E, commands + zero) + t, row by row (tension clipped at 0)."""
    rng = np.random.default_rng(3)
    cmd = rng.uniform(0.0, 2.0, (5, 6))
    cmd[0, 1] = 0.1  # with command_zero[1] = -0.3 this tendon would push: clipped to 0 N
    m = Measurements("x.csv", "tension", cmd, np.zeros((5, 3)), "measurement", np.arange(1, 6))
    x = np.array([60e9, -0.3, 0.01, -0.02, 0.03, 0.05, -0.1, 0.2])
    got = Predictor("cc", {"robot": ROBOT, "load": {}, "solver": {}}, ALL, m).tips(x, np.arange(5))
    robot = build_robot({**ROBOT, "youngs_modulus": 60e9})
    R = Rotation.from_rotvec(x[5:]).as_matrix()
    for i in range(5):
        c = cmd[i].copy()
        c[1] = max(0.0, c[1] - 0.3)
        tip = cc_run(robot, LoadCase(actuation=TendonActuation("tension", tuple(c))), SolverOptions()).tip_frame[:3, 3]
        assert np.allclose(got[i], R @ tip + x[2:5], rtol=0, atol=1e-12)


def test_world_and_base_frames():
    robot = {**ROBOT, "base_orientation": "horizontal"}
    cmd = np.array([[1.0, 0.0, 0.0, 0.5, 0.0, 0.0]])
    tips = {}
    for frame in ("base", "world"):
        m = Measurements("x.csv", "tension", cmd, np.zeros((1, 3)), frame, np.array([1]))
        tips[frame] = Predictor("cc", {"robot": robot, "load": {}, "solver": {}}, (), m).tips(np.zeros(0), [0])[0]
    r = build_robot(robot)
    assert np.allclose(tips["world"], np.asarray(r.base_rotation) @ tips["base"] + np.asarray(r.base_position))
    assert not np.allclose(tips["world"], tips["base"])


def test_chain_order_visits_every_sample_once_by_nearest_neighbour():
    c = np.array([[5.0], [0.0], [1.0], [4.0], [2.0]])
    assert chain_order(c).tolist() == [1, 2, 4, 3, 0]


def test_recovers_known_values_within_their_intervals():
    st = synthetic_study(60, ALL, seed=1, noise=1e-4)
    rows = split_rows(60, 0.25, seed=1)
    p = Predictor("cc", {"robot": st.robot, "load": {}, "solver": {}}, ALL, st.measurements)
    res = calibrate_on(p, st.calibration.parameters, st.measurements.tip_position, rows.train, 0.95, 200, None)
    truth = true_values(ALL)
    assert res.success, res.message
    assert np.all((res.ci_low <= truth) & (truth <= res.ci_high)), (res.values, truth)
    assert np.all(np.isfinite(res.ci_high - res.ci_low)) and not res.at_bound.any() and not res.unidentifiable
    # the residual standard deviation estimates the noise (1e-4 m per coordinate; 135 degrees of freedom)
    assert 0.8e-4 < res.sigma < 1.2e-4
    # the intervals are informative: E to better than 1 %
    assert (res.ci_high[0] - res.ci_low[0]) / truth[0] < 0.01


def _coverage(confidence_pairs, seeds):
    """Fraction of seeds whose interval holds the truth, per parameter, at each confidence of the pairs."""
    names = ("robot.youngs_modulus", "command_zero[1]", "registration.translation[0]", "registration.rotation[1]")
    truth = true_values(names)
    hits = {c: np.zeros(len(names)) for c in confidence_pairs}
    for seed in seeds:
        st = synthetic_study(30, names, seed=100 + seed, noise=2e-4)
        p = Predictor("cc", {"robot": st.robot, "load": {}, "solver": {}}, names, st.measurements)
        res = calibrate_on(p, st.calibration.parameters, st.measurements.tip_position, np.arange(30), 0.95, 200,
                           None)
        assert res.success, res.message
        dof = 3 * 30 - len(names)
        half95 = (res.ci_high - res.ci_low) / 2
        for c in confidence_pairs:
            half = half95 * stdtrit(dof, 0.5 + c / 2) / stdtrit(dof, 0.975)
            hits[c] += np.abs(res.values - truth) <= half
    return {c: h / len(seeds) for c, h in hits.items()}


@pytest.mark.slow
def test_interval_coverage_over_40_seeds():
    """95 % intervals hold the truth in 80-100 % of 40 seeds, 50 % intervals in 25-75 %.

    Bands: the count of hits is binomial(40, c); 80 % is 4.3 standard deviations (1.4 hits) below
    38 of 40, 25 % / 75 % are 3.2 standard deviations (3.2 hits) around 20 of 40, so a correct
    interval fails this test with a probability below 1e-3, while intervals half as wide as they
    should be (coverage 68 % at 95 %) or twice as wide (coverage 82 % at 50 %) fail it.
    """
    cov = _coverage((0.95, 0.5), range(40))
    assert np.all((cov[0.95] >= 0.8) & (cov[0.95] <= 1.0)), cov
    assert np.all((cov[0.5] >= 0.25) & (cov[0.5] <= 0.75)), cov


def test_value_beyond_a_bound_is_flagged_at_the_bound():
    names = ("robot.youngs_modulus", "registration.translation[2]")
    st = synthetic_study(30, names, seed=2, noise=1e-5, truth={"robot.youngs_modulus": 90e9})  # upper bound 80e9
    p = Predictor("cc", {"robot": st.robot, "load": {}, "solver": {}}, names, st.measurements)
    res = calibrate_on(p, st.calibration.parameters, st.measurements.tip_position, np.arange(30), 0.95, 100, None)
    assert res.at_bound.tolist() == [True, False]
    assert res.values[0] == pytest.approx(80e9, rel=1e-6)


def test_unidentifiable_pair_gets_infinite_intervals_and_is_named():
    """CC in tension mode sees only tendon_offset / E (curvature = T d / EI): both are named, neither crashes."""
    table = {**PARAMETERS, "robot.tendon_offset": (0.01, 0.012, 0.005, 0.02)}
    names = ("robot.youngs_modulus", "robot.tendon_offset", "registration.translation[0]")
    st = synthetic_study(30, names, seed=4, noise=1e-4, table=table)
    p = Predictor("cc", {"robot": st.robot, "load": {}, "solver": {}}, names, st.measurements)
    res = calibrate_on(p, fit_parameters(names, table), st.measurements.tip_position, np.arange(30), 0.95, 100,
                       None)
    assert res.unidentifiable == ("robot.youngs_modulus", "robot.tendon_offset")
    assert np.isinf(res.ci_high[:2]).all() and np.isfinite(res.ci_high[2])
    assert "not identifiable from these data: robot.youngs_modulus, robot.tendon_offset" in res.message
    # the identifiable ratio is still recovered: offset / E as generated
    assert res.values[1] / res.values[0] == pytest.approx(0.01 / 60e9, rel=2e-3)


def test_fit_sees_only_training_rows():
    names = ("robot.youngs_modulus", "registration.translation[0]")
    st = synthetic_study(40, names, seed=5)
    rows = split_rows(40, 0.25, seed=5)
    seen: list[np.ndarray] = []

    class Spy(Predictor):
        def predict(self, x, idx, backbones=False):
            seen.append(np.asarray(idx))
            return super().predict(x, idx, backbones)

    p = Spy("cc", {"robot": st.robot, "load": {}, "solver": {}}, names, st.measurements)
    res = calibrate_on(p, st.calibration.parameters, st.measurements.tip_position, rows.train, 0.95, 100, None)
    assert res.success and len(seen) == res.evaluations > 3
    assert p.timing.reused > 0 and p.timing.calls + p.timing.reused == res.evaluations  # registration steps reuse
    assert all(np.array_equal(s, rows.train) for s in seen)
    assert not np.isin(rows.test, np.concatenate(seen)).any()


def test_too_few_residuals_give_no_intervals():
    names = ("robot.youngs_modulus", "registration.translation[0]")
    res = fit(lambda x: np.array([x[0] / 60e9 - 1.0, x[1] - 0.01]), fit_parameters(names), 0.95, 50, None)
    assert np.isinf(res.ci_high).all() and "no intervals" in res.message
