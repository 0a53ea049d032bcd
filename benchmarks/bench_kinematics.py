"""Benchmark: batched constant-curvature forward kinematics vs a per-configuration loop.

Run:  python benchmarks/bench_kinematics.py [--n 1000000] [--loop-sample 2000] [--repeat 3]

* batched: ``forward_kinematics`` on ``n`` random 3-section configurations at once;
* loop: ``forward_kinematics`` called once per configuration (shape ``(3,)`` inputs) on a
  random subsample of ``--loop-sample`` configurations; the per-configuration rate measured on
  the subsample is extrapolated to ``n`` (the loop over all 10^6 would take minutes).

Both timings are the best of ``--repeat`` runs (``time.perf_counter``), in one process, on one
core (BLAS/OpenMP threads pinned to 1; the FK kernel is elementwise numpy and does not use
BLAS). The loop results are checked against the batched results on the subsample.
Targets: ratio >= 100x and >= 5e6 section transforms / s.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from workbench.kinematics import forward_kinematics, jacobian  # noqa: E402
from _timing import best_of as _best  # noqa: E402

N_SECTIONS = 3


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000, help="batched configurations")
    ap.add_argument("--loop-sample", type=int, default=2000, help="configurations timed in the Python loop")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    rng = np.random.default_rng(args.seed)
    shape = (args.n, N_SECTIONS)
    kappa = rng.uniform(-10.0, 10.0, shape)
    phi = rng.uniform(-np.pi, np.pi, shape)
    ell = rng.uniform(0.05, 0.3, shape)

    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    print(f"configs: {args.n} x {N_SECTIONS} sections (seed {args.seed}); best of {args.repeat}")

    t_batch, c_batch, T = _best(lambda: forward_kinematics(kappa, phi, ell), args.repeat)
    batch_rate = args.n / t_batch

    idx = rng.choice(args.n, size=min(args.loop_sample, args.n), replace=False)

    def loop():
        return [forward_kinematics(kappa[i], phi[i], ell[i]) for i in idx]

    t_loop, c_loop, T_loop = _best(loop, args.repeat)
    loop_rate = idx.size / t_loop
    err = np.max(np.abs(np.asarray(T_loop) - T[idx]))
    t_loop_extrap = args.n / loop_rate

    sect_rate = batch_rate * N_SECTIONS
    ratio = batch_rate / loop_rate
    sect_rate_cpu = args.n * N_SECTIONS / c_batch
    ratio_cpu = (args.n / c_batch) / (idx.size / c_loop)
    print(f"batched FK     : wall {t_batch:7.3f} s, cpu {c_batch:7.3f} s -> {batch_rate:10.4g} configs/s, "
          f"{sect_rate:.4g} section transforms/s (cpu-time basis: {sect_rate_cpu:.4g}/s)")
    print(f"per-config loop: wall {t_loop:7.3f} s, cpu {c_loop:7.3f} s for {idx.size} configs -> "
          f"{loop_rate:10.4g} configs/s; extrapolated to {args.n} configs: {t_loop_extrap:.1f} s")
    print(f"speed-up batched / loop: {ratio:.1f}x wall ({ratio_cpu:.1f}x cpu)   "
          f"(max |loop - batched| = {err:.2e})")
    print(f"targets (wall): ratio >= 100x: {'met' if ratio >= 100 else 'NOT met'}; "
          f">= 5e6 section transforms/s: {'met' if sect_rate >= 5e6 else 'NOT met'}")
    if c_batch < 0.8 * t_batch:
        print(f"note: cpu/wall = {c_batch / t_batch:.2f} -> the machine is shared/loaded; "
              "the cpu-time figures are the single-core capacity")

    # secondary: batched analytic Jacobian (informative, no target)
    nj = min(args.n, 100_000)
    t_jac, _, _ = _best(lambda: jacobian(kappa[:nj], phi[:nj], ell[:nj]), args.repeat)
    print(f"batched Jacobian (6 x 9): {nj / t_jac:.4g} configs/s on {nj} configs")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
