"""Malformed measurement files and calibration tables: each refused in exactly one line, before any fit.

Every case copies the good fixture study (``fixtures/calibration.toml`` + ``fixtures/measured.csv``)
into ``tmp_path``, makes one small edit to the study or the data file, and asserts that
:func:`workbench.measure.spec.load_calibration_study` raises a ``StudyError`` whose problems are
exactly the expected line (the file, the key path, and for a cell the column and the 1-based data
row).  ``models.get_model`` is made to fail, and a subprocess checks that validation imports no
model code, so the refusals come before anything could be fitted.
"""

from __future__ import annotations

import csv
import io
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from workbench.measure.spec import load_calibration_study
from workbench.study.messages import StudyError

FIX = Path(__file__).with_name("fixtures")
ROOT = Path(__file__).resolve().parents[2]


def _cell(row: int, col: str, value: str):
    """A data-file edit: the cell of 1-based data row ``row`` in column ``col`` set to ``value``."""
    def edit(rows: list[list[str]]) -> list[list[str]]:
        rows[row][rows[0].index(col)] = value
        return rows
    return edit


def _header(old: str, new: str):
    def edit(rows: list[list[str]]) -> list[list[str]]:
        rows[0][rows[0].index(old)] = new
        return rows
    return edit


def _keep(n: int):
    return lambda rows: rows[: n + 1]


def _forces(rows: list[list[str]]) -> list[list[str]]:
    """Add tip-force columns fx, fy, fz (0, 0, -0.1 N: in the base x-z plane)."""
    return [r + (["fx", "fy", "fz"] if i == 0 else ["0.0", "0.0", "-0.1"]) for i, r in enumerate(rows)]


PLANAR = 'preset = "rao_2021"\nsections = [{tendons = [{angles = [0.0, 3.141592653589793]}]}, ' \
         '{tendons = [{angles = [0.0, 3.141592653589793]}]}]'


def _ragged(rows: list[list[str]]) -> list[list[str]]:
    rows[5] = rows[5] + ["1.0"]
    return rows


EXPECTED_RANGE = "0.1, 0.2, 0.3"
#: (id, [(old, new) text edits of the study], data-file edit or raw bytes, expected line)
CASES = [
    # --- the data file -----------------------------------------------------------------------
    ("missing_file", [('file = "measured.csv"', 'file = "nope.csv"')], None,
     "{study}: measurements.file: cannot read {dir}/nope.csv: no such file"),
    ("empty_file", [], b"",
     "{study}: measurements.file: cannot read {data}: the file is empty (a header line with the column names and "
     "one line per sample)"),
    ("header_only", [], _keep(0), "{data}: no data rows (only the header line)"),
    ("header_and_blank_lines", [], lambda rows: rows[:1] + [[]] * 3, "{data}: no data rows (only the header line)"),
    ("not_utf8", [], b"T1,T2\n\xff\xfe,1\n",
     "{study}: measurements.file: cannot read {data}: not UTF-8 text (byte 0xff at offset 6)"),
    ("unknown_column", [], _header("z", "Z"),
     "{data}: column 'z' (measurements.tip_position.columns[2]): not in the file; did you mean 'Z'?"),
    ("nan_cell", [], _cell(7, "T3", "NaN"),
     "{data}: row 7, column 'T3' (measurements.commands): NaN (not a number)"),
    ("empty_cell", [], _cell(12, "y", ""), "{data}: row 12, column 'y' (measurements.tip_position): empty cell"),
    ("text_cell", [], _cell(3, "b2x", "12,5mm"),
     "{data}: row 3, column 'b2x' (measurements.backbone): text in a number column: '12,5mm'"),
    ("inf_cell", [], _cell(40, "x", "inf"), "{data}: row 40, column 'x' (measurements.tip_position): must be finite, "
                                            "got inf"),
    ("duplicate_header", [], _header("b3z", "b3y"),
     "{data}: duplicate column names in the header: 'b3y'"),
    ("ragged_row", [], _ragged,
     "{study}: measurements.file: cannot read {data}: not a readable CSV file (Error tokenizing data. C error: "
     "Expected 22 fields in line 6, saw 23)"),
    ("negative_tension", [], _cell(9, "T5", "-12.5"),
     "{data}: row 9, column 'T5' (measurements.commands): a tension must be >= 0 (a tendon cannot push), "
     "got -12.5 mN"),
    ("quaternion_norm", [], _cell(4, "qw", "0.9"),
     "{data}: row 4, columns qw, qx, qy, qz (measurements.tip_orientation): not a unit quaternion: |q| = "
     "{qnorm} (| |q| - 1 | must be <= 0.001)"),
    ("too_few_rows", [], _keep(10),
     "{study}: measurements.file: 10 data rows; calibrating 14 parameters needs at least 15 rows"),
    ("wrong_suffix", [('file = "measured.csv"', 'file = "measured.txt"')], None,
     "{study}: measurements.file: must be a .csv or .parquet file, got 'measured.txt'"),
    ("bad_parquet", [('file = "measured.csv"', 'file = "measured.parquet"')], None, None),
    # --- the [measurements] table --------------------------------------------------------------
    ("command_count", [('"T5", "T6"]', '"T5"]')], None,
     "{study}: measurements.commands.columns: the robot has 6 tendons, one column each in the order of "
     "robot.tendon_table() (section 1 at 90°, -30°, 210°; section 2 at 90°, -30°, 210°), got 5 columns"),
    ("unknown_unit", [('unit = "mN"', 'unit = "milliN"')], None,
     "{study}: measurements.commands.unit: unknown unit 'milliN'; N units: N, mN, kN"),
    ("force_unit_for_length", [('columns = ["x", "y", "z"]\nunit = "mm"', 'columns = ["x", "y", "z"]\nunit = "N"')],
     None, "{study}: measurements.tip_position.unit: 'N' is a unit of N, not of m; m units: m, cm, mm, um, µm, in"),
    ("length_unit_for_tension", [('unit = "mN"', 'unit = "mm"')], None,
     "{study}: measurements.commands.unit: 'mm' is a unit of m, not of N; N units: N, mN, kN"),
    ("zero_scale", [('unit = "mN"', 'unit = "mN"\nscale = 0.0')], None,
     "{study}: measurements.commands.scale: must be > 0 (SI value = scale * value * unit), got 0"),
    ("negative_scale", [('unit = "mm"\n\n[measurements.tip_orientation]', 'unit = "mm"\nscale = -1\n\n'
                         '[measurements.tip_orientation]')], None,
     "{study}: measurements.tip_position.scale: must be > 0 (SI value = scale * value * unit), got -1"),
    ("station_outside", [("stations = [0.1, 0.2, 0.3]", "stations = [0.1, 0.2, 0.45]")], None,
     "{study}: measurements.backbone.stations[2]: 0.45 m is outside [0, L] = [0, 0.4] m (the robot's length)"),
    ("backbone_count", [(", [\"b3x\", \"b3y\", \"b3z\"]]", "]")], None, None),
    ("backbone_triple", [('["b3x", "b3y", "b3z"]', '["b3x", "b3y"]')], None,
     "{study}: measurements.backbone.columns[2]: must name 3 columns (x, y, z), got 2"),
    ("column_twice", [('columns = ["x", "y", "z"]', 'columns = ["x", "y", "T1"]')], None,
     "{study}: measurements.tip_position.columns[2]: column 'T1' is already mapped by "
     "measurements.commands.columns[0]"),
    ("convention_in_tension", [('unit = "mN"', 'unit = "mN"\nconvention = "pull"')], None,
     "{study}: measurements.commands.convention: applies to length mode only (mode = \"tension\")"),
    ("no_convention_in_length", [('mode = "tension"', 'mode = "length"'), ('unit = "mN"', 'unit = "um"')], None,
     "{study}: measurements.commands.convention: missing required key in length mode: \"pull\" (a positive value "
     "reels the tendon in) or \"free_length\" (negative = reeled in)"),
    ("bad_mode", [('mode = "tension"', 'mode = "angle"')], None,
     "{study}: measurements.mode: must be 'tension' or 'length', got 'angle'"),
    ("bad_frame", [('frame = "measurement"', 'frame = "tracker"')], None,
     "{study}: measurements.frame: must be 'measurement', 'base' or 'world', got 'tracker'"),
    ("unknown_key", [('unit = "mN"', 'untis = "mN"')], None, None),
    ("force_without_frame", [("[calibration]\n", '[measurements.tip_force]\ncolumns = ["T1", "T2", "T3"]\n'
                              'unit = "N"\n\n[calibration]\n')], None,
     "{study}: measurements.tip_force.frame: missing required key"),
    # --- [study], [load], sections ------------------------------------------------------------
    ("kind_sweep", [('kind = "calibration"', 'kind = "sweep"')], None,
     "{study}: study.kind: must be 'calibration', got 'sweep'"),
    ("unknown_section", [("[solver]", "[solvr]")], None, None),
    ("load_tensions", [("pretension = 0.0", "pretension = 0.0\ntensions = [1.0, 0, 0, 0, 0, 0]")], None,
     "{study}: load.tensions: come from the data file ([measurements.commands]); [load] holds only pretension, "
     "tip_force, tip_torque"),
    ("load_negative_pretension", [("pretension = 0.0", "pretension = -1.0")], None,
     "{study}: load.pretension: must be >= 0.0 [N], got -1"),
    # --- [calibration] ----------------------------------------------------------------------
    ("unknown_model", [('models = ["cc", "cosserat"]', 'models = ["cc", "cosserrat"]')], None,
     "{study}: calibration.models[1]: unknown model 'cosserrat'; did you mean 'cosserat'?"),
    ("model_twice", [('models = ["cc", "cosserat"]', 'models = ["cc", "cc"]')], None,
     "{study}: calibration.models: lists a model twice"),
    ("planar_model", [('models = ["cc", "cosserat"]', 'models = ["cc", "ancf"]')], None,
     "{study}: robot.sections[0].tendons: model 'ancf' is planar only, but the tendon of section 0 at sigma = "
     "1.571 rad is not in the base x-z plane; change the key or drop the model"),
    ("no_tendon_model", [('models = ["cc", "cosserat"]', 'models = ["ancf3d"]')], None,
     "{study}: measurements.commands: model 'ancf3d' cannot carry tendon loads (tendon commands must be zero, "
     "no pretension); change the key or drop the model"),
    ("tip_force_model", [('preset = "rao_2021"', PLANAR), ('"T4", "T5", "T6"]', '"T4"]'),
                         ('models = ["cc", "cosserat"]', 'models = ["cc", "contact"]'),
                         ("lower = -0.5\nupper = 0.5", "lower = -0.5\nupper = 0.5\n\n[measurements.tip_force]\n"
                                                      'columns = ["fx", "fy", "fz"]\nunit = "N"\nframe = "base"')],
     _forces, "{study}: measurements.tip_force: model 'contact' cannot carry a tip force; change the key or drop the "
              "model"),
    ("unknown_parameter", [('"robot.sections[1].length"', '"robot.sections[1].lenght"')], None,
     "{study}: calibration.parameters[\"robot.sections[1].lenght\"]: not a value of the case: unknown field "
     "'lenght' of robot.sections[1]; did you mean 'length'?"),
    ("robot_level_section_key", [('"robot.sections[0].youngs_modulus"', '"robot.youngs_modulus"')], None,
     "{study}: calibration.parameters[\"robot.youngs_modulus\"]: not a value of the case: unknown field "
     "'youngs_modulus' of robot; known fields: name, preset, sections (a section's value: "
     "robot.sections[i].youngs_modulus, i = 0..1, one parameter per section)"),
    ("text_parameter", [('"robot.sections[1].length"', '"robot.sections[1].material"')], None,
     "{study}: calibration.parameters[\"robot.sections[1].material\"]: must name a number, "
     "robot.sections[1].material is str 'niti'"),
    ("solver_parameter", [('"robot.sections[1].length"', '"solver.n_elements"')], None,
     "{study}: calibration.parameters[\"solver.n_elements\"]: only robot.* and load.* values can be calibrated"),
    ("parameter_not_a_table", [("lower = 30e9, upper = 80e9 }", "lower = 30e9, upper = 80e9 }\n\"load.pretension\" = 0.1")],
     None, "{study}: calibration.parameters[\"load.pretension\"]: must be a table, got float 0.1"),
    ("bounds_reversed", [("lower = 0.18, upper = 0.22", "lower = 0.22, upper = 0.18")], None,
     "{study}: calibration.parameters[\"robot.sections[1].length\"]: lower must be < upper, got lower = 0.22 m, "
     "upper = 0.18 m"),
    ("bound_infinite", [("upper = 80e9", "upper = inf")], None,
     "{study}: calibration.parameters[\"robot.sections[0].youngs_modulus\"].upper: must be finite, got inf"),
    ("initial_outside", [("lower = 30e9, upper = 80e9", "lower = 60e9, upper = 80e9")], None, None),
    ("parameter_key_typo", [("lower = 30e9, upper", "lowr = 30e9, upper")], None, None),
    ("registration_missing", [("[calibration.registration]\n", ""), ("translation = {", "# translation = {"),
                              ("rotation = {", "# rotation = {")], None, None),
    ("registration_in_base", [('frame = "measurement"', 'frame = "base"')], None,
     "{study}: calibration.registration: measurements.frame = 'base' is a frame of the robot: there is no "
     "registration to calibrate; remove it or set measurements.frame = \"measurement\""),
    ("fraction_and_folds", [("test_fraction = 0.25", "test_fraction = 0.25\nfolds = 4")], None,
     "{study}: calibration: set exactly one of test_fraction and folds (got both)"),
    ("no_split", [("test_fraction = 0.25", "")], None,
     "{study}: calibration: set exactly one of test_fraction and folds (got neither)"),
    ("fraction_above_one", [("test_fraction = 0.25", "test_fraction = 1.5")], None,
     "{study}: calibration.test_fraction: must be < 1.0, got 1.5"),
    ("one_fold", [("test_fraction = 0.25", "folds = 1")], None,
     "{study}: calibration.folds: must be >= 2, got 1"),
    ("physics_rows_small", [("physics_rows = 20", "physics_rows = 5")], None,
     "{study}: calibration.physics_rows: must be >= the number of parameters + 1 = 15, got 5"),
    ("physics_rows_large", [("physics_rows = 20", "physics_rows = 35")], None,
     "{study}: calibration.physics_rows: must be <= the training rows of every fold (30 of the 40 rows), got 35"),
    ("seed_text", [("seed = 1", 'seed = "one"')], None,
     "{study}: calibration.seed: input should be a valid integer, got str 'one'"),
    ("command_zero_length", [("lower = -0.5\nupper = 0.5", "lower = [-0.5, -0.5, -0.5, -0.5, -0.5]\nupper = 0.5")],
     None, "{study}: calibration.command_zero.lower: must be one number or 6 (one per tendon), got 5"),
    ("command_zero_initial", [("lower = -0.5\nupper = 0.5", "lower = 0.1\nupper = 0.5")], None,
     "{study}: calibration.command_zero: need lower < initial < upper, got 0.1 < 0 < 0.5 N (initial "
     "defaults to 0; set initial)"),
    ("calibration_key_typo", [("test_fraction = 0.25", "test_fracton = 0.25")], None, None),
    ("command_zero_key_typo", [("lower = -0.5\nupper = 0.5", "lowr = -0.5\nupper = 0.5")], None,
     "{study}: calibration.command_zero.lowr: unknown key; did you mean 'lower'?"),
    ("registration_key_typo", [("translation = { lower", "translation = { inital = [0, 0, 0], lower")], None,
     "{study}: calibration.registration.translation.inital: unknown key; did you mean 'initial'?"),
    ("force_key_typo", [("[calibration]\n", '[measurements.tip_force]\ncolumns = ["T1", "T2", "T3"]\nunit = "N"\n'
                         'frme = "base"\n\n[calibration]\n')], None,
     "{study}: measurements.tip_force.frme: unknown key; did you mean 'frame'?"),
    ("missing_robot", [('[robot]\npreset = "rao_2021"\n', "")], None, "{study}: robot: missing section [robot]"),
]


def _write(tmp: Path, edits, data) -> Path:
    shutil.copy(FIX / "calibration.toml", tmp / "calibration.toml")
    text = (tmp / "calibration.toml").read_text(encoding="utf-8")
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    (tmp / "calibration.toml").write_text(text, encoding="utf-8")
    if isinstance(data, bytes):
        (tmp / "measured.csv").write_bytes(data)
    else:
        rows = list(csv.reader(io.StringIO((FIX / "measured.csv").read_text(encoding="utf-8"))))
        out = io.StringIO()
        csv.writer(out, lineterminator="\n").writerows(data(rows) if data else rows)
        (tmp / "measured.csv").write_text(out.getvalue(), encoding="utf-8")
    (tmp / "measured.parquet").write_text("not parquet\n", encoding="utf-8")
    return tmp / "calibration.toml"


#: expected lines that need a value computed from the fixture (or are long): case id -> line
SPECIAL = {
    "bad_parquet": "{study}: measurements.file: cannot read {dir}/measured.parquet: not a readable Parquet file "
                   "(Parquet magic bytes not found in footer. Either the file is corrupted or this is not a parquet "
                   "file.)",
    "backbone_count": "{study}: measurements.backbone.columns: one [x, y, z] column triple per station (3 stations), "
                      "got 2",
    "unknown_key": "{study}: measurements.commands.untis: unknown key; did you mean 'unit'?",
    "unknown_section": "{study}: solvr: unknown section; did you mean 'solver'?",
    "initial_outside": "{study}: calibration.parameters[\"robot.sections[0].youngs_modulus\"]: the initial value "
                       "5.4e+10 Pa (material niti: Rao, Peyron, Lilge, Burgner-Kahrs 2021, Front. Robot. AI 7:630245 "
                       "(tdcr-modeling robot): E = 54 GPa) must lie inside (lower, upper) = (6e+10, 8e+10) Pa; widen "
                       "the bounds or set initial",
    "parameter_key_typo": "{study}: calibration.parameters[\"robot.sections[0].youngs_modulus\"].lowr: unknown key; "
                          "did you mean 'lower'?",
    "registration_missing": "{study}: calibration.registration: missing: positions measured in the tracker's frame "
                            "(measurements.frame = \"measurement\") need the base-to-measurement transform "
                            "calibrated (translation and rotation bounds)",
    "calibration_key_typo": "{study}: calibration.test_fracton: unknown key; did you mean 'test_fraction'?",
}


def _expected(case_id: str, template: str | None, study: Path) -> str:
    import numpy as np

    rows = list(csv.reader(io.StringIO((FIX / "measured.csv").read_text(encoding="utf-8"))))
    q = np.array([float(rows[4][rows[0].index(c)]) for c in ("qx", "qy", "qz")])
    qnorm = f"{np.sqrt(0.81 + q @ q):.6g}"
    line = SPECIAL.get(case_id, template)
    return line.format(study=study, data=study.parent / "measured.csv", dir=study.parent, qnorm=qnorm)


@pytest.fixture(autouse=True)
def _no_model(monkeypatch):
    """Validation must refuse before any model could be asked for."""
    from workbench import models

    def refuse(*a, **k):
        raise AssertionError("a model was requested during validation")

    monkeypatch.setattr(models, "get_model", refuse)


def test_the_good_fixture_loads(tmp_path):
    study = load_calibration_study(_write(tmp_path, [], None))
    assert study.measurements.n == 40 and len(study.calibration.parameters) == 14


@pytest.mark.parametrize("case_id, edits, data, template", CASES, ids=[c[0] for c in CASES])
def test_each_malformed_study_is_refused_in_one_line(tmp_path, case_id, edits, data, template):
    path = _write(tmp_path, edits, data)
    with pytest.raises(StudyError) as info:
        load_calibration_study(path)
    expected = _expected(case_id, template, path)
    assert info.value.problems == [expected]
    assert str(path) in expected or str(tmp_path / "measured.csv") in expected


def test_at_least_thirty_malformed_cases():
    assert len(CASES) >= 30
    cells = [c for c in CASES if c[3] and "{data}: row " in c[3]]
    assert len(cells) >= 6  # cell problems name the file, the row and the column


def test_an_override_is_checked_like_the_file(tmp_path):
    path = _write(tmp_path, [], None)
    with pytest.raises(StudyError) as info:
        load_calibration_study(path, overrides=["calibration.physics_rows=3"])
    assert info.value.problems == [f"{path}: calibration.physics_rows: must be >= the number of parameters + 1 = 15, "
                                   f"got 3"]


def test_problems_of_one_file_are_capped(tmp_path):
    def many(rows):
        for r in range(1, 31):
            rows[r][rows[0].index("x")] = "?"
        return rows

    path = _write(tmp_path, [], many)
    with pytest.raises(StudyError) as info:
        load_calibration_study(path)
    p = info.value.problems
    assert len(p) == 21 and p[0].endswith("row 1, column 'x' (measurements.tip_position): text in a number column: '?'")
    assert p[-1] == f"{tmp_path / 'measured.csv'}: ... and 10 more problems in this file"


def test_validation_imports_no_model_code(tmp_path):
    """In a fresh process: loading the good study and refusing a bad one import no physics and no CC."""
    good = _write(tmp_path, [], None)
    bad_dir = tmp_path / "bad"
    bad_dir.mkdir()
    bad = _write(bad_dir, [], _cell(7, "T3", "NaN"))
    code = (f"import sys\nfrom workbench.measure.spec import load_calibration_study\n"
            f"load_calibration_study({str(good)!r})\n"
            f"try:\n    load_calibration_study({str(bad)!r})\nexcept Exception as e:\n    print(type(e).__name__)\n"
            f"print(sorted(m for m in sys.modules if m.startswith(('workbench.physics', 'workbench.models.cc', "
            f"'exudyn', 'scipy.optimize'))))\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120,
                         env={**__import__("os").environ, "PYTHONPATH": str(ROOT)})
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:2] == ["StudyError", "[]"]
