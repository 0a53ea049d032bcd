"""CLI end to end with the real CC model (pure numpy): run, resume, show, exit codes."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from workbench.cli import main
from workbench.study import read_manifest

STUDY = """\
[study]
name = "cli_cc"
models = ["cc"]

[robot]
preset = "steel_rod"
length = 0.8
tendon_count = 3

[load]
mode = "tension"
bend_angle = 1.0

[solver]
n_stations = 17

[sweep]
product = { "load.bend_angle" = [0.5, 1.0, 2.0], "load.bend_plane" = [0.0, 0.7] }
"""


@pytest.fixture
def study_file(tmp_path):
    p = tmp_path / "cli_cc.toml"
    p.write_text(STUDY)
    return p


def test_run_resume_show_with_cc_model(tmp_path, study_file, capsys):
    out = tmp_path / "data" / "cli_cc"
    rc = main(["run", str(study_file), "--out", str(out), "--in-process", "--no-report", "--progress", "off"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "cases 6: ok 6, failed 0" in text
    df = pd.read_parquet(out)
    assert len(df) == 6 and (df["status"] == "ok").all()
    # the CC model realises the commanded arc: tip at ((1 - cos th)/k cos phi, .. sin phi, sin th / k)
    for _, r in df.iterrows():
        th, phi = r["p.load.bend_angle"], r["p.load.bend_plane"]
        k = th / 0.8
        expect = np.array([(1 - math.cos(th)) / k * math.cos(phi), (1 - math.cos(th)) / k * math.sin(phi),
                           math.sin(th) / k])
        assert np.allclose([r["tip_x"], r["tip_y"], r["tip_z"]], expect, atol=1e-9), (th, phi)
        assert np.asarray(r["positions"]).reshape(17, 3)[-1] == pytest.approx(expect, abs=1e-9)
    man = read_manifest(out)
    assert man["study"]["study"]["name"] == "cli_cc" and man["n_cases"] == 6

    # resume: nothing left to run, same table
    assert main(["run", str(study_file), "--out", str(out), "--resume", "--in-process", "--no-report"]) == 0
    assert "(this run: 0 run, 6 already stored)" in capsys.readouterr().out
    assert len(pd.read_parquet(out)) == 6

    # running again without --resume is a user error
    assert main(["run", str(study_file), "--out", str(out), "--in-process", "--no-report"]) == 2
    assert "already holds results" in capsys.readouterr().err

    assert main(["show", str(out)]) == 0
    assert "cases 6: ok 6, failed 0" in capsys.readouterr().out


def test_changed_study_refuses_resume(tmp_path, study_file, capsys):
    out = tmp_path / "o"
    assert main(["run", str(study_file), "--out", str(out), "--in-process", "--no-report"]) == 0
    study_file.write_text(STUDY.replace("n_stations = 17", "n_stations = 9"))
    assert main(["run", str(study_file), "--out", str(out), "--resume", "--in-process", "--no-report"]) == 2
    err = capsys.readouterr().err
    assert "--resume refused" in err and "config hash" in err


def test_show_on_non_study_folder(tmp_path, capsys):
    assert main(["show", str(tmp_path)]) == 2
    assert "not a study result folder" in capsys.readouterr().err


def test_infeasible_arc_command_rejected_before_running(tmp_path, capsys):
    p = tmp_path / "planar.toml"
    p.write_text(STUDY.replace("tendon_count = 3", "tendon_count = 2"))
    assert main(["validate", str(p)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    # one line for the mistake (phi = 0.7 with an antagonistic pair), naming the 3 cases it breaks
    assert err == [err[0]] and err[0].startswith(f"{p}: load.bend_plane (3 of 6 cases, e.g. case 1: ")
    assert "phi = 0.7000 rad" in err[0]
