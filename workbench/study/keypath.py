"""Key paths into nested study parameters: ``load.tensions[0]``, ``robot.sections[1].diameter``.

One syntax everywhere a study names a value (sweep axes, ``[sweep] cases``, command-line
overrides, ``[report] axes``, result columns ``p.<path>``): dotted keys, each optionally followed
by ``[i]`` list indices (``i`` a non-negative integer).  The first key is the section.
:func:`parse_key_path` splits a path into its parts, :func:`get_value` reads the value it names
and :func:`with_value` returns a copy of the data with that value replaced (only the containers
along the path are copied).  Every failure is a :class:`KeyPathError` whose message is one line
naming the path and the reason::

    load.tensions[5]: index 5 is out of range (load.tensions has 2 entries)
    robot.length[0]: robot.length is a number, not a list; [0] needs a list
    robot.sections[1].diamter: unknown field 'diamter' of robot.sections[1]; did you mean 'diameter'?

Imports nothing from the workbench but the message helper, so every layer can use it.  Checked by
``tests/study/test_keypath.py``.
"""

from __future__ import annotations

import re
from typing import Any, Mapping

__all__ = ["KeyPathError", "parse_key_path", "format_key_path", "get_value", "with_value", "is_element_path"]

_SEGMENT = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)")
_INDEX = re.compile(r"\[(\d+)\]")


class KeyPathError(ValueError):
    """A key path that is malformed or does not name a value of the data (message: one line, path first)."""


def parse_key_path(text: str) -> tuple[str | int, ...]:
    """``"robot.sections[1].diameter"`` -> ``("robot", "sections", 1, "diameter")``.

    Raises
    ------
    KeyPathError
        ``text`` is not dotted keys with optional ``[i]`` indices.
    """
    parts: list[str | int] = []
    for seg in str(text).split("."):
        m = _SEGMENT.fullmatch(seg)
        if m is None:
            raise KeyPathError(f"{text}: malformed key path; expected dotted keys with [i] list indices, "
                               f"e.g. load.tensions[0] or robot.sections[1].diameter")
        parts.append(m.group(1))
        parts.extend(int(i) for i in _INDEX.findall(m.group(2)))
    return tuple(parts)


def format_key_path(parts: tuple[str | int, ...] | list[str | int]) -> str:
    """The inverse of :func:`parse_key_path`: ``("load", "tensions", 0)`` -> ``"load.tensions[0]"``."""
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out


def is_element_path(text: str) -> bool:
    """The path reaches below ``section.key``: a list element or a nested field (``load.tensions[0]``)."""
    return len(parse_key_path(text)) > 2


def _kind(v: Any) -> str:
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return "a number"
    if isinstance(v, str):
        return "a string"
    if v is None:
        return "not set"
    return f"a {type(v).__name__}"


def _step(node: Any, part: str | int, here: str, text: str, create: bool) -> Any:
    """The child ``part`` of ``node`` (``here`` is the path to ``node``); ``None`` for a creatable missing key."""
    if isinstance(part, int):
        if not isinstance(node, (list, tuple)):
            raise KeyPathError(f"{text}: {here} is {_kind(node)}, not a list; [{part}] needs a list")
        if part >= len(node):
            raise KeyPathError(f"{text}: index {part} is out of range ({here} has {len(node)} entries)")
        return node[part]
    if not isinstance(node, Mapping):
        raise KeyPathError(f"{text}: {here} is {_kind(node)}, not a table; .{part} needs a table")
    if part not in node:
        if create:
            return None
        from .messages import suggest

        raise KeyPathError(f"{text}: unknown field {part!r} of {here}{suggest(part, [str(k) for k in node])}"
                           .replace("; known keys:", "; known fields:"))
    return node[part]


def get_value(data: Mapping[str, Any], path: str) -> Any:
    """The value ``path`` names in ``data`` (nested dicts and lists).

    Raises
    ------
    KeyPathError
        Malformed path, unknown field, index on a non-list, index out of range.
    """
    parts = parse_key_path(path)
    node: Any = data
    for k, part in enumerate(parts):
        node = _step(node, part, format_key_path(parts[:k]) or "the data", path, create=False)
    return node


def with_value(data: Mapping[str, Any], path: str | tuple[str | int, ...], value: Any, *, create: bool = False) -> dict:
    """A copy of ``data`` with the value at ``path`` set to ``value``.

    Only the containers along the path are copied (``data`` itself is not changed).  A list
    element must exist (an index never extends a list).  ``create=True`` lets a missing table key
    be added (intermediate tables created), as a study file may leave a key at its default.

    Raises
    ------
    KeyPathError
        As :func:`get_value` (an unknown field only when ``create`` is false).
    """
    text = path if isinstance(path, str) else format_key_path(path)
    parts = parse_key_path(path) if isinstance(path, str) else tuple(path)
    if not isinstance(data, Mapping):
        raise KeyPathError(f"{text}: the data is {_kind(data)}, not a table")

    def put(node: Any, k: int) -> Any:
        part = parts[k]
        here = format_key_path(parts[:k]) or "the data"
        if node is None and create and isinstance(part, str):
            node = {}
        child = _step(node, part, here, text, create)
        new = value if k == len(parts) - 1 else put(child, k + 1)
        if isinstance(part, int):
            out = list(node)
            out[part] = new
            return out
        return {**node, part: new}

    return put(data, 0)
