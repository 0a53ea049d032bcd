"""``workbench robot show``: every preset and every committed study (``studies/`` and the regression tier's
copies) prints its robot and writes a non-empty PNG without running a simulation; bad input is one line
on stderr with exit code 2.

A study kind without a ``[robot]`` shows its trunk through its ``robot_show`` hook
(:class:`workbench.registry.KindInfo`; series_parallel: six-rod parallel modules, ``[geometry]``,
:mod:`workbench.experiments.series_parallel.show`); a kind with neither is told so in one line (exit 2).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from workbench import registry
from workbench.cli import main

ROOT = Path(__file__).parents[2]
STUDIES = sorted(ROOT.glob("studies/*.toml")) + sorted(ROOT.glob("tests/regression/studies/*.toml"))
SHOWN_BY_KIND = {"series_parallel"}  # study kinds whose trunk is no Robot: shown by their robot_show hook


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
    assert rc == 0, e
    assert "Traceback" not in o + e
    if _kind(path) in SHOWN_BY_KIND:
        for words in ("geometry.rod_diameter = ", "leg rest lengths L_i", "converged)", "EI = E pi d⁴/64",
                      "axial EA/L_i", "bending 3EI/L_i³", "module(s)"):
            assert words in o, words
        _check_picture(out)
        return
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
    (["examples/measured/measured.toml", "--case", "0"], "--case 0: a 'calibration' study has one nominal robot"),
])
def test_bad_input_is_one_line(args, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    rc, o, e, out = _show(args, tmp_path, capsys)
    assert rc == 2 and not out.exists()
    assert len(e.strip().splitlines()) == 1 and words in e, e


def test_a_calibration_study_shows_its_nominal_robot(tmp_path, capsys):
    """The calibration kind (``examples/measured``) has no sweep base: robot show takes its nominal robot, the
    robot the study starts calibrating from (Rao et al. 2021: NiTi, 1.4 mm rods)."""
    rc, o, e, out = _show([str(ROOT / "examples/measured/measured.toml")], tmp_path, capsys)
    assert rc == 0, e
    assert "its nominal robot (preset rao_2021; before calibration)" in o and "robot.sections[0].diameter = 0.0014" in o
    _check_picture(out)


def test_out_must_be_a_file(tmp_path, capsys):
    rc = main(["robot", "show", "steel_rod", "--out", str(tmp_path)])
    e = capsys.readouterr().err
    assert rc == 2 and e.startswith("--out") and len(e.strip().splitlines()) == 1


def test_series_parallel_derived_numbers_by_hand():
    """d = 6 mm, E = 200 GPa, nu = 0.3, rho = 7850 kg/m^3 (ModuleGeometry defaults), given rest lengths:
    A = pi 36e-6 / 4 = 2.8274e-5 m^2 -> EA = 5.6549e6 N, rho A = 0.22195 kg/m;
    I = pi 1.296e-9 / 64 = 6.3617e-11 m^4 -> EI = 12.723 N m^2; G = 200e9 / 2.6 = 76.923e9 Pa,
    J = 2 I -> GJ = 9.7873 N m^2; leg 0.5 m: EA/L = 1.1310e7 N/m, 3EI/L^3 = 305.36 N/m;
    leg 0.4 m: 3EI/L^3 = 596.41 N/m; module 0.22195 x (3 x 0.5 + 3 x 0.4) + 0.5 = 1.0993 kg, 2 modules 2.1985 kg."""
    from workbench.experiments.series_parallel.show import derived_quantities
    from workbench.physics.series_parallel import ModuleGeometry

    d = derived_quantities(ModuleGeometry(), [0.5, 0.5, 0.5, 0.4, 0.4, 0.4], n_modules=2)
    rel = 1e-4  # the hand values above carry 5 significant digits
    assert d.EA == pytest.approx(5.6549e6, rel=rel) and d.EI == pytest.approx(12.723, rel=rel)
    assert d.GJ == pytest.approx(9.7873, rel=rel) and d.mass_per_length == pytest.approx(0.22195, rel=rel)
    assert d.axial_stiffness[0] == pytest.approx(1.1310e7, rel=rel)
    assert d.axial_stiffness[3] == pytest.approx(1.4137e7, rel=rel)
    assert d.bending_stiffness[0] == pytest.approx(305.36, rel=rel)
    assert d.bending_stiffness[5] == pytest.approx(596.41, rel=rel)
    assert d.module_mass == pytest.approx(1.0993, rel=rel) and d.total_mass == pytest.approx(2.1985, rel=rel)


def test_series_parallel_home_lengths_and_flags(tmp_path, capsys):
    """The home rest lengths are the kind's own IK: longer than the 0.5 m height (the legs are S-shaped),
    and their excess over the height (4.6 mm) within 1 % of that of the Hermite predictor (the IK's start;
    8 elements: 0.5 % apart); --case / --tension apply to [robot] studies only."""
    import numpy as np

    from workbench.physics.series_parallel import ModuleGeometry, home_pose, leg_lengths_from_pose_hermite

    rc, o, e, _ = _show([str(ROOT / "studies/series_parallel.toml"), "solver.n_elements=8"], tmp_path, capsys)
    assert rc == 0, e
    L = float(re.search(r"L_i \[m\] = ([0-9.]+) \(each leg\)", o).group(1))
    g = ModuleGeometry()
    guess = float(np.mean(leg_lengths_from_pose_hermite(g, home_pose(g))))
    assert g.height < L and abs(L - guess) < 0.01 * (guess - g.height), (L, guess)
    assert "8 GE-beam elements per leg" in o
    for flag in (["--case", "0"], ["--tension", "1"]):
        (tmp_path / "robot.png").unlink(missing_ok=True)
        rc, o, e, out = _show([str(ROOT / "studies/series_parallel.toml"), *flag], tmp_path, capsys)
        assert rc == 2 and not out.exists() and len(e.strip().splitlines()) == 1
        assert f"{flag[0]} {flag[1]}: applies to studies with a [robot]" in e, e


def test_a_kind_with_neither_robot_nor_hook_is_refused(tmp_path, capsys, monkeypatch):
    from dataclasses import replace

    kinds = dict(registry.KINDS)
    kinds["series_parallel"] = replace(kinds["series_parallel"], robot_show=None)
    monkeypatch.setattr(registry, "KINDS", kinds)
    rc, o, e, out = _show([str(ROOT / "studies/series_parallel.toml")], tmp_path, capsys)
    assert rc == 2 and not out.exists() and len(e.strip().splitlines()) == 1
    assert "has no [robot] section" in e and "registers no robot_show" in e, e
