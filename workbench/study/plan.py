"""What a run computes: per case the models not stored yet, or stored as failed and retried.

:func:`plan_units` compares the cases of a study with the rows stored in its folder (one row
per case and model, :meth:`~workbench.study.store.ResultStore.stored_rows`) and returns the
*units* of work -- a case and the models still to compute for it -- and the stored rows to
remove first (so a recomputed model never leaves a second row):

- a model without a row is computed;
- a failed row is recomputed when its ``failure`` kind is one ``--resume`` retries by default
  (:data:`~workbench.study.outcomes.INFRASTRUCTURE`: timeout, memory, killed, lost), or for any
  kind with ``retry_failed`` (``--retry-failed``); other failed rows stay (a model failure is a
  result);
- a (case, model) with more than one row (written by two runs at once before the folder lock
  existed) is recomputed;
- for a kind whose models are computed together (``separable=False``, e.g. series-parallel),
  a case with anything to recompute is recomputed whole.

Pure: no I/O.  Checked by ``tests/study/test_retry.py``.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import Any, Iterable, Sequence

from .outcomes import INFRASTRUCTURE

__all__ = ["Plan", "Unit", "plan_units"]


@dataclass(frozen=True)
class Unit:
    """One unit of work: ``case`` (a :class:`~workbench.study.expand.Case`) and the ``models`` to compute."""

    case: Any
    models: tuple[str, ...]


@dataclass(frozen=True)
class Plan:
    """The units of a run, the stored rows ``(case_id, model)`` to remove first, and what is retried.

    ``retried`` counts the rows recomputed per reason (failure kinds, ``"duplicate"``).
    """

    units: list[Unit]
    remove: set[tuple[str, str]] = field(default_factory=set)
    retried: dict[str, int] = field(default_factory=dict)


def plan_units(cases: Sequence[Any], models: tuple[str, ...], stored: Iterable[Any], *,
               retry_failed: bool = False, separable: bool = True) -> Plan:
    """Plan a run (module docstring); ``stored`` are :class:`~workbench.study.store.StoredRow`-like."""
    rows: dict[tuple[str, str], list[Any]] = {}
    for r in stored:
        rows.setdefault((r.case_id, r.model), []).append(r)
    units, remove, retried = [], set(), Counter()
    for case in cases:
        need = []
        for m in models:
            have = rows.get((case.case_id, m))
            if not have:
                need.append(m)
                continue
            if len(have) > 1:
                reason = "duplicate"
            elif have[0].status != "ok" and (retry_failed or have[0].failure in INFRASTRUCTURE):
                reason = have[0].failure or "failed"
            else:
                continue
            need.append(m)
            remove.add((case.case_id, m))
            retried[reason] += len(have)
        if need and not separable and len(need) < len(models):
            need = list(models)
            remove.update((case.case_id, m) for m in models if (case.case_id, m) in rows)
        if need:
            units.append(Unit(case, tuple(need)))
    return Plan(units, remove, dict(retried))
