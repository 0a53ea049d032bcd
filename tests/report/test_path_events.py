"""The Findings sentence on load-path events (workbench.report.path_events): flagged ok rows are
named with their event and load fraction; rows without events, failed rows and tables without the
column say nothing."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from workbench.report.load import ResultSet
from workbench.report.path_events import path_event_findings


def _study(rows) -> ResultSet:
    df = pd.DataFrame(rows)
    return ResultSet(name="s", path=Path("."), results=df, manifest={}, axes=("p.load.bend_angle",),
                     baseline="cc", models=tuple(dict.fromkeys(df["model"])))


def _row(case, model, event="", fraction=float("nan"), status="ok"):
    return {"case_id": case, "model": model, "status": status, "p.load.bend_angle": 0.5 * int(case[-1]),
            "path_event": event, "path_event_fraction": fraction}


def test_flagged_cases_are_named_with_their_load_fraction():
    s = _study([_row("c1", "cosserat"), _row("c2", "cosserat", "jump", 0.8515625), _row("c1", "beam3d"),
                _row("c2", "beam3d"), _row("c3", "cosserat", "bifurcation", 0.25, status="failed")])
    out = path_event_findings(s)
    assert len(out) == 1 and "1 of 2 cases" in out[0]
    assert "jump at load fraction 0.852" in out[0] and "another equilibrium branch" in out[0]
    assert "bifurcation" not in out[0]  # the failed row is reported as failed, not here


def test_no_event_no_sentence():
    assert path_event_findings(_study([_row("c1", "cosserat"), _row("c2", "beam3d")])) == []
    old = _study([{"case_id": "c1", "model": "cosserat", "status": "ok"}])  # a table from before the column
    assert path_event_findings(old) == []
