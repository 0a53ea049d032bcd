"""Command-line overrides: key paths into the file, and an override that cannot apply refused in one line."""

from __future__ import annotations

from pathlib import Path

import pytest

from workbench.study import StudyError, expand, load_study
from workbench.study.overrides import apply_overrides, parse_override

ROOT = Path(__file__).resolve().parents[2]


def test_parse_override_key_paths():
    assert parse_override("load.tensions[0]=2.0") == (["load", "tensions", 0], 2.0)
    assert parse_override("solver.by_model.beam3d.tendon_model=eyelets") == (
        ["solver", "by_model", "beam3d", "tendon_model"], "eyelets")
    assert parse_override('sweep.product.load.tensions[0]=[1.0, 2.0]') == (
        ["sweep", "product", "load.tensions[0]"], [1.0, 2.0])
    with pytest.raises(StudyError) as e:
        parse_override("load.tensions[x]=1")
    assert e.value.problems == ["override 'load.tensions[x]=1': malformed key path; expected dotted keys with [i] list "
                                "indices, e.g. load.tensions[0] or robot.sections[1].diameter"]


def test_apply_an_element_override():
    raw = {"load": {"tensions": [1.0, 0.0]}, "solver": {}}
    out = apply_overrides(raw, ["load.tensions[1]=0.5", "solver.by_model.cc.n_elements=8"])
    assert out["load"]["tensions"] == [1.0, 0.5] and out["solver"] == {"by_model": {"cc": {"n_elements": 8}}}
    assert raw == {"load": {"tensions": [1.0, 0.0]}, "solver": {}}  # the file's data is not changed
    with pytest.raises(StudyError) as e:
        apply_overrides(raw, ["load.tensions[2]=1.0", "load.mode[0]=1", "robot.length[0]=1.0"])
    assert e.value.problems == [
        "override 'load.tensions[2]=1.0': index 2 is out of range (load.tensions has 2 entries)",
        "override 'load.mode[0]=1': load.mode is not set, not a list; [0] needs a list",
        "override 'robot.length[0]=1.0': robot.length is not set, not a list; [0] needs a list"]


def test_an_element_override_is_validated_like_the_file(write_study):
    path = write_study()
    assert expand(load_study(path, overrides=["load.tensions[0]=2.5"]))[0].params["load"]["tensions"] == [2.5, 0.0]
    with pytest.raises(StudyError) as e:
        load_study(path, overrides=["load.tensions[0]=-2.5"])
    assert e.value.problems == [f"{path}: load.tensions[0]: must be >= 0 [N], got -2.5"]


def test_an_override_the_sweep_sets_in_every_case_is_refused():
    """``bending`` sets solver.n_elements in every [sweep] case: the override would be recorded but not used."""
    path = ROOT / "studies" / "bending.toml"
    with pytest.raises(StudyError) as e:
        load_study(path, overrides=["solver.n_elements=8"])
    assert e.value.problems == [
        f"{path}: override 'solver.n_elements=8': [sweep] cases sets solver.n_elements in every case, so "
        f"solver.n_elements would not apply; change the sweep (e.g. sweep.cases...) or drop the override"]


def test_an_override_inside_a_swept_value_is_refused(write_study):
    path = write_study('\n[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0]] }\n')
    with pytest.raises(StudyError) as e:
        load_study(path, overrides=["load.tensions[1]=0.5"])
    assert e.value.problems == [
        f"{path}: override 'load.tensions[1]=0.5': [sweep] product sets load.tensions in every case, so "
        f"load.tensions[1] would not apply; change the sweep (e.g. sweep.product...) or drop the override"]
    # the other element of a swept element is not shadowed
    path = write_study('\n[sweep]\nproduct = { "load.tensions[0]" = [1.0, 2.0] }\n')
    cases = expand(load_study(path, overrides=["load.tensions[1]=0.5"]))
    assert [c.params["load"]["tensions"] for c in cases] == [[1.0, 0.5], [2.0, 0.5]]
