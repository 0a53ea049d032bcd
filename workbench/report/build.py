"""Build ``reports/<run folder>/report.html`` (one self-contained file) plus figures and tables.

:func:`build_report` loads the folder (:func:`.load.load_results`), compares the models
(:func:`workbench.compare.compare_table`) and draws, inside one ``matplotlib.rc_context(STYLE)``,
first the study-specific figure sets of ``workbench.registry.table("figures")`` whose ``matches(results)``
is true (in registry order; the report names no study), then the generic builders of
:data:`.figures.GENERIC_FIGURES` -- for a calibration study (:func:`.measurements.is_calibration`: rows per
model and fold, no sweep quantities) none of these but the Measurements section's figures
(:mod:`.measurements_figures`); then the per-case table (:mod:`.casetable`), the 3-D view's
data (:mod:`.viewer`) and the page (:mod:`.page`, sections in :mod:`.sections`).  The report is
written into a temporary folder and swapped in.  :mod:`.command` holds the one report command
line (``workbench report`` and ``python -m workbench.report``).
Checked by ``tests/report/`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import base64
import io
import os
import shutil
from pathlib import Path
from typing import Sequence

import matplotlib
import numpy as np
import pandas as pd

from .. import registry
from ..compare.table import compare_table
from ..study.store import MANIFEST
from .casetable import case_table
from .figures import GENERIC_FIGURES
from .findings import opening_sections
from .headline import baseline_cases, summary_columns
from .load import ResultSet, load_results, numeric
from .measurements import is_calibration
from .measurements_figures import measurement_figures
from .context import PageContext
from .page import render_page
from .escape import esc
from .style import STYLE, ReportFigure, code_categories, pair_label
from .viewer import viewer_scenes

__all__ = ["MAX_EMBEDDED_BYTES", "build_report", "default_report_dir", "study_figure_sets"]

_PNG_META = {"Software": None}
_SVG_META = {"Creator": None, "Date": None, "Format": None, "Type": None}


def _scalar_columns(df: pd.DataFrame) -> list[str]:
    cols = []
    for c in df.columns:
        v = df[c].dropna()
        if v.empty or not isinstance(v.iloc[0], (list, tuple, np.ndarray)):
            cols.append(c)
    return cols


def study_figure_sets(results: ResultSet) -> list[str]:
    """Names of the ``registry.table("figures")`` sets whose ``matches(results)`` is true, in registry order."""
    return [name for name, fs in registry.table("figures").items() if registry.resolve(fs.matches)(results)]


def _all_figures(results: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The study-specific figure sets that match, then the generic figures (call inside ``rc_context(STYLE)``)."""
    figs: list[ReportFigure] = []
    for name in study_figure_sets(results):
        figs += registry.resolve(registry.table("figures")[name].figures)(results, cmp)
    for builder in GENERIC_FIGURES:
        figs += builder(results, cmp)
    return figs


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
        cases = f" · {len(f.cases)} case(s), listed in the table" if f.cases else ""
        links = _point_links_html(f)
        hint = " · click a marked point for its row in the case table" if links else ""
        sections.append(
            f"<figure id='fig-{esc(f.name)}' data-figure='{esc(f.name)}'>"
            f"<h3>{esc(f.title)}</h3><div class='figwrap'>"
            f"<img alt='{esc(f.title)}' src='data:image/png;base64,{b64}' onclick=\"this.parentNode.classList.toggle('zoomed')\">"
            f"{links}</div><figcaption>{esc(f.summary)}<span class='note'>{esc(cases + hint)}</span></figcaption></figure>"
        )
    return sections


def _point_links_html(f: ReportFigure) -> str:
    """Links over the figure's clickable points (percent positions: they follow the scaled image)."""
    if not f.points:
        return ""
    W, H = f.figure.canvas.get_width_height()  # pixels at the saved dpi (savefig.dpi = figure.dpi)
    out = []
    for ax, x, y, cid, model, tip in f.points:
        px, py = ax.transData.transform((x, y))
        if not (np.isfinite(px) and np.isfinite(py)) or not (0 <= px <= W and 0 <= py <= H):
            continue
        out.append(f"<a class='pt' href='#case-{esc(cid)}-{esc(model)}' title='{esc(tip)}' "
                   f"style='left:{100 * px / W:.2f}%;top:{100 * (1 - py / H):.2f}%'></a>")
    return "".join(out)


def _summary_table(cmp: pd.DataFrame, study: ResultSet | None = None) -> pd.DataFrame:
    rows = []
    for (ref, m), g in cmp.groupby(["reference", "model"], sort=False):
        err_bars = summary_columns(baseline_cases(study, g) if study is not None else g)  # findings.py's numbers
        e = numeric(g["tip_error_pct"])
        some = bool(np.isfinite(e).any())

        def worst(col: str, f: float = 1.0) -> float:
            v = numeric(g[col]) if col in g else np.array([np.nan])
            return f * float(np.nanmax(v)) if np.isfinite(v).any() else np.nan

        rows.append({
            "comparison": pair_label(ref, m),
            "cases": int(np.isfinite(e).sum()),
            "median tip error [% L]": float(np.nanmedian(e)) if some else np.nan,
            "max tip error [% L]": worst("tip_error_pct"),
            "max tip error [mm]": worst("tip_error", 1e3),
            "max orientation error [deg]": worst("orientation_error_deg"),
            "max RMS shape error [% L]": worst("shape_error_rms_pct"),
            "median wall-time ratio (model / reference)": float(np.nanmedian(numeric(g["wall_time"]) / numeric(g["wall_time_ref"])))
            if g["wall_time_ref"].notna().any() else np.nan,
            **err_bars,
        })
    return pd.DataFrame(rows)


#: Downloads larger than this are linked as files next to the report instead of embedded.
MAX_EMBEDDED_BYTES = 40_000_000


def _data_uri(raw: bytes, mime: str) -> str:
    return f"data:{mime};base64,{base64.b64encode(raw).decode('ascii')}"


def _tables(study: ResultSet, cmp: pd.DataFrame, out: Path) -> tuple[pd.DataFrame, pd.DataFrame, list[str], list]:
    """Write the CSV and Parquet tables into ``out``; return (summary, failed, failed columns, downloads)."""
    summary = _summary_table(cmp, study) if not cmp.empty else pd.DataFrame()
    res = study.results
    failed = study.failed
    fcols = [c for c in ["case_id", "model", "error", *study.axes] if c in failed.columns]
    files = {
        "results.csv": (res[_scalar_columns(res)].to_csv(index=False).encode(), "text/csv",
                        "scalar columns, one row per case and model"),
        "metrics.csv": (cmp.to_csv(index=False).encode(), "text/csv", "errors, one row per case and model pair"),
        "summary.csv": (summary.to_csv(index=False).encode(), "text/csv", "per model pair"),
        "failed.csv": (failed[fcols].to_csv(index=False).encode(), "text/csv", "failed runs and reasons"),
    }
    buf = io.BytesIO()
    res.to_parquet(buf, index=False)
    files["results.parquet"] = (buf.getvalue(), "application/vnd.apache.parquet",
                                "the whole result table with array columns (pandas.read_parquet)")
    downloads = []
    total = sum(len(raw) for raw, _, _ in files.values())
    for name, (raw, mime, what) in files.items():
        (out / name).write_bytes(raw)
        uri = _data_uri(raw, mime) if total <= MAX_EMBEDDED_BYTES else name
        downloads.append((name, uri, what if total <= MAX_EMBEDDED_BYTES else what + "; file next to this report"))
    return summary, failed, fcols, downloads


def _banners(study: ResultSet) -> list[str]:
    out = []
    if study.missing_cases:
        out.append(f"Incomplete: {study.missing_cases} of {study.expected_cases} cases not run (a partial or "
                   "interrupted run). Figures and tables show only the cases that ran; "
                   "`workbench run <study> --resume` runs the rest.")
    return out


def default_report_dir(data_dir: str | Path) -> Path:
    """``reports/<name of the data folder>`` (relative to the current directory): one report per run folder."""
    return Path("reports") / Path(data_dir).resolve().name


def _swap_in(tmp: Path, out: Path) -> None:
    """Replace ``out`` by the finished ``tmp`` folder (two renames; the old report is deleted last)."""
    old = out.with_name(f".{out.name}.old-{os.getpid()}")
    if out.exists():
        os.replace(out, old)
    os.replace(tmp, out)
    shutil.rmtree(old, ignore_errors=True)


def _check_out(out: Path, data_dir: Path) -> None:
    """Refuse an output folder the swap would destroy: a file, the results (or a folder holding them), a
    result folder, a non-empty folder that holds no report.  A one-line :class:`ValueError` each."""
    o, d = out.resolve(), Path(data_dir).resolve()
    if o == d or o in d.parents:
        raise ValueError(f"--out {out}: holds the results {data_dir}; the report needs its own folder "
                         f"(default {default_report_dir(data_dir)})")
    if not out.exists():
        return
    if not out.is_dir():
        raise ValueError(f"--out {out}: exists and is not a folder (the report is a folder; it would replace the file)")
    if (out / MANIFEST).exists():
        raise ValueError(f"--out {out}: is a study result folder; the report would replace it")
    if any(out.iterdir()) and not (out / "report.html").exists():
        raise ValueError(f"--out {out}: not empty and holds no report.html; the report would replace its contents "
                         f"(choose another folder or empty it)")


def _recover(out: Path) -> None:
    """A kill between the two renames of :func:`_swap_in` left only ``.<name>.old-*``: put it back."""
    olds = sorted(out.parent.glob(f".{out.name}.old-*"))
    if not out.exists() and olds:
        os.replace(olds[-1], out)
    for p in list(out.parent.glob(f".{out.name}.old-*")) + list(out.parent.glob(f".{out.name}.tmp-*")):
        if p.exists():
            shutil.rmtree(p, ignore_errors=True)


def build_report(data_dir: str | Path, out_dir: str | Path | None = None, *, formats: Sequence[str] = ("png", "svg")) -> Path:
    """Write the comparison report of a study folder.

    Parameters
    ----------
    data_dir : path
        ``data/<run>/`` with Parquet part files and ``_manifest.json`` (see :mod:`.load`).
    out_dir : path, optional
        Output folder; default ``reports/<name of data_dir>`` (relative to the current directory),
        so two runs of one study (``--out data/x2``) never overwrite each other's report.
    formats : sequence of {"png", "svg", "pdf"}
        File formats of ``figures/<name>.<ext>`` (the HTML always inlines PNG).

    Returns
    -------
    Path
        ``<out_dir>/report.html``.  Also written: ``figures/*``, ``metrics.csv`` (one row per
        case and model pair), ``summary.csv`` (per model pair), ``results.csv`` (scalar columns of
        the result table), ``results.parquet`` (the whole table), ``failed.csv``; the CSV and
        Parquet files are embedded in the page as downloads too.  The report is written into a
        temporary sibling folder and swapped in when complete: a kill while writing leaves the
        previous report whole.

    Raises
    ------
    ValueError
        ``out_dir`` is a file, the results or a folder holding them, a result folder, or a
        non-empty folder without ``report.html`` (the swap would delete what it holds).
    """
    bad = sorted(set(formats) - {"png", "svg", "pdf"})
    if bad:
        raise ValueError(f"formats must be among png, svg, pdf; got {bad}")
    study = load_results(data_dir)
    out = Path(out_dir) if out_dir is not None else default_report_dir(data_dir)
    _check_out(out, Path(data_dir))
    out.parent.mkdir(parents=True, exist_ok=True)
    _recover(out)
    tmp = out.with_name(f".{out.name}.tmp-{os.getpid()}")
    shutil.rmtree(tmp, ignore_errors=True)
    (tmp / "figures").mkdir(parents=True)
    try:
        cmp = compare_table(study.results, baseline=study.baseline, derived=study.derived)
        summary, failed, fcols, downloads = _tables(study, cmp, tmp)
        with matplotlib.rc_context(STYLE):
            # Question / Findings / Assumptions / Sensitivity (findings.py), then the figures
            opening = opening_sections(study, cmp, lambda f: _write_figures([f], tmp / "figures", formats)[0])
            calibration = is_calibration(study)  # its rows have no sweep quantities: no sweep figures
            figs = [] if calibration else _all_figures(study, code_categories(study, cmp))
            figure_html = _write_figures(figs, tmp / "figures", formats)
            measured = _write_figures(measurement_figures(study), tmp / "figures", formats) if calibration else []
        scenes = viewer_scenes(study)
        table = case_table(study, cmp, figs, [c["id"] for c in scenes["cases"]])
        ctx = PageContext(study=study, cmp=cmp, summary=summary, failed=failed, failed_columns=tuple(fcols),
                          figures_html=tuple(figure_html), figure_names=tuple(f.name for f in figs),
                          downloads=tuple(downloads), viewer_cases=len(scenes["cases"]),
                          viewer_left_out=scenes["left_out"],
                          extra={"opening": opening, "measurement_figures": tuple(measured)})
        page = render_page(ctx, _banners(study), {"wb-cases": table, "wb-scenes": scenes})
        (tmp / "report.html").write_text(page, encoding="utf-8")
        _swap_in(tmp, out)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return out / "report.html"
