"""What a study asks, what it assumes and which paper rows it answers -- as data, for its figure caption.

Each experiment declares a :class:`StudyAbout`: the question, the assumptions (every parameter
the source paper does not give and every modelling choice, as :class:`workbench.assumptions.Assumption`
with the dotted key whose result column ``p.<key>`` holds the value used, or the value as text,
and where it comes from) and the seed-paper rows it answers.  :func:`about_summary` renders them
with the findings computed from the result table as one text block, the caption of the
experiment's first figure.  The report's own Question, Findings and Assumptions sections come
from the study file and the ``ASSUMED`` tuples of the preset, scenario and study kind
(:mod:`workbench.report.findings`); a caption names what the study adds to them.  An assumption
the preset already declares is referenced (:func:`from_preset`), not stated again.
Checked by ``tests/experiments/test_about.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import pandas as pd

from ..assumptions import Assumption
from ..robot.presets import preset_sources

__all__ = ["StudyAbout", "assumption_values", "about_summary", "from_preset"]


@dataclass(frozen=True)
class StudyAbout:
    """Question, assumptions and answered seed-paper rows of one study."""

    question: str
    assumptions: tuple[Assumption, ...]
    paper_rows: tuple[str, ...] = ()


def _value_text(values: pd.Series) -> str:
    vals = list(dict.fromkeys(str(v) for v in values.dropna()))
    if not vals:
        return "n/a"
    return vals[0] if len(vals) == 1 else f"swept: {', '.join(vals[:6])}{' ...' if len(vals) > 6 else ''}"


def from_preset(preset: str, key: str, what: str, note: str = "") -> Assumption:
    """The preset's assumption for its parameter ``key``, referenced: ``assumed, preset <preset>[, note]``.

    The value is read from the rows (``p.robot.<key>``); the preset's ``ASSUMED`` entry (shown in the
    report's Assumptions table) says where it comes from.

    Raises
    ------
    KeyError
        The preset declares no assumption ``key`` (a reference that would go stale).
    """
    if key not in preset_sources(preset)["assumed"]:
        raise KeyError(f"preset {preset!r} declares no assumption {key!r}")
    return Assumption(f"robot.{key}", f"assumed, preset {preset}" + (f", {note}" if note else ""), what=what)


def assumption_values(about: StudyAbout, ok: pd.DataFrame) -> list[str]:
    """One line per assumption: ``what = value (source)`` with the value read from the column ``p.<key>``,
    ``what: value (source)`` for a value given as text, else ``what (source)``."""
    out = []
    for a in about.assumptions:
        col = f"p.{a.key}"
        if a.key and col in ok.columns:
            out.append(f"{a.what} = {_value_text(ok[col])} ({a.source})")
        elif a.value:
            out.append(f"{a.what}: {a.value} ({a.source})" if a.source else f"{a.what}: {a.value}")
        else:
            out.append(f"{a.what} ({a.source})")
    return out


def about_summary(about: StudyAbout, ok: pd.DataFrame, findings: Sequence[str]) -> str:
    """``Question: ... Findings: ... Assumptions: ... Answers: ...`` as one caption text."""
    q = about.question.rstrip()
    parts = [f"Question: {q}{'' if q.endswith(('?', '.')) else '.'}",
             "Findings: " + ("; ".join(findings) if findings else "no successful case to report") + ".",
             "Assumptions: " + "; ".join(assumption_values(about, ok)) + "."]
    if about.paper_rows:
        parts.append("Answers (seed papers): " + "; ".join(about.paper_rows) + ".")
    return " ".join(parts)
