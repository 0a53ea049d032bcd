"""``workbench validate`` on calibration studies: the CLI path end to end.

The kind (``workbench/measure/kind.py``, registry ``KINDS["calibration"]``) loads through
:func:`workbench.measure.spec.load_calibration_study`: a malformed data file is one line on stderr naming
the data file, the row and the column, exit code 2; the fixture is accepted.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from workbench.cli import main

FIX = Path(__file__).with_name("fixtures")


def _copy(tmp: Path) -> Path:
    shutil.copy(FIX / "calibration.toml", tmp / "calibration.toml")
    shutil.copy(FIX / "measured.csv", tmp / "measured.csv")
    return tmp / "calibration.toml"


def test_validate_refuses_a_bad_cell_in_one_line(tmp_path, capsys):
    path = _copy(tmp_path)
    lines = (tmp_path / "measured.csv").read_text(encoding="utf-8").splitlines()
    cells = lines[7].split(",")
    cells[2] = "NaN"
    lines[7] = ",".join(cells)
    (tmp_path / "measured.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1] == f"{tmp_path / 'measured.csv'}: row 7, column 'T3' (measurements.commands): NaN (not a number)"


def test_validate_accepts_the_fixture_with_an_override(tmp_path, capsys):
    path = _copy(tmp_path)
    assert main(["validate", str(path), "calibration.seed=3"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"{path}: ok: study 'measured_fixture'") and "calibration.seed=3" in out
