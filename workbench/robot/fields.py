"""Checked reads of one key of a plain-data robot description, each problem one line with its key path.

The building blocks of :mod:`workbench.robot.spec`: a :class:`Reader` walks a nested mapping
(TOML data: dicts, lists, numbers, strings) and records ``"<key path>: <reason>"`` for every bad
value instead of raising, so a description reports all its problems in one pass.  Key paths use
the workbench's one syntax, dotted keys with ``[i]`` list indices
(``robot.sections[1].tendons[0].angles``).  Checked by ``tests/robot/test_spec_malformed.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from ..study.messages import suggest

__all__ = ["Reader", "is_number"]


def is_number(v: Any) -> bool:
    """``True`` for an int or float that is not a bool."""
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _g(v: float) -> str:
    return f"{v:g}"


@dataclass
class Reader:
    """Collects the problems of one description while its values are read.

    Attributes
    ----------
    problems : list of str
        One line per problem, ``"<key path>: <reason>"``, in reading order.
    """

    problems: list[str] = field(default_factory=list)

    def add(self, path: str, reason: str) -> None:
        """Record one problem at ``path``."""
        self.problems.append(f"{path}: {reason}")

    def table(self, value: Any, path: str, known: tuple[str, ...], required: tuple[str, ...] = ()) -> dict | None:
        """``value`` as a table whose keys are all ``known`` (unknown keys get a "did you mean").

        Returns ``None`` (with a problem) when ``value`` is not a table; a table with unknown
        keys is returned without them.
        """
        if not isinstance(value, Mapping):
            self.add(path, f"must be a table, got {type(value).__name__} {value!r}")
            return None
        out = {}
        for k, v in value.items():
            if k not in known:
                self.add(f"{path}.{k}", f"unknown key{suggest(str(k), list(known))}")
            else:
                out[k] = v
        for k in required:
            if k not in value:
                self.add(f"{path}.{k}", "missing required key")
        return out

    def number(self, table: Mapping[str, Any], key: str, path: str, unit: str, *, bound: str = ">0",
               upper: float | None = None) -> float | None:
        """The number ``table[key]`` (``None`` when absent or bad): finite, ``bound`` ``">0"``/``">=0"``/``"any"``.

        ``upper``: an exclusive upper bound (e.g. a Poisson ratio below 0.5).
        """
        if key not in table:
            return None
        v, where, u = table[key], f"{path}.{key}", f" [{unit}]" if unit else ""
        if not is_number(v):
            self.add(where, f"must be a number{u}, got {type(v).__name__} {v!r}")
            return None
        v = float(v)
        if not math.isfinite(v):
            self.add(where, f"must be finite{u}, got {v}")
        elif bound == ">0" and v <= 0:
            self.add(where, f"must be > 0{u}, got {_g(v)}")
        elif bound == ">=0" and v < 0:
            self.add(where, f"must be >= 0{u}, got {_g(v)}")
        elif upper is not None and v >= upper:
            self.add(where, f"must be < {_g(upper)}{u}, got {_g(v)}")
        else:
            return v
        return None

    def integer(self, table: Mapping[str, Any], key: str, path: str, *, low: int = 1) -> int | None:
        """The integer ``table[key]`` >= ``low`` (``None`` when absent or bad)."""
        if key not in table:
            return None
        v = table[key]
        if isinstance(v, bool) or not isinstance(v, int):
            self.add(f"{path}.{key}", f"must be an integer, got {type(v).__name__} {v!r}")
            return None
        if v < low or v > 100_000:
            self.add(f"{path}.{key}", f"must be an integer in [{low}, 100000], got {v}")
            return None
        return v

    def numbers(self, table: Mapping[str, Any], key: str, path: str, unit: str, *, n: int | None = None,
                bound: str = "any") -> tuple[float, ...] | None:
        """The list of numbers ``table[key]`` (exactly ``n`` entries when given; at least one)."""
        if key not in table:
            return None
        v, where, u = table[key], f"{path}.{key}", f" [{unit}]" if unit else ""
        if not isinstance(v, (list, tuple)):
            self.add(where, f"must be a list of numbers{u}, got {type(v).__name__} {v!r}")
            return None
        if n is not None and len(v) != n:
            self.add(where, f"expected {n} numbers{u}, got {len(v)}")
            return None
        if not v:
            self.add(where, "must hold at least one number")
            return None
        out = []
        for i, x in enumerate(v):
            reason = self._element_problem(x, unit, bound)
            if reason:
                self.add(f"{where}[{i}]", reason)
            else:
                out.append(float(x))
        return tuple(out) if len(out) == len(v) else None

    @staticmethod
    def _element_problem(x: Any, unit: str, bound: str) -> str | None:
        u = f" [{unit}]" if unit else ""
        if not is_number(x):
            return f"must be a number{u}, got {type(x).__name__} {x!r}"
        if not math.isfinite(float(x)):
            return f"must be finite{u}, got {float(x)}"
        if (bound == ">0" and x <= 0) or (bound == ">=0" and x < 0):
            return f"must be {'> 0' if bound == '>0' else '>= 0'}{u}, got {_g(float(x))}"
        return None

    def string(self, table: Mapping[str, Any], key: str, path: str, choices: tuple[str, ...] = ()) -> str | None:
        """The string ``table[key]``, one of ``choices`` when given (``None`` when absent or bad)."""
        if key not in table:
            return None
        v = table[key]
        if not isinstance(v, str):
            self.add(f"{path}.{key}", f"must be a string, got {type(v).__name__} {v!r}")
            return None
        if choices and v not in choices:
            self.add(f"{path}.{key}", f"unknown value {v!r}; expected one of {', '.join(choices)}")
            return None
        return v
