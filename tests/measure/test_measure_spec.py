"""A valid calibration study file -> CalibrationStudy: resolved values, sources, order, hash, overrides.

Malformed files are ``test_measure_malformed.py``; the reader's arrays ``test_measure_data.py``.
"""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from workbench.measure.spec import load_calibration_study
from workbench.study.keypath import with_value

FIX = Path(__file__).with_name("fixtures")


def _copy(tmp: Path, edits=()) -> Path:
    text = (FIX / "calibration.toml").read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    (tmp / "calibration.toml").write_text(text, encoding="utf-8")
    shutil.copy(FIX / "measured.csv", tmp / "measured.csv")
    return tmp / "calibration.toml"


def test_the_fixture_resolves_every_table(tmp_path):
    s = load_calibration_study(_copy(tmp_path))
    c = s.calibration
    assert s.name == "measured_fixture" and c.models == ("cc", "cosserat") and s.measurements.n == 40
    names = [p.name for p in c.parameters]
    assert names == ["robot.sections[0].youngs_modulus", "robot.sections[1].length",
                     *[f"command_zero[{i}]" for i in range(6)], *[f"registration.translation[{j}]" for j in range(3)],
                     *[f"registration.rotation[{j}]" for j in range(3)]]
    E, L1 = c.parameters[:2]
    assert (E.initial, E.lower, E.upper, E.unit) == (54e9, 30e9, 80e9, "Pa") and E.source.startswith("material niti")
    assert (L1.initial, L1.unit, L1.source) == (0.2, "m", "set in the study file")
    assert [p.unit for p in c.parameters[2:]] == ["N"] * 6 + ["m"] * 3 + ["rad"] * 3
    assert all(p.initial == 0.0 and p.source == "default: 0" for p in c.parameters[2:])
    assert (c.split.seed, c.split.test_fraction, c.split.folds, c.split.physics_rows) == (1, 0.25, None, 20)
    assert (c.confidence, c.max_evaluations) == (0.95, 100)
    assert s.load == {"pretension": 0.0, "tip_force": [0.0, 0.0, 0.0], "tip_torque": [0.0, 0.0, 0.0], "mode": "tension"}
    assert s.solver["n_elements"] == 16 and "by_model" not in s.solver
    assert len(s.robot["sections"]) == 2 and s.robot["preset"] == "rao_2021"


def test_resolved_is_plain_data_naming_the_data_file_by_its_hash(tmp_path):
    s = load_calibration_study(_copy(tmp_path))
    r = s.resolved()
    json.dumps(r, allow_nan=False)
    assert r["measurements"]["sha256"] == hashlib.sha256((tmp_path / "measured.csv").read_bytes()).hexdigest()
    assert r["measurements"]["rows"] == 40 and r["study"]["kind"] == "calibration"
    assert [p["name"] for p in r["calibration"]["parameters"]] == [p.name for p in s.calibration.parameters]


def test_the_config_hash_follows_the_data_and_the_settings_not_the_name(tmp_path):
    a = load_calibration_study(_copy(tmp_path)).config_hash
    assert load_calibration_study(_copy(tmp_path)).config_hash == a
    renamed = _copy(tmp_path, [('name = "measured_fixture"', 'name = "other"')])
    assert load_calibration_study(renamed).config_hash == a
    limited = _copy(tmp_path, [("n_elements = 16", "n_elements = 16\nmax_case_seconds = 60.0")])
    assert load_calibration_study(limited).config_hash == a  # a limit does not change a result
    assert load_calibration_study(_copy(tmp_path), overrides=["calibration.seed=2"]).config_hash != a
    path = _copy(tmp_path)
    df = pd.read_csv(tmp_path / "measured.csv")
    df.loc[3, "x"] += 0.001
    df.to_csv(tmp_path / "measured.csv", index=False)
    assert load_calibration_study(path).config_hash != a


def test_overrides_are_applied_and_recorded(tmp_path):
    s = load_calibration_study(_copy(tmp_path), overrides=["calibration.seed=5", "calibration.physics_rows=16"])
    assert s.overrides == ("calibration.seed=5", "calibration.physics_rows=16")
    assert (s.calibration.split.seed, s.calibration.split.physics_rows) == (5, 16)


def test_a_calibrated_key_path_can_be_set_in_the_resolved_robot(tmp_path):
    """The contract for the fit: with_value(create=True) on study.robot changes the robot built from it."""
    from workbench.robot.spec import robot_from_params

    s = load_calibration_study(_copy(tmp_path))
    nominal = robot_from_params(s.robot)
    case = with_value({"robot": s.robot}, "robot.sections[0].youngs_modulus", 60e9, create=True)
    case = with_value(case, "robot.sections[1].length", 0.21)
    changed = robot_from_params(case["robot"])
    EI0, EI1 = (r.sections[0].cross_section.EI for r in (nominal, changed))
    assert EI1 / EI0 == pytest.approx(60 / 54, rel=1e-12)
    assert changed.sections[1].cross_section.EI == nominal.sections[1].cross_section.EI
    assert changed.length == pytest.approx(0.41, rel=1e-12)


def test_a_preset_form_robot_and_k_folds_with_the_default_physics_rows(tmp_path):
    edits = [('preset = "rao_2021"', 'preset = "steel_rod"\ntendon_count = 3\nn_sections = 2'),
             ('"robot.sections[0].youngs_modulus" = { lower = 30e9, upper = 80e9 }',
              '"robot.youngs_modulus" = { lower = 100e9, upper = 300e9 }'),
             ('"robot.sections[1].length" = { lower = 0.18, upper = 0.22, initial = 0.2 }',
              '"robot.tendon_offset" = { lower = 0.01, upper = 0.03 }'),
             ("stations = [0.1, 0.2, 0.3]", "stations = [0.2, 0.4, 0.6]"),
             ("test_fraction = 0.25", "folds = 4"), ("physics_rows = 20", "")]
    s = load_calibration_study(_copy(tmp_path, edits))
    E, d = s.calibration.parameters[:2]
    assert (E.name, E.initial, E.unit, E.source) == ("robot.youngs_modulus", 210e9, "Pa", "preset steel_rod: assumed: "
                                                                                          "steel, 210 GPa")
    assert (d.initial, d.unit) == (0.02, "m")
    assert s.calibration.split.folds == 4 and s.calibration.split.physics_rows == 30  # 40 rows, 10 held out per fold


def test_length_mode_with_pull_and_a_shared_pretension(tmp_path):
    df = pd.read_csv(FIX / "measured.csv")
    path = _copy(tmp_path, [('mode = "tension"', 'mode = "length"'),
                            ('unit = "mN"', 'unit = "um"\nscale = 0.5\nconvention = "pull"'),
                            ("pretension = 0.0", "pretension = 0.5"), ("lower = -0.5\nupper = 0.5",
                                                                      "lower = -1e-3\nupper = 1e-3")])
    s = load_calibration_study(path)
    np.testing.assert_allclose(s.measurements.commands[:, 0], -0.5e-6 * df["T1"].to_numpy(), rtol=1e-15)
    assert s.load["pretension"] == 0.5 and s.load["mode"] == "length"
    assert [p.unit for p in s.calibration.parameters if p.name.startswith("command_zero")] == ["m"] * 6


def test_a_base_frame_study_needs_no_registration_and_may_give_tip_forces(tmp_path):
    df = pd.read_csv(FIX / "measured.csv")
    df["fx"], df["fy"], df["fz"] = 0.0, 0.0, -20.0
    path = _copy(tmp_path, [('frame = "measurement"', 'frame = "base"'),
                            ("[calibration]\n", '[measurements.tip_force]\ncolumns = ["fx", "fy", "fz"]\nunit = "mN"\n'
                                                'frame = "base"\n\n[calibration]\n'),
                            ("[calibration.registration]\n", ""), ("translation = {", "# "), ("rotation = {", "# ")])
    df.to_csv(tmp_path / "measured.csv", index=False)
    s = load_calibration_study(path)
    assert len(s.calibration.parameters) == 8 and s.measurements.frame == "base"
    np.testing.assert_allclose(s.measurements.tip_force[7], [0.0, 0.0, -0.02])


def test_a_load_value_and_a_list_element_can_be_calibrated(tmp_path):
    path = _copy(tmp_path, [("pretension = 0.0", "pretension = 0.2"),
                            ('"robot.sections[1].length" = { lower = 0.18, upper = 0.22, initial = 0.2 }',
                             '"load.pretension" = { lower = 0.0, upper = 1.0 }\n'
                             '"robot.sections[1].tendons[0].angles[1]" = { lower = -0.6, upper = -0.4 }')])
    p = load_calibration_study(path).calibration.parameters
    assert (p[1].name, p[1].initial, p[1].unit, p[1].source) == ("load.pretension", 0.2, "N", "set in the study file")
    assert (p[2].initial, p[2].unit) == (pytest.approx(-np.pi / 6), "rad")
    assert p[2].source.startswith("preset rao_2021: 3 tendons per section")
