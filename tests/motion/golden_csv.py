"""Golden CSV of a motion-study result folder (regression tier).

``python -m tests.motion.golden_csv <study.toml> <out.csv>`` runs the study into a temporary
folder and writes the rows sorted by (case_id, model) with the columns case_id, model, status,
tip_x, tip_y, tip_z, length_change, tip_twist and the deterministic ``x.*`` extras (timings left
out).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import pandas as pd

CORE = ["case_id", "model", "status", "tip_x", "tip_y", "tip_z", "length_change", "tip_twist"]


def golden_frame(folder: str | Path) -> pd.DataFrame:
    df = pd.read_parquet(Path(folder))
    extras = sorted(c for c in df.columns if c.startswith("x.") and "wall_time" not in c)
    out = df[CORE + extras].sort_values(["case_id", "model"], kind="stable").reset_index(drop=True)
    return out


def main(argv: list[str]) -> int:
    from workbench.motion import run_motion_study

    study, csv = argv
    with tempfile.TemporaryDirectory() as tmp:
        run_motion_study(study, Path(tmp) / "run")
        golden_frame(Path(tmp) / "run").to_csv(csv, index=False, float_format="%.17g")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
