"""Per-section lists of a code preset's scalar parameters (``diameter = [1.4e-3, 1.0e-3]``).

Reference: the same robot written section by section with the dataclasses; a scalar gives
exactly today's robot.
"""

from __future__ import annotations

import math

import pytest

from workbench.robot import CrossSection, Robot, Section, TendonGroup
from workbench.robot.presets import build_preset, per_section, preset_problems
from workbench.study.spec import parse_study


def by_hand(d1, d2, a1, a2) -> Robot:
    def sec(d, a):
        return Section(0.2, CrossSection.circular(d, 54e9, 6450.0, 0.3, yield_strength=1.2e9),
                       TendonGroup.evenly_spaced(3, 0.01, 4.0e4, a, area=4.0e4 / 210e9, strength=2.41e9), n_disks=10)
    return Robot(sections=(sec(d1, a1), sec(d2, a2)), name="steel_rod")


KW = dict(length=0.4, n_sections=2, youngs_modulus=54e9, density=6450.0, tendon_count=3, tendon_offset=0.01,
          disks_per_section=10)


def test_lists_give_the_robot_written_section_by_section():
    robot = build_preset("steel_rod", **KW, diameter=[1.4e-3, 1.0e-3], first_tendon_angle=[math.pi / 2, 5 * math.pi / 6])
    assert robot == by_hand(1.4e-3, 1.0e-3, math.pi / 2, 5 * math.pi / 6)


def test_a_scalar_is_every_section():
    assert build_preset("steel_rod", **KW, diameter=1.4e-3, first_tendon_angle=0.5) == by_hand(1.4e-3, 1.4e-3, 0.5, 0.5)
    assert build_preset("steel_rod", **KW, diameter=[1.4e-3, 1.4e-3]) == build_preset("steel_rod", **KW, diameter=1.4e-3)


def test_wrong_length_is_one_line():
    assert preset_problems({"preset": "steel_rod", "n_sections": 3, "disk_mass": [0.0, 1e-3]}) == [
        "robot.disk_mass: expected 3 values (one per section, n_sections = 3), got 2"]
    with pytest.raises(ValueError, match="disk_mass must hold 3 values"):
        per_section("disk_mass", [0.0, 1e-3], 3)


def test_a_study_with_per_section_lists_validates_and_keeps_the_lists():
    raw = {"study": {"name": "t", "models": ["cc"]},
           "robot": {"preset": "steel_rod", "n_sections": 2, "diameter": [6e-3, 4e-3], "first_tendon_angle": [0, 1]},
           "load": {"mode": "tension", "tensions": [1.0, 0.0, 1.0, 0.0]}}
    study = parse_study(raw, source="t.toml")
    assert study.base["robot"]["diameter"] == [6e-3, 4e-3]
    assert study.base["robot"]["first_tendon_angle"] == [0.0, 1.0]  # coerced to the default's type


def test_cojocaru_per_section_rod_and_wire():
    """Section k of the tronconic arm with its own rod and wire equals the scalar preset's section k
    built with that section's values."""
    listed = build_preset("cojocaru_tronconic", rod_diameter=[5e-3, 4e-3, 3e-3], wire_diameter=[1.2e-3, 1e-3, 0.8e-3])
    for k, (d, w) in enumerate(((5e-3, 1.2e-3), (4e-3, 1e-3), (3e-3, 0.8e-3))):
        scalar = build_preset("cojocaru_tronconic", rod_diameter=d, wire_diameter=w)
        assert listed.sections[k] == scalar.sections[k]
