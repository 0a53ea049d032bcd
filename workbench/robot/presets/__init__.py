"""Named robot presets: ``get_preset(name)(**params) -> Robot``, written as data (or as code by a plug-in).

Presets are the rows of ``workbench.registry.table("presets")`` (built-in and plug-in), imported
lazily by name.  Every built-in preset is a TOML file of this folder (:mod:`.data`,
``docs/robot-format.md``), in one of two forms:

* a **parametric** preset file (steel_rod, shao_harvester, ...) declares its parameters as data
  (``[parameters.<name>]``: default, unit, kind = given / assumed / setting, source, per_section)
  and names the formula ``derive = "module:function"`` that maps their values to the robot; a
  study uses it in the preset form ``{"preset": name, **parameters}`` (a per-section parameter
  may be a list of ``n_sections`` values);
* a **description** preset file (rao_2021) holds only the robot; a study overrides its values in the
  description form (:mod:`workbench.robot.spec`).

A plug-in may still register a **code preset**: a plain function of keyword parameters with
defaults, its module declaring ``GIVEN`` (name -> where the paper gives it), ``ASSUMED`` (a tuple
of :class:`workbench.assumptions.Assumption`), ``SETTINGS`` and ``PER_SECTION``.
``tests/robot/test_presets_sources.py`` checks that every parameter of every preset in the preset
form has exactly one source.
"""

from __future__ import annotations

import inspect
import sys
from typing import Any, Callable, Mapping

from ... import registry
from ...assumptions import declared_assumptions
from ...study.messages import check_robot_value, join_key, suggest
from ..description import Robot
from .data import DataPreset
from .per_section import per_section

__all__ = ["preset_names", "get_preset", "preset_parameters", "build_preset", "preset_sources", "data_preset",
           "per_section_parameters", "per_section", "preset_values", "preset_problems", "preset_value_sources"]


def preset_names() -> tuple[str, ...]:
    """The registered preset names: built-in and plug-in rows of ``registry.table("presets")``."""
    return tuple(registry.table("presets"))


def get_preset(name: str) -> Callable[..., Robot]:
    """Return the preset registered as ``name``: a function, or a :class:`~.data.DataPreset` (KeyError lists known names)."""
    rows = registry.table("presets")
    if name not in rows:
        raise KeyError(f"unknown robot preset {name!r}; known presets: {', '.join(rows)}")
    return registry.resolve(rows[name])


def data_preset(name: str) -> DataPreset | None:
    """The description-form :class:`~.data.DataPreset` registered as ``name``.

    ``None`` for a preset used in the preset form (a parametric data preset or a code preset) or an
    unknown name.
    """
    if name not in registry.table("presets"):
        return None
    preset = get_preset(name)
    return preset if isinstance(preset, DataPreset) and not preset.parametric else None


def preset_parameters(name: str) -> dict[str, Any]:
    """The parameters of preset ``name`` with their defaults (``{}`` for a description-form data preset)."""
    preset = get_preset(name)
    if isinstance(preset, DataPreset):
        return {k: p.default for k, p in preset.parameters.items()}
    sig = inspect.signature(preset)
    return {k: p.default for k, p in sig.parameters.items() if p.kind is p.KEYWORD_ONLY or p.default is not p.empty}


def per_section_parameters(name: str) -> tuple[str, ...]:
    """The parameters of preset ``name`` that take one value per section (``per_section`` / ``PER_SECTION``)."""
    preset = get_preset(name)
    if isinstance(preset, DataPreset):
        return tuple(k for k, p in preset.parameters.items() if p.per_section)
    return tuple(getattr(sys.modules[preset.__module__], "PER_SECTION", ()))


def build_preset(name: str, **params: Any) -> Robot:
    """Build preset ``name`` with parameter overrides; unknown parameters raise TypeError naming them."""
    fn = get_preset(name)
    if isinstance(fn, DataPreset):
        return fn(**params)
    known = preset_parameters(name)
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise TypeError(
            f"preset {name!r} has no parameter(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}"
        )
    return fn(**params)


def preset_sources(name: str) -> dict[str, dict[str, str]]:
    """``{"given": ..., "assumed": ..., "settings": ...}`` of preset ``name``: parameter -> where it comes from.

    Parametric data preset: its file's ``[parameters.<name>]`` by ``kind``; description-form data
    preset: its file's ``[preset.given]`` / ``[preset.assumed]`` (keys are relative key paths); code
    preset: its module's ``GIVEN``, ``ASSUMED`` (:func:`workbench.assumptions.declared_assumptions`)
    and ``SETTINGS``.  Empty dicts where none is declared.
    """
    preset = get_preset(name)
    if isinstance(preset, DataPreset) and preset.parametric:
        return {table: {k: p.source for k, p in preset.parameters.items() if p.kind == kind}
                for table, kind in (("given", "given"), ("assumed", "assumed"), ("settings", "setting"))}
    if isinstance(preset, DataPreset):
        return {"given": dict(preset.given), "assumed": dict(preset.assumed), "settings": {}}
    mod = sys.modules[preset.__module__]
    return {"given": dict(getattr(mod, "GIVEN", {}) or {}),
            "assumed": {a.key: a.source for a in declared_assumptions(mod)},
            "settings": dict(getattr(mod, "SETTINGS", {}) or {})}


def _preset_name_problem(preset: Any, where: str) -> str | None:
    names = preset_names()
    if preset is None:
        return (f"{where}.preset: missing required key (one of: {', '.join(names)}; or describe the "
                f"robot with [[{where}.sections]])")
    if not isinstance(preset, str):
        return f"{where}.preset: must be a string, got {type(preset).__name__} {preset!r}"
    if preset not in names:
        return (f"{where}.preset: unknown preset {preset!r}{suggest(preset, list(names))}"
                .replace("; known keys:", "; known presets:"))
    return None


def preset_values(params: Mapping[str, Any], where: str = "robot"
                  ) -> tuple[dict[str, Any] | None, dict[str, Any], list[str]]:
    """``(values, defaults, problems)`` of a preset-form table ``{"preset": name, **overrides}``.

    ``values`` are the preset's defaults with the checked overrides applied (numbers coerced
    to the default's type; a ``PER_SECTION`` parameter may be a list of ``n_sections`` values),
    ``None`` when the preset itself is bad; ``problems`` one line each, ``"<where>.<key>: ..."``.
    """
    preset = params.get("preset")
    bad = _preset_name_problem(preset, where)
    if bad:
        return None, {}, [bad]
    try:
        defaults = preset_parameters(preset)
    except ImportError as e:
        return None, {}, [f"{where}.preset: preset {preset!r} is not available in this installation ({e})"]
    per = per_section_parameters(preset)
    n = params.get("n_sections", defaults.get("n_sections"))
    out, problems = dict(defaults), []
    for k, v in params.items():
        if k == "preset":
            continue
        if k not in defaults:
            problems.append(f"{where}.{k}: unknown parameter of preset {preset!r}{suggest(k, list(defaults))}")
        elif isinstance(v, list) and k in per:
            if isinstance(n, int) and len(v) != n:
                problems.append(f"{where}.{k}: expected {n} values (one per section, n_sections = {n}), got {len(v)}")
                continue
            checked = [check_robot_value(k, x, defaults[k], where) for x in v]
            problems += [join_key(f"{where}.{k}[{i}]", p) for i, (_, p) in enumerate(checked) if p]
            out[k] = [x for x, _ in checked]
        else:
            cv, prob = check_robot_value(k, v, defaults[k], where)
            if prob:
                problems.append(join_key(f"{where}.{k}", prob))
            else:
                out[k] = cv
    return out, defaults, problems


def preset_problems(params: Mapping[str, Any], where: str = "robot") -> list[str]:
    """The problems of a preset-form table (:func:`preset_values`), one line each."""
    return preset_values(params, where)[2]


def preset_value_sources(params: Mapping[str, Any], where: str = "robot") -> dict[str, str]:
    """``<where>.<parameter>`` -> its source, for every parameter of the preset-form preset ``params`` names.

    A value the study sets and that differs from the default reads "set in the study file"; else
    the preset's declared source ("given by ...", "assumed: ...", "study choice").
    """
    name = params["preset"]
    src = preset_sources(name)
    defaults = preset_parameters(name)
    out = {}
    for k, default in defaults.items():
        if k in params and params[k] != default:
            out[f"{where}.{k}"] = "set in the study file"
        elif k in src["given"]:
            out[f"{where}.{k}"] = f"preset {name}: given by {src['given'][k]}"
        elif k in src["assumed"]:
            out[f"{where}.{k}"] = f"preset {name}: assumed: {src['assumed'][k]}"
        else:
            out[f"{where}.{k}"] = f"preset {name}: {src['settings'].get(k, 'no source stated')}"
    return out
