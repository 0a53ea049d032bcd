"""Presets written as data: a TOML file of the description format plus where each value comes from.

A data preset file (``workbench/robot/presets/<name>.toml``, ``docs/robot-format.md``) holds

* ``[preset]``: ``title``, ``source`` (the paper), and the tables ``given`` and ``assumed``
  (relative key path -> text; ``[*]`` stands for every index, e.g. ``"sections[*].length"``);
* ``[robot]``: the robot in the description format, exactly as a study's ``[robot]`` would be.

:data:`FILES` holds one :class:`DataPreset` per file of this folder, so a registry row reads
``"workbench.robot.presets.data:FILES.<name>"``; a plug-in's row names its own :class:`DataPreset`.
Checked by ``tests/robot/test_rao_preset.py``.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from types import MappingProxyType, SimpleNamespace
from typing import Any, Mapping

from ..description import Robot, RobotDescriptionError

__all__ = ["DataPreset", "FILES", "read_data_preset"]


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

    def __call__(self, **overrides: Any) -> Robot:
        """The robot with description-form ``overrides`` merged in.

        Raises
        ------
        RobotDescriptionError
            The merged description has problems (one per line, each naming its key path).
        """
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


def read_data_preset(name: str, text: str) -> DataPreset:
    """The :class:`DataPreset` of a preset file's ``text`` (``ValueError`` naming the file's bad key)."""
    raw = tomllib.loads(text)
    head, robot = raw.get("preset"), raw.get("robot")
    extra = sorted(set(raw) - {"preset", "robot"})
    if not isinstance(head, dict) or not isinstance(robot, dict) or extra:
        raise ValueError(f"preset file {name}.toml: needs exactly the tables [preset] and [robot]"
                         + (f" (unknown: {', '.join(extra)})" if extra else ""))
    return DataPreset(name=name, title=str(head.get("title", name)), source=str(head.get("source", "")),
                      description=MappingProxyType(robot),
                      given=MappingProxyType(dict(head.get("given", {}))),
                      assumed=MappingProxyType(dict(head.get("assumed", {}))))


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
