"""Every parameter of a preset in the preset form declares where it comes from (given by the paper,
assumed, or a study setting): the built-in parametric preset files' ``[parameters]`` tables, a plug-in's
code preset module's GIVEN / ASSUMED / SETTINGS.

Description-form data presets (rao_2021) state the source of each value in their file;
``tests/robot/test_rao_preset.py`` checks that every value of the robot they build has one.
"""

import pytest

from workbench.robot.presets import build_preset, data_preset, preset_parameters, preset_names, preset_sources

PRESET_FORM = [n for n in preset_names() if data_preset(n) is None]


def test_every_preset_is_code_or_data():
    assert "rao_2021" in preset_names() and data_preset("rao_2021") is not None
    assert {"steel_rod", "shao_harvester", "cojocaru_tronconic", "hannan_walker", "hannan_walker_3d"} <= set(PRESET_FORM)


@pytest.mark.parametrize("name", PRESET_FORM)
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
