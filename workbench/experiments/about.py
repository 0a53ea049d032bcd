"""What a study asks, what it assumes and which paper rows it answers -- as data, for its report.

Each experiment declares a :class:`StudyAbout` (the question, the assumptions: every parameter
the source paper does not give, with the result column that holds the value used and where the
value comes from, and the seed-paper rows it answers) and computes its findings from the result
table.  :func:`about_summary` renders them as one text block: until the report has its own
``Question`` / ``Findings`` / ``Assumptions`` sections, the experiments' first figure carries this
text as its caption; the data are kept separate so that a report section can take them over.
Checked by ``tests/experiments/test_about.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import pandas as pd

__all__ = ["Assumption", "StudyAbout", "assumption_values", "about_summary"]


@dataclass(frozen=True)
class Assumption:
    """One parameter the source paper does not give.

    Attributes
    ----------
    column : str
        Result column holding the value used (e.g. ``"p.robot.joint_stiffness"``), or ``""`` when
        the assumption is a modelling choice without a column.
    what : str
        What it is, with its unit.
    source : str
        Where the value comes from (``"assumed: ..."``, a preset docstring, a measurement).
    """

    column: str
    what: str
    source: str


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


def assumption_values(about: StudyAbout, ok: pd.DataFrame) -> list[str]:
    """One line per assumption: ``what = value (source)``, the value read from the result rows."""
    out = []
    for a in about.assumptions:
        if a.column and a.column in ok.columns:
            out.append(f"{a.what} = {_value_text(ok[a.column])} ({a.source})")
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
