"""A robot from plain data: the ``[robot]`` table of a study, in either of its two forms.

* **preset form** ``{"preset": name, **parameters}`` for a preset with parameters (a parametric
  preset file or a plug-in's code preset, :mod:`workbench.robot.presets`; a per-section parameter
  may be a list, one value per section);
* **description form** ``{"sections": [...], "gravity": [...], ...}`` (``docs/robot-format.md``),
  optionally on top of a *data preset* (``{"preset": "rao_2021", "sections": [{}, {...}]}``): the
  preset file's description with the table's values merged in (tables key by key, lists of tables
  entry by entry, anything else replaced).

Public API (the seam of issue 29): :func:`robot_from_params` builds the :class:`Robot`,
:func:`robot_problems` lists every problem in one line each naming its key path, and
:func:`robot_value_sources` says where each value comes from ("set in the study file", "material
niti: <source>", "preset rao_2021: <source>").  Checked by ``tests/robot/test_robot_spec.py`` and
``tests/robot/test_spec_malformed.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

from .describe import parse_description
from .description import Robot, RobotDescriptionError
from .section_spec import SET_IN_FILE

__all__ = ["is_description", "robot_description", "robot_from_params", "robot_problems", "robot_value_sources"]

def is_description(params: Mapping[str, Any]) -> bool:
    """``True`` when ``params`` is the description form (no preset, or a data preset), else the preset form."""
    from .presets import data_preset

    preset = params.get("preset")
    return preset is None or (isinstance(preset, str) and data_preset(preset) is not None)


def _parse(params: Any, where: str) -> tuple[Robot | None, list[str], dict[str, str]]:
    """:func:`~workbench.robot.describe.parse_description` with the data preset ``params`` names."""
    from .presets import data_preset

    preset = params.get("preset") if isinstance(params, Mapping) else None
    dp = data_preset(preset) if isinstance(preset, str) else None
    if preset is not None and dp is None:
        return None, [f"{where}.preset: not a data preset: {preset!r}"], {}
    return parse_description(params, dp, where)


def robot_description(params: Mapping[str, Any], where: str = "robot") -> dict[str, Any]:
    """The full description a description-form ``params`` stands for (its data preset's values merged in)."""
    from .describe import merged_description
    from .presets import data_preset

    preset = params.get("preset")
    return merged_description(params, data_preset(preset) if isinstance(preset, str) else None, where)[0]


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
    own = parse_description(dp.description, None, where)[2]  # the preset's own values, as a study file would set them
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
