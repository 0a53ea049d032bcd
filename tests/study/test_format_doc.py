"""docs/study-format.md is the format reference: its annotated examples use only keys the loaders know."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "study-format.md"
BLOCKS = re.findall(r"```toml\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)


KINDS = [tomllib.loads(b)["study"].get("kind", "sweep") for b in BLOCKS]


def test_the_page_has_one_reference_example_per_study_kind_and_runnable_sweep_examples():
    """The annotated reference of each kind (the first block of its section), and further sweep examples."""
    assert KINDS[0] == "sweep" and KINDS.count("series_parallel") == 1 and set(KINDS) == {"sweep", "series_parallel"}
    assert len(BLOCKS) == 3


def test_the_runnable_sweep_examples_are_valid_studies(tmp_path):
    """Every sweep example after the annotated reference (per-model settings, element sweeps) validates."""
    from workbench.study import load_study

    examples = [b for b, k in zip(BLOCKS[1:], KINDS[1:]) if k == "sweep"]
    assert examples
    for i, block in enumerate(examples):
        p = tmp_path / f"example{i}.toml"
        p.write_text(block)
        study = load_study(p)
        assert study.base["solver"].get("by_model") == {"beam3d": {"tendon_model": "eyelets"}}


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
    p.write_text(BLOCKS[KINDS.index("series_parallel")])
    kind = get_kind(kind_of(p))
    assert kind.name == "series_parallel"
    assert len(kind.expand(kind.load(p))) == 14  # 5 + 5 + 1 module samples (the last one: 8 mm rods) + 3 stack
