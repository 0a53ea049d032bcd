"""Synthetic study folders in the layout the study runner writes (``_manifest.json`` with the spec under
``"study"``, a zero-row schema part, parts of that schema), read by the one loader
(:mod:`workbench.study.folder`).

The "cc" rows are exact constant-curvature arcs (closed form); the physics rows are the
same arc with a softened curvature plus the Euler-Bernoulli cantilever sag under a
uniform load of gravity parameter gamma = q L^3 / EI, so the CC error grows with both
gamma and the bending angle, as a real study would show.  Nothing here is physics to
trust; it only exercises the comparison and report code paths.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

L = 0.5
M = 33


def arc_points(kappa, L=L, m=M, phi=0.0):
    s = np.linspace(0.0, L, m)
    if abs(kappa) < 1e-12:
        r, z = np.zeros(m), s
    else:
        r, z = (1 - np.cos(kappa * s)) / kappa, np.sin(kappa * s) / kappa
    return s, np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def frame_from_backbone(p):
    t = p[-1] - p[-2]
    t = t / np.linalg.norm(t)
    # rotation taking +z to t about the axis z x t
    z = np.array([0.0, 0.0, 1.0])
    v = np.cross(z, t)
    c = float(z @ t)
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    R = np.eye(3) + vx + vx @ vx / (1 + c)
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p[-1]
    return T


def physics_points(theta, gamma, phi=0.0, soften=0.04):
    s, p = arc_points(theta / L * (1 - soften * theta), phi=phi)
    xi = s / L
    sag = gamma * L * xi**2 * (6 - 4 * xi + xi**2) / 24.0  # cantilever under uniform load
    p = p.copy()
    p[:, 0] -= sag
    return s, p


def _row(case_id, model, params, s, p, *, wall=0.01, tensions=(0.0, 0.0), extra=None):
    T = frame_from_backbone(p)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1).sum()
    row = {
        "case_id": case_id,
        "model": model,
        "status": "ok",
        "error": "",
        "wall_time": wall,
        **{f"p.{k}": v for k, v in params.items()},
        "robot_length": L,
        "tip_x": p[-1, 0],
        "tip_y": p[-1, 1],
        "tip_z": p[-1, 2],
        "tip_frame": T.reshape(-1).tolist(),
        "length_change": seg - L,
        "tip_twist": 0.0,
        "converged": True,
        "iterations": 5,
        "stations": s.tolist(),
        "positions": p.reshape(-1).tolist(),
        "tendon_tensions": list(tensions),
    }
    row.update(extra or {})
    return row


def _failed(case_id, model, params, reason):
    return {
        "case_id": case_id,
        "model": model,
        "status": "failed",
        "error": reason,
        "wall_time": 1.5,
        **{f"p.{k}": v for k, v in params.items()},
        "robot_length": L,
    }


def _cid(params):
    return hashlib.sha1(json.dumps(params, sort_keys=True).encode()).hexdigest()[:12]


def static_rows(params_list, models=("cc", "ancf", "spring_link"), phi=0.0):
    rows = []
    for params in params_list:
        cid = _cid(params)
        theta = float(params.get("load.bend_angle", 0.8))
        gamma = float(params.get("robot.gamma", 0.1))
        for model in models:
            if model == "cc":
                s, p = arc_points(theta / L, phi=phi)
            elif model == "ancf":
                s, p = physics_points(theta, gamma, phi=phi)
            else:
                s, p = physics_points(theta, gamma * 1.08, phi=phi, soften=0.05)
                s, p = s[::4], p[::4]  # spring-link reports fewer stations
            rows.append(_row(cid, model, params, s, p, tensions=(3.0 * theta, 0.0)))
    return rows


def dynamic_rows(models=("cc", "beam3d")):
    t = np.linspace(0.0, 2.0, 81)
    rows = []
    for delay in (0.0, 0.5):
        params = {"actuation.delay": delay, "load.bend_angle": 1.0}
        cid = _cid(params)
        for model in models:
            ramp = np.clip((t - 0.2) / 1.0, 0, 1)
            theta_t = 1.0 * np.clip((t - 0.2 - (delay if model != "cc" else 0)) / 1.0, 0, 1)
            tips = []
            for th in theta_t:
                _, p = arc_points(th / L) if model == "cc" else physics_points(th, 0.05)
                tips.append(p[-1])
            tips = np.array(tips)
            s, p = arc_points(theta_t[-1] / L) if model == "cc" else physics_points(theta_t[-1], 0.05)
            lc = (-0.01 * ramp if model == "cc" else -0.002 * theta_t)
            ten = np.column_stack([20 * ramp, 2 * ramp])
            lens = np.column_stack([-0.02 * ramp, 0.02 * ramp])
            extra = {
                "time": t.tolist(),
                "series.tip_position": tips.reshape(-1).tolist(),
                "series.tendon_tensions": ten.reshape(-1).tolist(),
                "series.tendon_lengths": lens.reshape(-1).tolist(),
                "series.length_change": lc.tolist(),
                "p.tendons.axial_stiffness": 4.0e4,
            }
            row = _row(cid, model, params, s, p, tensions=ten[-1], extra=extra)
            row["length_change"] = float(lc[-1])
            rows.append(row)
    return rows


def manifest(name, sweep, models, report=None):
    """A runner manifest: the resolved spec under ``"study"`` (sweep axes as a ``product`` block), provenance."""
    spec = {"study": {"name": name, "models": list(models)}, "sweep": {"product": sweep} if sweep else {}}
    if report:
        spec["report"] = report
    return {
        "study": spec,
        "config_hash": "3f2a9c01d4e5",
        "versions": {"workbench": "0.1.0", "exudyn": "1.13.6", "numpy": "2.4.6"},
        "git_commit": "0123456789abcdef0123456789abcdef01234567",
        "host": "testhost",
        "start_time": "2026-01-01T10:00:00+00:00",
        "end_time": "2026-01-01T10:03:25+00:00",
        # a URL in provenance must not leak into the report as a link
        "repository": "https://example.org/trunk-workbench.git",
    }


def write_parts(folder: Path, df: pd.DataFrame, n_parts: int = 2) -> None:
    """``df`` as the runner stores it: a zero-row schema part, then ``n_parts`` parts of that one schema."""
    schema = pa.Table.from_pandas(df, preserve_index=False).schema.remove_metadata()
    pq.write_table(schema.empty_table(), folder / "part-0000000000000000000-schema.parquet")
    step = -(-len(df) // n_parts)
    for i in range(n_parts):
        part = pa.Table.from_pandas(df.iloc[i * step:(i + 1) * step], schema=schema, preserve_index=False)
        pq.write_table(part, folder / f"part-1000000000000000000-1-{i:06d}.parquet")


def write_runner_study(folder: Path) -> Path:
    """A study folder in the exact layout of the study runner (branch ``study``):
    ``_manifest.json`` with the resolved spec under ``"study"``, sweep blocks, ``git`` and
    ``runs``; a zero-row schema part; full ``p.robot.*`` preset parameters per row."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    thetas, gammas = [0.5, 1.0, 2.0], [0.0, 1.0, 4.0]
    robot = {"preset": "steel_rod", "length": L, "n_sections": 2, "tendon_offset": 0.02, "tendon_stiffness": 4.0e4}
    rows = []
    for th in thetas:
        for g in gammas:
            params = {**{f"robot.{k}": v for k, v in robot.items()}, "load.bend_angle": th, "load.mode": "tension",
                      "load.tip_force": "[0.0,0.0,0.0]", "derived.gravity_parameter": g}
            rows += static_rows([params], models=("cc", "ancf"))
    df = pd.DataFrame(rows)
    df["robot_gravity"] = 9.81
    write_parts(folder, df, n_parts=1)
    man = {
        "study": {
            "study": {"name": "runner_layout", "description": "CC vs ANCF on a two-section rod", "seed": 1,
                      "models": ["cc", "ancf"], "max_cases": 100},
            "robot": robot, "load": {"mode": "tension", "bend_angle": 1.0}, "solver": {"n_stations": M},
            "derived": {"gravity_parameter": 0.0},
            "sweep": {"product": {"load.bend_angle": thetas, "derived.gravity_parameter": gammas}},
        },
        "study_file": "studies/runner_layout.toml",
        "config_hash": "a4720eb391b3b514",
        "n_cases": 9,
        "versions": {"python": "3.11.7", "exudyn": "1.13.6", "dask": None},
        "git": {"commit": "feedfacecafe", "dirty": True},
        "runs": [
            {"host": "hostA", "start": "2026-01-01T10:00:00+00:00", "end": "2026-01-01T10:01:00+00:00", "wall_time": 60.0},
            {"host": "hostB", "start": "2026-01-02T10:00:00+00:00", "end": "2026-01-02T10:00:30+00:00", "wall_time": 30.5},
        ],
    }
    (folder / "_manifest.json").write_text(json.dumps(man, indent=1))
    return folder


def write_study(folder: Path, kind: str) -> Path:
    """Write a synthetic study of ``kind`` in {"1d", "2d", "none", "dynamic", "single", "3d"}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    models = ("cc", "ancf", "spring_link")
    report = None
    if kind == "1d":
        thetas = np.linspace(0.1, 2.0, 8)
        plist = [{"load.bend_angle": float(t), "robot.gamma": 0.05} for t in thetas]
        rows = static_rows(plist)
        # one failed physics case
        rows = [r for r in rows if not (r["case_id"] == _cid(plist[3]) and r["model"] == "ancf")]
        rows.append(_failed(_cid(plist[3]), "ancf", plist[3], "Newton did not converge after 200 load steps"))
        sweep = {"load.bend_angle": [float(t) for t in thetas]}
    elif kind in ("2d", "3d"):
        thetas = np.linspace(0.1, 2.5, 7)
        gammas = np.geomspace(0.01, 3.0, 6)
        plist = [{"load.bend_angle": float(t), "robot.gamma": float(g)} for t in thetas for g in gammas]
        rows = static_rows(plist, phi=0.0 if kind == "2d" else 0.7)
        bad = _cid(plist[-1])
        rows = [r for r in rows if not (r["case_id"] == bad and r["model"] == "spring_link")]
        rows.append(_failed(bad, "spring_link", plist[-1], "ModelFailure: joint limit exceeded"))
        sweep = {"load.bend_angle": [float(t) for t in thetas], "robot.gamma": [float(g) for g in gammas]}
        report = {"axes": ["gamma", "kappaL"]}
    elif kind == "none":
        plist = [{"load.bend_angle": 1.2, "robot.gamma": 0.2}]
        rows = static_rows(plist)
        sweep = {}
    elif kind == "single":
        thetas = np.linspace(0.2, 1.5, 5)
        plist = [{"load.bend_angle": float(t)} for t in thetas]
        rows = static_rows(plist, models=("ancf",))
        models = ("ancf",)
        sweep = {"load.bend_angle": [float(t) for t in thetas]}
    elif kind == "dynamic":
        rows = dynamic_rows()
        models = ("cc", "beam3d")
        sweep = {"actuation.delay": [0.0, 0.5]}
    else:
        raise ValueError(kind)
    write_parts(folder, pd.DataFrame(rows))
    (folder / "_manifest.json").write_text(json.dumps(manifest(f"synthetic_{kind}", sweep, models, report), indent=1))
    return folder
