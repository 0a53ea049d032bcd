"""Named robot presets: ``get_preset(name)(**params) -> Robot``.

Each preset is a plain function of keyword parameters (SI units) with documented defaults,
so a study file can name a preset and override any of its parameters.  Presets (the rows of
``workbench.registry.table("presets")``, built-in and plug-in) are imported lazily by name.

Every preset module declares where each parameter comes from, as data (the report's
"Assumptions" section reads it): ``GIVEN`` (parameters the source paper gives: name -> where),
``ASSUMED`` (not given: a tuple of :class:`workbench.assumptions.Assumption`, key = parameter name,
with the value's source or reason) and ``SETTINGS`` (chosen by each study); :func:`preset_sources`
returns the three as name -> text.  ``tests/robot/test_presets_sources.py`` checks that every
parameter of every preset is in exactly one of them.
"""

from __future__ import annotations

import inspect
from typing import Any, Callable

from ... import registry
from ...assumptions import declared_assumptions
from ..description import Robot

__all__ = ["preset_names", "get_preset", "preset_parameters", "build_preset", "preset_sources"]


def preset_names() -> tuple[str, ...]:
    """The registered preset names: built-in and plug-in rows of ``registry.table("presets")``."""
    return tuple(registry.table("presets"))


def get_preset(name: str) -> Callable[..., Robot]:
    """Return the preset function registered as ``name`` (KeyError lists known names)."""
    rows = registry.table("presets")
    if name not in rows:
        raise KeyError(f"unknown robot preset {name!r}; known presets: {', '.join(rows)}")
    return registry.resolve(rows[name])


def preset_parameters(name: str) -> dict[str, Any]:
    """The keyword parameters of preset ``name`` with their defaults."""
    sig = inspect.signature(get_preset(name))
    return {k: p.default for k, p in sig.parameters.items() if p.kind is p.KEYWORD_ONLY or p.default is not p.empty}


def build_preset(name: str, **params: Any) -> Robot:
    """Build preset ``name`` with parameter overrides; unknown parameters raise TypeError naming them."""
    fn = get_preset(name)
    known = preset_parameters(name)
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise TypeError(
            f"preset {name!r} has no parameter(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}"
        )
    return fn(**params)


def preset_sources(name: str) -> dict[str, dict[str, str]]:
    """``{"given": ..., "assumed": ..., "settings": ...}`` of preset ``name``: parameter -> where it comes from.

    From its module's ``GIVEN``, ``ASSUMED`` (:func:`workbench.assumptions.declared_assumptions`)
    and ``SETTINGS``; empty dicts where a module declares none.
    """
    import sys

    mod = sys.modules[get_preset(name).__module__]
    return {"given": dict(getattr(mod, "GIVEN", {}) or {}),
            "assumed": {a.key: a.source for a in declared_assumptions(mod)},
            "settings": dict(getattr(mod, "SETTINGS", {}) or {})}
