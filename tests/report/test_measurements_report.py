"""The report of a calibration study (``workbench/report/measurements.py``): a fake result folder in the row
schema of issue 30 (one row per model and fold), written with the runner's store, then the report.

The fake folder: 40 measured samples of a 0.2 m robot; CC's predictions miss the measurement by an error
that grows with the command magnitude, Cosserat's by 0.2 mm noise, and a GE-beam calibration failed.  The
test computes the findings numbers from the stored sample arrays (not from the ``err.*`` cells the
report reads) and checks the sentence, the Measurements section, the viewer's markers, that no sweep
figure is drawn, and that the failed model is named with its reason.
"""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

import numpy as np
import pytest

from workbench.report.build import build_report
from workbench.report.measurements import cell, points, texts
from workbench.report.style import fmt
from workbench.study.store import MANIFEST, ResultStore

L = 0.2
N, M = 40, 4
FAIL_REASON = "least_squares: the model did not solve at the start values (fold 0)"


def _errors(pred, meas, idx):
    e = np.linalg.norm(pred[idx] - meas[idx], axis=1)
    return {"rms": float(np.sqrt(np.mean(e**2))), "median": float(np.median(e)), "p95": float(np.percentile(e, 95)),
            "max": float(np.max(e))}


def _row(model, rows, split, cmd, meas, pred, common, view_rows, backbone_pts, fold=0):
    """One calibration row of the issue-30 schema for the samples ``rows`` (indices into the data)."""
    e_train, e_test = _errors(pred, meas, rows[split == 0]), _errors(pred, meas, rows[split == 1])
    k = len(view_rows)
    tips = pred[view_rows]
    s = np.linspace(0.0, 1.0, 11)[None, :, None]
    view = s * tips[:, None, :] + (1 - s) * np.array([0.0, 0.0, 0.01])  # a line from the base to the predicted tip
    row = {
        "case_id": f"fold{fold}", "model": model, "status": "ok", "error": "", "failure": "", "wall_time": 1.5,
        "fold": fold, "robot_length": L,
        "calib.converged": True, "calib.message": "`ftol` termination condition is satisfied.",
        "calib.evaluations": 17 if model == "cc" else 9, "calib.seconds_per_evaluation": 0.002 if model == "cc" else 0.8,
        "calib.names": json.dumps(["robot.youngs_modulus", "command_zero[0]", "registration.translation[0]"]),
        "calib.units": json.dumps(["Pa", "N", "m"]),
        "calib.sources": json.dumps(["preset rao_2021", "0 (no slack)", "0"]),
        "calib.initial": [6.0e10, 0.0, 0.0], "calib.lower": [3.0e10, -0.5, -0.1], "calib.upper": [8.0e10, 0.5, 0.1],
        "calib.values": [5.1e10, 0.21, 0.1] if model == "cc" else [5.4e10, 0.2, 0.0123],
        "calib.ci_low": [4.9e10, 0.18, 0.1] if model == "cc" else [5.3e10, 0.19, 0.0121],
        "calib.ci_high": [5.3e10, 0.24, 0.1] if model == "cc" else [5.5e10, 0.21, 0.0125],
        "calib.at_bound": [0.0, 0.0, 1.0] if model == "cc" else [0.0, 0.0, 0.0], "calib.confidence": 0.95,
        **{f"err.train_{k2}": v for k2, v in e_train.items()}, **{f"err.test_{k2}": v for k2, v in e_test.items()},
        "err.common_test_rms": _errors(pred, meas, common)["rms"],
        "sample.file_row": (rows + 1).tolist(), "sample.split": split.tolist(),
        "sample.commands": cmd[rows].reshape(-1).tolist(), "sample.measured": meas[rows].reshape(-1).tolist(),
        "sample.predicted": pred[rows].reshape(-1).tolist(),
        "view.file_row": (view_rows + 1).tolist(), "view.positions": view.reshape(-1).tolist(),
        "view.measured_backbone": backbone_pts[view_rows].reshape(-1).tolist() if backbone_pts is not None else [],
        "_shapes": {"sample.commands": [-1, M], "sample.measured": [-1, 3], "sample.predicted": [-1, 3],
                    "view.positions": [-1, 11, 3], "view.measured_backbone": [-1, 3, 3]},
    }
    return row


def _fake_data(rng):
    """Commands, measured tips, measured backbone points and the two models' predictions (module docstring)."""
    cmd = rng.uniform(0.0, 3.0, (N, M))
    mag = np.linalg.norm(cmd, axis=1)
    meas = np.column_stack([0.02 * (cmd[:, 0] - cmd[:, 2]), 0.02 * (cmd[:, 1] - cmd[:, 3]), L - 0.003 * mag])
    backbone = meas[:, None, :] * np.array([0.25, 0.5, 0.75])[None, :, None]
    pred_cc = meas + 0.002 * mag[:, None] * np.array([0.6, -0.3, 0.74])
    pred_cos = meas + rng.normal(0.0, 0.2e-3 / np.sqrt(3), (N, 3))
    return cmd, meas, backbone, pred_cc, pred_cos


def _manifest(spec_models, study_dir: Path, folds=None, sha=None) -> dict:
    """A runner manifest as the calibration kind writes it (the data file's SHA-256 in ``[measurements]``)."""
    cal = {"models": spec_models, "seed": 1, "physics_rows": 8, **({"folds": folds} if folds else {"test_fraction": 0.25})}
    spec = {"study": {"name": "measured_fake", "kind": "calibration", "models": spec_models,
                      "description": "Does CC explain the measured robot?"},
            "robot": {"preset": "rao_2021"},
            "measurements": {"file": "measured.csv", "mode": "tension", "frame": "measurement",
                             **({"sha256": sha} if sha else {})}, "calibration": cal}
    return {"study": spec, "study_file": str(study_dir / "measured.toml"), "config_hash": "ab12", "n_cases": 3,
            "versions": {"workbench": "0.1.0"}, "git": {"commit": "0" * 40, "dirty": False},
            "runs": [{"host": "testhost", "start": "2026-01-01T10:00:00+00:00", "end": "2026-01-01T10:01:00+00:00",
                      "wall_time": 60.0}]}


def _failed_row(model, fold, reason=FAIL_REASON):
    return {"case_id": f"fold{fold}", "model": model, "status": "failed", "error": reason,
            "failure": "model", "wall_time": 3.0, "fold": fold, "robot_length": L}


def make_calibration_folder(folder: Path) -> dict:
    """Write the fake calibration result folder; return what the test needs to check it independently."""
    rng = np.random.default_rng(3)
    cmd, meas, backbone, pred_cc, pred_cos = _fake_data(rng)
    order = rng.permutation(N)
    test, train = np.sort(order[:10]), np.sort(order[10:])
    p_train, p_test = np.sort(train[:8]), np.sort(test[:6])
    view_rows = p_test[:4]
    all_rows = np.arange(N)
    cc_split = np.isin(all_rows, test).astype(int)
    cos_rows = np.concatenate([p_train, p_test])
    cos_split = np.r_[np.zeros(len(p_train), int), np.ones(len(p_test), int)]
    folder.mkdir(parents=True)
    study_dir = folder.parent / "study"
    study_dir.mkdir()
    data = "T1,T2,T3,T4,x,y,z\n" + "".join(",".join(f"{v:.6g}" for v in [*cmd[i], *meas[i]]) + "\n" for i in range(N))
    (study_dir / "measured.csv").write_text(data)
    store = ResultStore(folder)
    store.add([_row("cc", all_rows, cc_split, cmd, meas, pred_cc, p_test, view_rows, None),
               _row("cosserat", cos_rows, cos_split, cmd, meas, pred_cos, p_test, view_rows, backbone),
               _failed_row("beam3d", 0)])
    store.close()
    sha = hashlib.sha256(data.encode()).hexdigest()
    (folder / MANIFEST).write_text(json.dumps(_manifest(["cc", "cosserat", "beam3d"], study_dir, sha=sha)))
    return {"meas": meas, "pred": {"cc": pred_cc, "cosserat": pred_cos}, "common": p_test, "test": test,
            "view_rows": view_rows,
            "backbone": backbone, "sha": sha}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    base = tmp_path_factory.mktemp("calib")
    truth = make_calibration_folder(base / "data")
    html = build_report(base / "data", base / "report", formats=("png",))
    return truth, html, html.read_text(encoding="utf-8")


def _scenes(page: str) -> dict:
    m = re.search(r'<script type="application/json" id="wb-scenes">(.*?)</script>', page, re.S)
    return json.loads(m.group(1).replace("<\\/", "</").replace(":\\/\\/", "://"))


def test_findings_line_numbers_from_the_samples(built):
    truth, _, page = built
    meas, common = truth["meas"], truth["common"]
    rms = {m: float(np.sqrt(np.mean(np.sum((p[common] - meas[common]) ** 2, axis=1)))) for m, p in truth["pred"].items()}
    assert rms["cc"] > 5 * rms["cosserat"]  # the fake is built so: the line must name cosserat the better model
    expected = (f"On {len(common)} held-out rows, Cosserat rod explains the measurements to {fmt(1e3 * rms['cosserat'])} mm "
                f"RMS ({fmt(100 * rms['cosserat'] / L)} % L); CC's error is {fmt(1e3 * rms['cc'])} mm "
                f"({fmt(100 * rms['cc'] / L)} % L), {fmt(rms['cc'] / rms['cosserat'])}x larger.")
    findings = page.split("<ul class='findings'>", 1)[1].split("</ul>", 1)[0]
    assert expected in findings.replace("&#x27;", "'")


def test_failed_model_named_with_its_reason(built):
    _, _, page = built
    findings = page.split("<ul class='findings'>", 1)[1].split("</ul>", 1)[0]
    assert "No verdict on GE beam: its calibration failed on every fold (fold 0: " + FAIL_REASON in findings
    section = page.split("id='measurements'", 1)[1] if "id='measurements'" in page else page.split('id="measurements"', 1)[1]
    assert "failed: fold 0: " + FAIL_REASON in section


def test_measurements_section_tables_and_provenance(built):
    truth, _, page = built
    assert re.search(r"<h2[^>]*>Measurements</h2>", page)
    sec = page.split(">Measurements</h2>", 1)[1]
    assert "robot.youngs_modulus" in sec and "at bound" in sec and "preset rao_2021" in sec
    assert sec.count("at bound</td>") == 1  # only CC's registration.translation[0] sits at its bound
    assert "95 % interval" in sec
    assert "measured.csv" in sec and truth["sha"] in sec and "seed 1" in sec
    e = np.linalg.norm(truth["pred"]["cc"] - truth["meas"], axis=1)
    # CC's held-out max over all its test rows (not only the common ones), in mm and % L, as the error table prints it
    table = page.split("<table class='errors'>", 1)[1].split("</table>", 1)[0]
    worst = float(np.max(e[truth["test"]]))
    assert f"{fmt(1e3 * worst)} mm ({fmt(100 * worst / L)} % L)" in table


def test_no_sweep_figure_only_measurement_figures(built):
    _, html, page = built
    drawn = set(re.findall(r"data-figure='([^']+)'", page))
    assert drawn == {"measured_error_vs_command", "measured_residual_maps", "measured_vs_predicted"}
    assert {p.stem for p in (html.parent / "figures").iterdir()} == drawn
    assert "<h2>Summary</h2>" not in page


def test_viewer_draws_predicted_backbones_and_measured_markers(built):
    truth, _, page = built
    scenes = _scenes(page)
    assert scenes["frame"] == "measurement"
    assert [c["id"] for c in scenes["cases"]] == [f"row-{r + 1}" for r in sorted(truth["view_rows"])]
    for c, r in zip(scenes["cases"], sorted(truth["view_rows"])):
        assert set(c["models"]) == {"cc", "cosserat"}
        marks = {m["label"]: np.array(m["points"]) for m in c["markers"]}
        np.testing.assert_allclose(marks["measured tip"][0], truth["meas"][r], atol=1e-6)
        np.testing.assert_allclose(marks["measured backbone"], truth["backbone"][r], atol=1e-6)
        tip = np.array(c["models"]["cosserat"]["frames"][0][1])[-1]
        np.testing.assert_allclose(tip, truth["pred"]["cosserat"][r], atol=1e-6)


def test_cells_read_as_stored():
    assert texts('["a", "b"]') == ["a", "b"] and texts(np.array(["a"], dtype=object)) == ["a"]
    assert cell(None).size == 0 and cell(float("nan")).size == 0 and cell("[1, 2]").tolist() == [1.0, 2.0]
    assert points(list(range(12)), leading=2).shape == (2, 2, 3) and points([], leading=3).shape == (3, 0, 3)


def _three_folds(folder: Path) -> tuple[np.ndarray, dict]:
    """Folds 0 and 2 with both models, fold 1 with CC only (Cosserat's calibration failed there)."""
    rng = np.random.default_rng(5)
    cmd, meas, _, pred_cc, pred_cos = _fake_data(rng)
    parts = np.array_split(rng.permutation(N), 3)
    rows, common = [], {}
    for f, test in enumerate(parts):
        test = np.sort(test)
        train = np.setdiff1d(np.arange(N), test)
        p_train, p_test = train[:6], test[:4]
        common[f] = p_test
        rows.append(_row("cc", np.arange(N), np.isin(np.arange(N), test).astype(int), cmd, meas, pred_cc, p_test,
                         p_test[:2], None, fold=f))
        if f == 1:
            rows.append(_failed_row("cosserat", 1, "least_squares: maximum number of evaluations reached"))
        else:
            rows.append(_row("cosserat", np.r_[p_train, p_test], np.r_[np.zeros(6, int), np.ones(4, int)], cmd, meas,
                             pred_cos, p_test, p_test[:2], None, fold=f))
    folder.mkdir(parents=True)
    store = ResultStore(folder)
    store.add(rows)
    store.close()
    (folder / MANIFEST).write_text(json.dumps(_manifest(["cc", "cosserat"], folder.parent, folds=3)))
    return meas, {"cc": pred_cc, "cosserat": pred_cos, "common": np.concatenate([common[0], common[2]])}


def test_folds_pool_only_the_folds_every_model_solved(tmp_path):
    from workbench.report.load import load_results
    from workbench.report.measurements import calibration_findings

    meas, t = _three_folds(tmp_path / "data")
    rows = t["common"]  # the rows of folds 0 and 2; pooled RMS = RMS over their union
    rms = {m: float(np.sqrt(np.mean(np.sum((t[m][rows] - meas[rows]) ** 2, axis=1)))) for m in ("cc", "cosserat")}
    lines = calibration_findings(load_results(tmp_path / "data"))
    assert lines[0] == (f"On {len(rows)} held-out rows (folds 0, 2 of 3, where every model succeeded), Cosserat rod "
                        f"explains the measurements to {fmt(1e3 * rms['cosserat'])} mm RMS "
                        f"({fmt(100 * rms['cosserat'] / L)} % L); CC's error is {fmt(1e3 * rms['cc'])} mm "
                        f"({fmt(100 * rms['cc'] / L)} % L), {fmt(rms['cc'] / rms['cosserat'])}x larger.")
    assert ("Cosserat rod: the calibration failed on 1 of 3 folds (fold 1: least_squares: maximum number of "
            "evaluations reached); its numbers are over the other folds.") in lines


def test_every_calibration_failed_no_verdict(tmp_path):
    folder = tmp_path / "data"
    folder.mkdir()
    store = ResultStore(folder)
    store.add([_failed_row("cc", 0, "robot.sections[1].length: bounds hold no valid robot"), _failed_row("cosserat", 0)])
    store.close()
    (tmp_path / "measured.csv").write_text("T1,x\n1,2\n")  # the run recorded no SHA-256: the report hashes the file
    (folder / MANIFEST).write_text(json.dumps(_manifest(["cc", "cosserat"], tmp_path)))
    page = build_report(folder, tmp_path / "report", formats=("png",)).read_text(encoding="utf-8")
    sha = hashlib.sha256(b"T1,x\n1,2\n").hexdigest()
    assert f"SHA-256 <code>{sha} (not recorded by the run: hashed now)</code>" in page
    findings = page.split("<ul class='findings'>", 1)[1].split("</ul>", 1)[0]
    assert "No verdict: no model has a held-out error (every calibration failed)." in findings
    assert "No verdict on CC: its calibration failed on every fold (fold 0: robot.sections[1].length: bounds" in findings
    assert "No verdict on Cosserat rod: its calibration failed on every fold (fold 0: " + FAIL_REASON in findings
    assert "data-figure=" not in page


@pytest.mark.browser
def test_calibration_report_in_headless_chromium(built, tmp_path):
    from browser import CHROMIUM, open_report

    if CHROMIUM is None:
        pytest.skip("headless Chromium not installed (apt-get install chromium)")
    truth, html, _ = built
    selftest, other = open_report(html, tmp_path / "calibration.png", height=3000)
    assert other == []  # no script error: the viewer drew the markers without failing
    assert selftest["cases"] == len(truth["view_rows"]) and selftest["figures"] == 3
    assert selftest["pixels"] > 1000 and selftest["rows"] == 3


def test_cc_alone_is_judged_on_all_its_held_out_rows(tmp_path):
    """Without a physics result there are no common rows: CC's verdict is on every held-out row it predicted."""
    from workbench.report.load import load_results
    from workbench.report.measurements import calibration_findings

    rng = np.random.default_rng(3)
    cmd, meas, _, pred_cc, _ = _fake_data(rng)
    test = np.sort(rng.permutation(N)[:10])
    folder = tmp_path / "data"
    folder.mkdir()
    store = ResultStore(folder)
    store.add([_row("cc", np.arange(N), np.isin(np.arange(N), test).astype(int), cmd, meas, pred_cc, test[:4],
                    test[:2], None), _failed_row("cosserat", 0)])
    store.close()
    (folder / MANIFEST).write_text(json.dumps(_manifest(["cc", "cosserat"], tmp_path)))
    rms = float(np.sqrt(np.mean(np.sum((pred_cc[test] - meas[test]) ** 2, axis=1))))
    lines = calibration_findings(load_results(folder))
    assert lines[0] == (f"On {len(test)} held-out rows, CC explains the measurements to {fmt(1e3 * rms)} mm RMS "
                        f"({fmt(100 * rms / L)} % L).")
    assert lines[1].startswith("No verdict on Cosserat rod: its calibration failed on every fold (fold 0: ")
