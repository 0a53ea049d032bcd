"""docs/study-format.md is the format reference: its annotated examples use only keys the loaders know."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "study-format.md"
BLOCKS = re.findall(r"```toml\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)


def test_the_page_has_one_example_per_study_kind():
    assert len(BLOCKS) == 2
    kinds = [tomllib.loads(b)["study"].get("kind", "sweep") for b in BLOCKS]
    assert kinds == ["sweep", "series_parallel"]


def test_the_sweep_example_names_only_known_keys():
    from workbench.robot.presets import preset_parameters
    from workbench.study.scenarios import scenario_parameters
    from workbench.study.schema import SECTION_MODELS, StudyFile

    raw = tomllib.loads(BLOCKS[0])
    assert set(raw) <= set(StudyFile.model_fields)
    for section, model in SECTION_MODELS.items():
        assert set(raw.get(section, {})) <= set(model.model_fields), section
    robot = dict(raw["robot"])
    assert set(robot) - {"preset"} <= set(preset_parameters(robot["preset"]))
    scenario = dict(raw["scenario"])
    assert set(scenario) - {"name"} <= set(scenario_parameters(scenario["name"]))


def test_the_series_parallel_example_is_a_valid_study(tmp_path):
    from workbench.study import get_kind, kind_of

    p = tmp_path / "sp.toml"
    p.write_text(BLOCKS[1])
    kind = get_kind(kind_of(p))
    assert kind.name == "series_parallel"
    assert len(kind.expand(kind.load(p))) == 14  # 5 + 5 + 1 module samples (the last one: 8 mm rods) + 3 stack
