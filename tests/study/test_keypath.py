"""Key paths (``workbench.study.keypath``): parse, read, replace, and the one-line messages of bad paths."""

from __future__ import annotations

import pytest

from workbench.study.keypath import (KeyPathError, format_key_path, get_value, is_element_path, parse_key_path,
                                     with_value)

DATA = {
    "load": {"tensions": [1.0, 2.0], "mode": "tension"},
    "robot": {"length": 0.8, "sections": [{"diameter": 1.4e-3}, {"diameter": 1.0e-3, "tendons": [{"angles": [0.0]}]}]},
}


@pytest.mark.parametrize("text, parts", [
    ("load.tensions", ("load", "tensions")),
    ("load.tensions[0]", ("load", "tensions", 0)),
    ("robot.sections[1].tendons[0].angles[0]", ("robot", "sections", 1, "tendons", 0, "angles", 0)),
    ("a.b[2][3]", ("a", "b", 2, 3)),
])
def test_parse_and_format_round_trip(text, parts):
    assert parse_key_path(text) == parts
    assert format_key_path(parts) == text


@pytest.mark.parametrize("text", ["load..tensions", "load.tensions[-1]", "load.tensions[x]", "load.tensions]",
                                  "load.1tensions", "", "load.tensions[0", "sweep.product[\"a\"]"])
def test_malformed_paths_are_one_line(text):
    with pytest.raises(KeyPathError, match="malformed key path") as e:
        parse_key_path(text)
    assert "\n" not in str(e.value) and str(e.value).startswith(f"{text}: ")


def test_get_value():
    assert get_value(DATA, "load.tensions[1]") == 2.0
    assert get_value(DATA, "robot.sections[1].diameter") == 1.0e-3
    assert get_value(DATA, "robot.sections[1].tendons[0].angles") == [0.0]


@pytest.mark.parametrize("path, message", [
    ("load.tensions[5]", "load.tensions[5]: index 5 is out of range (load.tensions has 2 entries)"),
    ("robot.length[0]", "robot.length[0]: robot.length is a number, not a list; [0] needs a list"),
    ("load.mode[0]", "load.mode[0]: load.mode is a string, not a list; [0] needs a list"),
    ("robot.sections[1].diamter", "robot.sections[1].diamter: unknown field 'diamter' of robot.sections[1]; "
                                  "did you mean 'diameter'?"),
    ("robot.length.x", "robot.length.x: robot.length is a number, not a table; .x needs a table"),
    ("robot.sections.x", "robot.sections.x: robot.sections is a list, not a table; .x needs a table"),
])
def test_bad_paths_name_the_key(path, message):
    with pytest.raises(KeyPathError) as e:
        get_value(DATA, path)
    assert str(e.value) == message
    with pytest.raises(KeyPathError) as e:
        with_value(DATA, path, 1.0)
    assert str(e.value) == message


def test_with_value_copies_only_the_path():
    out = with_value(DATA, "robot.sections[1].diameter", 0.9e-3)
    assert out["robot"]["sections"][1]["diameter"] == 0.9e-3
    assert DATA["robot"]["sections"][1]["diameter"] == 1.0e-3  # the input is not changed
    assert out["load"] is DATA["load"] and out["robot"]["sections"][0] is DATA["robot"]["sections"][0]
    assert with_value(DATA, "load.tensions[0]", 3.0)["load"]["tensions"] == [3.0, 2.0]


def test_create_adds_table_keys_never_list_entries():
    with pytest.raises(KeyPathError, match="unknown field 'n_elements' of solver"):
        with_value({"solver": {}}, "solver.n_elements", 8)
    assert with_value({"solver": {}}, "solver.by_model.cc.n_elements", 8, create=True) == \
        {"solver": {"by_model": {"cc": {"n_elements": 8}}}}
    with pytest.raises(KeyPathError, match="out of range"):
        with_value(DATA, "load.tensions[2]", 1.0, create=True)


def test_is_element_path():
    assert not is_element_path("load.tensions")
    assert is_element_path("load.tensions[0]") and is_element_path("solver.by_model.cc.n_elements")
