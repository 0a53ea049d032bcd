"""The report of a calibration study: its Measurements section and its findings line.

A calibration study (``[study] kind = "calibration"``, ``docs/measurements.md``) stores one row per
model and fold (the row schema of issue 30: ``calib.*`` calibrated values with confidence intervals,
``err.*`` tip errors, ``sample.*`` the evaluated samples, ``view.*`` the backbones of the 3-D view).
Those rows have no ``tip_x`` nor backbones per case, so the report draws none of a sweep's
CC-vs-physics figures for them (:func:`is_calibration`, read by :mod:`.build`); instead:

* :func:`calibration_findings`: the findings line -- which model explains the measurements and by
  how much, on the rows every model predicted (``err.common_test_rms``, the fold's physics
  held-out rows; over several folds the RMS pooled over the rows of the folds on which every
  model with a result succeeded); a model whose calibration failed is named with its reason, and
  gets no verdict when it failed on every fold;
* :func:`measurements_section`: per model the calibrated values of fold 0 with their confidence
  intervals (linearised, from the Jacobian at the optimum), units, start-value sources and "at
  bound" flags; the train / held-out tip errors (RMS, median, 95th percentile, max in mm and % L;
  over several folds the mean over the folds with the smallest and largest value), evaluations and
  seconds per evaluation; the comparison on the common held-out rows; the split, seed and the
  data file with its SHA-256 (provenance); the figures of :mod:`.measurements_figures`.

Cells are read as the store writes them (flattened ``list<double>``; lists of text also as a JSON
string), shapes recovered from the row's own counts (:func:`points`).  Checked by
``tests/report/test_measurements_report.py``.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .escape import esc
from ..units import unit_of
from .context import PageContext, Section
from .load import ResultSet
from .style import fmt, model_label

__all__ = ["FitSummary", "calibration_findings", "cell", "common_rows", "fit_summaries", "is_calibration",
           "measurements_section", "points", "texts"]

#: CC models: the model under test whose error the findings line compares with the physics models'
_CC = ("cc",)


def is_calibration(study: ResultSet) -> bool:
    """A calibration study: ``[study] kind = "calibration"`` in the manifest, or rows with ``calib.values``."""
    inner = study.spec.get("study") if isinstance(study.spec.get("study"), Mapping) else {}
    return str(inner.get("kind", "")) == "calibration" or "calib.values" in study.results.columns


def cell(v: Any) -> np.ndarray:
    """A stored array cell as a float array (``None`` / NaN / empty -> ``(0,)``; a JSON string is parsed)."""
    if isinstance(v, str):
        try:
            v = json.loads(v)
        except ValueError:
            return np.zeros(0)
    if v is None or (np.isscalar(v) and not np.isfinite(float(v))):
        return np.zeros(0)
    return np.asarray(v, dtype=float).reshape(-1)


def texts(v: Any) -> list[str]:
    """A stored list of text (a list / array of strings, or a JSON string of one) as ``list[str]``."""
    if isinstance(v, str):
        try:
            v = json.loads(v)
        except ValueError:
            return [v]
    if v is None or (np.isscalar(v) and not isinstance(v, str)):
        return []
    return [str(x) for x in list(v)]


def points(v: Any, leading: int | None = None) -> np.ndarray:
    """A stored array of 3-D points as ``(n, 3)`` or, given ``leading = k``, ``(k, m, 3)`` [m]."""
    a = cell(v)
    if leading is None:
        return a.reshape(-1, 3)
    if a.size == 0 or leading == 0:
        return np.zeros((leading or 0, 0, 3))
    return a.reshape(leading, -1, 3)


@dataclass(frozen=True, eq=False)
class FitSummary:
    """One model's calibrations: its ok rows (one per fold, by fold) and its failed folds with reasons."""

    model: str
    rows: tuple[Mapping[str, Any], ...]
    failed: tuple[tuple[int, str], ...]

    @property
    def first(self) -> Mapping[str, Any] | None:
        """The row of the lowest ok fold (fold 0 when it succeeded)."""
        return self.rows[0] if self.rows else None


def _fold(row: Mapping[str, Any]) -> int:
    f = row.get("fold")
    try:
        return int(f)
    except (TypeError, ValueError):
        return 0


def fit_summaries(study: ResultSet) -> list[FitSummary]:
    """One :class:`FitSummary` per model, in the report's model order."""
    out = []
    for m in study.models:
        sub = study.results[study.results["model"].astype(str) == m]
        recs = sorted((r.to_dict() for _, r in sub.iterrows()), key=_fold)
        ok = tuple(r for r in recs if str(r.get("status")) == "ok")
        bad = tuple((_fold(r), str(r.get("error") or r.get("failure") or "no reason recorded")) for r in recs
                    if str(r.get("status")) != "ok")
        out.append(FitSummary(m, ok, bad))
    return out


def common_rows(sums: list[FitSummary], fold: int) -> int:
    """Held-out rows every model of ``fold`` predicted: the ``physics_test`` rows (a physics row's test
    samples), else -- no physics model has a result -- the CC row's test samples (:func:`_verdict_column`)."""
    counts = {}
    for s in sums:
        for r in s.rows:
            if _fold(r) == fold:
                counts[s.model] = int(np.sum(cell(r.get("sample.split")) == 1))
    physics = [n for m, n in counts.items() if m not in _CC]
    return physics[0] if physics else next(iter(counts.values()), 0)


def _verdict_column(sums: list[FitSummary]) -> str:
    """The error the models are judged by: on the common held-out rows, or -- no physics model has a result,
    so CC is alone -- on all its held-out rows."""
    physics = any(s.rows for s in sums if s.model not in _CC)
    return "err.common_test_rms" if physics else "err.test_rms"


def _common_folds(sums: list[FitSummary]) -> set[int]:
    """The folds on which every model with a result succeeded (the models are compared on these only)."""
    judged = [{_fold(r) for r in s.rows} for s in sums if s.rows]
    return set.intersection(*judged) if judged else set()


def _pooled(sums: list[FitSummary], s: FitSummary, col: str, folds: set[int]) -> tuple[float, int]:
    """RMS of ``col`` pooled over the common held-out rows of ``folds``, and the number of those rows."""
    num, n_all = 0.0, 0
    for r in s.rows:
        if _fold(r) not in folds:
            continue
        n = common_rows(sums, _fold(r))
        v = float(r.get(col, np.nan))
        if n and np.isfinite(v):
            num += n * v * v
            n_all += n
    return (float(np.sqrt(num / n_all)) if n_all else np.nan), n_all


def _length(sums: list[FitSummary]) -> float:
    """The nominal robot's length [m] (``robot_length`` of the first ok row)."""
    L = [float(r.get("robot_length", np.nan)) for s in sums for r in s.rows]
    L = [x for x in L if np.isfinite(x) and x > 0]
    return L[0] if L else np.nan


def _mm_pct(err: float, L: float) -> str:
    return f"{fmt(1e3 * err)} mm ({fmt(100.0 * err / L)} % L)"


def _failure_text(s: FitSummary, n_folds: int) -> str:
    reasons = "; ".join(f"fold {f}: {why}" for f, why in s.failed)
    if not s.rows:
        return f"No verdict on {model_label(s.model)}: its calibration failed on every fold ({reasons})."
    return (f"{model_label(s.model)}: the calibration failed on {len(s.failed)} of {n_folds} folds ({reasons}); "
            "its numbers are over the other folds.")


def calibration_findings(study: ResultSet) -> list[str]:
    """The findings of a calibration study (module docstring), numbers from the rows."""
    sums = fit_summaries(study)
    n_folds = len({_fold(r) for s in sums for r in s.rows} | {f for s in sums for f, _ in s.failed}) or 1
    L = _length(sums)
    common = _common_folds(sums)
    scored = []
    for s in sums:
        if s.rows:
            rms, n = _pooled(sums, s, _verdict_column(sums), common)
            if np.isfinite(rms):
                scored.append((rms, n, s))
    out = []
    if any(s.rows for s in sums) and not common:
        out.append("No verdict: no fold on which every model with a result succeeded (the models' held-out errors "
                   "would be on different rows).")
    elif scored:
        scored.sort(key=lambda t: t[0])
        best_rms, n, best = scored[0]
        folds = (f" ({len(common)} folds)" if len(common) == n_folds else
                 f" (folds {', '.join(map(str, sorted(common)))} of {n_folds}, where every model succeeded)")
        folds = folds if n_folds > 1 else ""
        text = (f"On {n} held-out rows{folds}, {model_label(best.model)} explains the measurements to "
                f"{_mm_pct(best_rms, L).replace(' mm', ' mm RMS', 1)}")
        for rms, _, s in scored[1:]:
            ratio = rms / best_rms if best_rms > 0 else np.inf
            text += f"; {model_label(s.model)}'s error is {_mm_pct(rms, L)}, {fmt(ratio)}x larger"
        out.append(text + ".")
    elif sums:
        out.append("No verdict: no model has a held-out error (every calibration failed).")
    for s in sums:
        if s.failed:
            out.append(_failure_text(s, n_folds))
        for r in s.rows:
            if not _truthy(r.get("calib.converged")):
                out.append(f"{model_label(s.model)}, fold {_fold(r)}: least squares did not converge "
                           f"({r.get('calib.message') or 'no message'}); its values are the last iterate.")
    return out


def _truthy(v: Any) -> bool:
    if isinstance(v, str):
        return v.strip().lower() in ("true", "1", "yes")
    try:
        return bool(v) and not (isinstance(v, float) and np.isnan(v))
    except (TypeError, ValueError):
        return False


def _parameter_table(row: Mapping[str, Any]) -> str:
    names, units, sources = (texts(row.get(f"calib.{k}")) for k in ("names", "units", "sources"))
    vals = {k: cell(row.get(f"calib.{k}")) for k in ("initial", "lower", "upper", "values", "ci_low", "ci_high",
                                                     "at_bound")}
    level = float(row.get("calib.confidence", np.nan))
    body = []
    for i, name in enumerate(names):
        def v(k: str) -> float:
            a = vals[k]
            return float(a[i]) if i < a.size else np.nan
        unit = units[i] if i < len(units) and units[i] else (unit_of(name) or "")
        at = v("at_bound") > 0.5
        flag = "<td class='bad'>at bound</td>" if at else "<td></td>"
        src = sources[i] if i < len(sources) else ""
        body.append(f"<tr><td><code>{esc(name)}</code></td><td>{esc(unit)}</td><td class='num'>{esc(fmt(v('values')))}"
                    f"</td><td class='num'>{esc(_interval(v('ci_low'), v('ci_high')))}</td>{flag}"
                    f"<td class='num'>{esc(fmt(v('initial')))}</td><td>{esc(src)}</td>"
                    f"<td class='num'>[{esc(fmt(v('lower')))}, {esc(fmt(v('upper')))}]</td></tr>")
    pct = f"{fmt(100 * level)} %" if np.isfinite(level) else "n/a"
    head = ("<tr><th>parameter</th><th>unit</th><th>calibrated</th><th>" + esc(pct) + " interval</th><th></th>"
            "<th>start</th><th>start from</th><th>bounds</th></tr>")
    return f"<table class='calibrated'><thead>{head}</thead><tbody>{''.join(body)}</tbody></table>"


def _interval(lo: float, hi: float) -> str:
    """``[lo, hi]``; an infinite side: the data do not determine the value (a singular Jacobian direction)."""
    if np.isinf(lo) or np.isinf(hi):
        return "not identifiable (unbounded)"
    return f"[{fmt(lo)}, {fmt(hi)}]"


_ERRORS = (("rms", "RMS"), ("median", "median"), ("p95", "95th pct."), ("max", "max"))


def _over_folds(rows, col: str, L: float) -> str:
    v = np.array([float(r.get(col, np.nan)) for r in rows], dtype=float)
    v = v[np.isfinite(v)]
    if not v.size:
        return "n/a"
    text = _mm_pct(float(v.mean()), L)
    return text if v.size == 1 else f"{text}; {fmt(1e3 * v.min())}–{fmt(1e3 * v.max())} mm"


def _error_table(sums: list[FitSummary], L: float) -> str:
    head = ("<tr><th>model</th><th>set</th>" + "".join(f"<th>{t}</th>" for _, t in _ERRORS)
            + "<th>samples</th><th>evaluations</th><th>s / evaluation</th></tr>")
    body = []
    for s in sums:
        if not s.rows:
            why = "; ".join(f"fold {f}: {r}" for f, r in s.failed)
            body.append(f"<tr class='failed'><td>{esc(model_label(s.model))}</td><td colspan='7'>failed: {esc(why)}"
                        "</td></tr>")
            continue
        for part, split in (("train", 0), ("test", 1)):
            n = [int(np.sum(cell(r.get("sample.split")) == split)) for r in s.rows]
            cells = "".join(f"<td class='num'>{esc(_over_folds(s.rows, f'err.{part}_{k}', L))}</td>" for k, _ in _ERRORS)
            ev = np.nanmean([float(r.get("calib.evaluations", np.nan)) for r in s.rows])
            spe = np.nanmean([float(r.get("calib.seconds_per_evaluation", np.nan)) for r in s.rows])
            what = "fitted on" if split == 0 else "held out"
            extra = (f"<td class='num'>{esc(fmt(ev))}</td><td class='num'>{esc(fmt(spe))}</td>" if split == 0
                     else "<td></td><td></td>")
            body.append(f"<tr><td>{esc(model_label(s.model))}</td><td>{what}</td>{cells}"
                        f"<td class='num'>{esc('+'.join(str(x) for x in n))}</td>{extra}</tr>")
    return f"<table class='errors'><thead>{head}</thead><tbody>{''.join(body)}</tbody></table>"


def _common_table(sums: list[FitSummary], L: float) -> str:
    """Each model's verdict error (:func:`_verdict_column`), its ratio to the best and its number of rows."""
    rows, common, col = [], _common_folds(sums), _verdict_column(sums)
    for s in sums:
        rms, n = _pooled(sums, s, col, common) if s.rows else (np.nan, 0)
        rows.append((s.model, rms, n, "failed" if not s.rows else "n/a (no common fold)"))
    best = min((r for r in rows if np.isfinite(r[1])), key=lambda r: r[1], default=None)
    body = "".join(
        f"<tr><td>{esc(model_label(m))}</td><td class='num'>{esc(_mm_pct(rms, L) if np.isfinite(rms) else why)}"
        f"</td><td class='num'>{esc(fmt(rms / best[1]) + 'x' if best and np.isfinite(rms) and best[1] > 0 else '')}"
        f"</td><td class='num'>{n}</td></tr>" for m, rms, n, why in rows)
    where = "the common held-out rows" if col == "err.common_test_rms" else "all held-out rows (no physics result)"
    return (f"<table class='common'><thead><tr><th>model</th><th>RMS tip error on {where}</th>"
            f"<th>/ best</th><th>rows</th></tr></thead><tbody>{body}</tbody></table>")


def _data_file(study: ResultSet, meas: Mapping[str, Any]) -> tuple[str, str]:
    """The data file's name and SHA-256: as recorded (manifest ``data_file``, ``[measurements] sha256`` of the
    resolved spec, a ``data.sha256`` cell), else hashed now from the file next to the study file, said so."""
    man = study.manifest
    data = man.get("data_file") if isinstance(man.get("data_file"), Mapping) else {}
    col = study.results["data.sha256"].dropna() if "data.sha256" in study.results else ()
    name = str(data.get("name") or meas.get("file") or "n/a")
    sha = data.get("sha256") or meas.get("sha256") or (str(col.iloc[0]) if len(col) else "")
    if sha:
        return name, str(sha)
    path = Path(str(man.get("study_file") or "")).parent / name
    if name != "n/a" and man.get("study_file") and path.is_file():
        return name, hashlib.sha256(path.read_bytes()).hexdigest() + " (not recorded by the run: hashed now)"
    return name, "not recorded"


def _provenance(study: ResultSet) -> str:
    spec = study.spec
    meas = spec.get("measurements") if isinstance(spec.get("measurements"), Mapping) else {}
    cal = spec.get("calibration") if isinstance(spec.get("calibration"), Mapping) else {}
    name, sha = _data_file(study, meas)
    split = (f"{fmt(float(cal['test_fraction']))} of the rows held out" if cal.get("test_fraction") is not None
             else f"{cal.get('folds')} folds" if cal.get("folds") is not None else "n/a")
    return (f"<p class='note'>Data file <code>{esc(name)}</code>, SHA-256 <code>{esc(sha)}</code>; mode "
            f"{esc(meas.get('mode', 'n/a'))}, positions measured in the {esc(meas.get('frame', 'n/a'))} frame. "
            f"Split: {esc(split)}, seed {esc(cal.get('seed', 'n/a'))}; physics models are fitted on and predict "
            f"{esc(cal.get('physics_rows', 'n/a'))} rows of each side (seeded subsamples). The held-out rows never "
            "enter a fit.</p>")


_HOW = ("<p class='note'>Each model's unknown parameters are fitted by nonlinear least squares (scipy "
        "<code>least_squares</code>) to the measured tip positions of the training rows, then the model predicts "
        "the held-out rows. The intervals are linearised: from the Jacobian at the optimum and the residual "
        "variance, with a t-quantile; they are not exact for a nonlinear model, and may reach past the bounds. "
        "<em>not identifiable</em>: the training rows do not determine the value (the Jacobian at the optimum is "
        "singular in its direction), whatever the fit returned. <em>at bound</em>: the value ended within 1e-6 of the bounds' span from a bound, so the bound, not the data, set it. The parameter "
        "values are fold 0's (the first fold that succeeded); errors over several folds are the mean over the "
        "folds followed by the smallest and largest fold's value.</p>")


def measurements_section(ctx: PageContext) -> Section | None:
    """The Measurements section of a calibration study (``None`` for any other study)."""
    study = ctx.study
    if not is_calibration(study):
        return None
    sums = fit_summaries(study)
    L = _length(sums)
    parts = [_provenance(study), "<h3>Which model explains the measurements</h3>",
             "<p class='note'>RMS tip error on the held-out rows every model predicted (the physics models' "
             "subsample; CC predicts every held-out row, its error on all of them is in the next table).</p>",
             _common_table(sums, L), "<h3>Tip errors</h3>", _error_table(sums, L),
             "<h3>Calibrated values</h3>", _HOW]
    for s in sums:
        if s.first is None:
            parts.append(f"<h4>{esc(model_label(s.model))}</h4><p class='bad'>{esc(_failure_text(s, 1))}</p>")
            continue
        r = s.first
        conv = "" if _truthy(r.get("calib.converged")) else " · did not converge"
        parts.append(f"<h4>{esc(model_label(s.model))} (fold {_fold(r)}; {esc(r.get('calib.message') or '')}"
                     f"{esc(conv)})</h4>" + _parameter_table(r))
    parts += list((ctx.extra or {}).get("measurement_figures") or ())
    return Section("measurements", "Measurements", "".join(parts))
