"""study/messages.py: the one TOML reader (each kind's wording), suggestions, the moved names."""

from __future__ import annotations

import pytest

from workbench.study import messages
from workbench.study.messages import StudyError, check_robot_value, read_toml, suggest


def test_read_toml_reads_a_file(tmp_path):
    p = tmp_path / "a.toml"
    p.write_text('[study]\nname = "x"\n')
    assert read_toml(p) == {"study": {"name": "x"}}


def test_read_toml_default_wording_is_the_sweep_studys(tmp_path):
    with pytest.raises(StudyError) as e:
        read_toml(tmp_path / "missing.toml")
    assert e.value.problems == [f"{tmp_path / 'missing.toml'}: cannot read file: No such file or directory"]
    bad = tmp_path / "bad.toml"
    bad.write_text("[study\n")
    with pytest.raises(StudyError) as e:
        read_toml(bad)
    assert e.value.problems[0].startswith(f"{bad}: TOML syntax error: ")


def test_read_toml_keeps_a_callers_wording(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[study\n")
    with pytest.raises(StudyError) as e:
        read_toml(bad, cannot_read="cannot read", syntax_error="invalid TOML")
    assert e.value.problems[0].startswith(f"{bad}: invalid TOML: ")
    with pytest.raises(StudyError) as e:
        read_toml(tmp_path / "nope.toml", cannot_read="cannot read", syntax_error="invalid TOML")
    assert e.value.problems == [f"{tmp_path / 'nope.toml'}: cannot read: No such file or directory"]


def test_suggest_and_robot_value_typing():
    assert suggest("lenght", ["length", "diameter"]) == "; did you mean 'length'?"
    assert suggest("zzz", ["b", "a"]) == "; known keys: a, b"
    assert suggest("zzz", []) == ""
    assert check_robot_value("length", -1.0, 0.8) == (-1.0, "must be > 0 [m], got -1")
    assert check_robot_value("tendon_count", 2.0, 3)[1] == "must be an integer, got float 2.0"
    assert check_robot_value("length", 1, 0.8) == (1.0, None)
