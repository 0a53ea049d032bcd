"""Golden CSV of a series-parallel study's result folder (regression tier).

``python -m tests.experiments.series_parallel.golden_csv <study.toml> <out.csv>`` runs the study into a temporary
folder and writes the rows sorted by (case_id, model) with the columns case_id, model, status,
tip_x, tip_y, tip_z, length_change, tip_twist and the deterministic ``x.*`` extras (timings left
out).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import pandas as pd

import numpy as np

CORE = ["case_id", "model", "status", "tip_x", "tip_y", "tip_z", "length_change", "tip_twist"]


def golden_frame(folder: str | Path) -> pd.DataFrame:
    """Golden form (as ``tests/regression/golden.py`` of the regression tier): key columns, scalar
    results, ``max_abs_position`` (largest distance of a backbone point from the base [m]), every
    ``x.*`` extra; numbers of failed rows blanked; sorted by (case_id, model)."""
    df = pd.read_parquet(Path(folder))
    out = df[CORE].copy()
    out["max_abs_position"] = [float(np.max(np.linalg.norm(np.asarray(v, float).reshape(-1, 3), axis=1)))
                               if v is not None and len(v) else float("nan") for v in df["positions"]]
    for c in sorted(c for c in df.columns if c.startswith("x.")):
        out[c] = pd.to_numeric(df[c], errors="coerce")
    out.loc[out["status"] != "ok", [c for c in out.columns if c not in ("case_id", "model", "status")]] = np.nan
    return out.sort_values(["case_id", "model"]).reset_index(drop=True)


def main(argv: list[str]) -> int:
    from workbench.experiments.series_parallel.kind import KIND
    from workbench.study.runner import run_cases

    study, csv = argv
    with tempfile.TemporaryDirectory() as tmp:
        run_cases(KIND, KIND.load(study), Path(tmp) / "run")
        golden_frame(Path(tmp) / "run").to_csv(csv, index=False, float_format="%.12e", lineterminator="\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
