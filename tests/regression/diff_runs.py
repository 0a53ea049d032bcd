"""Compare two sets of study runs bit for bit (a refactoring check).

A refactoring must not change a single stored number.  This tool runs every committed study
(``studies/*.toml``) into a root folder, builds each report from it, and compares two such
roots: the Parquet tables cell by cell (bitwise for floats and arrays; the wall-time columns,
which measure the machine, aside) and each ``report.html`` byte for byte.

Usage::

    python -m tests.regression.diff_runs run ROOT [--studies a,b] [--workers 2] [--no-report] [--from DIR]
    python -m tests.regression.diff_runs report DATA_ROOT OUT_ROOT   # reports of stored runs
    python -m tests.regression.diff_runs diff OLD_ROOT NEW_ROOT [--what data|reports|both]

``--from tests/regression/studies`` runs the regression-size copies instead of ``studies/``.
``run`` writes ``ROOT/data/<study>`` and ``ROOT/reports/<study>``.  Reports carry the run's
provenance (host, start time, commit), so to diff reports of two code versions build both from
the *same* data root with ``report`` and diff those.  ``diff`` exits 1 on any difference and
prints where it is.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

_TIMING = {"wall_time"}


def _studies(names: str | None, folder: Path = Path("studies")) -> list[Path]:
    files = sorted(folder.glob("*.toml"))
    if names:
        want = set(names.split(","))
        files = [f for f in files if f.stem in want]
    return files


def cmd_run(root: Path, names: str | None, workers: int, report: bool, folder: Path = Path("studies")) -> int:
    """Run each study of ``folder`` into ``root/data/<stem>`` (and build ``root/reports/<name>``)."""
    rc = 0
    for f in _studies(names, folder):
        out = root / "data" / f.stem
        cmd = [sys.executable, "-m", "workbench", "run", str(f), "--out", str(out), "--progress", "off",
               "--reports-dir", str(root / "reports")] + ([] if report else ["--no-report"])
        if workers > 1:
            cmd += ["--workers", str(workers)]
        print(" ".join(cmd), flush=True)
        rc |= subprocess.run(cmd).returncode
    return rc


def cmd_report(data_root: Path, out_root: Path) -> int:
    from workbench.report.build import build_report

    for d in sorted(p for p in (data_root / "data").iterdir() if p.is_dir() and not p.name.startswith("_")):
        print(build_report(d, out_root / "reports" / d.name), flush=True)
    return 0


def _table(folder: Path) -> pd.DataFrame:
    df = pd.read_parquet(folder)
    return df.sort_values(["case_id", "model"]).reset_index(drop=True)


def _same(a, b) -> bool:
    if isinstance(a, (list, tuple, np.ndarray)) or isinstance(b, (list, tuple, np.ndarray)):
        a, b = np.asarray(a), np.asarray(b)
        return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
    if isinstance(a, float) and isinstance(b, float):
        return np.float64(a).tobytes() == np.float64(b).tobytes()
    if a is None or b is None:
        return a is b
    try:
        if pd.isna(a) and pd.isna(b):
            return type(a) is type(b)
    except (TypeError, ValueError):
        pass
    return type(a) is type(b) and a == b


def diff_tables(old: Path, new: Path, limit: int = 10) -> list[str]:
    """Differences between the stored tables of two run folders (empty list: identical)."""
    a, b = _table(old), _table(new)
    out: list[str] = []
    ca, cb = [c for c in a.columns if c not in _TIMING], [c for c in b.columns if c not in _TIMING]
    if ca != cb:
        out.append(f"columns differ: only old {sorted(set(ca) - set(cb))}, only new {sorted(set(cb) - set(ca))}"
                   + ("" if set(ca) != set(cb) else " (order)"))
    if len(a) != len(b):
        return out + [f"rows differ: {len(a)} vs {len(b)}"]
    for c in [c for c in ca if c in cb]:
        if str(a[c].dtype) != str(b[c].dtype):
            out.append(f"{c}: dtype {a[c].dtype} vs {b[c].dtype}")
        bad = [i for i, (x, y) in enumerate(zip(a[c], b[c])) if not _same(x, y)]
        if bad:
            i = bad[0]
            out.append(f"{c}: {len(bad)} cells differ, first {a.at[i, 'case_id']}/{a.at[i, 'model']}: "
                       f"{str(a.at[i, c])[:80]} vs {str(b.at[i, c])[:80]}")
        if len(out) >= limit:
            break
    return out


def cmd_diff(old_root: Path, new_root: Path, what: str) -> int:
    bad = 0
    for sub in ("data", "reports") if what == "both" else (what,):
        old_dirs = (sorted(p.name for p in (old_root / sub).iterdir() if p.is_dir() and not p.name.startswith("_"))
                    if (old_root / sub).exists() else [])
        for name in old_dirs:
            o, n = old_root / sub / name, new_root / sub / name
            if not n.exists():
                print(f"{sub}/{name}: missing in {new_root}")
                bad += 1
                continue
            if sub == "data":
                d = diff_tables(o, n)
            else:
                ho, hn = o / "report.html", n / "report.html"
                d = [] if ho.read_bytes() == hn.read_bytes() else [f"report.html differs ({ho.stat().st_size} "
                                                                   f"vs {hn.stat().st_size} bytes)"]
            print(f"{sub}/{name}: " + ("identical" if not d else "DIFFERENT"))
            for line in d:
                print("    " + line)
            bad += bool(d)
    return 1 if bad else 0


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="diff_runs", description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("root", type=Path)
    r.add_argument("--studies")
    r.add_argument("--workers", type=int, default=2)
    r.add_argument("--no-report", action="store_true")
    r.add_argument("--from", dest="folder", type=Path, default=Path("studies"))
    rp = sub.add_parser("report")
    rp.add_argument("data_root", type=Path)
    rp.add_argument("out_root", type=Path)
    d = sub.add_parser("diff")
    d.add_argument("old", type=Path)
    d.add_argument("new", type=Path)
    d.add_argument("--what", choices=("data", "reports", "both"), default="both")
    a = p.parse_args(argv)
    if a.cmd == "run":
        return cmd_run(a.root, a.studies, a.workers, not a.no_report, a.folder)
    if a.cmd == "report":
        return cmd_report(a.data_root, a.out_root)
    return cmd_diff(a.old, a.new, a.what)


if __name__ == "__main__":
    sys.exit(main())
