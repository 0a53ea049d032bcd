"""Problem messages of study files: one line per problem, ``<key path>: <reason>``.

Shared by the validation of every study kind (:mod:`workbench.study.spec` and the series-parallel
kind's ``workbench/experiments/series_parallel/spec.py``): the :class:`StudyError` they raise,
the "did you mean" suggestion, the translation of pydantic errors into one line each, the
typing of preset and scenario parameters by their defaults (:func:`check_robot_value`) and
the one TOML reader (:func:`read_toml`; each caller keeps its own wording).  Imports nothing
from the workbench, so validation never pulls in execution code.

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

__all__ = [
    "StudyError", "UNITS", "suggest", "fmt_loc", "num", "translate", "known_keys", "pydantic_problems",
    "check_robot_value", "read_toml",
]


class StudyError(ValueError):
    """A study file is invalid; ``problems`` holds one line per problem."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        super().__init__("\n".join(self.problems))


#: Units per ``[load]`` / ``[solver]`` key, for messages.
UNITS = {
    "bend_angle": "rad", "bend_plane": "rad", "tensions": "N", "length_changes": "m",
    "pretension": "N", "tip_force": "N", "tip_torque": "N m", "duration": "s", "ramp_time": "s",
    "start_delays": "s", "ramp_durations": "s", "time_step": "s",
}


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
    unit = UNITS.get(key) or next((UNITS[str(p)] for p in reversed(loc) if str(p) in UNITS), None)
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
_ROBOT_UNITS = {"length": "m", "diameter": "m", "offset": "m", "modulus": "Pa", "stiffness": "N",
                "density": "kg/m^3", "mass": "kg", "gravity": "m/s^2", "angle": "rad", "radius": "m"}


def _robot_unit(key: str) -> str:
    for k, u in _ROBOT_UNITS.items():
        if k in key:
            return f" [{u}]"
    return ""


def check_robot_value(key: str, value: Any, default: Any) -> tuple[Any, str | None]:
    """Check one robot override against the preset default's type and physical sanity.

    Returns ``(coerced_value, problem_or_None)``.
    """
    u = _robot_unit(key)
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
        return value, None
    if isinstance(default, float) or default is None:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            if default is None and isinstance(value, (str, list)):
                return value, None
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
        The file cannot be read (``OSError``) or is not valid TOML.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as e:
        raise StudyError([f"{p}: {cannot_read}: {e.strerror or e}"]) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise StudyError([f"{p}: {syntax_error}: {e}"]) from None
