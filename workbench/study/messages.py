"""Problem messages of study files: one line per problem, ``<key path>: <reason>``.

Shared by the validation of every study kind (:mod:`workbench.study.spec` and the series-parallel
kind's ``workbench/experiments/series_parallel/spec.py``): the :class:`StudyError` they raise,
the "did you mean" suggestion, the translation of pydantic errors into one line each, the
typing of preset and scenario parameters by their defaults (:func:`check_robot_value`) and
the one TOML reader (:func:`read_toml`; each caller keeps its own wording).  Units come from the
one unit table (:func:`workbench.units.unit_of`); imports nothing else from the workbench, so
validation never pulls in execution code.

Checked by ``tests/study/test_spec.py`` (the messages of ``tests/study/bad_configs``),
``tests/motion/test_motion_spec.py`` and ``tests/study/test_messages.py``.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from ..units import unit_of

__all__ = [
    "StudyError", "param_unit", "suggest", "fmt_loc", "num", "translate", "known_keys", "pydantic_problems",
    "check_robot_value", "collapse_indexed", "join_key", "read_toml", "MAX_COUNT", "MAX_DEPTH",
]


class StudyError(ValueError):
    """A study file is invalid; ``problems`` holds one line per problem."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        super().__init__("\n".join(self.problems))


def param_unit(name: str) -> str | None:
    """The unit of ``[load]`` / ``[solver]`` key ``name`` (bare, as in a message's key path), else ``None``."""
    return unit_of(f"load.{name}") or unit_of(f"solver.{name}")


def suggest(key: str, known: list[str]) -> str:
    """``"; did you mean 'k'?"`` for the closest known key, else ``"; known keys: ..."`` (or ``""``)."""
    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    if close:
        return f"; did you mean {close[0]!r}?"
    return f"; known keys: {', '.join(sorted(known))}" if known else ""


def fmt_loc(loc: tuple) -> str:
    """A location as a key path: ``("sweep", "product", "robot.length", 1)`` -> ``sweep.product["robot.length"][1]``."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif "." in str(part):
            out += f'["{part}"]'
        else:
            out += ("." if out else "") + str(part)
    return out


def num(v: Any) -> str:
    """A value for a message (floats as ``%g``)."""
    return repr(v) if not isinstance(v, float) else f"{v:g}"


def translate(err: dict, prefix: tuple, model: type[BaseModel] | None) -> str:
    """One pydantic error -> 'key.path: reason'."""
    loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and p in ("float", "list[float]", "list", "int", "str", "none")))
    # pydantic adds union member tags to loc ("float", "list[float]"); stripped above
    full = prefix + loc
    typ, inp = err["type"], err.get("input")
    key = str(loc[-1]) if loc else ""
    unit = param_unit(key) or next((u for u in map(param_unit, map(str, reversed(loc))) if u), None)
    u = f" [{unit}]" if unit else ""
    if typ == "extra_forbidden":
        known = known_keys(model, loc[:-1])
        return f"{fmt_loc(full)}: unknown key{suggest(key, known)}"
    if typ == "missing":
        if len(full) == 1:
            return f"{fmt_loc(full)}: missing section [{full[0]}]"
        return f"{fmt_loc(full)}: missing required key"
    if typ == "finite_number":
        return f"{fmt_loc(full)}: must be finite{u}, got {inp}"
    if typ in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        ctx = err.get("ctx", {})
        op, bound = {"greater_than": (">", "gt"), "greater_than_equal": (">=", "ge"),
                     "less_than": ("<", "lt"), "less_than_equal": ("<=", "le")}[typ]
        return f"{fmt_loc(full)}: must be {op} {ctx.get(bound)}{u}, got {num(inp)}"
    if typ == "literal_error":
        return f"{fmt_loc(full)}: must be {err['ctx']['expected']}, got {inp!r}"
    if typ in ("too_short", "too_long"):
        return f"{fmt_loc(full)}: {err['msg'].lower()}"
    if typ == "string_pattern_mismatch":
        return f"{fmt_loc(full)}: must match {err['ctx']['pattern']} (letters, digits, '_' and '-'), got {inp!r}"
    if typ == "value_error" and "error" in err.get("ctx", {}):  # a validator's own message
        return f"{fmt_loc(full)}: {err['ctx']['error']}"
    return f"{fmt_loc(full)}: {err['msg'][0].lower() + err['msg'][1:]}, got {type(inp).__name__} {inp!r}"


def known_keys(model: type[BaseModel] | None, loc: tuple) -> list[str]:
    """Field names of the (nested) pydantic model at ``loc`` (``[]`` when not a model)."""
    m = model
    for part in loc:
        if m is None or isinstance(part, int):
            return []
        f = m.model_fields.get(str(part))
        if f is None:
            return []
        ann = f.annotation
        m = ann if isinstance(ann, type) and issubclass(ann, BaseModel) else None
    return list(m.model_fields) if m is not None else []


def pydantic_problems(exc: ValidationError, prefix: tuple, model: type[BaseModel]) -> list[str]:
    """The errors of ``exc`` as one line each (``prefix`` is the section's location)."""
    seen: dict[tuple, str] = {}
    for e in exc.errors():
        # a value failing every member of a union produces one error per member: keep one,
        # preferring the scalar member's (more specific) message
        loc = tuple(p for p in e["loc"] if not (isinstance(p, str) and p in ("float", "list[float]", "list", "int", "str", "none")))
        if loc in seen and e["type"].endswith("_type"):
            continue
        seen[loc] = translate(e, prefix, model)
    return list(seen.values())


# ---------------------------------------------------------------------------------------
# parameters typed by their defaults (presets, scenarios), physical sanity by name
# ---------------------------------------------------------------------------------------
_POSITIVE_PAT = re.compile(r"(length|diameter|modulus|stiffness|offset|radius|thickness|^n_|_count$|per_section$|^k_|_per_disk$)")
_NONNEG_PAT = re.compile(r"(density|mass|gravity|spacing|friction)")
#: a preset or scenario parameter the unit table does not list takes the unit of the first
#: quantity its name contains: word -> a key of that quantity in :data:`workbench.units.UNITS`
_QUANTITY_OF_WORD = {"length": "robot.length", "diameter": "robot.diameter", "offset": "robot.tendon_offset",
                     "modulus": "robot.youngs_modulus", "stiffness": "robot.tendon_stiffness",
                     "density": "robot.density", "mass": "robot.payload_mass", "gravity": "robot.gravity",
                     "angle": "load.bend_angle", "radius": "robot.length"}


def _robot_unit(key: str, section: str = "robot") -> str:
    """``" [unit]"`` of parameter ``key`` of ``section`` (``robot`` or ``scenario``), else ``""``."""
    if key.endswith("_direction"):  # a direction vector (e.g. gravity_direction): signed, no unit
        return ""
    unit = unit_of(f"{section}.{key}")
    if unit is None:
        unit = next((unit_of(q) for w, q in _QUANTITY_OF_WORD.items() if w in key), None)
    return f" [{unit}]" if unit else ""


#: Upper bound of integer preset / scenario parameters (counts of sections, disks, tendons,
#: samples): beyond it building the robot alone would exhaust time or memory.
MAX_COUNT = 10_000


def _check_list(key: str, value: Any, default: tuple | list, section: str = "robot") -> tuple[Any, str | None]:
    """A list override of a list-valued default: numbers (or what the default holds), finite, sane by name."""
    u = _robot_unit(key, section)
    if not isinstance(value, list):
        return value, f"must be a list (like the default {list(default)!r}), got {type(value).__name__} {value!r}"
    if not value:
        return value, "must not be an empty list"
    numeric = all(isinstance(d, (int, float)) and not isinstance(d, bool) for d in default)
    if not numeric:
        return value, None
    out = []
    for i, v in enumerate(value):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            return value, f"[{i}] must be a number{u}, got {type(v).__name__} {v!r}"
        v = float(v)
        if not math.isfinite(v):
            return value, f"[{i}] must be finite{u}, got {v}"
        signed = key.endswith("_direction")  # a direction vector's components have either sign
        if not signed and _POSITIVE_PAT.search(key) and v <= 0:
            return value, f"[{i}] must be > 0{u}, got {num(v)}"
        if not signed and _NONNEG_PAT.search(key) and v < 0:
            return value, f"[{i}] must be >= 0{u}, got {num(v)}"
        out.append(v)
    return out, None


_INDEXED = re.compile(r"^(?P<head>.*?)\[(?P<i>\d+)\](?P<tail>[^:]*): (?P<reason>.*)$")


def collapse_indexed(problems: list[str]) -> list[str]:
    """Lines that differ only in one list index merged: ``a[0]: r``, ``a[1]: r`` -> ``a[0, 1]: r``.

    One mistake repeated over a list (``models = ["x", "x"]``) is then one line.  Order kept.
    """
    groups: dict[tuple[str, str, str], list[str]] = {}
    order: list[Any] = []
    for line in problems:
        m = _INDEXED.match(line)
        if not m:
            order.append(line)
            continue
        key = (m["head"], m["tail"], m["reason"])
        if key not in groups:
            groups[key] = []
            order.append(key)
        groups[key].append(m["i"])
    out = []
    for item in order:
        if isinstance(item, str):
            out.append(item)
        else:
            head, tail, reason = item
            out.append(f"{head}[{', '.join(groups[item])}]{tail}: {reason}")
    return out


def join_key(key: str, problem: str) -> str:
    """``"<key>: <problem>"``, with an element index that starts ``problem`` moved into the key.

    ``join_key("robot.d", "[1] must be finite")`` -> ``"robot.d[1]: must be finite"``.
    """
    if problem.startswith("[") and "] " in problem:
        idx, _, rest = problem.partition("] ")
        return f"{key}{idx}]: {rest}"
    return f"{key}: {problem}"


def check_robot_value(key: str, value: Any, default: Any, section: str = "robot") -> tuple[Any, str | None]:
    """Check one robot (or, ``section="scenario"``, scenario) override against the default's type and sanity.

    Integers are bounded by :data:`MAX_COUNT`; list defaults take lists whose entries are
    checked like scalars (``"[i] must be finite"``: the caller prefixes the key).  The unit in a
    message is the unit table's for ``<section>.<key>``, else the quantity the name says.
    Returns ``(coerced_value, problem_or_None)``.
    """
    u = _robot_unit(key, section)
    if isinstance(default, (list, tuple)):
        return _check_list(key, value, default, section)
    if isinstance(default, bool):
        if not isinstance(value, bool):
            return value, f"must be a boolean (true/false), got {type(value).__name__} {value!r}"
        return value, None
    if isinstance(default, int) and not isinstance(default, bool):
        if isinstance(value, bool) or not isinstance(value, int):
            return value, f"must be an integer, got {type(value).__name__} {value!r}"
        if _POSITIVE_PAT.search(key) and value < 1:
            return value, f"must be >= 1, got {value}"
        if value < 0:
            return value, f"must be >= 0, got {value}"
        if value > MAX_COUNT:
            return value, f"must be <= {MAX_COUNT} (a sanity bound), got {value}"
        return value, None
    if isinstance(default, float) or default is None:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            if default is None and isinstance(value, str):
                return value, None
            if default is None and isinstance(value, list):
                return _check_list(key, value, [0.0] if all(
                    isinstance(x, (int, float)) and not isinstance(x, bool) for x in value) else [""], section)
            return value, f"must be a number{u}, got {type(value).__name__} {value!r}"
        v = float(value)
        if not math.isfinite(v):
            return v, f"must be finite{u}, got {v}"
        if _POSITIVE_PAT.search(key) and v <= 0:
            return v, f"must be > 0{u}, got {num(v)}"
        if _NONNEG_PAT.search(key) and v < 0:
            return v, f"must be >= 0{u}, got {num(v)}"
        return v, None
    if isinstance(default, str):
        if not isinstance(value, str):
            return value, f"must be a string, got {type(value).__name__} {value!r}"
        return value, None
    return value, None


#: Deepest nesting of arrays / tables a study file may have (the formats need 4).
MAX_DEPTH = 16


def _too_deep(obj: Any, loc: str = "", depth: int = 0) -> str | None:
    """The key path of the first value nested deeper than :data:`MAX_DEPTH`, else ``None``."""
    if depth > MAX_DEPTH:
        return loc or "<top>"
    if isinstance(obj, dict):
        for k, v in obj.items():
            found = _too_deep(v, f"{loc}.{k}" if loc else str(k), depth + 1)
            if found:
                return found
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            found = _too_deep(v, f"{loc}[{i}]", depth + 1)
            if found:
                return found
    return None


def read_toml(path: str | Path, *, cannot_read: str = "cannot read file",
              syntax_error: str = "TOML syntax error") -> dict[str, Any]:
    """The TOML file ``path`` as a mapping; one-line :class:`StudyError` when it cannot be read.

    Parameters
    ----------
    path : path-like
    cannot_read, syntax_error : str
        Wording of the two failures (``"<path>: <wording>: <reason>"``).  Each study kind keeps
        the wording it had: sweep studies the defaults, series-parallel studies ``"cannot read"``
        and ``"invalid TOML"``.

    Raises
    ------
    StudyError
        The file cannot be read (``OSError``, a folder), is not UTF-8, is not valid TOML or
        is nested deeper than :data:`MAX_DEPTH`.
    """
    p = Path(path)
    if p.is_dir():
        raise StudyError([f"{p}: {cannot_read}: is a folder, not a TOML file"])
    try:
        data = p.read_bytes()
    except OSError as e:
        raise StudyError([f"{p}: {cannot_read}: {e.strerror or e}"]) from None
    except ValueError as e:  # e.g. a NUL byte in the path
        raise StudyError([f"{p!r}: {cannot_read}: {e}"]) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data[:e.start].count(b"\n") + 1
        raise StudyError([f"{p}: {cannot_read}: not UTF-8 text (byte 0x{data[e.start]:02x} on line {line}); "
                          f"TOML files must be UTF-8"]) from None
    try:
        out = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise StudyError([f"{p}: {syntax_error}: {e}"]) from None
    except RecursionError:
        raise StudyError([f"{p}: {syntax_error}: arrays or tables nested too deeply"]) from None
    deep = _too_deep(out)
    if deep:
        raise StudyError([f"{p}: {deep}: nested more than {MAX_DEPTH} levels deep"])
    return out
