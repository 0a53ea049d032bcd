"""Build ``reports/<study>/report.html`` (one self-contained file) plus figures and CSVs.

:func:`build_report` loads the folder (:func:`.load.load_results`), compares the models
(:func:`workbench.compare.compare_table`) and draws, inside one ``matplotlib.rc_context(STYLE)``,
first the study-specific figure sets of ``workbench.registry.FIGURES`` whose ``matches(results)``
is true (in registry order; the report names no study), then the generic builders of
:data:`.figures.GENERIC_FIGURES`.  :mod:`.command` holds the one report command line
(``workbench report`` and ``python -m workbench.report``).
Checked by ``tests/report/`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import base64
import html
import io
import json
from datetime import datetime
from pathlib import Path
from typing import Any, Sequence

import matplotlib
import numpy as np
import pandas as pd

from .. import registry
from ..compare.table import compare_table
from .figures import GENERIC_FIGURES, STYLE, ReportFigure, code_categories, fmt, model_label, pair_label, short_label
from .findings import opening_sections
from .headline import baseline_cases, summary_columns
from .load import ResultSet, load_results, numeric

__all__ = ["build_report", "study_figure_sets"]

_PNG_META = {"Software": None}
_SVG_META = {"Creator": None, "Date": None, "Format": None, "Type": None}


def _esc(text: Any) -> str:
    """HTML-escape and defuse URLs (the report must contain no http(s):// references)."""
    s = html.escape(str(text))
    return s.replace("://", ":&#8203;//")


def _scalar_columns(df: pd.DataFrame) -> list[str]:
    cols = []
    for c in df.columns:
        v = df[c].dropna()
        if v.empty or not isinstance(v.iloc[0], (list, tuple, np.ndarray)):
            cols.append(c)
    return cols


def study_figure_sets(results: ResultSet) -> list[str]:
    """Names of the ``registry.FIGURES`` sets whose ``matches(results)`` is true, in registry order."""
    return [name for name, fs in registry.FIGURES.items() if registry.resolve(fs.matches)(results)]


def _all_figures(results: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The study-specific figure sets that match, then the generic figures (call inside ``rc_context(STYLE)``)."""
    figs: list[ReportFigure] = []
    for name in study_figure_sets(results):
        figs += registry.resolve(registry.FIGURES[name].figures)(results, cmp)
    for builder in GENERIC_FIGURES:
        figs += builder(results, cmp)
    return figs


def _provenance(man: dict) -> dict[str, str]:
    """Host, start, end, wall time and commit from either manifest convention (see load)."""
    runs = [r for r in (man.get("runs") or []) if isinstance(r, dict)]
    start = runs[0].get("start") if runs else man.get("start_time")
    end = runs[-1].get("end") if runs else man.get("end_time")
    hosts = sorted({str(r.get("host")) for r in runs if r.get("host")}) or [str(man.get("host", "n/a"))]
    if runs and all(isinstance(r.get("wall_time"), (int, float)) for r in runs):
        wall = f"{sum(r['wall_time'] for r in runs):.1f} s" + (f" over {len(runs)} runs" if len(runs) > 1 else "")
    else:
        try:
            wall = f"{(datetime.fromisoformat(str(end)) - datetime.fromisoformat(str(start))).total_seconds():.1f} s"
        except (TypeError, ValueError):
            wall = "n/a"
    git = man.get("git")
    if isinstance(git, dict):
        commit = str(git.get("commit") or "n/a (not a git checkout)")
        if git.get("dirty"):
            commit += " (uncommitted changes)"
    else:
        commit = str(man.get("git_commit", man.get("commit", "n/a")))
    return {"host": ", ".join(hosts), "start": str(start or "n/a"), "end": str(end or "n/a"), "wall": wall, "commit": commit}


def _table(df: pd.DataFrame, float_fmt=fmt, max_rows: int = 200) -> str:
    head = "".join(f"<th>{_esc(c)}</th>" for c in df.columns)
    body = []
    for _, r in df.head(max_rows).iterrows():
        cells = []
        for v in r:
            if isinstance(v, (float, np.floating)):
                cells.append(f"<td class='num'>{_esc(float_fmt(float(v)))}</td>")
            else:
                cells.append(f"<td>{_esc(v)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    more = f"<p class='note'>({len(df) - max_rows} more rows in the CSV)</p>" if len(df) > max_rows else ""
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>{more}"


def _summary_table(cmp: pd.DataFrame, study: ResultSet | None = None) -> pd.DataFrame:
    rows = []
    for (ref, m), g in cmp.groupby(["reference", "model"], sort=False):
        err_bars = summary_columns(baseline_cases(study, g) if study is not None else g)  # findings.py's numbers
        e = numeric(g["tip_error_pct"])
        rows.append({
            "comparison": pair_label(ref, m),
            "cases": int(np.isfinite(e).sum()),
            "median tip error [% L]": float(np.nanmedian(e)) if np.isfinite(e).any() else np.nan,
            "max tip error [% L]": float(np.nanmax(e)) if np.isfinite(e).any() else np.nan,
            "max tip error [mm]": 1e3 * float(np.nanmax(numeric(g["tip_error"]))) if np.isfinite(e).any() else np.nan,
            "max orientation error [deg]": float(np.nanmax(numeric(g["orientation_error_deg"]))) if g["orientation_error_deg"].notna().any() else np.nan,
            "max RMS shape error [% L]": float(np.nanmax(numeric(g["shape_error_rms_pct"]))) if "shape_error_rms_pct" in g and g["shape_error_rms_pct"].notna().any() else np.nan,
            "median wall-time ratio (model / reference)": float(np.nanmedian(numeric(g["wall_time"]) / numeric(g["wall_time_ref"]))) if g["wall_time_ref"].notna().any() else np.nan,
            **err_bars,
        })
    return pd.DataFrame(rows)


_CSS = """
body{font-family:-apple-system,'Segoe UI',Helvetica,Arial,sans-serif;max-width:1180px;margin:24px auto;padding:0 18px;color:#222;line-height:1.45}
h1{font-size:1.6em;margin-bottom:0.1em} h2{font-size:1.25em;border-bottom:1px solid #ddd;padding-bottom:3px;margin-top:1.6em}
.sub{color:#666;margin-top:0}
table{border-collapse:collapse;font-size:0.86em;margin:0.5em 0}
th,td{border:1px solid #ddd;padding:3px 8px;text-align:left;vertical-align:top} th{background:#f4f4f4}
td.num{text-align:right;font-variant-numeric:tabular-nums}
figure{margin:1.2em 0 1.8em 0} figure img{max-width:100%;height:auto;border:1px solid #eee}
figcaption{font-size:0.92em;color:#333;background:#f8f8f5;border-left:3px solid #88a;padding:6px 10px;margin-top:4px}
.failed td{background:#fff3f3} .note{color:#666;font-size:0.88em} code{background:#f3f3f3;padding:0 3px}
ul.findings li{margin:0.25em 0} table.assumptions td:first-child{white-space:nowrap}
dl.prov{display:grid;grid-template-columns:max-content auto;gap:2px 14px;font-size:0.9em} dl.prov dt{font-weight:600} dl.prov dd{margin:0}
"""


def _write_figures(figs: list[ReportFigure], figdir: Path, formats: Sequence[str]) -> list[str]:
    """Save every figure in ``formats`` under ``figdir``; return its HTML ``<figure>`` (PNG inlined)."""
    sections = []
    for f in figs:
        buf = io.BytesIO()
        f.figure.savefig(buf, format="png", metadata=_PNG_META)
        png = buf.getvalue()
        if "png" in formats:
            (figdir / f"{f.name}.png").write_bytes(png)
        if "svg" in formats:
            f.figure.savefig(figdir / f"{f.name}.svg", format="svg", metadata=_SVG_META)
        if "pdf" in formats:
            f.figure.savefig(figdir / f"{f.name}.pdf", format="pdf", metadata={"Creator": None, "Producer": None})
        b64 = base64.b64encode(png).decode("ascii")
        sections.append(
            f"<figure id='fig-{_esc(f.name)}' data-figure='{_esc(f.name)}'>"
            f"<h3>{_esc(f.title)}</h3>"
            f"<img alt='{_esc(f.title)}' src='data:image/png;base64,{b64}'>"
            f"<figcaption>{_esc(f.summary)}</figcaption></figure>"
        )
    return sections


def build_report(data_dir: str | Path, out_dir: str | Path | None = None, *, formats: Sequence[str] = ("png", "svg")) -> Path:
    """Write the comparison report of a study folder.

    Parameters
    ----------
    data_dir : path
        ``data/<study>/`` with Parquet part files and ``_manifest.json`` (see :mod:`.load`).
    out_dir : path, optional
        Output folder; default ``reports/<study name from manifest>`` (relative to the
        current directory).
    formats : sequence of {"png", "svg", "pdf"}
        File formats of ``figures/<name>.<ext>`` (the HTML always inlines PNG).

    Returns
    -------
    Path
        ``<out_dir>/report.html``.  Also written: ``figures/*``, ``metrics.csv`` (one row
        per case and model pair), ``summary.csv`` (per model pair), ``results.csv``
        (scalar columns of the result table), ``failed.csv``.
    """
    bad = sorted(set(formats) - {"png", "svg", "pdf"})
    if bad:
        raise ValueError(f"formats must be among png, svg, pdf; got {bad}")
    study = load_results(data_dir)
    out = Path(out_dir) if out_dir is not None else Path("reports") / study.name
    figdir = out / "figures"
    figdir.mkdir(parents=True, exist_ok=True)
    for old in figdir.glob("*"):
        if old.suffix in (".png", ".svg", ".pdf"):
            old.unlink()

    cmp = compare_table(study.results, reference=study.reference, derived=study.derived)
    summary = _summary_table(cmp, study) if not cmp.empty else pd.DataFrame()
    cmp.to_csv(out / "metrics.csv", index=False)
    summary.to_csv(out / "summary.csv", index=False)
    res = study.results
    res[_scalar_columns(res)].to_csv(out / "results.csv", index=False)
    failed = study.failed
    fcols = [c for c in ["case_id", "model", "error", *study.axes] if c in failed.columns]
    failed[fcols].to_csv(out / "failed.csv", index=False)

    with matplotlib.rc_context(STYLE):
        # Question / Findings / Assumptions / Sensitivity (findings.py), then the figures
        opening = opening_sections(study, cmp, lambda f: _write_figures([f], figdir, formats)[0])
        figs = _all_figures(study, code_categories(study, cmp))
        sections = _write_figures(figs, figdir, formats)
    html_text = _page(study, cmp, summary, failed, fcols, sections, [f.name for f in figs], opening)
    path = out / "report.html"
    path.write_text(html_text, encoding="utf-8")
    return path


def _swept_text(study: ResultSet, n_cases: int) -> str:
    ok = study.ok
    if not study.axes:
        return "nothing (single case)" if n_cases == 1 else "no numeric parameter varies"
    return ", ".join(
        f"{short_label(a, study.labels)} ({', '.join(study.categories[a])})" if a in study.categories else
        f"{short_label(a, study.labels)} ({fmt(np.nanmin(numeric(ok[a])))} … {fmt(np.nanmax(numeric(ok[a])))}, "
        f"{pd.Series(numeric(ok[a])).nunique()} values)"
        for a in study.axes
    )


def _provenance_html(study: ResultSet, failed: pd.DataFrame) -> str:
    man = study.manifest
    n_cases = study.results["case_id"].nunique()
    models = ", ".join(model_label(m) for m in study.models) or "none"
    versions = man.get("versions") or {}
    vtxt = ", ".join(f"{k} {v if v is not None else 'n/a'}" for k, v in versions.items()) if isinstance(versions, dict) else str(versions)
    pv = _provenance(man)
    desc = (study.spec.get("study") or {}).get("description") if isinstance(study.spec.get("study"), dict) else study.spec.get("description")
    model_time = float(np.nansum(numeric(study.results["wall_time"]))) if "wall_time" in study.results else np.nan
    prov = [
        ("study", study.name + (f" — {desc}" if desc else "")),
        ("swept", _swept_text(study, n_cases)),
        ("models compared", models + (f" (reference: {model_label(study.reference)})" if study.reference in study.models else "")),
        ("cases", f"{n_cases} cases, {len(study.results)} model runs, {len(failed)} failed"),
        ("config hash", man.get("config_hash", "n/a")),
        ("git commit", pv["commit"]),
        ("versions", vtxt or "n/a"),
        ("host", pv["host"]),
        ("start / end", f"{pv['start']} / {pv['end']}"),
        ("wall time", f"{pv['wall']} (time inside models, summed: {fmt(model_time)} s)"),
        ("data", str(study.path)),
    ]
    known = {"spec", "study", "config_hash", "git", "git_commit", "commit", "versions", "host", "start_time",
             "end_time", "runs"}
    for k, v in man.items():
        if k not in known and not isinstance(v, (dict, list)):
            prov.append((str(k), v))
    return "<dl class='prov'>" + "".join(f"<dt>{_esc(k)}</dt><dd>{_esc(v)}</dd>" for k, v in prov) + "</dl>"


def _failed_html(failed: pd.DataFrame, fcols: list[str]) -> str:
    if not len(failed):
        return "<p class='note'>No failed cases.</p>"
    rows = _table(failed[fcols]).replace("<tr><td>", "<tr class='failed'><td>")
    per_model = ", ".join(f"{_esc(m)} {n}" for m, n in failed["model"].astype(str).value_counts().sort_index().items())
    fail_html = (f"<h2>Failed cases</h2><p>{len(failed)} failed model runs ({per_model}), excluded from all "
                 "figures and metrics.</p>")
    if len(failed) > 8:  # a long list would push the results off the first screen
        return fail_html + f"<details><summary>show the {len(failed)} failed runs and their reasons</summary>{rows}</details>"
    return fail_html + rows


_DEFINITIONS = (
    "<p class='note'>Errors compare each model with the reference at the same case. Tip error: distance between tip "
    "positions, in metres and in % of the robot length L. Orientation error: angle of the relative tip rotation. "
    "Shape error: maximum / RMS distance between the backbones at matched reference arc-length stations. "
    "Curvature: best-fit circle per section. The files <code>metrics.csv</code>, <code>summary.csv</code>, "
    "<code>results.csv</code> and <code>failed.csv</code> next to this report hold the tables; "
    "<code>figures/</code> holds each figure as PNG and SVG.</p>"
)


def _page(study: ResultSet, cmp, summary, failed, fcols, sections, fig_names, opening: str = "") -> str:
    if summary.empty:
        sum_html = ("<p class='note'>Only one model (or no case with two successful models): "
                    "there is nothing to compare, the figures show the results alone.</p>")
    else:
        sum_html = _table(summary)
    spec = study.spec
    spec_html = (
        "<details><summary>Resolved study spec (manifest)</summary><pre>"
        + _esc(json.dumps(spec, indent=1, default=str)) + "</pre></details>"
        if spec else ""
    )
    toc = " · ".join(f"<a href='#fig-{_esc(n)}'>{_esc(n)}</a>" for n in fig_names)
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
        f"<title>{_esc(study.name)} – trunk-workbench report</title><style>{_CSS}</style></head><body>"
        f"<h1>Study report: {_esc(study.name)}</h1>"
        f"<p class='sub'>Constant-curvature (CC) kinematics vs physics models — generated by trunk-workbench</p>"
        f"{opening}{_provenance_html(study, failed)}{_failed_html(failed, fcols)}<h2>Summary</h2>{sum_html}{_DEFINITIONS}"
        f"<h2>Figures</h2><p class='note'>{toc}</p>{''.join(sections)}{spec_html}"
        "</body></html>"
    )
