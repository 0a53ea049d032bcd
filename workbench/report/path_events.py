"""The Findings sentence on load-path events: cases whose static solve could not follow the load path.

A static solve follows the load from the unloaded state (:func:`workbench.physics._stepping.load_ramp`);
a jump that could not be refined (a limit point or snap) or a change of the tangent stiffness's sign
is stored in the row (``path_event``, ``path_event_fraction``; the row stays ``ok``).  Such an answer
may lie on another equilibrium branch than the one loaded from the start, so the report names those
cases with the load fraction where the event happened.  Called by :func:`.findings.findings_list`;
checked by ``tests/report/test_path_events.py``.
"""

from __future__ import annotations

from .load import ResultSet
from .style import case_title, fmt, model_label

__all__ = ["path_event_findings"]

_LISTED = 5  # cases named per model; the rest are counted


def path_event_findings(study: ResultSet) -> list[str]:
    """One sentence per model with load-path events in its successful rows (none: an empty list)."""
    ok = study.ok
    if ok.empty or "path_event" not in ok:
        return []
    flagged = ok[ok["path_event"].fillna("").astype(str) != ""]
    out = []
    for m in study.models:
        rows = flagged[flagged["model"] == m]
        if rows.empty:
            continue
        n_all = int((ok["model"] == m).sum())
        named = [f"{r['path_event']} at load fraction {fmt(float(r['path_event_fraction']))} "
                 f"({case_title(r.to_dict(), study.axes, study.labels)})" for _, r in rows.head(_LISTED).iterrows()]
        more = f" and {len(rows) - _LISTED} more" if len(rows) > _LISTED else ""
        out.append(f"{model_label(m)}: the load path had an event in {len(rows)} of {n_all} cases: "
                   f"{'; '.join(named)}{more}. These answers may lie on another equilibrium branch than "
                   f"the one loaded from the unloaded state (columns path_event, path_event_fraction).")
    return out

