"""The report's Assumptions table names each robot value's true source (issue 29).

A preset value the study changes reads "set in the study file"; a backbone strength left at the
preset's while the study changes the material says so; a description-form robot shows the study
file, the named material and the data preset as the sources of its values.  CC only (no physics).
"""

from __future__ import annotations

from pathlib import Path

from workbench.report.assumptions import assumption_rows
from workbench.report.load import load_results
from workbench.study import RunConfig, SerialExecutor, load_study, run_study

ROOT = Path(__file__).resolve().parents[2]

STEEL = """
[study]
name = "src"
models = ["cc"]
[robot]
preset = "steel_rod"
youngs_modulus = 54e9
[load]
mode = "tension"
tensions = [1.0, 0.0]
"""


def _rows(tmp_path: Path, text: str) -> dict[str, object]:
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    run_study(load_study(tmp_path / "s.toml"), tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    return {r.key: r for r in assumption_rows(load_results(tmp_path / "out"))}


def test_a_changed_preset_value_reads_set_in_the_study_file(tmp_path):
    rows = _rows(tmp_path, STEEL)
    assert rows["robot.youngs_modulus"].source == "set in the study file"
    assert rows["robot.youngs_modulus"].value == "5.40e+10"
    strength = rows["robot.yield_strength"].source
    assert strength.startswith("still the preset's (hardened and tempered spring steel 52CrMoV4")
    assert "the study sets youngs_modulus" in strength
    assert rows["robot.density"].source == "steel, 7850 kg/m^3"  # unchanged: the preset's own source


def test_a_description_names_study_file_material_and_preset(tmp_path):
    text = (ROOT / "studies" / "rao_rotated.toml").read_text(encoding="utf-8").replace(
        'models = ["cc", "cosserat"]', 'models = ["cc"]')
    rows = _rows(tmp_path, text)
    assert rows["robot.sections[1].diameter"].source == "set in the study file"
    assert rows["robot.sections[1].diameter"].value == "0.001"
    assert rows["robot.sections[0].diameter"].source.startswith("preset rao_2021: backbone radius 0.7 mm")
    assert rows["robot.sections[1].youngs_modulus"].source.startswith("material niti: Rao")
    assert rows["robot.sections[1].youngs_modulus"].value == "5.40e+10"
