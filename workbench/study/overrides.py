"""``key=value`` overrides of a study file from the command line (``workbench run s.toml solver.n_elements=32``).

:func:`apply_overrides` sets each dotted key in the parsed file before validation, so an override
is checked exactly like the file (the same one-line messages); the value is read as a TOML value
(``32``, ``1e-3``, ``true``, ``[1.0, 0.0]``, ``"eyelets"``) and, when it is not one, taken as a
bare string (``solver.tendon_model=eyelets``).  The first dot separates the section; a sweep axis
keeps its dots (``sweep.product.robot.length=[0.5, 0.8]`` sets ``[sweep] product["robot.length"]``).
The applied overrides are recorded in the run's manifest record.  Checked by
``tests/study/test_cli_errors.py``.
"""

from __future__ import annotations

import tomllib
from typing import Any, Mapping, Sequence

from .messages import StudyError

__all__ = ["apply_overrides", "parse_override"]


def parse_override(text: str) -> tuple[list[str], Any]:
    """``"solver.n_elements=32"`` -> ``(["solver", "n_elements"], 32)``; :class:`StudyError` when malformed."""
    key, sep, value = text.partition("=")
    key = key.strip()
    section, dot, rest = key.partition(".")
    if not sep and text.endswith(".toml"):
        raise StudyError([f"{text}: a second study file? run takes one study (validate takes several); an override "
                          f"is <section>.<key>=<value>, e.g. solver.n_elements=32"])
    if not sep or not dot or not section or not rest:
        raise StudyError([f"override {text!r}: expected <section>.<key>=<value>, e.g. solver.n_elements=32"])
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError):
        parsed = value.strip()
    if section == "sweep":
        block, _, axis = rest.partition(".")
        return (["sweep", block, axis] if axis else ["sweep", block]), parsed
    return [section, rest], parsed


def apply_overrides(raw: Mapping[str, Any], overrides: Sequence[str]) -> dict[str, Any]:
    """A copy of the parsed study ``raw`` with every override set (tables created as needed)."""
    out = {k: (dict(v) if isinstance(v, dict) else v) for k, v in raw.items()}
    problems = []
    for text in overrides:
        try:
            path, value = parse_override(text)
        except StudyError as e:
            problems += e.problems
            continue
        node = out
        for part in path[:-1]:
            child = node.get(part)
            if child is None:
                child = node[part] = {}
            elif isinstance(child, dict):
                child = node[part] = dict(child)
            else:
                problems.append(f"override {text!r}: {'.'.join(path[:-1])} is not a table in the study file")
                break
            node = child
        else:
            node[path[-1]] = value
    if problems:
        raise StudyError(problems)
    return out
