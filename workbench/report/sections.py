"""The standard sections of the report page (builders ``<name>_section(ctx) -> Section | None``).

Listed, in page order, by :data:`.page.SECTIONS`: ``provenance`` (what ran, where, when, with
which versions), ``failed`` (failed runs and their reasons), ``summary`` (per model pair),
``cases`` (the sortable, filterable per-case table with the embedded downloads), ``viewer``
(the interactive 3-D view), ``figures`` and ``spec`` (the resolved study spec).  Every text is
HTML-escaped here (:func:`esc`); URLs are defused (a report holds no ``http(s)://``).  Checked
by ``tests/report/test_report_build.py`` and the browser tests.
"""

from __future__ import annotations

import json
from datetime import datetime
from typing import Any

import numpy as np
import pandas as pd

from .escape import esc
from .load import ResultSet, numeric
from .measurements import is_calibration
from .context import PageContext, Section
from .style import fmt, model_label, short_label
from .viewer import NOT_PHYSICS, disk_model

__all__ = ["html_table", "provenance_section", "failed_section", "summary_section", "cases_section",
           "viewer_section", "figures_section", "spec_section"]


_esc = esc


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


def html_table(df: pd.DataFrame, float_fmt=fmt, max_rows: int = 200) -> str:
    head = "".join(f"<th>{esc(c)}</th>" for c in df.columns)
    body = []
    for _, r in df.head(max_rows).iterrows():
        cells = []
        for v in r:
            if isinstance(v, (float, np.floating)):
                cells.append(f"<td class='num'>{esc(float_fmt(float(v)))}</td>")
            else:
                cells.append(f"<td>{esc(v)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    more = f"<p class='note'>({len(df) - max_rows} more rows in the CSV)</p>" if len(df) > max_rows else ""
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>{more}"


_table = html_table


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
        ("models compared", models + (f" (reference: {model_label(study.baseline)})" if study.baseline in study.models else "")),
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
    return "<dl class='prov'>" + "".join(f"<dt>{esc(k)}</dt><dd>{esc(v)}</dd>" for k, v in prov) + "</dl>"


def _failed_html(failed: pd.DataFrame, fcols: list[str]) -> str:
    if not len(failed):
        return "<p class='note'>No failed cases.</p>"
    rows = _table(failed[fcols]).replace("<tr><td>", "<tr class='failed'><td>")
    per_model = ", ".join(f"{esc(m)} {n}" for m, n in failed["model"].astype(str).value_counts().sort_index().items())
    fail_html = (f"<h2>Failed cases</h2><p>{len(failed)} failed model runs ({per_model}), excluded from all "
                 "figures and metrics.</p>")
    if len(failed) > 8:  # a long list would push the results off the first screen
        return fail_html + f"<details><summary>show the {len(failed)} failed runs and their reasons</summary>{rows}</details>"
    return fail_html + rows


_DEFINITIONS = (
    "<p class='note'>Errors compare each model with the reference at the same case. Tip error: distance between tip "
    "positions, in metres and in % of the robot length L. Orientation error: angle of the relative tip rotation. "
    "Shape error: maximum / RMS distance between the backbones at matched reference arc-length stations. "
    "Curvature: best-fit circle per section. The tables are embedded in this page (Cases, Downloads) and "
    "written next to it (<code>metrics.csv</code>, <code>summary.csv</code>, <code>results.csv</code>, "
    "<code>failed.csv</code>, <code>results.parquet</code>); <code>figures/</code> holds each figure as a file.</p>"
)


def provenance_section(ctx: PageContext) -> Section:
    return Section("provenance", "Provenance", _provenance_html(ctx.study, ctx.failed), heading=False)


def failed_section(ctx: PageContext) -> Section:
    return Section("failed", "Failed cases", _failed_html(ctx.failed, list(ctx.failed_columns)), heading=False)


def summary_section(ctx: PageContext) -> Section | None:
    if is_calibration(ctx.study):  # no model pairs per case: its comparison is the Measurements section
        return None
    if ctx.summary.empty:
        body = ("<p class='note'>Only one model (or no case with two successful models): "
                "there is nothing to compare, the figures show the results alone.</p>")
    else:
        body = html_table(ctx.summary)
    return Section("summary", "Summary", body + _DEFINITIONS)


def cases_section(ctx: PageContext) -> Section:
    links = " ".join(f"<a download='{esc(name)}' href='{esc(uri)}'>{esc(name)}</a> <span class='note'>({esc(what)})</span>"
                     for name, uri, what in ctx.downloads)
    body = (
        "<p class='note'>One row per case and model (failed runs included, shaded). Click a column title to sort, "
        "type in the box under it to filter (text: part of the value; numbers: <code>&gt; 1</code>, "
        "<code>&lt;= 0.5</code>, <code>0..5</code>). Errors are against the reference model "
        f"{esc(model_label(ctx.study.baseline))}; each row links to the figures that draw its case and to the 3-D view. "
        "<span id='wb-case-count'></span></p>"
        f"<p class='downloads'>Downloads (embedded in this page): {links}</p>"
        "<div class='scroll'><table id='wb-case-table' data-rows='0'><thead></thead><tbody></tbody></table></div>"
        "<noscript><p class='note'>The table needs JavaScript; the same rows are in the downloads above.</p></noscript>"
    )
    return Section("cases", "Cases", body)


def _disk_backbone(ctx: PageContext) -> str:
    """Whose backbone the 3-D view draws disks and tendons on (:func:`.viewer.disk_model`), in words."""
    main = disk_model(ctx.study.models)
    if main is None:
        return "the first model's backbone"
    if main in NOT_PHYSICS:
        return f"the {esc(model_label(main))} backbone (no physics model)"
    return (f"the {esc(model_label(main))} backbone (the first physics model; in a case without its result, the "
            "next physics model's)")


def viewer_section(ctx: PageContext) -> Section | None:
    if not ctx.viewer_cases:
        return None
    if is_calibration(ctx.study):
        return Section("viewer", "3-D view", _MEASURED_VIEW + _viewer_html())
    frame = ctx.study.frame
    left = (f" The view holds the first {ctx.viewer_cases} cases in parameter order; {ctx.viewer_left_out} more are in "
            "the downloads." if ctx.viewer_left_out else "")
    body = (
        f"<p class='note'>Backbones of one case, every model overlaid, in the {esc(frame)} frame"
        + (" (z up, gravity as the blue arrow)" if frame == "world" else " (backbone along base +z)")
        + f"; disks (grey) and tendons (brown) on {_disk_backbone(ctx)}, drawn with a rotation-minimising "
        "frame (the backbone's twist is not stored). Drag to rotate, wheel to zoom, double click to reset. "
        f"Dynamic cases: the time slider steps through the stored backbone frames.{left}</p>" + _viewer_html()
    )
    return Section("viewer", "3-D view", body)


_MEASURED_VIEW = (
    "<p class='note'>Held-out samples the calibration chose for the view (spread over the commands): each model's "
    "predicted backbone after its calibration (its first successful fold), in the measurement frame (the tracker's "
    "axes; gravity is not drawn), the measured tip as a black cross and measured backbone points, where the data "
    "file has them, as magenta crosses. Drag to rotate, wheel to zoom, double click to reset.</p>")


def _viewer_html() -> str:
    """The viewer's controls and canvas (``assets/viewer.js`` fills them)."""
    return (
        "<div id='wb-viewer'><div class='controls'><label>case <select class='wb-case'></select></label>"
        "<button type='button' data-view='iso'>3-D</button><button type='button' data-view='xz'>x-z</button>"
        "<button type='button' data-view='yz'>y-z</button><button type='button' data-view='xy'>x-y</button>"
        "<label><input type='checkbox' class='wb-disks' checked> disks</label>"
        "<label><input type='checkbox' class='wb-tendons' checked> tendons</label></div>"
        "<div class='controls wb-timebar'><button type='button' class='wb-play'>&#9654; play</button>"
        "<input type='range' class='wb-time' min='0' max='0' value='0' style='width:420px'>"
        "<span class='wb-tlabel'></span></div>"
        "<canvas width='900' height='560' data-drawn-pixels='0'></canvas><div class='wb-info note'></div></div>"
    )


def figures_section(ctx: PageContext) -> Section | None:
    if not ctx.figures_html and is_calibration(ctx.study):  # its figures are in the Measurements section
        return None
    toc = " · ".join(f"<a href='#fig-{esc(n)}'>{esc(n)}</a>" for n in ctx.figure_names)
    return Section("figures", "Figures", f"<p class='note'>{toc} — click a figure to see it at full size.</p>"
                   + "".join(ctx.figures_html))


def spec_section(ctx: PageContext) -> Section | None:
    spec = ctx.study.spec
    if not spec:
        return None
    return Section("spec", "Study spec", "<details><summary>Resolved study spec (manifest)</summary><pre>"
                   + esc(json.dumps(spec, indent=1, default=str)) + "</pre></details>", heading=False)
