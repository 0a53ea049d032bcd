"""Every preset parameter declares where it comes from (given by the paper, assumed, or a study setting)."""

import pytest

from workbench.robot.presets import build_preset, preset_names, preset_parameters, preset_sources


@pytest.mark.parametrize("name", preset_names())
def test_every_parameter_has_exactly_one_source(name):
    src = preset_sources(name)
    params = set(preset_parameters(name))
    declared = [set(src[k]) for k in ("given", "assumed", "settings")]
    assert set().union(*declared) == params, (name, params ^ set().union(*declared))
    assert sum(len(d) for d in declared) == len(params), f"{name}: a parameter is declared twice"
    assert all(text.strip() for d in src.values() for text in d.values())


@pytest.mark.parametrize("name", ["steel_rod", "cojocaru_tronconic", "hannan_walker"])
def test_steel_tendons_carry_area_and_strength(name):
    robot = build_preset(name)
    for _, _, g in robot.tendon_table():
        assert g.area > 0 and 1e9 < g.strength < 3e9
    assert abs(robot.tendon_table()[0][2].axial_stiffness / robot.tendon_table()[0][2].area - 210e9) < 5e9 \
        or name == "hannan_walker"  # HW: cable stiffness and area are separate assumptions
