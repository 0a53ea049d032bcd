"""A robot from plain data: the ``[robot]`` table of a study, in either of its two forms.

* **preset form** ``{"preset": name, **parameters}`` for a preset written as code
  (:mod:`workbench.robot.presets`; a per-section parameter may be a list, one value per section);
* **description form** ``{"sections": [...], "gravity": [...], ...}`` (``docs/robot-format.md``),
  optionally on top of a *data preset* (``{"preset": "rao_2021", "sections": [{}, {...}]}``): the
  preset file's description with the table's values merged in (tables key by key, lists of tables
  entry by entry, anything else replaced).

Public API (the seam of issue 29): :func:`robot_from_params` builds the :class:`Robot`,
:func:`robot_problems` lists every problem in one line each naming its key path, and
:func:`robot_value_sources` says where each value comes from ("set in the study file", "material
niti: <source>", "preset rao_2021: <source>").  Checked by ``tests/robot/test_spec.py`` and
``tests/robot/test_spec_malformed.py``.
"""

from __future__ import annotations

import copy
from typing import Any, Mapping

from .description import Payload, Robot, RobotDescriptionError
from .fields import Reader
from .orientation import BASE_ORIENTATIONS, base_rotation_for
from .section_spec import SET_IN_FILE, read_section

__all__ = ["ROBOT_KEYS", "is_description", "merged_description", "robot_from_params", "robot_problems",
           "robot_value_sources"]

#: The keys of a description-form ``[robot]`` table.
ROBOT_KEYS = ("preset", "name", "sections", "gravity", "base_position", "base_orientation", "base_rotation",
              "payload")
_DEFAULTS = {"gravity": "default: no gravity", "base_position": "default: at the world origin",
             "base_orientation": "default: vertical (identity)", "payload": "default: no payload"}


def is_description(params: Mapping[str, Any]) -> bool:
    """``True`` when ``params`` is the description form (no preset, or a data preset), else the preset form."""
    from .presets import data_preset

    preset = params.get("preset")
    return preset is None or (isinstance(preset, str) and data_preset(preset) is not None)


def _merge(base: Any, over: Any, path: str, r: Reader) -> Any:
    """``over`` merged onto ``base``: tables key by key, lists of tables entry by entry (same length)."""
    if isinstance(base, Mapping) and isinstance(over, Mapping):
        out = dict(base)
        for k, v in over.items():
            out[k] = _merge(base[k], v, f"{path}.{k}", r) if k in base else copy.deepcopy(v)
        return out
    if isinstance(base, list) and isinstance(over, list) and base and all(isinstance(x, Mapping) for x in base):
        if len(over) != len(base):
            r.add(path, f"the preset has {len(base)} entries here; give {len(base)} tables (an empty one keeps "
                        f"its entry), got {len(over)}")
            return copy.deepcopy(base)
        return [_merge(b, o, f"{path}[{i}]", r) for i, (b, o) in enumerate(zip(base, over))]
    return copy.deepcopy(over)


def merged_description(params: Mapping[str, Any], where: str = "robot") -> tuple[dict[str, Any], list[str]]:
    """The description ``params`` stands for: its data preset's with ``params`` merged in, and the problems."""
    from .presets import data_preset

    r = Reader()
    preset = params.get("preset")
    if preset is None:
        return dict(params), []
    dp = data_preset(preset) if isinstance(preset, str) else None
    if dp is None:
        return dict(params), [f"{where}.preset: not a data preset: {preset!r}"]
    merged = _merge(dp.description, {k: v for k, v in params.items() if k != "preset"}, where, r)
    return {"preset": preset, **merged}, r.problems


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


def _parse(params: Any, where: str) -> tuple[Robot | None, list[str], dict[str, str]]:
    """(robot or None, problems, sources) of a description-form table."""
    sources: dict[str, str] = {}
    if not isinstance(params, Mapping):
        return None, [f"{where}: must be a table, got {type(params).__name__}"], sources
    desc, problems = merged_description(params, where)
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


def _preset_form_problems(params: Mapping[str, Any], where: str) -> list[str]:
    from .presets import preset_problems

    return preset_problems(params, where)


def robot_problems(params: Any, where: str = "robot") -> list[str]:
    """Every problem of the ``[robot]`` table ``params``, one line each naming its key path.

    ``[]`` when :func:`robot_from_params` builds the robot.  Nothing is simulated.
    """
    if isinstance(params, Mapping) and not is_description(params):
        return _preset_form_problems(params, where)
    return _parse(params, where)[1]


def robot_from_params(params: Mapping[str, Any], where: str = "robot") -> Robot:
    """The :class:`Robot` of a ``[robot]`` table in either form.

    The preset form is passed to :func:`workbench.robot.presets.build_preset` as it is (its
    values are checked where the study is read, :func:`robot_problems`).

    Raises
    ------
    RobotDescriptionError
        A description with problems (the message lists them, one per line).
    TypeError, ValueError
        A preset-form parameter the preset does not know, or a value it refuses.
    """
    if isinstance(params, Mapping) and not is_description(params):
        from .presets import build_preset

        rest = {k: v for k, v in params.items() if k != "preset"}
        return build_preset(params["preset"], **rest)
    robot, problems, _ = _parse(params, where)
    if robot is None:
        raise RobotDescriptionError("\n".join(problems))
    return robot


def robot_value_sources(params: Mapping[str, Any], where: str = "robot") -> dict[str, str]:
    """Key path -> where its value comes from, for every value of the robot ``params`` describes.

    Description form: "set in the study file", "material <name>: <source>", "default: ...", and
    for a data preset's values that the study leaves as they are, "preset <name>: <source>".
    Preset form: the preset's declared source of each parameter (given by its paper, assumed with
    a reason, or a study setting) unless the study sets a different value ("set in the study file").
    """
    from .presets import data_preset, preset_value_sources

    if not is_description(params):
        return preset_value_sources(params, where)
    robot, _, sources = _parse(params, where)
    preset = params.get("preset")
    if preset is None:
        return sources
    dp = data_preset(preset)
    over = {k: v for k, v in params.items() if k != "preset"}
    own = _parse(dp.description, where)[2]  # the preset's own values, as a study file would set them
    for key, text in sources.items():
        if text == SET_IN_FILE and key in own and _leaf(over, key, where) is None:
            sources[key] = dp.source_of(key[len(where) + 1:])
    return sources


def _leaf(data: Any, key: str, where: str) -> Any:
    """The value at key path ``key`` (``where.a[1].b``) in ``data``, ``None`` when absent."""
    import re

    node = data
    for name, index in re.findall(r"\.?([A-Za-z_][A-Za-z0-9_]*)|\[(\d+)\]", key[len(where):]):
        if name:
            if not isinstance(node, Mapping) or name not in node:
                return None
            node = node[name]
        else:
            if not isinstance(node, list) or int(index) >= len(node):
                return None
            node = node[int(index)]
    return node
