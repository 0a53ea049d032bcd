"""The description form of ``[robot]`` -> :class:`Robot`, its problems and the source of each value.

The parser behind :mod:`workbench.robot.spec` (the public API) and
:class:`workbench.robot.presets.data.DataPreset`: a table of the format of ``docs/robot-format.md``
(base pose, gravity, payload, ``sections``; each section by :mod:`workbench.robot.section_spec`),
optionally merged onto a data preset's description.  Imports no preset (the caller passes the
data preset), so presets and the public API can both use it.  Checked by
``tests/robot/test_robot_spec.py`` and ``tests/robot/test_spec_malformed.py``.
"""

from __future__ import annotations

import copy
from typing import Any, Mapping

from .description import Payload, Robot, RobotDescriptionError
from .fields import Reader
from .orientation import BASE_ORIENTATIONS, base_rotation_for
from .section_spec import SET_IN_FILE, read_section

__all__ = ["ROBOT_KEYS", "merge", "merged_description", "parse_description"]

#: The keys of a description-form ``[robot]`` table.
ROBOT_KEYS = ("preset", "name", "sections", "gravity", "base_position", "base_orientation", "base_rotation",
              "payload")
_DEFAULTS = {"gravity": "default: no gravity", "base_position": "default: at the world origin",
             "base_orientation": "default: vertical (identity)", "payload": "default: no payload"}


def merge(base: Any, over: Any, path: str, r: Reader) -> Any:
    """``over`` merged onto ``base``: tables key by key, lists of tables entry by entry (same length)."""
    if isinstance(base, Mapping) and isinstance(over, Mapping):
        out = dict(base)
        for k, v in over.items():
            out[k] = merge(base[k], v, f"{path}.{k}", r) if k in base else copy.deepcopy(v)
        return out
    if isinstance(base, list) and isinstance(over, list) and base and all(isinstance(x, Mapping) for x in base):
        if len(over) != len(base):
            r.add(path, f"the preset has {len(base)} entries here; give {len(base)} tables (an empty one keeps "
                        f"its entry), got {len(over)}")
            return copy.deepcopy(base)
        return [merge(b, o, f"{path}[{i}]", r) for i, (b, o) in enumerate(zip(base, over))]
    return copy.deepcopy(over)


def merged_description(params: Mapping[str, Any], preset: Any = None, where: str = "robot"
                       ) -> tuple[dict[str, Any], list[str]]:
    """The description ``params`` stands for, and the problems of merging it.

    ``preset``: the data preset ``params["preset"]`` names (an object with a ``description``
    mapping, :class:`workbench.robot.presets.data.DataPreset`), ``None`` without one.  Tables
    merge key by key, lists of tables entry by entry (same length), anything else is replaced.
    """
    if preset is None:
        return dict(params), []
    r = Reader()
    merged = merge(preset.description, {k: v for k, v in params.items() if k != "preset"}, where, r)
    return {"preset": params["preset"], **merged}, r.problems


def _base(r: Reader, t: Mapping[str, Any], where: str, sources: dict[str, str]) -> dict[str, Any]:
    """Gravity, base pose, payload and name as :class:`Robot` keyword arguments."""
    out: dict[str, Any] = {}
    for key in ("gravity", "base_position"):
        v = r.numbers(t, key, where, "m/s^2" if key == "gravity" else "m", n=3)
        if v is not None:
            out[key] = v
    if "base_orientation" in t and "base_rotation" in t:
        r.add(f"{where}.base_rotation", "set base_orientation or base_rotation, not both")
    elif "base_orientation" in t:
        name = r.string(t, "base_orientation", where, tuple(BASE_ORIENTATIONS))
        if name is not None:
            out["base_rotation"] = base_rotation_for(name)
    elif "base_rotation" in t:
        rows = t["base_rotation"]
        if not (isinstance(rows, list) and len(rows) == 3):
            r.add(f"{where}.base_rotation", f"must be 3 rows of 3 numbers (world <- base), got {rows!r}")
        else:
            m = [r.numbers({"x": row}, "x", f"{where}.base_rotation[{i}]", "", n=3) for i, row in enumerate(rows)]
            if all(x is not None for x in m):
                out["base_rotation"] = tuple(m)
    if "payload" in t:
        p = r.table(t["payload"], f"{where}.payload", ("mass", "offset"))
        if p is not None:
            mass = r.number(p, "mass", f"{where}.payload", "kg", bound=">=0") if "mass" in p else 0.0
            offset = r.numbers(p, "offset", f"{where}.payload", "m", n=3) if "offset" in p else (0.0, 0.0, 0.0)
            if mass is not None and offset is not None:
                out["payload"] = Payload(mass=mass, offset=offset)
    name = r.string(t, "name", where)
    out["name"] = name if name is not None else str(t.get("preset") or "robot")
    for key in ("gravity", "base_position", "base_orientation", "base_rotation", "payload", "name"):
        if key in t:
            sources[f"{where}.{key}"] = SET_IN_FILE
    return out


def parse_description(params: Any, preset: Any = None, where: str = "robot") -> tuple[Robot | None, list[str], dict[str, str]]:
    """``(robot or None, problems, sources)`` of a description-form table (``preset``: as :func:`merged_description`)."""
    sources: dict[str, str] = {}
    if not isinstance(params, Mapping):
        return None, [f"{where}: must be a table, got {type(params).__name__}"], sources
    desc, problems = merged_description(params, preset, where)
    r = Reader(list(problems))
    t = r.table(desc, where, ROBOT_KEYS, required=("sections",))
    if t is None or r.problems and "sections" not in t:
        return None, r.problems, sources
    kwargs = _base(r, t, where, sources)
    raw = t.get("sections")
    if not isinstance(raw, list) or not raw:
        r.add(f"{where}.sections", f"must be a non-empty list of tables [[{where}.sections]], got {raw!r}")
        return None, r.problems, sources
    sections = [read_section(r, s, f"{where}.sections[{i}]", sources) for i, s in enumerate(raw)]
    if r.problems:
        return None, r.problems, sources
    try:
        robot = Robot(sections=tuple(sections), **kwargs)
    except RobotDescriptionError as e:  # a rotation that is not one (the only check left to Robot)
        return None, [f"{where}.base_rotation: {e}"], sources
    for key, text in _DEFAULTS.items():
        if not any(k.startswith(f"{where}.{key}") for k in sources):
            sources[f"{where}.{key}"] = text
    return robot, [], sources
