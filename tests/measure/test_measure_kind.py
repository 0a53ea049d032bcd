"""The calibration study kind: cases, payloads, limits and the row of each (model, fold).

Studies are built directly (:mod:`fit_support`), not read from a file (the reader is
``workbench.measure.spec``'s; ``tests/study/test_kind_contract.py`` runs the kind on a file).  A
"physics" model here is CC called through the per-sample path (registered under another name), so
the physics path is checked against the batched CC path at test speed; a real physics model is in
``test_measure_calibrate_physics.py``.
"""

from __future__ import annotations

import json
import sys
import types
from dataclasses import replace

import numpy as np
import pytest

from fit_support import split_rows, synthetic_study, true_values
from workbench import models as models_module
from workbench import registry
from workbench.measure import kind as kind_module
from workbench.measure.rows import calibration_row, spread_samples
from workbench.measure.types import SPLIT_CODES, Split
from workbench.models import ModelFailure
from workbench.models.cc import run as cc_run
from workbench.study import get_kind
from workbench.study.params import flatten_params

NAMES = ("robot.youngs_modulus", "command_zero[1]", "registration.translation[0]", "registration.translation[1]",
         "registration.translation[2]", "registration.rotation[2]")
#: the columns of docs/measurements.md ("Result rows"), ok rows
COLUMNS = ("case_id", "model", "status", "error", "failure", "wall_time", "fold", "robot_length", "calib.converged",
           "calib.message", "calib.evaluations", "calib.seconds_per_evaluation", "calib.names", "calib.units",
           "calib.sources", "calib.initial", "calib.lower", "calib.upper", "calib.values", "calib.ci_low",
           "calib.ci_high", "calib.at_bound", "calib.confidence", "err.train_rms", "err.train_median",
           "err.train_p95", "err.train_max", "err.test_rms", "err.test_median", "err.test_p95", "err.test_max",
           "err.common_test_rms", "sample.file_row", "sample.split", "sample.commands", "sample.measured",
           "sample.predicted", "view.file_row", "view.positions", "view.measured_backbone")


def _fake_models(monkeypatch, fail_row: int | None = None):
    """``cc_each`` = CC through the per-sample path; ``fails`` raises ModelFailure on file row ``fail_row``;
    ``stalls`` returns a result that did not converge."""
    real = models_module.get_model

    def fails(robot, load, options):
        if fail_row is not None and abs(load.actuation.values[0] - fails.command) < 1e-12:
            raise ModelFailure("Newton diverged")
        return cc_run(robot, load, options)

    def stalls(robot, load, options):
        res = cc_run(robot, load, options)
        return replace(res, solver=replace(res.solver, converged=False, message="load step limit"))

    table = {"cc_each": cc_run, "fails": fails, "stalls": stalls}
    monkeypatch.setattr(models_module, "get_model", lambda name: table[name] if name in table else real(name))
    return fails


def _row(study, model, rows):
    return calibration_row("c0", model, study, rows, flatten_params({"calibration": {"fold": rows.fold}}))


def test_kind_is_registered():
    assert get_kind("calibration") is kind_module.KIND
    assert registry.table("kinds")["calibration"].target == "workbench.measure.kind:KIND"


def test_one_case_per_fold_with_stable_ids():
    kind = kind_module.KIND
    st = synthetic_study(20, NAMES[:1], models=("cc", "cosserat"))
    assert kind.count(st) == len(kind.expand(st)) == 1
    five = replace(st, calibration=replace(st.calibration, split=Split(1, None, 5, 20)))
    cases = kind.expand(five)
    assert [c.params["calibration"]["fold"] for c in cases] == [0, 1, 2, 3, 4] == [c.index for c in cases]
    assert len({c.case_id for c in cases}) == 5
    assert [c.case_id for c in kind.expand(five)] == [c.case_id for c in cases]
    other = replace(five, config_hash="another")
    assert not {c.case_id for c in kind.expand(other)} & {c.case_id for c in cases}
    assert kind.models(st) == ("cc", "cosserat")
    rec = flatten_params(kind.recorded_params(five, cases[2]))
    assert rec["p.calibration.fold"] == 2 and rec["p.robot.preset"] == "steel_rod"


def test_limits_from_the_solver_table():
    st = synthetic_study(10, NAMES[:1], solver={"max_case_seconds": 120.0})
    assert kind_module.KIND.limits(st).seconds == 120.0
    assert kind_module.KIND.limits(synthetic_study(10, NAMES[:1])).seconds == 3600.0
    assert "max_case_seconds" not in kind_module.KIND.expand(st)[0].params["solver"]


def test_cc_row_has_every_column_and_stores(tmp_path):
    from workbench.study.store import ResultStore, array_shapes, read_table

    st = synthetic_study(80, NAMES, seed=7, noise=1e-4)
    rows = split_rows(80, 0.25, seed=7, physics=10)
    row = _row(st, "cc", rows)
    assert row["status"] == "ok", row["error"]
    assert set(COLUMNS) <= set(row), set(COLUMNS) - set(row)
    truth = true_values(NAMES)
    assert np.all((np.array(row["calib.ci_low"]) <= truth) & (truth <= np.array(row["calib.ci_high"])))
    assert json.loads(row["calib.names"]) == list(NAMES)
    n = rows.train.size + rows.test.size
    assert row["sample.file_row"] == sorted(row["sample.file_row"]) and len(row["sample.file_row"]) == n
    assert row["sample.split"].count(SPLIT_CODES["test"]) == rows.test.size
    assert len(row["sample.predicted"]) == len(row["sample.measured"]) == 3 * n
    # errors of ~1e-4 m noise per coordinate: the tip error's RMS is sqrt(3) 1e-4 m
    for part in ("train", "test"):
        assert 1.2e-4 < row[f"err.{part}_rms"] < 2.4e-4
        assert row[f"err.{part}_median"] <= row[f"err.{part}_p95"] <= row[f"err.{part}_max"]
    assert row["err.common_test_rms"] > 0
    # the viewer's samples are physics_test samples (the ones every model predicts)
    assert set(row["view.file_row"]) <= set(st.measurements.file_rows[rows.physics_test].tolist())
    assert len(row["view.positions"]) == len(row["view.file_row"]) * 33 * 3
    tip = np.array(row["view.positions"]).reshape(-1, 33, 3)[:, -1]
    i = np.searchsorted(row["sample.file_row"], row["view.file_row"])
    assert np.allclose(tip, np.array(row["sample.predicted"]).reshape(-1, 3)[i], atol=1e-12)
    store = ResultStore(tmp_path / "out")
    store.add([dict(row)])
    store.close()
    back = read_table(tmp_path / "out").iloc[0]
    assert back["calib.values"].tolist() == row["calib.values"]
    assert array_shapes(tmp_path / "out")["sample.predicted"] == [-1, 3]


def test_physics_path_equals_the_batched_path(monkeypatch):
    """CC through the per-sample loop (the physics path) calibrates to the values of the batched path."""
    _fake_models(monkeypatch)
    st = synthetic_study(24, NAMES[:3], seed=8, noise=1e-4)
    rows = split_rows(24, 0.25, seed=8)
    batched, each = _row(st, "cc", rows), _row(st, "cc_each", rows)
    assert each["status"] == "ok", each["error"]
    assert np.allclose(each["calib.values"], batched["calib.values"], rtol=1e-6, atol=1e-9)
    assert each["sample.file_row"] == batched["sample.file_row"]
    assert each["err.test_rms"] == pytest.approx(batched["err.test_rms"], rel=1e-6)
    assert each["calib.seconds_per_evaluation"] > 0


def test_failing_model_gives_a_failed_row_with_the_reason(monkeypatch):
    st = synthetic_study(12, NAMES[:2], seed=9)
    rows = split_rows(12, 0.25, seed=9)
    fails = _fake_models(monkeypatch, fail_row=int(rows.train[2]) + 1)
    fails.command = st.measurements.commands[rows.train[2], 0]
    payload = ("c1", {"calibration": {"fold": 0}}, ("cc", "fails", "stalls"), st, rows)
    out = {r["model"]: r for r in kind_module.calibration_rows(payload)}
    assert out["cc"]["status"] == "ok"
    bad = out["fails"]
    assert bad["status"] == "failed" and bad["failure"] == "model"
    assert f"file row {int(rows.train[2]) + 1}: ModelFailure: Newton diverged" in bad["error"]
    assert "not converged: load step limit" in out["stalls"]["error"]
    assert all(r["case_id"] == "c1" and r["p.calibration.fold"] == 0 for r in out.values())


def test_payload_takes_the_fold_rows_of_the_split(monkeypatch):
    st = synthetic_study(20, NAMES[:1])
    try:
        import workbench.measure.split  # noqa: F401 - helper meas-data's module, once merged
    except ImportError:
        fake = types.ModuleType("workbench.measure.split")
        fake.fold_rows = lambda n, split: [split_rows(n, split.test_fraction, split.seed)]
        monkeypatch.setitem(sys.modules, "workbench.measure.split", fake)
    case = kind_module.KIND.expand(st)[0]
    cid, params, models, study, rows = kind_module.KIND.payload(st, case, ("cc",))
    assert cid == case.case_id and models == ("cc",) and study is st
    assert rows.fold == 0 and rows.train.size + rows.test.size == 20


def test_spread_samples_is_deterministic_and_spread():
    c = np.array([[0.0, 0.0], [1.0, 1.0], [0.9, 1.0], [0.0, 1.0], [1.0, 0.0], [0.5, 0.5]])
    assert spread_samples(c, 4).tolist() == [0, 1, 3, 4]
    assert spread_samples(c, 20).size == 6 and spread_samples(c[:0], 3).size == 0


def test_a_robot_the_values_cannot_build_is_a_failed_row():
    st = synthetic_study(10, NAMES[:1], seed=10)
    bad = replace(st.calibration.parameters[0], name="robot.diameter", initial=-1e-3, lower=-2e-3, upper=-0.5e-3)
    st = replace(st, calibration=replace(st.calibration, parameters=(bad,)))
    row = _row(st, "cc", split_rows(10, 0.2, seed=10))
    assert row["status"] == "failed" and row["failure"] == "model"
    assert row["error"].startswith("calibration failed: model cc: the robot with robot.diameter = -0.001 cannot be "
                                   "built: ")
    assert np.isnan(row["calib.values"]).all() and row["calib.evaluations"] == 1
