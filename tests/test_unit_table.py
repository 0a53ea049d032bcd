"""The one unit table: generic keys only, extended through registry rows, one lookup for every reader."""

from __future__ import annotations

import pytest

from workbench import registry, units
from workbench.study.columns import field_metadata
from workbench.study.messages import check_robot_value, param_unit


def test_the_generic_table_holds_no_study_keys():
    study_sections = ("motion.", "pose.", "x.", "scenario.delay", "scenario.sample")
    assert not [k for k in units.UNITS if k.startswith(study_sections)]
    assert all(isinstance(u, str) or u is None for _, u in units.UNITS.values())


def test_registered_rows_extend_the_table():
    rows = [r for r in (*registry.KINDS.values(), *registry.FIGURES.values()) if r.units]
    assert rows
    for r in rows:
        for key in registry.resolve(r.units):
            assert units.quantity(key) is not None and key not in units.UNITS
    assert units.quantity("p.scenario.delay") == ("wire delay", "s")       # a figure set's key
    assert units.unit_of("x.min_leg_gap") == "m"                           # a study kind's key
    assert units.quantity("p.robot.something_new") is None                # never guessed


def test_one_spelling_for_metadata_messages_and_report():
    assert field_metadata("robot_gravity") == {b"unit": "m/s²".encode()}
    assert check_robot_value("density", -1.0, 7850.0)[1] == "must be >= 0 [kg/m³], got -1"
    assert check_robot_value("gravity", -1.0, 9.81)[1] == "must be >= 0 [m/s²], got -1"
    assert param_unit("tip_torque") == "N m" and param_unit("max_case_seconds") == "s"
    # a scenario parameter takes its registered unit; an unlisted one the unit its name says
    assert check_robot_value("delay", float("nan"), 0.0, "scenario")[1] == "must be finite [s], got nan"
    assert check_robot_value("disk_length", -1.0, 0.01)[1] == "must be > 0 [m], got -1"


def test_a_registered_key_may_not_redefine_a_generic_one(monkeypatch):
    bad = {"robot.length": ("length", "mm")}
    monkeypatch.setattr(registry, "FIGURES", {"x": registry.FigureSet("a:b", "a:c", units="t:bad")})
    monkeypatch.setattr(registry, "resolve", lambda t: bad)
    units._registered.cache_clear()
    try:
        with pytest.raises(ValueError, match="robot.length"):
            units.quantity("unknown.key")
    finally:
        units._registered.cache_clear()
