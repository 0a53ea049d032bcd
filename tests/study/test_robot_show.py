"""``workbench robot show``: every preset and every committed study (``studies/`` and the regression tier's
copies) prints its robot and writes a non-empty PNG without running a simulation; bad input is one line
on stderr with exit code 2.

A study kind without a ``[robot]`` (series_parallel: six-rod parallel modules, ``[geometry]``) is told
so in one line (exit 2): its trunk is not a tendon-driven :class:`~workbench.robot.Robot`.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from workbench import registry
from workbench.cli import main

ROOT = Path(__file__).parents[2]
STUDIES = sorted(ROOT.glob("studies/*.toml")) + sorted(ROOT.glob("tests/regression/studies/*.toml"))
NO_ROBOT = {"series_parallel"}  # study kinds whose trunk is no Robot


def _kind(path: Path) -> str:
    from workbench.study import kind_of

    return kind_of(path)


def _show(args, tmp_path, capsys):
    out = tmp_path / "robot.png"
    rc = main(["robot", "show", *args, "--out", str(out)])
    o, e = capsys.readouterr()
    return rc, o, e, out


def _check_picture(out: Path) -> None:
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000


@pytest.mark.parametrize("name", list(registry.PRESETS))
def test_every_preset(name, tmp_path, capsys):
    rc, o, e, out = _show([name], tmp_path, capsys)
    assert rc == 0, e
    assert f"preset {name} with its defaults" in o
    for words in ("EI [N m²]", "m' [kg/m]", "total mass", "gamma", "first bending frequency", "stresses at"):
        assert words in o, words
    _check_picture(out)


def test_there_are_committed_studies():
    assert len(STUDIES) >= 20


@pytest.mark.parametrize("path", STUDIES, ids=[str(p.relative_to(ROOT)) for p in STUDIES])
def test_every_committed_study(path, tmp_path, capsys):
    rc, o, e, out = _show([str(path)], tmp_path, capsys)
    if _kind(path) in NO_ROBOT:
        assert rc == 2 and len(e.strip().splitlines()) == 1 and "has no [robot] section" in e, e
        assert not out.exists()
        return
    assert rc == 0, e
    assert f"study {path}: its base robot" in o and "Traceback" not in o + e
    _check_picture(out)


def test_a_study_shows_its_derived_gravity_and_its_sweep(tmp_path, capsys):
    """quickstart's base gamma = 1 sets g = gamma EI / (m' L^3) = 13.360 / (0.22195 x 0.512) = 117.57 m/s^2."""
    rc, o, e, _ = _show([str(ROOT / "studies/quickstart.toml")], tmp_path, capsys)
    assert rc == 0, e
    assert "gamma = q L³/EI: 1 at |g| = 117.6 m/s²" in o
    assert "swept in the study, not shown (see --case): derived.gravity_parameter" in o
    assert "  robot.diameter = 0.006 [m]" in o and "  robot.base_orientation = horizontal" in o


def test_one_case_of_a_study(tmp_path, capsys):
    """quickstart's sweep: bend angle x gamma in (0.001, 0.01, 0.1, 1, 10); the case with gamma = 10 shows g =
    10 x 117.57 m/s^2, whichever index it has."""
    from workbench.study import load_study
    from workbench.study.expand import expand

    study = load_study(ROOT / "studies/quickstart.toml")
    case = next(c for c in expand(study) if c.swept.get("derived.gravity_parameter") == 10.0)
    for pick in (str(case.index), case.case_id):
        rc, o, e, out = _show([str(ROOT / "studies/quickstart.toml"), "--case", pick], tmp_path, capsys)
        assert rc == 0, e
        assert f"case {case.index} ({case.case_id}; preset steel_rod); derived.gravity_parameter = 10.0" in o
        assert "gamma = q L³/EI: 10 at |g| = 1176 m/s²" in o


def test_nested_parameters_are_printed_by_key_path():
    """A description-form robot's parameters (nested tables and lists) print one leaf per line."""
    from workbench.cli_robot import summary_lines
    from workbench.robot.presets import build_preset
    from workbench.study.robot_summary import summarize_robot

    params = {"sections": [{"length": 0.2, "tendons": [{"angles": [0.0, 3.14]}]}], "gravity": [0.0, 0.0, -9.81]}
    lines = summary_lines(summarize_robot(build_preset("steel_rod")), "test", params)
    assert "  robot.sections[0].length = 0.2" in lines
    assert "  robot.sections[0].tendons[0].angles = [0.0, 3.14]" in lines
    assert "  robot.gravity = [0.0, 0.0, -9.81] [m/s²]" in lines


def test_override_and_tension(tmp_path, capsys):
    rc, o, e, _ = _show([str(ROOT / "studies/bending.toml"), "robot.diameter=0.004", "--tension", "5"],
                        tmp_path, capsys)
    assert rc == 0, e
    lines = o.splitlines()
    head = lines.index("sections") + 1
    row = dict(zip(re.split(r"\s{2,}", lines[head].strip()), lines[head + 1].split()))
    # d = 4 mm: EI = 210e9 pi (4e-3)^4 / 64 = 2.639 N m^2, m' = 7850 pi (4e-3)^2 / 4 = 0.09865 kg/m
    assert (row["d [mm]"], row["EI [N m²]"], row["m' [kg/m]"], row["L [m]"]) == ("4", "2.639", "0.09865", "0.8")
    assert "stresses at the command: 5 N on the first tendon of every section" in o


@pytest.mark.parametrize("args, words", [
    (["no_such_thing"], "not a robot preset (known: steel_rod"),
    (["studies/no_such.toml"], "cannot read file"),
    (["steel_rod", "robot.length=1"], "robot.length=1: applies to a study file, not to the preset"),
    (["steel_rod", "--case", "0"], "--case 0: applies to a study file, not to the preset"),
    (["studies/quickstart.toml", "--case", "20"], "--case 20: no such case in studies/quickstart.toml (20 cases"),
    (["studies/quickstart.toml", "robot.diameter=-1"], "robot.diameter: must be > 0"),
    (["studies/quickstart.toml", "robot.lenght=1"], "robot.lenght"),
    (["steel_rod", "--tension", "abc"], "--tension: not a number"),
    (["steel_rod", "--tension", "-2"], "--tension: tensions must be finite and >= 0"),
    (["steel_rod", "--tension", "1,2,3"], "--tension: give one tension per tendon: the robot has 2, got 3"),
])
def test_bad_input_is_one_line(args, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    rc, o, e, out = _show(args, tmp_path, capsys)
    assert rc == 2 and not out.exists()
    assert len(e.strip().splitlines()) == 1 and words in e, e


def test_out_must_be_a_file(tmp_path, capsys):
    rc = main(["robot", "show", "steel_rod", "--out", str(tmp_path)])
    e = capsys.readouterr().err
    assert rc == 2 and e.startswith("--out") and len(e.strip().splitlines()) == 1
