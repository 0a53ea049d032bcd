"""The report's opening sections: Question, Findings, Assumptions, Sensitivity.

:func:`opening_sections` returns their HTML, built from data only; the page shows them first
(:data:`.page.SECTIONS`, headings exactly ``Question``, ``Findings``, ``Assumptions``, ``Sensitivity``):

* Question: ``[report] question`` (else the study description);
* Findings: every comparison's headline with its discretisation error bar
  (:mod:`.headline`; dynamics: the peak over time and the final value), marked **not converged**
  where the error bar exceeds 10 % of the error (:mod:`workbench.compare.convergence`); stresses
  against the declared strengths (inadmissible hardware is said to make the result an elastic
  idealisation); load-path events (:mod:`.path_events`); the study's own sentences (``registry.table("figures")[...].findings``); failed runs;
* Assumptions: :func:`.assumptions.assumption_rows`;
* Sensitivity: per ``[report] sensitivity`` key the headline against the assumed value with
  error bars (:mod:`.errorbars`), and whether it moves by more than its error bar.

The page builder passes ``render(ReportFigure) -> html`` (the sensitivity figures).  Checked by ``tests/report/test_findings.py``.
"""

from __future__ import annotations

import html
from typing import Callable, Mapping

import numpy as np
import pandas as pd

from .. import registry
from ..compare.convergence import CC_MODELS
from .assumptions import assumption_rows
from .context import PageContext, Section
from .errorbars import sensitivity_figures
from .headline import Headline, baseline_cases, headlines, sensitivity_keys
from .path_events import path_event_findings
from .load import ResultSet, numeric
from .measurements import calibration_findings, is_calibration
from .style import ReportFigure, case_title, fmt, model_label, pair_label

__all__ = ["opening_sections", "findings_list", "stress_findings", "question_section", "findings_section",
           "assumptions_section", "sensitivity_section"]


def _esc(text) -> str:
    return html.escape(str(text)).replace("://", ":&#8203;//")


def _pm(h: Headline) -> str:
    if not np.isfinite(h.disc_pct):
        bar = "no error estimate"
    elif h.exempt_only:
        bar = "(exempt from the error estimate: the model's discretisation is the robot's own structure)"
    else:
        bar = f"± {fmt(h.disc_pct)} % L" + (" (one side exempt)" if h.disc_exempt else "") + _tolerance_note(h)
    return f"{fmt(h.error_pct)} % L ({fmt(1e3 * h.error)} mm) {bar}"


def _tolerance_note(h: Headline) -> str:
    """Which side's bar is a solver-tolerance estimate (``registry.table("models")[m].accuracy == "tolerance"``:
    a tighter re-solve, :func:`workbench.study.estimate.tolerance_estimate`), not a mesh estimate."""
    models = registry.table("models")
    sides = [m for m in (h.baseline, h.model)
             if m in models and models[m].accuracy == "tolerance"]
    return f" ({', '.join(model_label(m) for m in sides)}: solver-tolerance estimate)" if sides else ""


def _case_text(study: ResultSet, case_id: str, model: str | None = None) -> str:
    """The case's title from ``model``'s row where it has one (its ``p.solver.n_elements`` is the
    resolution that model ran at, ``[solver.by_model.<model>]``), else from the case's first row."""
    rows = study.ok[study.ok["case_id"] == case_id]
    if model is not None and "model" in rows and (rows["model"] == model).any():
        rows = rows[rows["model"] == model]
    return case_title(rows.iloc[0].to_dict(), study.axes, study.labels) if len(rows) else case_id[:8]


def _headline_sentence(study: ResultSet, h: Headline) -> str:
    what = "peak tip error over time" if h.dynamic else "largest tip error"
    physics = h.baseline if h.model in CC_MODELS else h.model  # its row records its own resolution
    s = f"{pair_label(h.baseline, h.model)}: {what} {_pm(h)} ({_case_text(study, h.case_id, physics)})"
    if h.dynamic and np.isfinite(h.final_pct):
        s += f"; at the end of that case {fmt(h.final_pct)} % L"
    if not h.cc_pair and "target" in (h.baseline, h.model):
        return s + " (against the commanded target: the error bar is the model's own estimate, the target has none)."
    if not h.cc_pair:
        return s + " (neither side is the CC model: the error bar is the sum of both sides' estimates)."
    if not h.converged:
        return s + ". NOT CONVERGED: the discretisation error bar exceeds 10 % of the error."
    if h.n_not_converged:
        nc = f"; {h.n_not_converged} of {h.n_cases} cases are not converged"
    elif h.exempt_only:
        nc = f"; {h.n_cases} cases compared"  # no bar to judge: "converged" would claim a check that did not run
    else:
        nc = f"; all {h.n_cases} cases converged (error bar at most 10 % of their error)"
    return s + nc + "."


def stress_findings(study: ResultSet) -> list[str]:
    """Largest stresses per physics model over the baseline cases, against the declared strengths."""
    ok = baseline_cases(study, study.ok)
    out = []
    for m in study.models:
        rows = ok[(ok["model"] == m)]
        if m in ("cc", "cc_fit", "target") or rows.empty:
            continue
        parts = []
        for col, what in (("x.max_stress_backbone", "backbone"), ("x.max_stress_tendon", "tendon")):
            if col in rows and np.isfinite(numeric(rows[col])).any():
                parts.append(f"{what} {fmt(1e-6 * np.nanmax(numeric(rows[col])))} MPa")
        if not parts:
            continue
        text = f"{model_label(m)}: largest stresses {', '.join(parts)}"
        if "x.stress_ratio" in rows and np.isfinite(numeric(rows["x.stress_ratio"])).any():
            r = numeric(rows["x.stress_ratio"])
            worst = rows.iloc[int(np.nanargmax(r))]
            bad = int(np.sum(r > 1.0))
            text += f"; stress / strength up to {fmt(np.nanmax(r))} ({_case_text(study, worst['case_id'], m)})"
            if bad:
                text += (f". INADMISSIBLE hardware in {bad} of {int(np.isfinite(r).sum())} cases: the assumed "
                         f"backbone or tendons would yield or break there, so these results are an elastic "
                         f"idealisation.")
            else:
                text += ": every case is admissible."
        else:
            text += " (no strength declared: not judged)."
        out.append(text)
    return out


def findings_list(study: ResultSet, cmp: pd.DataFrame) -> list[str]:
    """The Findings sentences (see the module docstring)."""
    if is_calibration(study):  # rows per model and fold: the verdict on the held-out measurements
        items = calibration_findings(study)
    else:
        items = [_headline_sentence(study, h) for h in headlines(study, cmp)]
    if not items:
        items.append("Nothing to compare (one model, or no case with two successful models).")
    items += stress_findings(study)
    items += path_event_findings(study)  # static solves whose load path jumped (may be on another branch)
    for name, fs in registry.table("figures").items():
        if fs.findings and registry.resolve(fs.matches)(study):
            items += list(registry.resolve(fs.findings)(study, cmp))
    n_failed = len(study.failed)
    if n_failed:
        items.append(f"{n_failed} model runs failed and are left out (see 'Failed cases').")
    return items


def _assumptions_html(study: ResultSet) -> str:
    rows = assumption_rows(study)
    if not rows:
        return "<p class='note'>No parameter of this study is marked as assumed.</p>"
    body = "".join(f"<tr><td><code>{_esc(r.key)}</code></td><td>{_esc(r.value)}</td><td>{_esc(r.source)}</td></tr>"
                   for r in rows)
    return ("<table class='assumptions'><thead><tr><th>parameter</th><th>value used</th><th>where it comes from"
            f"</th></tr></thead><tbody>{body}</tbody></table>")


def _sensitivity_html(study: ResultSet, cmp: pd.DataFrame, render: Callable[[ReportFigure], str]) -> str:
    keys = sensitivity_keys(study)
    rep = study.spec.get("report") if isinstance(study.spec.get("report"), Mapping) else {}
    note = f"<p>{_esc(rep['sensitivity_note'])}</p>" if rep.get("sensitivity_note") else ""
    if not keys:
        return note or "<p>No assumption of this study is swept (the study file gives no sensitivity sweep).</p>"
    figs, texts = sensitivity_figures(study, cmp)
    parts = [note] + [f"<p>{_esc(t)}</p>" for t in texts]
    return "".join(parts) + "".join(render(f) for f in figs)


def opening_sections(study: ResultSet, cmp: pd.DataFrame, render: Callable[[ReportFigure], str]) -> dict[str, str]:
    """Inner HTML of the four opening sections by id (``question``, ``findings``, ``assumptions``,
    ``sensitivity``); call inside ``matplotlib.rc_context(STYLE)``.  The page builder passes the
    result as ``PageContext.extra["opening"]``; the section builders below read it."""
    rep = study.spec.get("report") if isinstance(study.spec.get("report"), Mapping) else {}
    inner = study.spec.get("study") if isinstance(study.spec.get("study"), Mapping) else {}
    question = rep.get("question") or inner.get("description") or "(the study file states no question)"
    findings = "".join(f"<li>{_esc(t)}</li>" for t in findings_list(study, cmp))
    return {
        "question": f"<p>{_esc(question)}</p>",
        "findings": f"<ul class='findings'>{findings}</ul>",
        "assumptions": _assumptions_html(study),
        "sensitivity": _sensitivity_html(study, cmp, render),
    }


def _section(ctx: PageContext, key: str, title: str) -> Section | None:
    body = (ctx.extra.get("opening") or {}).get(key)
    return None if body is None else Section(key, title, body)


def question_section(ctx: PageContext) -> Section | None:
    """The study's question (``[report] question``)."""
    return _section(ctx, "question", "Question")


def findings_section(ctx: PageContext) -> Section | None:
    """Findings generated from the data, with error bars."""
    return _section(ctx, "findings", "Findings")


def assumptions_section(ctx: PageContext) -> Section | None:
    """Every parameter the source does not give, its value and where it comes from."""
    return _section(ctx, "assumptions", "Assumptions")


def sensitivity_section(ctx: PageContext) -> Section | None:
    """The sensitivity sweeps of the assumptions, with their figures."""
    return _section(ctx, "sensitivity", "Sensitivity")
