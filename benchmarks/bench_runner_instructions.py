"""Instructions per case of the isolated executor (the CLI default), counted by valgrind's callgrind.

    python benchmarks/bench_runner_instructions.py [--cases 50 250] [--root .]

Runs ``run_study`` with the isolated executor on 0 ms cases (the busy-wait model of
``bench_runner.py`` with no spin) under ``valgrind --tool=callgrind --trace-children=yes`` for two
case counts and prints the instructions per extra case of the runner process and of its sandbox
child, ``(Ir(N2) - Ir(N1)) / (N2 - N1)``.  Instruction counts depend far less on the machine's load
than the wall and CPU clocks of ``bench_runner.py`` (+-30 % on this shared machine), so two trees
(``--root``, e.g. a ``git worktree`` of another commit) can be compared in one run; not exactly:
the store's flush timer (every 2 s) and the 1 s polls run more often when the run is slow
(repeated runs of one tree differed by up to 0.3 M per case in the child).  ``PYTHONHASHSEED=0``.
The runner process's count includes parsing and expanding the study (which ``bench_runner.py`` does not time).
Takes about a minute per tree; needs ``valgrind`` on the PATH.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

_CHILD = """
import sys, tempfile
from pathlib import Path
root, n = sys.argv[1], int(sys.argv[2])
sys.path[:0] = [root, root + "/benchmarks"]
import bench_runner as B
from workbench.study import IsolatedExecutor, RunConfig, run_cases
with tempfile.TemporaryDirectory() as d:
    s = run_cases(B.lookup_kind(B.lookup_0ms), B.make_study(n), Path(d) / "out", IsolatedExecutor(),
                  RunConfig(progress=False))
    assert s.n_ok == n, s
"""


def count(root: Path, n: int) -> tuple[int, int]:
    """Instructions of the runner process and of the largest other process (the sandbox child)."""
    with tempfile.TemporaryDirectory() as d:
        script = Path(d) / "one.py"
        script.write_text(_CHILD)
        log = Path(d) / "log.txt"
        with open(log, "w") as err:
            subprocess.run(["valgrind", "--tool=callgrind", "--trace-children=yes",
                            f"--callgrind-out-file={d}/cg.%p", sys.executable, str(script), str(root), str(n)],
                           check=True, stdout=subprocess.DEVNULL, stderr=err,
                           env={**os.environ, "PYTHONHASHSEED": "0"})
        text = log.read_text()
    counts = {int(p): int(c.replace(",", "")) for p, c in re.findall(r"==(\d+)== Collected : ([\d,]+)", text)}
    first = min(counts)  # the runner process starts first
    others = [c for p, c in counts.items() if p != first]
    return counts[first], max(others)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, nargs=2, default=(50, 250))
    ap.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[1])
    args = ap.parse_args()
    n1, n2 = args.cases
    (r1, c1), (r2, c2) = count(args.root.resolve(), n1), count(args.root.resolve(), n2)
    per = lambda a, b: (b - a) / (n2 - n1) / 1e6  # noqa: E731
    print(f"{args.root}: instructions per case (0 ms cases, isolated executor, {n1} -> {n2} cases): "
          f"runner {per(r1, r2):.3f} M, sandbox child {per(c1, c2):.3f} M, both {per(r1 + c1, r2 + c2):.3f} M")


if __name__ == "__main__":
    main()
