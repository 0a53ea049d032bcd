"""Measure the solver noise of the small studies (how tolerances.toml was chosen).

``python -m tests.regression.measure_noise [stem ...]`` runs each small study as committed and
with perturbed solver settings that should not change the physics: Newton tolerance 100x
tighter and 10x looser than the study's.  It prints, per result column, the largest absolute
and relative change over all ok rows.  The tolerances are ~10x the largest observed change
(and far below the effect of a 1 % Young's-modulus change, see test_sensitivity.py).
"""

from __future__ import annotations

import argparse
import copy
import dataclasses
import tempfile
from pathlib import Path

import pandas as pd

from .golden import KEY_COLUMNS, STUDIES_DIR, golden_frame, small_study_paths


def with_solver(study, **solver):
    """Copy of ``study`` with solver options changed (new case ids)."""
    base = copy.deepcopy(study.base)
    base["solver"].update(solver)
    return dataclasses.replace(study, base=base)


def remap_case_ids(frame: pd.DataFrame, study_from, study_to) -> pd.DataFrame:
    """Rename the case ids of ``study_from``'s cases to those of the same cases (by sweep index) of ``study_to``."""
    from workbench.study import expand

    ids = {a.case_id: b.case_id for a, b in zip(expand(study_from), expand(study_to), strict=True)}
    out = frame.copy()
    out["case_id"] = out["case_id"].map(ids)
    return out.sort_values(["case_id", "model"]).reset_index(drop=True)


def max_changes(a: pd.DataFrame, b: pd.DataFrame) -> pd.DataFrame:
    key = ["case_id", "model"]
    m = a.merge(b, on=key, suffixes=("", "_b"))
    m = m[(m["status"] == "ok") & (m["status_b"] == "ok")]
    rows = []
    for c in [c for c in a.columns if c not in KEY_COLUMNS]:
        d = (m[c] - m[c + "_b"]).abs()
        rel = d / m[c].abs().where(m[c].abs() > 0)
        rows.append({"column": c, "max_abs_change": d.max(), "max_rel_change": rel.max(),
                     "max_abs_value": m[c].abs().max()})
    return pd.DataFrame(rows)


def _run(kind, study, out: Path) -> pd.DataFrame:
    """Run ``study`` with its kind's pipeline (serial, in-process) into ``out``; golden-form table."""
    from workbench.study import RunConfig, SerialExecutor, read_table, run_cases

    run_cases(kind, study, out, SerialExecutor(), RunConfig(progress=False))
    return golden_frame(read_table(out))


def main(argv: list[str] | None = None) -> int:
    from workbench.study import get_kind, kind_of

    ap = argparse.ArgumentParser(prog="python -m tests.regression.measure_noise")
    ap.add_argument("stems", nargs="*")
    args = ap.parse_args(argv)
    paths = [STUDIES_DIR / f"{s}.toml" for s in args.stems] if args.stems else small_study_paths()
    pd.set_option("display.width", 160)
    for p in paths:
        kind = get_kind(kind_of(p))
        study = kind.load(str(p))
        if not hasattr(study, "base"):
            print(f"== {p.stem}: skipped (its study kind has no [solver] newton_tolerance to perturb)")
            continue
        tol = study.base["solver"]["newton_tolerance"]
        with tempfile.TemporaryDirectory() as tmp:
            ref = _run(kind, study, Path(tmp) / "ref")
            for name, kw in (("newton_tolerance x 0.01", {"newton_tolerance": tol * 1e-2}),
                             ("newton_tolerance x 10", {"newton_tolerance": tol * 10})):
                s2 = with_solver(study, **kw)
                other = remap_case_ids(_run(kind, s2, Path(tmp) / name.replace(" ", "_")), s2, study)
                print(f"== {p.stem}: {name}")
                print(max_changes(ref, other).to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
