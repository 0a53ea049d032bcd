"""Presets written as data: a TOML file of the description format plus where each value comes from.

A data preset file (``workbench/robot/presets/<name>.toml``, ``docs/robot-format.md``) holds

* ``[preset]``: ``title``, ``source`` (the paper), and the tables ``given`` and ``assumed``
  (relative key path -> text; ``[*]`` stands for every index, e.g. ``"sections[*].length"``);
* ``[robot]``: the robot in the description format, exactly as a study's ``[robot]`` would be.

A **parametric** preset file (the built-in presets of papers and of the validation tests) also holds

* ``[preset] derive = "module:function"``: the formula that maps the parameter values to the
  :class:`Robot` (keyword-only arguments, no defaults; e.g. section length = length / n_sections);
* ``[parameters.<name>]``: ``default``, ``unit``, ``kind`` (``"given"`` by the source paper,
  ``"assumed"`` or a study ``"setting"``), ``source`` (where the value comes from) and
  ``per_section = true`` when a study may give one value per section as a list;

and its ``[robot]`` table is the robot at the default values (an example of the format;
``tests/robot/test_data_presets.py`` checks that it equals ``derive(defaults)`` bit for bit).
A study uses a parametric preset in the preset form ``{"preset": name, **parameters}``.

:data:`FILES` holds one :class:`DataPreset` per file of this folder, so a registry row reads
``"workbench.robot.presets.data:FILES.<name>"``; a plug-in's row names its own :class:`DataPreset`.
Checked by ``tests/robot/test_rao_preset.py`` and ``tests/robot/test_data_presets.py``.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from types import MappingProxyType, SimpleNamespace
from typing import Any, Mapping

from ..description import Robot, RobotDescriptionError

__all__ = ["DataPreset", "Parameter", "FILES", "read_data_preset"]

#: The kinds of a parameter's source (``[parameters.<name>] kind``).
KINDS = ("given", "assumed", "setting")


@dataclass(frozen=True)
class Parameter:
    """One parameter of a parametric preset: its default (a TOML array becomes a tuple), unit, kind of source
    (one of :data:`KINDS`), source text, and whether a study may give one value per section.

    Read by :func:`read_data_preset`; checked by ``tests/robot/test_data_presets.py``."""

    default: Any
    unit: str
    kind: str
    source: str
    per_section: bool = False


@dataclass(frozen=True)
class DataPreset:
    """One data preset.

    Attributes
    ----------
    name : str
        Its registry name (the file's stem).
    title, source : str
        What it is and the paper (or other source) describing it.
    description : Mapping
        The ``[robot]`` table of the file (description format).
    given, assumed : Mapping[str, str]
        Relative key path (``"sections[*].length"``) -> where the source gives it / why assumed.
    """

    name: str
    title: str
    source: str
    description: Mapping[str, Any] = field(repr=False)
    given: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    assumed: Mapping[str, str] = field(default_factory=lambda: MappingProxyType({}))
    parameters: Mapping[str, Parameter] = field(default_factory=lambda: MappingProxyType({}))
    derive: str = ""

    @property
    def parametric(self) -> bool:
        """``True`` for a preset used in the preset form (it has ``[parameters]`` and ``derive``)."""
        return bool(self.parameters)

    def __call__(self, **overrides: Any) -> Robot:
        """The robot with ``overrides``: parameter values (parametric) or description-form values merged in.

        Raises
        ------
        RobotDescriptionError
            The merged description has problems (one per line, each naming its key path).
        TypeError
            A parametric preset got a parameter it does not have.
        """
        if self.parametric:
            unknown = sorted(set(overrides) - set(self.parameters))
            if unknown:
                raise TypeError(f"preset {self.name!r} has no parameter(s) {', '.join(unknown)}; "
                                f"known: {', '.join(sorted(self.parameters))}")
            from ...registry import resolve

            return resolve(self.derive)(**{**{k: p.default for k, p in self.parameters.items()}, **overrides})
        from ..describe import parse_description

        robot, problems, _ = parse_description({"preset": self.name, **overrides}, self)
        if robot is None:
            raise RobotDescriptionError("\n".join(problems))
        return robot

    def source_of(self, key: str) -> str:
        """``"preset <name>: <text>"`` for relative key path ``key`` (or its nearest enclosing key)."""
        generic = re.sub(r"\[\d+\]", "[*]", key)
        parts = generic.split(".")
        for n in range(len(parts), 0, -1):
            k = ".".join(parts[:n])
            for table, kind in ((self.given, "given by"), (self.assumed, "assumed")):
                if k in table:
                    return f"preset {self.name}: {kind} {table[k]}" if kind == "assumed" else \
                        f"preset {self.name}: {table[k]} ({self.source})"
        return f"preset {self.name}: no source stated"


def _parameters(name: str, table: Any) -> dict[str, Parameter]:
    """The ``[parameters]`` of preset file ``name`` (``ValueError`` naming the bad key)."""
    if not isinstance(table, dict):
        raise ValueError(f"preset file {name}.toml: parameters: must be a table")
    out = {}
    for key, p in table.items():
        where = f"preset file {name}.toml: parameters.{key}"
        if not isinstance(p, dict) or set(p) - {"default", "unit", "kind", "source", "per_section"} \
                or not {"default", "unit", "kind", "source"} <= set(p):
            raise ValueError(f"{where}: needs default, unit, kind and source (optional per_section), got "
                             f"{sorted(p) if isinstance(p, dict) else p!r}")
        if p["kind"] not in KINDS or not str(p["source"]).strip():
            raise ValueError(f"{where}: kind must be one of {', '.join(KINDS)} and source a non-empty text")
        default = tuple(p["default"]) if isinstance(p["default"], list) else p["default"]  # frozen, as a code default
        out[key] = Parameter(default, str(p["unit"]), p["kind"], str(p["source"]), bool(p.get("per_section")))
    return out


def read_data_preset(name: str, text: str) -> DataPreset:
    """The :class:`DataPreset` of a preset file's ``text`` (``ValueError`` naming the file's bad key)."""
    raw = tomllib.loads(text)
    head, robot = raw.get("preset"), raw.get("robot")
    extra = sorted(set(raw) - {"preset", "robot", "parameters"})
    if not isinstance(head, dict) or not isinstance(robot, dict) or extra:
        raise ValueError(f"preset file {name}.toml: needs the tables [preset] and [robot] (and [parameters] with "
                         "[preset] derive)" + (f" (unknown: {', '.join(extra)})" if extra else ""))
    parameters = _parameters(name, raw["parameters"]) if "parameters" in raw else {}
    if bool(parameters) != bool(head.get("derive")):
        raise ValueError(f"preset file {name}.toml: [parameters] and [preset] derive go together")
    if parameters and (head.get("given") or head.get("assumed")):
        raise ValueError(f"preset file {name}.toml: a parametric preset states its sources in [parameters.<name>] "
                         "(kind, source), not in [preset.given] / [preset.assumed]")
    return DataPreset(name=name, title=str(head.get("title", name)), source=str(head.get("source", "")),
                      description=MappingProxyType(robot),
                      given=MappingProxyType(dict(head.get("given", {}))),
                      assumed=MappingProxyType(dict(head.get("assumed", {}))),
                      parameters=MappingProxyType(parameters), derive=str(head.get("derive", "")))


def _files() -> SimpleNamespace:
    folder = resources.files("workbench.robot.presets")
    out = {}
    for entry in sorted(folder.iterdir(), key=lambda p: p.name):
        if entry.name.endswith(".toml"):
            stem = entry.name[: -len(".toml")]
            out[stem] = read_data_preset(stem, entry.read_text(encoding="utf-8"))
    return SimpleNamespace(**out)


#: One :class:`DataPreset` per ``*.toml`` file of this folder, as attributes named by the file's stem.
FILES = _files()
