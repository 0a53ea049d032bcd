"""The data-file units of the one units table: factors to SI and the refusals of a wrong unit."""

from __future__ import annotations

import pytest

from workbench import units


@pytest.mark.parametrize("unit, si, factor", [("mm", "m", 1e-3), ("um", "m", 1e-6), ("µm", "m", 1e-6),
                                              ("cm", "m", 1e-2), ("in", "m", 0.0254), ("m", "m", 1.0),
                                              ("mN", "N", 1e-3), ("kN", "N", 1e3), ("deg", "rad", 3.141592653589793 / 180)])
def test_factors_to_si(unit, si, factor):
    assert units.si_factor(unit, si) == pytest.approx(factor, rel=1e-15)


def test_every_si_unit_is_its_own_factor_and_a_unit_of_the_table():
    table_units = {u for _, u in units.UNITS.values() if isinstance(u, str)}
    for unit, (si, factor) in units.CONVERSIONS.items():
        assert si in table_units
        assert (factor == 1.0) == (unit == si)


def test_unknown_and_wrong_kind_units_are_one_line_each():
    with pytest.raises(ValueError, match=r"^unknown unit 'mmm'; m units: m, cm, mm, um, µm, in$"):
        units.si_factor("mmm", "m")
    with pytest.raises(ValueError, match=r"^'mN' is a unit of N, not of m; m units: m, cm, mm, um, µm, in$"):
        units.si_factor("mN", "m")
