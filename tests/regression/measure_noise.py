"""Measure the solver noise of the small studies (how tolerances.toml was chosen).

``python -m tests.regression.measure_noise [stem ...]`` runs each small study as committed and
with perturbed solver settings that should not change the physics: Newton tolerance 100x
tighter and 10x looser than the study's.  It prints, per result column, the largest absolute
and relative change over all ok rows.  Study kinds whose loaded study has no ``base`` solver
table (series_parallel, closed_loop) are perturbed in their study file: the tolerance keys of
:data:`FILE_TOLERANCES` are written into its ``[solver]`` table, 100x tighter and 10x looser than
the kind's default.  ``--save DIR`` keeps every run's golden-form table (per-row changes, e.g. of
step counts).  How the tolerances follow from the changes: the header of ``tolerances.toml``.
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


def _save(directory: str | None, stem: str, run: str, frame: pd.DataFrame) -> None:
    """Write ``frame`` to ``directory/<stem>.<run>.csv`` when ``directory`` is given."""
    if directory:
        Path(directory).mkdir(parents=True, exist_ok=True)
        frame.to_csv(Path(directory) / f"{stem}.{run}.csv", index=False, float_format="%.12e")


#: Solver tolerance keys (and their defaults) of the study kinds perturbed in their study file.
FILE_TOLERANCES = {
    "series_parallel": {"length_tolerance": 1e-10, "fk_tolerance": 1e-10},  # experiments/series_parallel/spec.py
    "closed_loop": {"newton_tolerance": 1e-9},  # the SolverOptions default (the study file states none)
}


def with_file_tolerances(path: Path, factor: float, out: Path) -> Path:
    """A copy of the study file ``path`` at ``out`` with its kind's tolerance keys times ``factor`` in ``[solver]``."""
    import tomllib

    from workbench.study import kind_of

    text = path.read_text()
    solver = tomllib.loads(text).get("solver", {})
    keys = {k: solver.get(k, v) * factor for k, v in FILE_TOLERANCES[kind_of(path)].items()}
    lines = [ln for ln in text.splitlines() if ln.split("=")[0].strip() not in keys]
    at = next(i for i, ln in enumerate(lines) if ln.strip() == "[solver]") + 1
    lines[at:at] = [f"{k} = {v!r}" for k, v in keys.items()]
    out.write_text("\n".join(lines) + "\n")
    return out


def _main_file(p: Path, kind, save: str | None) -> None:
    """Perturb a study kind without a ``base`` solver table in its study file (:data:`FILE_TOLERANCES`)."""
    from workbench.study import kind_of

    if kind_of(p) not in FILE_TOLERANCES:
        print(f"== {p.stem}: skipped (no [solver] tolerance known to perturb for its study kind)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        ref = _run(kind, kind.load(str(p)), Path(tmp) / "ref")
        _save(save, p.stem, "ref", ref)
        ids = [c.case_id for c in kind.expand(kind.load(str(p)))]
        for name, factor in (("tolerances x 0.01", 1e-2), ("tolerances x 10", 10.0)):
            q = with_file_tolerances(p, factor, Path(tmp) / f"{p.stem}.toml")
            spec = kind.load(str(q))
            # the case ids hash the solver settings: same cases by expansion order
            remap = dict(zip((c.case_id for c in kind.expand(spec)), ids, strict=True))
            other = _run(kind, spec, Path(tmp) / name.replace(" ", "_"))
            other = other.assign(case_id=other["case_id"].map(remap)).sort_values(["case_id", "model"])
            _save(save, p.stem, name.replace(" ", "_"), other)
            print(f"== {p.stem}: {name}")
            print(max_changes(ref, other).to_string(index=False, float_format=lambda v: f"{v:.3g}"))


def main(argv: list[str] | None = None) -> int:
    from workbench.study import get_kind, kind_of

    ap = argparse.ArgumentParser(prog="python -m tests.regression.measure_noise")
    ap.add_argument("stems", nargs="*")
    ap.add_argument("--save", metavar="DIR", help="also write each run's golden-form table to DIR/<stem>.<run>.csv "
                    "(per-row changes, e.g. of step counts)")
    args = ap.parse_args(argv)
    paths = [STUDIES_DIR / f"{s}.toml" for s in args.stems] if args.stems else small_study_paths()
    pd.set_option("display.width", 160)
    for p in paths:
        kind = get_kind(kind_of(p))
        study = kind.load(str(p))
        if not hasattr(study, "base"):
            _main_file(p, kind, args.save)
            continue
        tol = study.base["solver"]["newton_tolerance"]
        with tempfile.TemporaryDirectory() as tmp:
            ref = _run(kind, study, Path(tmp) / "ref")
            _save(args.save, p.stem, "ref", ref)
            for name, kw in (("newton_tolerance x 0.01", {"newton_tolerance": tol * 1e-2}),
                             ("newton_tolerance x 10", {"newton_tolerance": tol * 10})):
                s2 = with_solver(study, **kw)
                other = remap_case_ids(_run(kind, s2, Path(tmp) / name.replace(" ", "_")), s2, study)
                _save(args.save, p.stem, name.replace(" ", "_"), other)
                print(f"== {p.stem}: {name}")
                print(max_changes(ref, other).to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
