"""Named materials (``workbench/robot/materials.toml``): every value has a source, the presets' cited values agree."""

from __future__ import annotations

import pytest

from workbench.robot.materials import MATERIAL_FIELDS, material, material_names
from workbench.robot.presets import preset_parameters


@pytest.mark.parametrize("name", material_names())
def test_every_value_has_a_named_source(name):
    m = material(name)
    values = {k: getattr(m, k) for k in MATERIAL_FIELDS if getattr(m, k) is not None}
    assert values, name
    assert set(m.sources) == set(values), name
    assert all(len(text) > 10 for text in m.sources.values())
    assert m.source_text(next(iter(values))).startswith(f"material {name}: ")


@pytest.mark.parametrize("name", material_names())
def test_values_are_physical(name):
    m = material(name)
    assert m.youngs_modulus is None or 1e9 < m.youngs_modulus < 5e11
    assert m.poisson_ratio is None or 0.0 < m.poisson_ratio < 0.5
    assert m.density is None or 500.0 < m.density < 20000.0
    if m.yield_strength is not None and m.tensile_strength is not None:
        assert m.yield_strength < m.tensile_strength


def test_the_presets_cited_values_are_the_materials():
    """The same data sheets as the presets' defaults (steel_rod.toml, cojocaru_tronconic.toml)."""
    steel_rod = preset_parameters("steel_rod")
    assert material("spring_steel").yield_strength == steel_rod["yield_strength"]
    assert material("music_wire_05mm").tensile_strength == steel_rod["tendon_strength"]
    assert (material("steel").youngs_modulus, material("steel").poisson_ratio, material("steel").density) == \
        (steel_rod["youngs_modulus"], steel_rod["poisson_ratio"], steel_rod["density"])
    assert material("music_wire_1mm").tensile_strength == preset_parameters("cojocaru_tronconic")["wire_strength"]
    assert (material("steel").youngs_modulus, material("steel").poisson_ratio, material("steel").density) == \
        (210e9, 0.3, 7850.0)


def test_a_value_no_source_gives_is_left_out():
    assert material("niti").yield_strength is None  # superelastic plateau, not a yield strength
    assert material("niti").density is None
    assert material("steel").yield_strength is None  # no grade, no strength


def test_unknown_material_is_one_line_listing_the_known():
    with pytest.raises(KeyError) as e:
        material("nitinol")
    msg = str(e.value)
    assert "unknown material 'nitinol'" in msg and "niti" in msg and "\n" not in msg


def test_material_is_frozen():
    with pytest.raises(AttributeError):
        material("niti").youngs_modulus = 1.0  # type: ignore[misc]
