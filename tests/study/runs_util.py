"""Helpers of the run-robustness tests: the fake 30-case study and its CLI command lines.

``KILL_STUDY`` runs 30 cases of two fake models (``study_fakes``; the 13 N cases raise, by
design) through the CLI; :func:`cli_args` builds a ``workbench run`` command line with the
20 ms fake models, :func:`env` the environment that finds ``study_fakes``, :func:`same_table`
compares two stored tables cell by cell (wall times aside).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pandas as pd

HERE = Path(__file__).parent
ROOT = HERE.parents[1]

KILL_STUDY = """\
[study]
name = "killme"
models = ["cc", "ancf"]

[robot]
preset = "steel_rod"

[load]
mode = "tension"
tensions = [1.0, 0.0]

[solver]
n_stations = 5

[sweep]
product = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0], [13.0, 0.0], [6.0, 0.0]], "robot.length" = [0.5, 0.6, 0.7, 0.8, 0.9] }
"""


def env(**extra: str) -> dict[str, str]:
    e = dict(os.environ)
    e["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(HERE), e.get("PYTHONPATH", "")])
    e.update(extra)
    return e


def cli_args(study_path: Path, out: Path, *extra: str, lookup: str = "study_fakes:lookup_spin_20ms",
             in_process: bool = True) -> list[str]:
    return [sys.executable, str(HERE / "fake_workbench.py"), lookup, "run", str(study_path), "--out", str(out),
            *(["--in-process"] if in_process else []), "--no-report", "--progress", "off", "--flush-rows", "4", *extra]


def canon(df: pd.DataFrame) -> pd.DataFrame:
    df = df.drop(columns=["wall_time"]).sort_values(["case_id", "model"]).reset_index(drop=True)
    return df[sorted(df.columns)]


def same_table(a: pd.DataFrame, b: pd.DataFrame) -> bool:
    a, b = canon(a), canon(b)
    return list(a.columns) == list(b.columns) and len(a) == len(b) and all(
        a[c].map(repr).tolist() == b[c].map(repr).tolist() for c in a.columns)


def parts(folder: Path) -> list[Path]:
    return [p for p in folder.glob("part-*.parquet") if "schema" not in p.name] if folder.exists() else []
