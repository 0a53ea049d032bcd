"""Derive ``tolerances.toml`` from measured solver noise: the tolerance rule as code.

``python -m tests.regression.measure_noise --save DIR [stem ...]`` reruns each small study with its
solver tolerances 100x tighter and 10x looser and keeps the three golden-form tables;
``python -m tests.regression.derive_tolerances DIR`` then writes ``tests/regression/tolerances.toml``
from them and the committed goldens (``--check`` only prints what would change).  The rule is
:data:`RULE` (also the file's header); :func:`column_tolerance` applies it to one column and
``tests/regression/test_tolerances.py`` checks the committed file against the goldens.
"""

from __future__ import annotations

import argparse
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from .golden import GOLDEN_DIR, KEY_COLUMNS, TOLERANCES_FILE, read_golden, small_study_paths

__all__ = ["RULE", "FLOOR", "MULTIPLES", "COUNT_SLACK", "is_count", "floor_of", "guarded", "count_slack", "round_up2",
           "ColumnTolerance", "column_tolerance", "main"]

#: Round-off floor of a float column, relative to its scale ``max(1, largest |golden value|)`` (SI units).
FLOOR = 1e-12
#: Multiples of the measured noise tried in turn (the first that stays below every guarded value is used).
MULTIPLES = (10.0, 5.0, 2.0)
#: A count that changed under the perturbations gets this fraction of its smallest golden value as slack (at
#: least 1); one that did not change compares exactly.
COUNT_SLACK = 0.1
_COUNT = re.compile(r"(steps|iterations|solves|halvings|n_links|n_elements|dimension|held|saturated|pull_end|"
                    r"pull_peak_resolved)$")

RULE = f"""\
# Per-column tolerances of the regression tier: a value passes when |got - expected| <= abs + rel * |expected|.
# [default] applies to every study; a [<stem>] table sets columns for one study.  Written by
# python -m tests.regression.derive_tolerances from measured noise -- edit the rule there, not here.
#
# The rule (tests/regression/derive_tolerances.py; tests/regression/test_tolerances.py checks it):
# * noise = the largest change of the column over the study's ok rows when the small study is rerun
#   with its solver tolerances 100x tighter and 10x looser (python -m tests.regression.measure_noise
#   --save DIR; newton_tolerance, or length_tolerance / fk_tolerance of series_parallel) and between
#   the unperturbed rerun and the committed golden (series_parallel is not bit-reproducible), stored
#   with each entry as `noise` (absolute) and, for relative entries, `rel_noise`;
# * floor = {FLOOR:g} x max(1, largest |golden value| of the column): round-off across CPUs / BLAS builds;
# * a float column gets abs = k x noise (never below the floor), rounded up to 2 digits, with the first
#   k of {', '.join(f'{k:g}' for k in MULTIPLES)} that keeps the tolerance below every guarded golden value; where an
#   absolute tolerance would reach a small value of the column, rel = k x the largest relative change
#   (abs = floor) is tried at the same k first; a k below 10 is named in the entry's comment (noise-limited);
# * guarded values: golden ok values with |v| > max(noise, floor); smaller ones are zeros within the
#   noise (e.g. the out-of-plane coordinates of planar cases), bounded by the tolerance.  Solver residuals
#   (x.ik_residual, x.fk_residual, x.release_residual) are such values: a residual is wherever the
#   iteration stopped below its tolerance, so it moves with the tolerance by its own size; the entry
#   bounds it (|got - expected| <= 10 x that change) rather than reproducing it;
# * counts (steps, iterations, solves, ...) compare exactly when the perturbations did not change them;
#   iteration counts that did (they follow the tolerance) get slack = {COUNT_SLACK:g} x their smallest golden
#   value (at least 1): at a fixed tolerance another machine's round-off moves them by an odd iteration,
#   not by the change a 100x tighter tolerance makes (stored as `noise`).
# A tolerance must stay below every golden value it guards: test_tolerances.py fails otherwise (after a
# re-bless that moves a golden, re-measure and re-derive rather than widen by hand).
"""


def is_count(column: str) -> bool:
    """True for integer counters (compared exactly or with a measured slack)."""
    return bool(_COUNT.search(column))


def floor_of(values) -> float:
    """The round-off floor :data:`FLOOR` ``x max(1, max |values|)``."""
    v = np.abs(np.asarray(values, dtype=float))
    v = v[np.isfinite(v)]
    return FLOOR * max(1.0, float(v.max()) if v.size else 0.0)


def guarded(values, noise: float, column: str) -> np.ndarray:
    """The golden values a tolerance must stay below: ``|v| > max(noise, floor)`` (counts: ``v != 0``)."""
    v = np.abs(np.asarray(values, dtype=float))
    v = v[np.isfinite(v)]
    if is_count(column):
        return v[v > 0]
    return v[v > max(noise, floor_of(v))]


def count_slack(noise: float, guarded_counts) -> float:
    """The slack of a count: 0 if it did not change (``noise == 0``), else
    ``max(1, floor(COUNT_SLACK x smallest guarded count))``."""
    g = np.asarray(guarded_counts, float)
    if noise == 0 or not g.size:
        return 0.0
    return float(max(1, math.floor(COUNT_SLACK * g.min())))


def round_up2(x: float) -> float:
    """``x`` rounded up to two significant digits."""
    if x <= 0 or not math.isfinite(x):
        return 0.0
    e = math.floor(math.log10(x)) - 1
    return math.ceil(x / 10.0**e - 1e-9) * 10.0**e


@dataclass(frozen=True)
class ColumnTolerance:
    """One derived entry: ``abs``, ``rel``, the measured ``noise`` / ``rel_noise`` and a ``note`` (or ``problem``)."""

    abs: float
    rel: float
    noise: float
    rel_noise: float
    note: str = ""
    problem: str = ""


def column_tolerance(column: str, golden: np.ndarray, changes: np.ndarray, ref: np.ndarray) -> ColumnTolerance:
    """Apply the rule to one column.

    ``golden``: its ok golden values; ``changes``: per row and perturbation ``|perturbed - ref|``;
    ``ref``: the reference run's values of the same rows (for relative changes).
    """
    ch = np.asarray(changes, float)
    fin = np.isfinite(ch)
    noise = round_up2(float(ch[fin].max())) if fin.any() else 0.0  # stored with two digits, rounded up
    ref = np.asarray(ref, float)
    g = guarded(golden, noise, column)
    if is_count(column):
        slack = count_slack(noise, g)
        bad = g.size and slack >= g.min()
        return ColumnTolerance(slack, 0.0, noise, 0.0,
                               f"iteration count: {COUNT_SLACK:g} x its smallest value" if slack else "",
                               f"count slack {slack:g} >= smallest count {g.min():g}" if bad else "")
    floor = floor_of(golden)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel_ch = np.where(np.abs(ref) > 0, ch / np.abs(ref), np.where(ch > floor, np.inf, 0.0))
    rel_noise = float(np.nanmax(rel_ch)) if np.isfinite(rel_ch).any() or np.isinf(rel_ch).any() else 0.0
    rel_noise = round_up2(rel_noise) if math.isfinite(rel_noise) else rel_noise
    for k in MULTIPLES:
        a = round_up2(max(k * noise, floor))
        if not g.size or a < g.min():
            return ColumnTolerance(a, 0.0, noise, 0.0, "" if k == MULTIPLES[0] else f"noise-limited: {k:g} x noise")
        if math.isfinite(rel_noise):
            r = round_up2(k * rel_noise)
            if np.all(floor + r * g < g):
                return ColumnTolerance(round_up2(floor), r, noise, rel_noise,
                                       "relative" + ("" if k == MULTIPLES[0] else f", noise-limited: {k:g} x noise"))
    a = round_up2(max(MULTIPLES[-1] * noise, floor))
    return ColumnTolerance(a, 0.0, noise, 0.0, "UNRESOLVED",
                           f"{MULTIPLES[-1]:g} x noise {noise:.2g} >= golden value {g.min():.3g}: the value is not "
                           f"resolved by the solver tolerance")


def _changes(stem: str, folder: Path) -> tuple[pd.DataFrame, list[pd.DataFrame]]:
    ref = pd.read_csv(folder / f"{stem}.ref.csv", dtype={"case_id": str, "model": str, "status": str})
    others = [pd.read_csv(p, dtype={"case_id": str, "model": str, "status": str})
              for p in sorted(folder.glob(f"{stem}.*x_*.csv"))]
    return ref, others


def study_tolerances(stem: str, folder: Path) -> dict[str, ColumnTolerance]:
    """The derived entries of every golden column of study ``stem``."""
    golden = read_golden(GOLDEN_DIR / f"{stem}.csv")
    ok = golden[golden["status"] == "ok"]
    ref, others = _changes(stem, folder)
    out = {}
    for c in [c for c in golden.columns if c not in KEY_COLUMNS]:
        changes, refs = [], []
        for o in [*others, golden]:  # the golden too: a rerun at the same settings need not reproduce it bit for bit
            m = ref.merge(o, on=["case_id", "model"], suffixes=("", "_b"))
            m = m[(m["status"] == "ok") & (m["status_b"] == "ok")]
            if c in m and c + "_b" in m:
                changes.append((m[c] - m[c + "_b"]).abs().to_numpy())
                refs.append(m[c].to_numpy())
        ch = np.concatenate(changes) if changes else np.zeros(0)
        rf = np.concatenate(refs) if refs else np.zeros(0)
        out[c] = column_tolerance(c, ok[c].to_numpy(dtype=float), ch, rf)
    return out


def _entry(c: str, t: ColumnTolerance) -> str:
    parts = [f"abs = {t.abs:.2g}"]
    if t.rel:
        parts += [f"rel = {t.rel:.2g}", f"rel_noise = {t.rel_noise:.2g}"]
    parts.append(f"noise = {t.noise:.2g}")
    note = f"  # {t.note}" if t.note else ""
    return f'"{c}" = {{ {", ".join(parts)} }}{note}'


#: A result column whose noise exceeds this fraction of its largest value marks the study as limited by its
#: solver tolerance (noted in the file: the tier cannot see changes smaller than that).
LIMITED = 1e-6


def tolerance_limited(stem: str, cols: dict[str, ColumnTolerance]) -> str:
    """A note when a result column (tip, length change, ...) moves by more than :data:`LIMITED` of its
    largest golden value under the perturbations, else ``""``."""
    from .golden import RESULT_COLUMNS

    golden = read_golden(GOLDEN_DIR / f"{stem}.csv")
    ok = golden[golden["status"] == "ok"]
    worst = []
    for c in RESULT_COLUMNS:
        scale = float(np.nanmax(np.abs(ok[c].to_numpy(float)))) if c in ok and ok[c].notna().any() else 0.0
        if c in cols and scale > 0 and cols[c].noise > max(LIMITED * scale, 1e-9):  # 1e-9: not a round-off zero
            worst.append(f"{c} by {cols[c].noise:.2g} ({cols[c].noise / scale:.1g} of its largest value)")
    if not worst:
        return ""
    return (f"limited by the solver tolerance: under the perturbations {', '.join(worst)} move; tighten the "
            f"study's solver tolerance to make the tier see smaller changes")


def perturbed_runs(stem: str, folder: Path) -> int:
    """How many perturbed runs of ``stem`` the folder holds (0: only the rerun against the golden)."""
    return len(_changes(stem, folder)[1])


def render(tables: dict[str, dict[str, ColumnTolerance]], measured: str, notes: dict[str, str] | None = None) -> str:
    """The whole ``tolerances.toml`` text (``notes``: a comment line per study)."""
    lines = [RULE, f"# Measured: {measured}.", "", "[default]", ""]
    for stem, cols in tables.items():
        if notes and notes.get(stem):
            lines.append(f"# {notes[stem]}")
        lines.append(f"[{stem}]")
        lines += [_entry(c, t) for c, t in cols.items()]
        lines.append("")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m tests.regression.derive_tolerances")
    ap.add_argument("folder", help="the --save DIR of measure_noise (every small study measured)")
    ap.add_argument("--measured", default="python -m tests.regression.measure_noise", help="when / where (header)")
    ap.add_argument("--check", action="store_true", help="print the problems only, write nothing")
    args = ap.parse_args(argv)
    folder = Path(args.folder)
    tables = {p.stem: study_tolerances(p.stem, folder) for p in small_study_paths()}
    notes = {s: f"{perturbed_runs(s, folder)} of the 2 perturbed runs measured (measure_noise did not finish the "
                f"others); noise also includes the rerun's change against the golden"
             for s in tables if perturbed_runs(s, folder) < 2}
    for stem, cols in tables.items():
        loose = tolerance_limited(stem, cols)
        if loose:
            notes[stem] = "; ".join(filter(None, [notes.get(stem), loose]))
    problems = [f"{s} {c}: {t.problem}" for s, cols in tables.items() for c, t in cols.items() if t.problem]
    print("\n".join(problems) or "every tolerance below the golden values it guards")
    if not args.check:
        TOLERANCES_FILE.write_text(render(tables, args.measured, notes))
        print(f"wrote {TOLERANCES_FILE}")
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
