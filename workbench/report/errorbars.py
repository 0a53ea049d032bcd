"""Figures with discretisation error bars: the headline comparison per case, and the sensitivity sweeps.

:func:`error_bar_figures` (a generic figure, :data:`.figures.GENERIC_FIGURES`): for every CC
comparison the judged error of each baseline case (tip error; dynamics: its peak over time) in
% of L with its discretisation error bar, cases ordered by the first plot axis; cases marked not
converged (:mod:`workbench.compare.convergence`) are drawn as red crosses.  :func:`sensitivity_figures`
(the report's Sensitivity section): per ``[report] sensitivity`` key the headline of every CC
comparison against the assumed value, over the cases that exist at every value, with error bars.
Checked by ``tests/report/test_findings.py``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.convergence import is_cc_pair
from ..study.expand import sweep_keys
from .headline import baseline_cases, baseline_value, sensitivity_keys
from .kind_hooks import kind_hook
from .load import ResultSet, numeric
from .style import ReportFigure, axis_label, fmt, model_color, pair_label, short_label

__all__ = ["error_bar_figures", "sensitivity_figures"]


def _cc_pairs(cmp: pd.DataFrame) -> list[tuple[str, str]]:
    pairs = list(dict.fromkeys(zip(cmp["reference"].astype(str), cmp["model"].astype(str))))
    return [p for p in pairs if is_cc_pair(*p)]


def _pct(g: pd.DataFrame, col: str) -> np.ndarray:
    return 100.0 * numeric(g[col]) / numeric(g["robot_length"])


def error_bar_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """One figure, a panel per CC comparison (``[]`` without discretisation estimates)."""
    if cmp.empty or "disc_error" not in cmp or not np.isfinite(numeric(cmp["disc_error"])).any():
        return []
    base = baseline_cases(study, cmp)
    pairs = [p for p in _cc_pairs(base) if p[1] not in ("cc", "cc_fit") or p[0] not in ("cc", "cc_fit")]
    if not pairs:
        return []
    fig = Figure(figsize=(min(4.6 * len(pairs), 13.0) + 0.4, 3.6), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, len(pairs), squeeze=False)[0])
    texts = []
    x_ax = study.axes[0] if study.axes else None
    for ax, (ref, m) in zip(axs, pairs):
        g = base[(base["reference"] == ref) & (base["model"] == m)]
        g = g.sort_values([c for c in ([x_ax] if x_ax in g else []) + ["case_id"]])
        e, d = _pct(g, "judged_error"), _pct(g, "disc_error")
        nc = g["not_converged"].astype(bool).to_numpy()
        x = np.arange(len(g))
        floor = 1e-7
        col = model_color(m if m not in ("cc", "cc_fit") else ref, study.models)
        ax.errorbar(x[~nc], np.maximum(e[~nc], floor), yerr=np.nan_to_num(d[~nc]), fmt="o", ms=4, color=col,
                    capsize=2, label="converged (error bar ≤ 10 % of the error)")
        if nc.any():
            ax.errorbar(x[nc], np.maximum(e[nc], floor), yerr=np.nan_to_num(d[nc]), fmt="x", ms=6, color="#c00000",
                        capsize=2, label="not converged")
        ax.set_yscale("log")
        ax.set_xlabel(f"case (sorted by {short_label(x_ax, study.labels)})" if x_ax else "case")
        ax.set_ylabel("error [% L], discretisation error bar")
        ax.set_title(pair_label(ref, m))
        ax.legend(frameon=False, fontsize=7)
        texts.append(f"{pair_label(ref, m)}: {int(nc.sum())} of {len(g)} cases not converged; largest error bar "
                     f"{fmt(np.nanmax(d) if np.isfinite(d).any() else np.nan)} % L.")
    fig.suptitle("Errors with their discretisation error bars")
    return [ReportFigure("error_bars", "Errors with discretisation error bars", fig,
                         "Each point is one case's judged error (tip error; dynamics: peak over time) with the "
                         "Richardson estimate of its discretisation error as the error bar (log scale; errors "
                         "below 1e-7 % L drawn at 1e-7). " + " ".join(texts))]


def _other_keys(study: ResultSet, col: str) -> list[str]:
    """The configured sweep keys (else the kind's ``axes`` hook) other than the sensitivity ones, as columns."""
    keys = [f"p.{k}" for k in sweep_keys(study.spec.get("sweep"))]
    hook = kind_hook(study.spec, "axes") if not keys else None
    if hook is not None:
        keys = list(hook(list(study.results.columns)))
    sens = set(sensitivity_keys(study))
    return [k for k in keys if k != col and k not in sens and k in study.results.columns]


def _comparable(g: pd.DataFrame, col: str, others: list[str]) -> pd.DataFrame:
    """Rows whose other-axis values occur at every value of ``col`` (all rows if none do)."""
    others = [c for c in others if c in g]
    if not others:
        return g
    sig = g[others].astype(object).map(str).agg("|".join, axis=1)  # str(NaN) = "nan": missing cells compare too
    common = set.intersection(*[set(sig[g[col] == v]) for v in g[col].dropna().unique()])
    return g[sig.isin(common)] if common else g


def _one_key(study: ResultSet, cmp: pd.DataFrame, col: str) -> tuple[ReportFigure | None, str]:
    sub = baseline_cases(study, cmp, [k for k in sensitivity_keys(study) if k != col])  # the others at baseline
    sub = sub[sub[col].notna()]
    base = baseline_value(study, col)
    others = _other_keys(study, col)
    fig = Figure(figsize=(5.2, 3.5), layout="constrained")
    ax = fig.subplots()
    sentences = []
    for ref, m in _cc_pairs(sub):
        g = _comparable(sub[(sub["reference"] == ref) & (sub["model"] == m)], col, others)
        vals = sorted(g[col].dropna().unique(), key=lambda v: float(v) if isinstance(v, (int, float)) else str(v))
        head, bar = [], []
        for v in vals:
            gv = g[g[col] == v]
            e = numeric(gv["judged_error"])
            i = int(np.nanargmax(e)) if np.isfinite(e).any() else 0
            head.append(100 * e[i] / float(gv["robot_length"].iloc[i]))
            bar.append(100 * float(gv["disc_error"].iloc[i]) / float(gv["robot_length"].iloc[i]))
        xs = np.arange(len(vals)) if not all(isinstance(v, (int, float)) for v in vals) else np.array(vals, float)
        ax.errorbar(xs, head, yerr=np.nan_to_num(bar), fmt="o-", capsize=3, label=pair_label(ref, m),
                    color=model_color(m if m not in ("cc", "cc_fit") else ref, study.models))
        spread = max(head) - min(head) if head else np.nan
        worst_bar = np.nanmax(bar) if np.isfinite(bar).any() else np.nan
        pairs_txt = "; ".join(f"{fmt(float(v)) if isinstance(v, (int, float)) else v}"
                              f"{' (baseline)' if base is not None and str(v) == str(base) else ''}: {fmt(h)} % L"
                              for v, h in zip(vals, head))
        verdict = ("moves it by more than its error bar" if np.isfinite(spread) and spread > worst_bar
                   else "stays within its error bar")
        sentences.append(f"{pair_label(ref, m)}, headline vs {short_label(col, study.labels)}: {pairs_txt} — the "
                         f"assumption {verdict} (spread {fmt(spread)} % L, largest error bar {fmt(worst_bar)} % L).")
    if not sentences:
        return None, f"{short_label(col, study.labels)}: no comparable cases to show."
    if base is not None and isinstance(base, (int, float)):
        ax.axvline(float(base), color="0.5", ls=":", lw=1)
    if all(isinstance(v, (int, float)) for v in sub[col].dropna().unique()) and \
            numeric(sub[col]).min() > 0 and numeric(sub[col]).max() / numeric(sub[col]).min() > 20:
        ax.set_xscale("log")
    ax.set_xlabel(axis_label(col, study.labels))
    ax.set_ylabel("headline error [% L]")
    ax.legend(frameon=False, fontsize=7.5)
    name = "sensitivity_" + "".join(ch if ch.isalnum() else "_" for ch in col[2:])
    fig.suptitle(f"Sensitivity to {short_label(col, study.labels)} (dotted: the study's baseline)")
    return ReportFigure(name, f"Sensitivity: {short_label(col, study.labels)}", fig, " ".join(sentences)), \
        " ".join(sentences)


def sensitivity_figures(study: ResultSet, cmp: pd.DataFrame) -> tuple[list[ReportFigure], list[str]]:
    """One figure and one paragraph per sensitivity key (see the module docstring)."""
    figs, texts = [], []
    if cmp.empty or "judged_error" not in cmp:
        return figs, ["No comparison to show."]
    for col in sensitivity_keys(study):
        f, t = _one_key(study, cmp, col)
        if f is not None:
            figs.append(f)
        texts.append(t)
    return figs, texts
