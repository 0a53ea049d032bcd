"""Figures of a calibration study's Measurements section (matplotlib ``Figure`` objects, the report's style).

From each model's first successful fold (fold 0 when it succeeded; :func:`.measurements.fit_summaries`),
its held-out samples (``sample.split == 1``):

* ``measured_error_vs_command``: tip error [mm] against the command magnitude (Euclidean norm of the
  sample's tendon commands as measured, SI), one colour per model;
* ``measured_residual_maps``: the tip error over the input space, one panel per model, at the
  samples' coordinates along the two leading principal components of the commands (centred, the
  SVD of every evaluated sample's commands of all models), one colour scale;
* ``measured_vs_predicted``: predicted against measured tip coordinate (x, y, z of the measurement
  frame) [mm], the diagonal is a perfect model.

Call inside ``matplotlib.rc_context(STYLE)``.  Checked by ``tests/report/test_measurements_report.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, NullFormatter

from .load import ResultSet
from .measurements import cell, fit_summaries, points
from .style import ReportFigure, fmt, model_color, model_label

__all__ = ["measurement_figures", "held_out"]


def held_out(row: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """The held-out samples of a row: ``file_row``, ``commands (n, m)``, ``measured``, ``predicted (n, 3)``, ``error (n,)``."""
    split = cell(row.get("sample.split"))
    rows = cell(row.get("sample.file_row"))
    n = rows.size
    cmd = cell(row.get("sample.commands"))
    cmd = cmd.reshape(n, -1) if n and cmd.size else np.zeros((n, 0))
    meas, pred = points(row.get("sample.measured")), points(row.get("sample.predicted"))
    keep = split == 1
    err = np.linalg.norm(pred[keep] - meas[keep], axis=1) if len(pred) == n and len(meas) == n else np.zeros(0)
    return {"file_row": rows[keep], "commands": cmd[keep], "measured": meas[keep] if len(meas) == n else meas[:0],
            "predicted": pred[keep] if len(pred) == n else pred[:0], "error": err}


def _command_unit(study: ResultSet) -> tuple[str, float]:
    meas = study.spec.get("measurements") if isinstance(study.spec.get("measurements"), Mapping) else {}
    return ("mm", 1e3) if str(meas.get("mode")) == "length" else ("N", 1.0)


def _samples(study: ResultSet) -> list[tuple[str, dict[str, np.ndarray]]]:
    return [(s.model, held_out(s.first)) for s in fit_summaries(study) if s.first is not None]


def _error_vs_command(study: ResultSet, data) -> ReportFigure:
    unit, f = _command_unit(study)
    fig = Figure(figsize=(7.0, 4.0))
    ax = fig.add_subplot()
    parts = []
    for m, d in data:
        mag = f * np.linalg.norm(d["commands"], axis=1) if d["commands"].size else np.zeros(0)
        ax.scatter(mag, 1e3 * d["error"], s=14, color=model_color(m, study.models), label=model_label(m), alpha=0.8)
        if d["error"].size:
            parts.append(f"{model_label(m)} median {fmt(1e3 * float(np.median(d['error'])))} mm over "
                         f"{d['error'].size} held-out rows")
    ax.set_xlabel(f"command magnitude |u| [{unit}]")
    ax.set_ylabel("tip error [mm]")
    if all(d["error"].size and np.all(d["error"] > 0) for _, d in data) and data:
        ax.set_yscale("log")
    ax.legend()
    fig.tight_layout()
    return ReportFigure("measured_error_vs_command", "Held-out tip error vs command magnitude", fig,
                        "; ".join(parts) + " (each model's first fold).")


def _principal_axes(data) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mean, the two leading principal directions and their share of the variance, from every sample's commands."""
    allc = np.vstack([d["commands"] for _, d in data if d["commands"].size] or [np.zeros((0, 1))])
    if allc.shape[0] < 2:
        return np.zeros(allc.shape[1]), np.zeros((2, allc.shape[1])), np.zeros(2)
    mean = allc.mean(axis=0)
    _, sv, vt = np.linalg.svd(allc - mean, full_matrices=False)
    share = sv**2 / max(float(np.sum(sv**2)), 1e-300)
    pcs = np.zeros((2, allc.shape[1]))
    pcs[:min(2, vt.shape[0])] = vt[:2]
    return mean, pcs, np.pad(share[:2], (0, max(0, 2 - share[:2].size)))


def _residual_maps(study: ResultSet, data) -> ReportFigure:
    unit, f = _command_unit(study)
    mean, pcs, share = _principal_axes(data)
    errs = 1e3 * np.concatenate([d["error"] for _, d in data])
    log = bool(errs.size and np.all(errs > 0) and errs.max() / errs.min() > 20)  # models far apart: log colours
    norm = LogNorm(errs.min(), errs.max()) if log else Normalize(0.0, float(errs.max()) if errs.size else 1.0)
    fig = Figure(figsize=(3.4 * len(data) + 1.2, 3.8), layout="constrained")
    axs = fig.subplots(1, len(data), squeeze=False)[0]
    sc = None
    for ax, (m, d) in zip(axs, data):
        xy = f * (d["commands"] - mean) @ pcs.T if d["commands"].size else np.zeros((0, 2))
        sc = ax.scatter(xy[:, 0], xy[:, 1], c=1e3 * d["error"], cmap="viridis", norm=norm, s=18)
        ax.set_title(model_label(m))
        ax.set_xlabel(f"PC 1 of the commands [{unit}]")
        ax.set_ylabel(f"PC 2 [{unit}]")
    if sc is not None:
        cb = fig.colorbar(sc, ax=list(axs), label="tip error [mm]" + (" (log scale)" if log else ""))
        cb.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: fmt(v)))
        cb.ax.yaxis.set_minor_formatter(NullFormatter())
    return ReportFigure("measured_residual_maps", "Held-out tip error over the input space", fig,
                        "Each held-out sample at its commands' coordinates along the two leading principal "
                        "components of all evaluated samples' commands (centred, not scaled; they carry "
                        f"{fmt(100 * share[0])} % and {fmt(100 * share[1])} % of the variance); colour: tip error, "
                        "one scale for every model" + (", logarithmic (the models' errors are far apart)." if log
                                                       else "."))


def _measured_vs_predicted(study: ResultSet, data) -> ReportFigure:
    fig = Figure(figsize=(10.0, 3.6))
    axs = fig.subplots(1, 3)
    for j, (ax, name) in enumerate(zip(axs, "xyz")):
        lo, hi = np.inf, -np.inf
        for m, d in data:
            if not d["measured"].size:
                continue
            x, y = 1e3 * d["measured"][:, j], 1e3 * d["predicted"][:, j]
            ax.scatter(x, y, s=12, color=model_color(m, study.models), label=model_label(m), alpha=0.8)
            lo, hi = min(lo, x.min(), y.min()), max(hi, x.max(), y.max())
        if np.isfinite(lo):
            ax.plot([lo, hi], [lo, hi], color="#999999", lw=0.8, ls="--")
        ax.set_xlabel(f"measured {name} [mm]")
        ax.set_ylabel(f"predicted {name} [mm]")
    axs[0].legend()
    fig.tight_layout()
    return ReportFigure("measured_vs_predicted", "Predicted vs measured tip position (held-out rows)", fig,
                        "Tip coordinates in the measurement frame; on the dashed diagonal a model predicts the "
                        "measurement exactly.")


def measurement_figures(study: ResultSet) -> list[ReportFigure]:
    """The three figures of the Measurements section (none when no model has held-out samples)."""
    data = [(m, d) for m, d in _samples(study) if d["error"].size]
    if not data:
        return []
    return [_error_vs_command(study, data), _residual_maps(study, data), _measured_vs_predicted(study, data)]
