"""Regression tier: run the small studies and compare them with committed golden tables.

Layout (shared by every study):

* ``tests/regression/studies/<stem>.toml`` -- small version of ``studies/<stem>.toml`` (a few cases);
* ``tests/regression/golden/<stem>.csv`` -- golden table, one row per (case_id, model), sorted,
  columns ``case_id, model, status`` + the scalar results (:data:`RESULT_COLUMNS` and every
  ``x.*`` extra present);
* ``tests/regression/tolerances.toml`` -- ``[default]`` and optional ``[<stem>]`` tables mapping a
  column to ``{ abs = ..., rel = ... }``; a value passes when
  ``|got - expected| <= abs + rel * |expected|``.

Re-blessing (deliberate, with the reason in the commit message): ``python -m tests.regression.bless``.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import pandas as pd

__all__ = [
    "REGRESSION_DIR", "STUDIES_DIR", "GOLDEN_DIR", "TOLERANCES_FILE", "KEY_COLUMNS", "RESULT_COLUMNS",
    "run_small_study", "run_study_object", "golden_frame", "compare_to_golden", "load_tolerances",
    "tolerances_for", "read_golden", "write_golden", "small_study_paths",
]

REGRESSION_DIR = Path(__file__).resolve().parent
STUDIES_DIR = REGRESSION_DIR / "studies"
GOLDEN_DIR = REGRESSION_DIR / "golden"
TOLERANCES_FILE = REGRESSION_DIR / "tolerances.toml"

KEY_COLUMNS = ("case_id", "model", "status")
RESULT_COLUMNS = ("tip_x", "tip_y", "tip_z", "length_change", "tip_twist", "max_abs_position")
_FLOAT_FORMAT = "%.12e"


#: Small studies too slow for the default run (stem -> why): their regression and browser tests are
#: marked ``slow`` (``pytest -m slow`` or ``-m regression`` runs them).
SLOW_SMALL_STUDIES = {
    "wire_delay_arm": "beam3d dynamics of the three-section arm: 60-170 s even at regression size",
}


def small_study_paths() -> list[Path]:
    """The small studies, sorted by stem."""
    return sorted(STUDIES_DIR.glob("*.toml"))


def run_study_object(study, out_dir: str | Path) -> pd.DataFrame:
    """Run a loaded :class:`workbench.study.Study` in-process (serial) into ``out_dir``; raw table."""
    from workbench.study import RunConfig, SerialExecutor, read_table, run_study

    out = Path(out_dir)
    run_study(study, out, SerialExecutor(), RunConfig(progress=False))
    return read_table(out)


def run_small_study(path: str | Path, out_dir: str | Path) -> pd.DataFrame:
    """Run the small study at ``path`` into ``out_dir`` (must not hold results); golden-form table."""
    from workbench.study import RunConfig, SerialExecutor, get_kind, kind_of, read_table, run_cases

    kind = get_kind(kind_of(path))  # the study's kind ([study] kind), as the CLI chooses it
    run_cases(kind, kind.load(str(path)), Path(out_dir), SerialExecutor(), RunConfig(progress=False))
    return golden_frame(read_table(out_dir))


def _max_abs_position(cell: Any) -> float:
    if cell is None or (isinstance(cell, float) and math.isnan(cell)):
        return float("nan")
    a = np.asarray(cell, dtype=float).reshape(-1, 3)
    return float(np.max(np.linalg.norm(a, axis=1))) if a.size else float("nan")


def golden_frame(df: pd.DataFrame) -> pd.DataFrame:
    """Reduce a result table to the golden form: key columns + scalar results, sorted.

    ``max_abs_position`` is the largest distance of a backbone point from the base [m] (a
    summary of the whole backbone, not only the tip).  Failed rows keep NaN results.
    """
    missing = [c for c in ("case_id", "model", "status") if c not in df.columns]
    if missing:
        raise ValueError(f"result table lacks column(s) {missing}; expected a workbench study table")
    out = pd.DataFrame({
        "case_id": df["case_id"].astype(str),
        "model": df["model"].astype(str),
        "status": df["status"].astype(str),
    })
    for c in RESULT_COLUMNS[:-1]:
        out[c] = pd.to_numeric(df[c], errors="coerce") if c in df.columns else np.nan
    out["max_abs_position"] = [_max_abs_position(v) for v in df["positions"]] if "positions" in df.columns else np.nan
    for c in sorted(c for c in df.columns if str(c).startswith("x.")):
        out[c] = pd.to_numeric(df[c], errors="coerce")
    # a failed row's numbers are not results
    out.loc[out["status"] != "ok", [c for c in out.columns if c not in KEY_COLUMNS]] = np.nan
    return out.sort_values(["case_id", "model"]).reset_index(drop=True)


def write_golden(frame: pd.DataFrame, path: str | Path) -> None:
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    frame.to_csv(path, index=False, float_format=_FLOAT_FORMAT, lineterminator="\n")


def read_golden(path: str | Path) -> pd.DataFrame:
    return pd.read_csv(path, dtype={"case_id": str, "model": str, "status": str}, keep_default_na=True)


def load_tolerances(path: str | Path = TOLERANCES_FILE) -> dict[str, dict[str, dict[str, float]]]:
    """``{table: {column: {"abs": a, "rel": r, ...}}}``; every entry checked (finite, >= 0).

    An entry may also carry the measured ``noise`` / ``rel_noise`` it was derived from
    (``derive_tolerances.py``); they are kept and do not enter the comparison.
    """
    with open(path, "rb") as f:
        raw = tomllib.load(f)
    if "default" not in raw:
        raise ValueError(f"{path}: needs a [default] table of column tolerances")
    out: dict[str, dict[str, dict[str, float]]] = {}
    for table, cols in raw.items():
        if not isinstance(cols, dict):
            raise ValueError(f"{path}: [{table}] must be a table of column = {{ abs = ..., rel = ... }}")
        out[table] = {}
        for col, tol in cols.items():
            if not isinstance(tol, dict) or set(tol) - {"abs", "rel", "noise", "rel_noise"} or not set(tol) & {"abs", "rel"}:
                raise ValueError(f"{path}: [{table}].{col} must be {{ abs = ..., rel = ..., noise = ... }}, got {tol!r}")
            t = {"abs": float(tol.get("abs", 0.0)), "rel": float(tol.get("rel", 0.0)),
                 **{k: float(tol[k]) for k in ("noise", "rel_noise") if k in tol}}
            if not all(math.isfinite(v) and v >= 0 for v in t.values()):
                raise ValueError(f"{path}: [{table}].{col}: tolerances must be finite and >= 0, got {tol!r}")
            out[table][col] = t
    return out


def tolerances_for(stem: str, tolerances: Mapping[str, Mapping[str, Mapping[str, float]]]
                   ) -> dict[str, dict[str, float]]:
    """The ``[default]`` table overridden column-wise by ``[<stem>]``."""
    merged = {c: dict(t) for c, t in tolerances.get("default", {}).items()}
    for c, t in tolerances.get(stem, {}).items():
        merged[c] = dict(t)
    return merged


def compare_to_golden(df: pd.DataFrame, golden: pd.DataFrame,
                      tolerances: Mapping[str, Mapping[str, float]]) -> list[str]:
    """Mismatches between a golden-form table ``df`` and the ``golden`` one, one line each.

    ``tolerances`` maps column -> ``{"abs": a, "rel": r}`` (see :func:`tolerances_for`).  A numeric
    column of the golden without a tolerance is itself a problem (every column is checked).
    NaN equals NaN (failed rows); NaN against a number is a mismatch.
    """
    problems: list[str] = []
    key = ["case_id", "model"]
    for name, t in (("result", df), ("golden", golden)):
        dup = t.duplicated(key)
        if dup.any():
            problems.append(f"{name} table has duplicate (case_id, model) rows: "
                            + ", ".join(f"{r.case_id}/{r.model}" for r in t[dup].itertuples()))
    if problems:
        return problems
    a = df.set_index(key)
    g = golden.set_index(key)
    for k in g.index.difference(a.index):
        problems.append(f"{k[0]} {k[1]}: missing row (in golden, not in result)")
    for k in a.index.difference(g.index):
        problems.append(f"{k[0]} {k[1]}: extra row (in result, not in golden)")
    value_cols = [c for c in g.columns if c != "status"]
    for c in [c for c in a.columns if c not in g.columns]:
        problems.append(f"column {c}: in result, not in golden")
    for c in value_cols:
        if c not in a.columns:
            problems.append(f"column {c}: in golden, not in result")
        elif c not in tolerances:
            problems.append(f"column {c}: no tolerance in tolerances.toml (add one, chosen from measured noise)")
    common = g.index.intersection(a.index)
    for k in common:
        sa, sg = str(a.at[k, "status"]), str(g.at[k, "status"])
        if sa != sg:
            problems.append(f"{k[0]} {k[1]} status: got {sa!r}, expected {sg!r}")
            continue
        for c in value_cols:
            if c not in a.columns or c not in tolerances:
                continue
            got, exp = float(a.at[k, c]), float(g.at[k, c])
            tol = tolerances[c]["abs"] + tolerances[c]["rel"] * abs(exp) if math.isfinite(exp) else 0.0
            if math.isnan(got) and math.isnan(exp):
                continue
            if not (math.isfinite(got) and math.isfinite(exp)) or abs(got - exp) > tol:
                problems.append(f"{k[0]} {k[1]} {c}: got {got:.12g}, expected {exp:.12g}, "
                                f"|diff| {abs(got - exp):.3g} > tolerance {tol:.3g} "
                                f"(abs {tolerances[c]['abs']:g} + rel {tolerances[c]['rel']:g})")
    return problems
