"""The parametric data presets (``workbench/robot/presets/*.toml`` with ``[parameters]`` and ``derive``).

Each file holds the robot at its default parameter values in the description format and names the
formula that maps parameter values to the robot: the two must give the same :class:`Robot`, bit for
bit (data and code cannot drift).  The file is the only place defaults live (the formula has none).
"""

import inspect

import pytest

from workbench import registry
from workbench.robot.presets import build_preset, get_preset, preset_names, preset_parameters, preset_sources
from workbench.robot.presets.data import DataPreset, read_data_preset
from workbench.robot.spec import robot_from_params
from workbench.units import UNITS

PARAMETRIC = [n for n in preset_names()
              if isinstance(get_preset(n), DataPreset) and get_preset(n).parametric]


def test_the_built_in_presets_are_parametric_data_presets():
    assert {"steel_rod", "shao_harvester", "cojocaru_tronconic", "hannan_walker", "hannan_walker_3d"} \
        <= set(PARAMETRIC)


@pytest.mark.parametrize("name", PARAMETRIC)
def test_the_files_robot_is_derive_of_the_defaults_bit_for_bit(name):
    preset = get_preset(name)
    from_file = robot_from_params(dict(preset.description))
    assert from_file == build_preset(name)
    assert from_file == registry.resolve(preset.derive)(**preset_parameters(name))


@pytest.mark.parametrize("name", PARAMETRIC)
def test_the_file_is_the_only_place_of_the_defaults(name):
    preset = get_preset(name)
    sig = inspect.signature(registry.resolve(preset.derive))
    assert set(sig.parameters) == set(preset.parameters)
    assert all(p.kind is p.KEYWORD_ONLY and p.default is p.empty for p in sig.parameters.values())


@pytest.mark.parametrize("name", PARAMETRIC)
def test_units_agree_with_the_units_table(name):
    for key, p in get_preset(name).parameters.items():
        unit = UNITS.get(f"robot.{key}", (None, None))[1]
        if isinstance(unit, str):
            assert p.unit == unit, (name, key)


def test_the_3d_trunk_shares_the_planar_trunks_values_and_sources():
    planar, spatial = get_preset("hannan_walker").parameters, get_preset("hannan_walker_3d").parameters
    shared = set(planar) & set(spatial)
    assert len(shared) == 9
    assert all(planar[k] == spatial[k] for k in shared), [k for k in shared if planar[k] != spatial[k]]


def test_a_changed_default_changes_the_robot():
    assert build_preset("steel_rod", length=0.7) != build_preset("steel_rod")
    assert build_preset("steel_rod", length=0.7) == robot_from_params(
        {**dict(get_preset("steel_rod").description),
         "sections": [{**get_preset("steel_rod").description["sections"][0], "length": 0.7}]})


def test_unknown_parameter_is_named():
    with pytest.raises(TypeError, match="preset 'steel_rod' has no parameter.s. lenght"):
        build_preset("steel_rod", lenght=0.7)


def test_sources_come_from_the_file():
    src = preset_sources("steel_rod")
    assert src["assumed"]["youngs_modulus"] == "steel, 210 GPa"
    assert src["settings"]["length"] == "study choice" and src["given"] == {}


HEAD = '[preset]\ntitle = "t"\nderive = "m:f"\n[robot]\nname = "x"\n'


@pytest.mark.parametrize("text, message", [
    (HEAD + '[parameters.a]\ndefault = 1.0\nunit = "m"\nkind = "guess"\nsource = "s"\n', "kind must be one of"),
    (HEAD + '[parameters.a]\ndefault = 1.0\nunit = "m"\nkind = "given"\nsource = " "\n', "source a non-empty"),
    (HEAD + '[parameters.a]\ndefault = 1.0\nkind = "given"\nsource = "s"\n', "parameters.a: needs default, unit"),
    (HEAD + '[parameters.a]\ndefault = 1.0\nunit = "m"\nkind = "given"\nsource = "s"\nper_sectoin = true\n',
     "parameters.a: needs default"),
    (HEAD, r"\[parameters\] and \[preset\] derive go together"),
    (HEAD + '[preset.assumed]\n"a" = "why"\n[parameters.a]\ndefault = 1.0\nunit = "m"\nkind = "given"\nsource = "s"\n',
     r"states its sources in \[parameters.<name>\]"),
    ('[preset]\ntitle = "t"\n[robot]\nname = "x"\n[parameters.a]\ndefault = 1.0\nunit = "m"\nkind = "given"\n'
     'source = "s"\n', r"\[parameters\] and \[preset\] derive go together"),
])
def test_malformed_preset_files_are_refused(text, message):
    with pytest.raises(ValueError, match=message):
        read_data_preset("bad", text)
