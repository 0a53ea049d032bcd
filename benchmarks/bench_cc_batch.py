"""Benchmark: vectorised CC (``workbench.models.cc_batch``) on many samples vs ``cc.run`` per sample.

Run:  python benchmarks/bench_cc_batch.py [--n 30000] [--loop-sample 300] [--repeat 5]

On the Rao et al. 2021 robot (2 sections, 6 tendons) with ``n`` random tension rows and ``n``
random length rows: the wall time of :func:`cc_tip_positions` and of :func:`cc_backbones`
(21 stations) over all rows (best of ``--repeat``), and the per-row time of ``cc.run`` measured
on ``--loop-sample`` rows and extrapolated to ``n``.  The batched tips are checked against
``cc.run`` on the subsample (max difference printed).  Issue 30's target: a CC calibration on
30 000 rows within 10 s, i.e. one evaluation well under 1 s.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _timing import best_of  # noqa: E402

from workbench.models import SolverOptions, get_model  # noqa: E402
from workbench.models.cc_batch import cc_backbones, cc_tip_positions  # noqa: E402
from workbench.robot import LoadCase, TendonActuation  # noqa: E402
from workbench.robot.presets import build_preset  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=30000)
    ap.add_argument("--loop-sample", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    robot = build_preset("rao_2021")
    rng = np.random.default_rng(0)
    rows = {"tension": rng.uniform(0.0, 4.0, (a.n, robot.n_tendons)),
            "length": rng.uniform(-2e-3, 2e-3, (a.n, robot.n_tendons))}
    cc = get_model("cc")
    print(f"load average {os.getloadavg()[0]:.2f}; {a.n} rows, robot rao_2021")
    for mode, cmds in rows.items():
        t_tip, _, tips = best_of(lambda: cc_tip_positions(robot, mode, cmds), a.repeat)
        t_bb, _, _ = best_of(lambda: cc_backbones(robot, mode, cmds, 21), a.repeat)
        sub = cmds[: a.loop_sample]
        t0 = time.perf_counter()
        ref = np.array([cc(robot, LoadCase(actuation=TendonActuation(mode, tuple(r))), SolverOptions()).tip_position
                        for r in sub])
        per_row = (time.perf_counter() - t0) / len(sub)
        err = float(np.max(np.abs(ref - tips[: len(sub)])))
        print(f"{mode:8s} cc_tip_positions {t_tip * 1e3:8.1f} ms   cc_backbones(21) {t_bb * 1e3:8.1f} ms   "
              f"cc.run loop {per_row * 1e3:.3f} ms/row -> {per_row * a.n:.1f} s for {a.n} rows "
              f"({per_row * a.n / t_tip:.0f}x)   max |tip - cc.run| {err:.1e} m")


if __name__ == "__main__":
    main()
