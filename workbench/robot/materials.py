"""Named materials as data: ``material(name) -> Material`` read from ``materials.toml``.

Each material holds Young's modulus, Poisson ratio, density, yield (0.2 % proof) strength and
tensile strength [SI] where a source gives them, and the source of each value (a standard, data
sheet or handbook, named in the file).  A value no source gives is ``None``: a robot description
that uses the material must then set it itself (:mod:`workbench.robot.spec` says so in one line).
Checked by ``tests/robot/test_materials.py`` (every value has a source, the presets' cited
values agree).
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from types import MappingProxyType
from typing import Mapping

__all__ = ["Material", "MATERIAL_FIELDS", "material", "material_names"]

#: The value fields of a material, with their units.
MATERIAL_FIELDS: Mapping[str, str] = MappingProxyType({
    "youngs_modulus": "Pa", "poisson_ratio": "", "density": "kg/m^3",
    "yield_strength": "Pa", "tensile_strength": "Pa"})


@dataclass(frozen=True)
class Material:
    """One named material.

    Attributes
    ----------
    name : str
        Its key in ``materials.toml`` (``"niti"``, ``"spring_steel"``).
    description : str
        What it is (grade, condition).
    youngs_modulus : float or None
        Young's modulus E [Pa].
    poisson_ratio : float or None
        Poisson ratio nu [-].
    density : float or None
        Density rho [kg/m^3].
    yield_strength : float or None
        0.2 % proof stress Rp0.2 [Pa] (the allowable backbone stress).
    tensile_strength : float or None
        Minimum tensile strength Rm [Pa] (the allowable stress of a tendon wire).
    sources : Mapping[str, str]
        Field name -> where its value comes from (one entry for every value that is not ``None``).
    """

    name: str
    description: str
    youngs_modulus: float | None = None
    poisson_ratio: float | None = None
    density: float | None = None
    yield_strength: float | None = None
    tensile_strength: float | None = None
    sources: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))

    def source_text(self, key: str) -> str:
        """``"material <name>: <source>"`` of ``key`` (the provenance text of the description format)."""
        return f"material {self.name}: {self.sources[key]}"


@lru_cache(maxsize=1)
def _table() -> dict[str, Material]:
    raw = tomllib.loads(resources.files("workbench.robot").joinpath("materials.toml").read_text(encoding="utf-8"))
    out = {}
    for name, entry in raw.items():
        entry = dict(entry)
        sources = dict(entry.pop("sources", {}))
        values = {k: float(entry.pop(k)) for k in MATERIAL_FIELDS if k in entry}
        description = str(entry.pop("description", ""))
        if entry:
            raise ValueError(f"materials.toml: {name}: unknown field(s) {', '.join(sorted(entry))}")
        missing = sorted(set(values) - set(sources))
        if missing:
            raise ValueError(f"materials.toml: {name}.sources: no source for {', '.join(missing)}")
        out[name] = Material(name=name, description=description, sources=MappingProxyType(sources), **values)
    return out


def material_names() -> tuple[str, ...]:
    """The known material names, in file order."""
    return tuple(_table())


def material(name: str) -> Material:
    """The material named ``name``.

    Raises
    ------
    KeyError
        Unknown name; the one-line message lists the known materials.
    """
    try:
        return _table()[name]
    except KeyError:
        raise KeyError(f"unknown material {name!r}; known materials: {', '.join(material_names())}") from None
