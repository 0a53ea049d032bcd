"""One ``[[robot.sections]]`` table of the description format -> :class:`~workbench.robot.Section`.

The keys, their units and defaults are documented in ``docs/robot-format.md``.  A section's
backbone is either a *geometry* (solid rod ``diameter`` or tube ``outer_diameter`` /
``inner_diameter``, with a ``material`` and/or ``youngs_modulus``, ``poisson_ratio`` or
``shear_modulus``, ``density``, ``yield_strength``; an optional ``tip`` table tapers it) or
*stiffnesses* (``bending_stiffness``, ``axial_stiffness``, ``torsional_stiffness``, optional
``shear_stiffness``, ``mass_per_length``: an equivalent rod without stress geometry).  A value the
user sets replaces the material's.  Every value's source is recorded (``sources``: key path ->
text).  Checked by ``tests/robot/test_robot_spec.py`` and ``tests/robot/test_spec_malformed.py``.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

from .description import CrossSection, Section, TendonGroup
from .fields import Reader
from ..units import unit_of
from .materials import Material, material, material_names

__all__ = ["SECTION_KEYS", "TENDON_KEYS", "read_section", "SET_IN_FILE"]

#: Provenance text of a value the description itself sets.
SET_IN_FILE = "set in the study file"

GEOMETRY_KEYS = ("diameter", "outer_diameter", "inner_diameter", "material", "youngs_modulus", "poisson_ratio",
                 "shear_modulus", "density", "yield_strength", "tip")
STIFFNESS_KEYS = ("bending_stiffness", "axial_stiffness", "torsional_stiffness", "shear_stiffness", "mass_per_length")
#: The keys of one section table.
SECTION_KEYS = ("length", *GEOMETRY_KEYS, *STIFFNESS_KEYS, "disks", "tendons")
#: The keys of one tendon group table.
TENDON_KEYS = ("angles", "count", "first_angle", "offset", "tip_offset", "axial_stiffness", "material",
               "youngs_modulus", "area", "diameter", "strength")


def _material(r: Reader, table: Mapping[str, Any], path: str) -> Material | None:
    name = r.string(table, "material", path)
    if name is None:
        return None
    try:
        return material(name)
    except KeyError:
        r.add(f"{path}.material", f"unknown material {name!r}; known materials: {', '.join(material_names())}")
        return None


def _value(r: Reader, t: Mapping[str, Any], key: str, path: str, mat: Material | None, sources: dict[str, str],
           *, bound: str = ">0", upper: float | None = None, mat_key: str | None = None) -> float | None:
    """The user's value of ``key``, else the material's (``mat_key``), recording the source."""
    if key in t:
        v = r.number(t, key, path, unit_of(f"robot.{key}") or "", bound=bound, upper=upper)
        sources[f"{path}.{key}"] = SET_IN_FILE
        return v
    mk = mat_key or key
    if mat is not None and getattr(mat, mk) is not None:
        sources[f"{path}.{key}"] = mat.source_text(mk)
        return getattr(mat, mk)
    return None


def _poisson(r: Reader, t: Mapping[str, Any], path: str, E: float | None, mat: Material | None,
             sources: dict[str, str]) -> float | None:
    if "poisson_ratio" in t and "shear_modulus" in t:
        r.add(f"{path}.shear_modulus", "set poisson_ratio or shear_modulus, not both")
        return None
    if "shear_modulus" in t:
        G = r.number(t, "shear_modulus", path, "Pa")
        sources[f"{path}.shear_modulus"] = SET_IN_FILE
        if G is None or E is None:
            return None
        nu = E / (2.0 * G) - 1.0
        if not -1.0 < nu < 0.5:
            r.add(f"{path}.shear_modulus", f"gives a Poisson ratio E / (2 G) - 1 = {nu:g} outside (-1, 0.5)")
            return None
        return nu
    nu = _value(r, t, "poisson_ratio", path, mat, sources, bound="any", upper=0.5)
    if nu is not None and nu <= -1.0:
        r.add(f"{path}.poisson_ratio", f"must be > -1, got {nu:g}")
        return None
    return nu


def _need(r: Reader, values: Mapping[str, Any], path: str, mat: Material | None, t: Mapping[str, Any]) -> None:
    """Material values neither set nor given by the material: one line naming the first, listing the rest.

    Nothing when a ``material`` is named but unknown or not a string (its own line says so).
    """
    if "material" in t and mat is None:
        return
    missing = [k for k, v in values.items() if v is None and k not in t]
    if missing:
        why = f"material {mat.name} gives none" if mat is not None else "no material given"
        more = f"; also missing: {', '.join(missing[1:])}" if len(missing) > 1 else ""
        r.add(f"{path}.{missing[0]}", f"missing ({why}){more}; set it in the section or name a material")


def _diameters(r: Reader, t: Mapping[str, Any], path: str) -> tuple[float | None, float]:
    """(outer, inner) diameters of a rod (``diameter``) or tube (``outer_diameter``, ``inner_diameter``)."""
    if "diameter" in t and ("outer_diameter" in t or "inner_diameter" in t):
        r.add(f"{path}.diameter", "set diameter (solid rod) or outer_diameter/inner_diameter (tube), not both")
        return None, 0.0
    if "inner_diameter" in t and "outer_diameter" not in t:
        r.add(f"{path}.outer_diameter", "missing (a tube needs outer_diameter with inner_diameter)")
        return None, 0.0
    if "diameter" not in t and "outer_diameter" not in t:
        r.add(f"{path}.diameter", "missing (set diameter, outer_diameter/inner_diameter, or bending_stiffness ...)")
        return None, 0.0
    D = r.number(t, "diameter" if "diameter" in t else "outer_diameter", path, "m")
    d = r.number(t, "inner_diameter", path, "m", bound=">=0") if "inner_diameter" in t else 0.0
    if D is not None and d is not None and d >= D:
        r.add(f"{path}.inner_diameter", f"must be < outer_diameter ({D:g} m), got {d:g}")
        return None, 0.0
    return D, d if d is not None else 0.0


def _geometry(r: Reader, t: Mapping[str, Any], path: str, sources: dict[str, str]
              ) -> tuple[CrossSection | None, CrossSection | None]:
    """Base and tip cross-sections of a geometry-form section."""
    mat = _material(r, t, path)
    if "material" in t:
        sources[f"{path}.material"] = SET_IN_FILE
    D, d = _diameters(r, t, path)
    for key in ("diameter", "outer_diameter", "inner_diameter"):
        if key in t:
            sources[f"{path}.{key}"] = SET_IN_FILE
    E = _value(r, t, "youngs_modulus", path, mat, sources)
    nu = _poisson(r, t, path, E, mat, sources)
    rho = _value(r, t, "density", path, mat, sources, bound=">=0")
    sy = _value(r, t, "yield_strength", path, mat, sources)
    needed = {"youngs_modulus": E, "poisson_ratio": nu, "density": rho}
    if "shear_modulus" in t:
        del needed["poisson_ratio"]
    _need(r, needed, path, mat, t)
    if sy is not None and "yield_strength" not in t and "youngs_modulus" in t and mat is not None:
        sources[f"{path}.yield_strength"] += f" (youngs_modulus set in the study file; the strength is still {mat.name}'s)"
    if None in (D, E, nu, rho):
        return None, None
    base = CrossSection.tube(D, d, E, rho, nu, yield_strength=sy)
    if "tip" not in t:
        return base, None
    before = len(r.problems)
    tip_t = r.table(t["tip"], f"{path}.tip", ("diameter", "outer_diameter", "inner_diameter"))
    if tip_t is None or len(r.problems) > before:  # not a table, or a misspelt key (its line says which)
        return base, None
    Dt, dt = _diameters(r, tip_t, f"{path}.tip")
    sources[f"{path}.tip"] = SET_IN_FILE
    return base, None if Dt is None else CrossSection.tube(Dt, dt, E, rho, nu, yield_strength=sy)


def _stiffness(r: Reader, t: Mapping[str, Any], path: str, sources: dict[str, str]) -> CrossSection | None:
    """The cross-section of a stiffness-form section (an equivalent rod, no stress geometry)."""
    mixed = [k for k in GEOMETRY_KEYS if k in t and k != "diameter"]
    if mixed:
        r.add(f"{path}.{mixed[0]}", "a section given by bending_stiffness takes no material data "
                                    "(set the stiffnesses, or a material and diameter)")
        return None
    vals = {}
    for k in STIFFNESS_KEYS:
        if k in t:
            vals[k] = r.number(t, k, path, unit_of(f"robot.{k}"), bound=">=0" if k == "mass_per_length" else ">0")
            sources[f"{path}.{k}"] = SET_IN_FILE
        elif k in ("bending_stiffness", "axial_stiffness", "torsional_stiffness"):
            r.add(f"{path}.{k}", "missing (a section given by its stiffnesses needs bending, axial and torsional)")
            vals[k] = None
    diameter = r.number(t, "diameter", path, "m") if "diameter" in t else None
    if any(v is None for k, v in vals.items()) or ("diameter" in t and diameter is None):
        return None
    return CrossSection(EI=vals["bending_stiffness"], EA=vals["axial_stiffness"], GJ=vals["torsional_stiffness"],
                        mass_per_length=vals.get("mass_per_length", 0.0), GA=vals.get("shear_stiffness"),
                        diameter=diameter)


def _disks(r: Reader, raw: Any, path: str, length: float | None, sources: dict[str, str]
           ) -> tuple[int | None, float | None]:
    """(count, mass) of the section's disks from ``{count, mass}`` or ``{positions, mass}``."""
    t = r.table(raw, path, ("count", "mass", "positions"))
    if t is None:
        return None, None
    sources[path] = SET_IN_FILE
    mass = r.number(t, "mass", path, "kg", bound=">=0") if "mass" in t else 0.0
    if ("count" in t) == ("positions" in t):
        r.add(f"{path}.count", "set count or positions (one of them)")
        return None, mass
    if "count" in t:
        return r.integer(t, "count", path), mass
    pos = r.numbers(t, "positions", path, "m", bound=">0")
    if pos is None or length is None:
        return None, mass
    n = len(pos)
    even = [length * (k + 1) / n for k in range(n)]
    if any(abs(p - e) > 1e-9 * length for p, e in zip(pos, even)):
        r.add(f"{path}.positions", "the robot model holds equally spaced disks ending at the section end: "
                                   f"expected [{', '.join(f'{e:g}' for e in even)}] m for {n} disks")
        return None, mass
    return n, mass


def _tendon_group(r: Reader, raw: Any, path: str, sources: dict[str, str]) -> TendonGroup | None:
    """One ``[[robot.sections.tendons]]`` table."""
    t = r.table(raw, path, TENDON_KEYS, required=("offset",))
    if t is None:
        return None
    for k in t:
        sources[f"{path}.{k}"] = SET_IN_FILE
    mat = _material(r, t, path)
    if ("angles" in t) == ("count" in t):
        r.add(f"{path}.angles", "set angles (a list) or count (evenly spaced from first_angle), one of them")
        angles = None
    elif "angles" in t:
        angles = r.numbers(t, "angles", path, "rad")
    else:
        n, first = r.integer(t, "count", path), r.number(t, "first_angle", path, "rad", bound="any")
        first = 0.0 if "first_angle" not in t else first
        angles = None if n is None or first is None else tuple(first + 2.0 * math.pi * k / n for k in range(n))
    if "first_angle" in t and "angles" in t:
        r.add(f"{path}.first_angle", "only with count (angles lists every angle)")
    offset = r.number(t, "offset", path, "m")
    tip = r.number(t, "tip_offset", path, "m") if "tip_offset" in t else None
    if "area" in t and "diameter" in t:
        r.add(f"{path}.diameter", "set area or diameter of the wire, not both")
    area = r.number(t, "area", path, "m^2") if "area" in t else None
    if "diameter" in t:
        d = r.number(t, "diameter", path, "m")
        area = None if d is None else math.pi * d**2 / 4.0
    strength = _value(r, t, "strength", path, mat, sources, mat_key="tensile_strength")
    if "axial_stiffness" in t:
        if "youngs_modulus" in t:
            r.add(f"{path}.youngs_modulus", "set axial_stiffness, or youngs_modulus (or material) with area or "
                                            "diameter, not both")
        ea = r.number(t, "axial_stiffness", path, "N")
    else:
        E = _value(r, t, "youngs_modulus", path, mat, sources)
        if E is None or area is None:
            r.add(f"{path}.axial_stiffness", "missing (set axial_stiffness, or youngs_modulus or a material with "
                                             "area or diameter)")
            return None
        ea = E * area
        sources[f"{path}.axial_stiffness"] = f"youngs_modulus x area ({sources.get(f'{path}.youngs_modulus')})"
    if None in (angles, offset, ea) or ("tip_offset" in t and tip is None):
        return None
    return TendonGroup(angles=angles, offset=offset, axial_stiffness=ea, offset_tip=tip, area=area,
                       strength=strength)


def _tendons(r: Reader, raw: Any, path: str, sources: dict[str, str]) -> tuple[bool, TendonGroup | None]:
    """(ok, group) of the section's tendon groups; groups alike but for their angles are merged."""
    if not isinstance(raw, list):
        r.add(path, f"must be a list of tables [[...tendons]], got {type(raw).__name__} {raw!r}")
        return False, None
    groups = [_tendon_group(r, g, f"{path}[{i}]", sources) for i, g in enumerate(raw)]
    if any(g is None for g in groups):
        return False, None
    if not groups:
        return True, None
    first = groups[0]
    for i, g in enumerate(groups[1:], start=1):
        for name in ("offset", "offset_tip", "axial_stiffness", "area", "strength"):
            if getattr(g, name) != getattr(first, name):
                r.add(f"{path}[{i}]", f"differs from {path}[0] in {name}: a section holds one tendon group "
                                      "(groups may differ only in their angles)")
                return False, None
    angles = tuple(a for g in groups for a in g.angles)
    return True, TendonGroup(angles=angles, offset=first.offset, axial_stiffness=first.axial_stiffness,
                             offset_tip=first.offset_tip, area=first.area, strength=first.strength)


def read_section(r: Reader, raw: Any, path: str, sources: dict[str, str]) -> Section | None:
    """The :class:`Section` of one section table (``None`` with problems recorded in ``r``)."""
    t = r.table(raw, path, SECTION_KEYS, required=("length", "disks"))
    if t is None:
        return None
    length = r.number(t, "length", path, "m")
    sources[f"{path}.length"] = SET_IN_FILE
    if "bending_stiffness" in t:
        base, tip = _stiffness(r, t, path, sources), None
        if "tip" in t:
            r.add(f"{path}.tip", "a taper needs a geometry (diameter / outer_diameter), not stiffnesses")
    else:
        base, tip = _geometry(r, t, path, sources)
    n_disks, disk_mass = _disks(r, t["disks"], f"{path}.disks", length, sources) if "disks" in t else (None, None)
    ok, group = _tendons(r, t["tendons"], f"{path}.tendons", sources) if "tendons" in t else (True, None)
    if None in (length, base, n_disks, disk_mass) or not ok or ("tip" in t and tip is None):
        return None
    return Section(length=length, cross_section=base, tendons=group, n_disks=n_disks, disk_mass=disk_mass,
                   cross_section_tip=tip)
