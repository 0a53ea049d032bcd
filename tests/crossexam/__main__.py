"""``python -m tests.crossexam [--seed S] [--count N] [--start I] [--slow] [--verbose]``: the agreement table.

Runs every applicable pair (:mod:`tests.crossexam.pairs`) on cases ``I .. I + N - 1`` of seed
``S`` and prints one markdown row per pair (cases, agreeing, refused, not judged (a side timed out), disagreeing, the
largest distance in L and in tolerances, seconds), then one line per failing (case, pair);
``--verbose`` prints each failure's message with its study file (and each verdict with its
seconds on stderr).  Exit code 1 when a pair disagrees.  The table of
``docs/models.md`` ("Cross-examination") comes from here.
"""

from __future__ import annotations

import argparse
import sys
import time

from tests.crossexam.cases import generate
from tests.crossexam.pairs import PAIRS, compare, pairs_for, relative


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="python -m tests.crossexam")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--count", type=int, default=30)
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--slow", action="store_true", help="include the slow-only pairs")
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args(argv)
    rows = {n: dict(cases=0, ok=0, refused=0, failing=0, timeout=0, worst=0.0, worst_rel=0.0) for n in PAIRS}
    bad, t0 = [], time.perf_counter()
    for case in generate(args.seed, args.count, args.start):
        for name in pairs_for(case, args.slow):
            v = compare(case, name)
            if args.verbose:
                print(f"  {case.name} {name}: {v.a.seconds:.1f} + {v.b.seconds:.1f} s, "
                      f"{'refused' if v.refused else 'failed' if v.failed else f'{relative(v):.2f} x tolerance'}",
                      file=sys.stderr, flush=True)
            r = rows[name]
            r["cases"] += 1
            if v.refused:
                r["refused"] += 1
            elif v.ok:
                r["ok"] += 1
            elif v.timed_out:
                r["timeout"] += 1
            else:
                r["failing"] += 1
                bad.append(v)
            if not (v.refused or v.failed):
                r["worst"] = max(r["worst"], v.distance / v.length)
                r["worst_rel"] = max(r["worst_rel"], relative(v))
    secs = time.perf_counter() - t0
    print(f"seed {args.seed}, cases {args.start}..{args.start + args.count - 1}: {secs:.0f} s")
    print("| pair | cases | agree | refused | not judged (timeout) | disagree | largest distance [L] | largest distance / tolerance |")
    print("|---|---|---|---|---|---|---|---|")
    for n, r in rows.items():
        if r["cases"]:
            print(f"| {n} | {r['cases']} | {r['ok']} | {r['refused']} | {r['timeout']} | {r['failing']} | "
                  f"{r['worst']:.1e} | {r['worst_rel']:.2f} |")
    for v in bad:
        print("DISAGREE " + (v.message() if args.verbose else v.message().splitlines()[0]))
    refusals = {}
    for case in generate(args.seed, args.count, args.start):
        for name in pairs_for(case, args.slow):
            v = compare(case, name)
            if v.refused:
                refusals.setdefault(v.refused.split(";")[0][:120], []).append(f"{case.index}:{name}")
    for why, where in refusals.items():
        print(f"REFUSED x{len(where)} {why} ({', '.join(where[:4])}{' ...' if len(where) > 4 else ''})")
    return 0 if not bad else 1


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
