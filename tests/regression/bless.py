"""Re-bless golden tables: ``python -m tests.regression.bless [stem ...]`` (from the repository root).

Runs the small studies ``tests/regression/studies/<stem>.toml`` (all of them without arguments)
in-process and rewrites ``tests/regression/golden/<stem>.csv``.  This is deliberate: only
re-bless after a change whose effect on the results you understand, and put the reason in the
commit message (what changed, by how much, why that is correct).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from .golden import GOLDEN_DIR, STUDIES_DIR, read_golden, run_small_study, small_study_paths, write_golden


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m tests.regression.bless", description=__doc__.split("\n\n")[0])
    ap.add_argument("stems", nargs="*", help="study stems (default: every tests/regression/studies/*.toml)")
    args = ap.parse_args(argv)
    paths = [STUDIES_DIR / f"{s}.toml" for s in args.stems] if args.stems else small_study_paths()
    missing = [str(p) for p in paths if not p.exists()]
    if missing:
        print(f"no such small study: {', '.join(missing)}", file=sys.stderr)
        return 2
    for p in paths:
        with tempfile.TemporaryDirectory() as tmp:
            frame = run_small_study(p, Path(tmp) / p.stem)
        out = GOLDEN_DIR / f"{p.stem}.csv"
        changed = "new" if not out.exists() else ("unchanged" if read_golden(out).shape == frame.shape else "rewritten")
        write_golden(frame, out)
        n_fail = int((frame["status"] != "ok").sum())
        print(f"{p.stem}: {len(frame)} rows ({n_fail} failed) -> {out} [{changed}]")
    print("Goldens rewritten.  Review `git diff tests/regression/golden/` and commit with the REASON for "
          "the change in the commit message.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
