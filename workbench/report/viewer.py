"""Data of the report's interactive 3-D view: every case's backbones, all models overlaid.

:func:`viewer_scenes` turns the ok rows into the JSON that ``assets/viewer.js`` draws: per case
the models' backbones in the report's frame (world by default), over time for dynamic cases
(the stored ``series.backbone`` frames; the final shape otherwise), the disks and tendon
routing of the case's robot (:func:`.scene.case_scene`, drawn on the backbone of the case's
:func:`disk_model`: the first physics model, whatever the report's reference is), gravity, and the extra polylines a
study kind registers (its ``lines`` hook, :mod:`.kind_hooks`).  Coordinates are rounded to 1 µm to
keep the page small.  The viewer is a small vendored canvas script (no library, no network):
an orthographic view of a few polylines needs nothing more, and it keeps every report one
offline file of modest size.  A calibration study's view (:func:`measured_scenes`) draws the
models' predicted backbones of its ``view.*`` held-out samples and the measured points as markers.  Checked by ``tests/report/test_viewer.py`` and the browser tests.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..compare.table import array_cell, row_positions
from .kind_hooks import kind_hook
from .load import ResultSet, numeric
from .measurements import cell, fit_summaries, is_calibration, points
from .scene import base_vectors_in, case_scene, gravity_in, to_frame
from .shapes import backbone_frames
from .style import case_title, model_color, model_label

__all__ = ["MAX_VIEWER_CASES", "NOT_PHYSICS", "disk_model", "measured_scenes", "viewer_scenes"]

#: cases the viewer carries at most (in canonical order); more are left out with a note
MAX_VIEWER_CASES = 400


#: Row models that are not a physics backbone (CC predictions, commanded targets, controller plans).
NOT_PHYSICS = ("cc", "cc_fit", "target", "plan", "cc_closed_loop")


def disk_model(models) -> str | None:
    """The model whose backbone carries the disks and tendons in the 3-D view: the first physics model.

    ``models`` in the report's model order; the first not in :data:`NOT_PHYSICS`, else the first
    model (a study of CC models only), ``None`` for none.  The report's reference model plays no
    part: with a physics reference (e.g. ``beam3d``) and ``cc`` listed first, the disks still sit
    on the first physics model's backbone, as the caption (:func:`.sections.viewer_section`) says.
    Checked by ``tests/report/test_viewer.py``.
    """
    models = [str(m) for m in models]
    physics = [m for m in models if m not in NOT_PHYSICS]
    return physics[0] if physics else (models[0] if models else None)


def _r(a) -> list:
    return np.round(np.asarray(a, dtype=float), 6).tolist()


def _model_frames(row: dict, scene, frame: str) -> tuple[list, np.ndarray] | None:
    """``([[t, points], ...], all points)`` of one model row in ``frame``."""
    fr = backbone_frames(row)
    if fr is not None:
        t, P = fr
        W = to_frame(P, scene, frame)
        return [[float(ti), _r(Wi)] for ti, Wi in zip(t, W)], W.reshape(-1, 3)
    bp = row_positions(row)
    if bp is None:
        return None
    tt = array_cell(row.get("time"))
    W = to_frame(bp[1], scene, frame)
    return [[float(tt[-1]) if tt is not None and tt.size else 0.0, _r(W)]], W


def _case(study: ResultSet, cid: str, rows: dict[str, dict], lines=None) -> dict[str, Any] | None:
    row0 = next(iter(rows.values()))
    scene = case_scene(row0)
    models, pts = {}, []
    for m, r in rows.items():
        got = _model_frames(r, scene, study.frame)
        if got is None:
            continue
        frames, P = got
        pts.append(P)
        stations = array_cell(r.get("stations"))
        models[m] = {"label": model_label(m), "color": model_color(m, study.models), "reference": m == study.baseline,
                     "stations": _r(stations) if stations is not None else [], "frames": frames}
    if not models:
        return None
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    base = to_frame(np.zeros(3), scene, study.frame)
    L = float(row0.get("robot_length") or 0.0) or float(np.linalg.norm(hi - lo)) or 1.0
    main = disk_model([m for m in study.models if m in models] + [m for m in models if m not in study.models])
    extra = _extra_lines(lines(rows) if lines is not None else [], scene, study.frame)
    return {
        "id": str(cid), "title": case_title(row0, study.axes, study.labels) + f"  [{str(cid)[:8]}]",
        "L": L, "extent": float(max(np.max(np.maximum(hi, base) - np.minimum(lo, base)), 1e-3 * L)), "center": _r(0.5 * (np.minimum(lo, base) + np.maximum(hi, base))), "base": _r(base),
        "gravity": _r(gravity_in(scene, study.frame)), "main": main,
        "e0": _r(base_vectors_in([1.0, 0.0, 0.0], scene, study.frame)),
        "disks": [[float(s), float(r)] for s, r in zip(scene.disk_s, scene.disk_radius) if r > 0],
        "tendons": [list(map(float, t)) for t in scene.tendons],
        "models": models, "lines": extra,
    }


def _extra_lines(lines: list, scene, frame: str) -> list:
    """``[[color, points], ...]``: the kind's ``(model, (k, n, 3) base-frame points)`` in ``frame``, model colours."""
    out = []
    for m, P in lines:
        out += [[model_color(m), _r(line)] for line in to_frame(P, scene, frame)]
    return out


def _measured_view(study: ResultSet) -> dict[int, dict[str, Any]]:
    """Per ``view.file_row`` of a calibration study: each model's predicted backbone and tip, the measured tip
    and measured backbone points (measurement frame) -- from each model's first successful fold."""
    out: dict[int, dict[str, Any]] = {}
    for s in fit_summaries(study):
        r = s.first
        rows = cell(r.get("view.file_row")).astype(int) if r is not None else np.zeros(0, int)
        if not rows.size:
            continue
        P, MB = points(r.get("view.positions"), rows.size), points(r.get("view.measured_backbone"), rows.size)
        srow = cell(r.get("sample.file_row")).astype(int)
        meas, pred = points(r.get("sample.measured")), points(r.get("sample.predicted"))
        for i, fr in enumerate(rows):
            c = out.setdefault(int(fr), {"models": {}, "tip": None, "backbone": None, "errors": {}})
            c["models"][s.model] = P[i]
            hit = np.nonzero(srow == fr)[0]
            if hit.size and len(meas) == srow.size == len(pred):
                c["tip"] = meas[hit[0]]
                c["errors"][s.model] = float(np.linalg.norm(pred[hit[0]] - meas[hit[0]]))
            if MB.shape[1]:
                c["backbone"] = MB[i]
    return out


def measured_scenes(study: ResultSet) -> dict[str, Any]:
    """The 3-D view of a calibration study: per held-out ``view.*`` sample the models' predicted backbones and
    the measured tip (and backbone points) as markers, in the measurement frame (``assets/viewer.js``)."""
    cases = []
    lengths = numeric(study.ok["robot_length"]) if "robot_length" in study.ok else np.zeros(0)
    L0 = float(lengths[np.isfinite(lengths)][0]) if np.isfinite(lengths).any() else 0.0
    for fr, c in sorted(_measured_view(study).items()):
        markers = []
        if c["tip"] is not None:
            markers.append({"label": "measured tip", "color": "#000000", "size": 7, "points": [_r(c["tip"])]})
        if c["backbone"] is not None and len(c["backbone"]):
            markers.append({"label": "measured backbone", "color": "#e6007e", "size": 5, "points": _r(c["backbone"])})
        allp = np.vstack([*c["models"].values(), *[np.asarray(m["points"]) for m in markers]])
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        base = next(iter(c["models"].values()))[0]
        L = L0 or float(np.ptp(allp, axis=0).max()) or 1.0
        err = ", ".join(f"{model_label(m)} {1e3 * e:.3g} mm" for m, e in c["errors"].items())
        cases.append({
            "id": f"row-{fr}", "title": f"held-out file row {fr}" + (f" · tip error {err}" if err else ""),
            "L": L, "extent": float(max(np.max(hi - lo), 1e-3 * L)), "center": _r(0.5 * (lo + hi)), "base": _r(base),
            "gravity": [0.0, 0.0, 0.0], "note": "measurement frame (gravity not drawn)", "main": None,
            "e0": [1.0, 0.0, 0.0], "disks": [], "tendons": [], "lines": [], "markers": markers,
            "models": {m: {"label": model_label(m), "color": model_color(m, study.models),
                           "reference": m == study.baseline, "stations": [], "frames": [[0.0, _r(P)]]}
                       for m, P in c["models"].items()},
        })
    return {"frame": "measurement", "cases": cases, "left_out": 0}


def viewer_scenes(study: ResultSet) -> dict[str, Any]:
    """``{"frame", "cases": [...], "left_out": n}`` for ``assets/viewer.js`` (ok rows, canonical order);
    a calibration study's view is :func:`measured_scenes`."""
    if is_calibration(study):
        return measured_scenes(study)
    ok = study.ok
    ids = list(dict.fromkeys(ok["case_id"]))
    hook = kind_hook(study.spec, "lines")
    lines = hook(study) if hook is not None else None
    cases = []
    for cid in ids[:MAX_VIEWER_CASES]:
        rows = {str(r["model"]): r.to_dict() for _, r in ok[ok["case_id"] == cid].iterrows()}
        c = _case(study, cid, rows, lines)
        if c is not None:
            cases.append(c)
    return {"frame": study.frame, "cases": cases, "left_out": max(0, len(ids) - MAX_VIEWER_CASES)}
