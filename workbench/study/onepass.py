"""One validation pass for every problem of a study file: the later checks run on what is valid.

:func:`workbench.study.spec.parse_study` checks a file in stages (schema, robot preset, load
rules, sweep axes, then every case: :mod:`workbench.study.checks`).  A schema error in one key
must not hide the problems of the others, so the later stages run on the valid part:

- a section whose schema fails is validated again without its failing keys
  (:func:`repair_section`): they take their defaults (a robot key already does,
  :func:`~workbench.study.checks.check_named_params`);
- a sweep axis (or block) with a problem is left out of the case checks (:func:`valid_sweep`);
- every key that had a problem is *unset* (:func:`problem_keys`): a later line that involves
  it -- keyed by it, or naming it in its reason -- would be about the default, not the user's
  value, and is dropped (:func:`knock_on`); so are, when a robot key is unset, the case lines
  that depend on the robot as a whole (its build, the tendon / section counts), and, when a key of
  a ``[solver.by_model.<model>]`` table is unset, the lines about that model.

Pure functions of the problem lines.  Checked by ``tests/study/test_spec.py``
(``test_schema_error_does_not_hide_case_checks`` and its neighbours).
"""

from __future__ import annotations

import re
from typing import Any, Iterable, Mapping

from pydantic import BaseModel, ValidationError

from .schema import SAMPLED_BLOCKS

__all__ = ["knock_on", "problem_keys", "repair_section", "valid_sweep"]

_KEY = re.compile(r"[^\s:(]+")
_SWEEP = re.compile(r'^sweep\.(?P<block>\w+)(?:\["(?P<axis>[^"]+)"\])?')
#: Reasons of the case checks that depend on the robot's tendon or section count.
_COUNT_RULE = ("(one per tendon of the robot)", "(one per section)", "the robot has no tendons")


def repair_section(model: type[BaseModel], table: Mapping[str, Any], error: ValidationError) -> BaseModel | None:
    """``table`` validated without the top-level keys ``error`` blames; ``None`` if that is not possible.

    A model-level error (no key) cannot be repaired; nor can a table whose remaining keys fail.
    """
    bad = set()
    for e in error.errors():
        if not e["loc"]:
            return None
        bad.add(e["loc"][0])
    try:
        return model.model_validate({k: v for k, v in table.items() if k not in bad})
    except ValidationError:
        return None


def _key_of(line: str) -> str:
    """The key path a problem line starts with, list indices dropped (``load.tensions[0]`` -> ``load.tensions``)."""
    m = _KEY.match(line)
    key = m.group(0) if m else ""
    return key.split("[", 1)[0]


def problem_keys(problems: Iterable[str]) -> set[str]:
    """The keys (``section.key``, or ``section`` for a whole-table problem) that have a problem.

    ``[study]``, ``[report]`` and ``[sweep]`` keys are left out: no case parameter comes from them
    (a bad sweep axis is left out of the cases instead, :func:`valid_sweep`).
    """
    return {k for k in map(_key_of, problems) if k and k.partition(".")[0] not in ("sweep", "study", "report")}


def _names(line: str, key: str) -> bool:
    """``line`` mentions ``key`` or its name as a word (``mode`` in ``needs mode = "length"``)."""
    name = key.partition(".")[2]
    if not name:
        return False
    return key in line or re.search(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])", line) is not None


def knock_on(line: str, unset: set[str]) -> bool:
    """``line`` (a later stage's problem) involves a key that had a problem of its own (see the module)."""
    key = _key_of(line)
    if key in unset or key.partition(".")[0] in unset:
        return True
    tables = {k.split(".")[2] for k in unset if k.startswith("solver.by_model.") and k.count(".") >= 2}
    if any(f"model '{m}'" in line for m in tables):
        return True  # a model whose [solver.by_model.<model>] table had a problem runs without it in the checks
    reason = line.partition(": ")[2]
    if any(_names(reason, k) for k in unset):
        return True
    if any(k.startswith("robot.") for k in unset):
        return key == "robot" or any(r in line for r in _COUNT_RULE)
    return False


def valid_sweep(sweep: Mapping[str, Any], problems: Iterable[str]) -> dict[str, Any]:
    """``sweep`` without the axes (or blocks, when the problem is the block's own) that have a problem."""
    bad_axes: dict[str, set[str]] = {}
    bad_blocks: set[str] = set()
    for line in problems:
        m = _SWEEP.match(line)
        if not m:
            continue
        block, axis = m["block"], m["axis"]
        if axis is None or block == "cases" or (block == "zip") or (block in SAMPLED_BLOCKS and line.startswith(
                f"sweep.{block}.n")):
            bad_blocks.add(block)  # the block itself (or one of its paired / per-case entries)
        else:
            bad_axes.setdefault(block, set()).add(axis)
    out: dict[str, Any] = {}
    for block, body in sweep.items():
        if block in bad_blocks:
            continue
        if isinstance(body, Mapping):
            kept = {k: v for k, v in body.items() if k not in bad_axes.get(block, set())}
            if block in SAMPLED_BLOCKS and not set(kept) - {"n"}:
                continue
            if kept:
                out[block] = kept
        else:
            out[block] = body
    return out
