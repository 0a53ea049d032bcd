"""``key=value`` overrides of a study file from the command line (``workbench run s.toml solver.n_elements=32``).

:func:`apply_overrides` sets each dotted key in the parsed file before validation, so an override
is checked exactly like the file (the same one-line messages); the value is read as a TOML value
(``32``, ``1e-3``, ``true``, ``[1.0, 0.0]``, ``"eyelets"``) and, when it is not one, taken as a
bare string (``solver.tendon_model=eyelets``).  The key is a key path (:mod:`workbench.study.keypath`:
``load.tensions[0]=2.0``, ``solver.by_model.beam3d.tendon_model=eyelets``); a sweep axis
keeps its dots (``sweep.product.robot.length=[0.5, 0.8]`` sets ``[sweep] product["robot.length"]``).
The applied overrides are recorded in the run's manifest record.  Checked by
``tests/study/test_cli_errors.py``.
"""

from __future__ import annotations

import tomllib
from typing import Any, Mapping, Sequence

from .keypath import KeyPathError, parse_key_path, with_value
from .messages import StudyError

__all__ = ["apply_overrides", "parse_override", "unapplied_overrides"]


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
    try:
        parts = parse_key_path(key)
    except KeyPathError as e:
        raise StudyError([f"override {text!r}: {str(e).partition(': ')[2]}"]) from None
    return list(parts), parsed


def apply_overrides(raw: Mapping[str, Any], overrides: Sequence[str]) -> dict[str, Any]:
    """A copy of the parsed study ``raw`` with every override set (tables created as needed).

    A key path may name a list element (``load.tensions[0]=2.0``): the list must be in the file
    (an index never extends a list).
    """
    out = dict(raw)
    problems = []
    for text in overrides:
        try:
            path, value = parse_override(text)
        except StudyError as e:
            problems += e.problems
            continue
        if path[0] == "sweep":  # a sweep axis keeps its dots: sweep.<block>["<axis>"]
            block = out.get("sweep")
            if block is not None and not isinstance(block, dict):
                problems.append(f"override {text!r}: sweep is not a table in the study file")
                continue
            sweep = dict(block or {})
            if len(path) == 3:
                inner = sweep.get(path[1])
                if inner is not None and not isinstance(inner, dict):
                    problems.append(f"override {text!r}: sweep.{path[1]} is not a table in the study file")
                    continue
                sweep[path[1]] = {**(inner or {}), path[2]: value}
            else:
                sweep[path[1]] = value
            out["sweep"] = sweep
            continue
        try:
            out = with_value(out, tuple(path), value, create=True)
        except KeyPathError as e:
            problems.append(f"override {text!r}: {str(e).partition(': ')[2]}")
    if problems:
        raise StudyError(problems)
    return out


def _block_of(sweep: Mapping[str, Any], axis: str) -> str:
    """The ``[sweep]`` block that names ``axis``."""
    for block, body in sweep.items():
        if (isinstance(body, Mapping) and axis in body) or (
                isinstance(body, list) and any(isinstance(e, Mapping) and axis in e for e in body)):
            return str(block)
    return "?"


def unapplied_overrides(overrides: Sequence[str], sweep: Mapping[str, Any], solver: Mapping[str, Any],
                        models: Sequence[str]) -> list[str]:
    """The overrides that would change no case, one line each naming the key and why.

    An override of a value that a ``[sweep]`` axis sets (the axis, or a value containing it) is
    replaced in every case by the axis; an override of a ``[solver]`` option that every model's
    ``[solver.by_model.<model>]`` table sets reaches no model.  Both are errors before anything runs
    (the run would record an override that did nothing).  Checked by ``tests/study/test_overrides.py``.
    """
    from .by_model import setters
    from .expand import sweep_keys

    out = []
    axes = sweep_keys(sweep)
    for text in overrides:
        path, _ = parse_override(text)
        if path[0] == "sweep":
            continue
        parts = tuple(path)
        key = text.partition("=")[0].strip()
        axis = next((a for a in axes if parts[:len(parse_key_path(a))] == parse_key_path(a)), None)
        if axis is not None:
            block = _block_of(sweep, axis)
            out.append(f"override {text!r}: [sweep] {block} sets {axis} in every case, so {key} would not apply; "
                       f"change the sweep (e.g. sweep.{block}...) or drop the override")
            continue
        if parts[0] == "solver" and len(parts) == 2 and models:
            shadow = setters(solver, str(parts[1]), models)
            if len(shadow) == len(models):
                out.append(f"override {text!r}: every model sets {parts[1]} in [solver.by_model] "
                           f"({', '.join(shadow)}), so it would not apply; override "
                           f"solver.by_model.<model>.{parts[1]} instead")
    return out
