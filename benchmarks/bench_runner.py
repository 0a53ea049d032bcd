"""Per-case overhead of the study runner vs a bare Python loop, and Dask speed-up.

    python benchmarks/bench_runner.py [--cases 1500] [--quick]

The same N cheap cases run (a) in a bare loop calling the model function on a pre-built
robot, (b) through ``run_study`` with the in-process serial executor, the isolated child
process executor, and Dask (an already running LocalCluster with 1 and 2 worker processes;
cluster start-up is timed separately).  The model is a busy-wait of 1.5 ms (the cost of a
small Exudyn static case, see docs/notes) or 20 ms that returns a full PhysicsResult
(33 stations), so flattening, pickling and Parquet writing are all included.

Targets (issue 18): runner overhead <= 20 % of a 1.5 ms case; >= 1.8x speed-up on 2 workers for
20 ms cases.  All ratios printed are measured in this one run.  Besides wall times it prints CPU
times, which a shared machine disturbs far less: the runner process's CPU per case and the CPU of
the whole process tree (runner, its sandbox child, Dask nannies, workers and their sandboxes) per
case, the CPU overhead per case (tree CPU minus the bare loop's), and for 20 ms cases the 2-core
CPU-bound ceiling of the speed-up; and the load average before and after.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from workbench.models.result import PhysicsResult, SolverInfo  # noqa: E402

SPIN = {"1.5ms": 1.5e-3, "20ms": 20e-3, "0ms": 0.0}


def _model(robot, load, options, spin):
    # spin on this thread's CPU clock: a case costs `spin` CPU seconds however loaded the machine
    # is (its wall time then grows with the load), so CPU accounting stays exact
    t_end = time.thread_time() + spin
    while time.thread_time() < t_end:
        pass
    L = robot.length
    s = np.linspace(0.0, L, options.n_stations)
    t0 = load.actuation.values[0]
    kappa = t0 * robot.sections[0].tendons.offset / robot.sections[0].cross_section.EI
    pos = np.column_stack([(1 - np.cos(kappa * s)) / kappa, 0 * s, np.sin(kappa * s) / kappa])
    F = np.eye(4)
    F[:3, 3] = pos[-1]
    return PhysicsResult(model="bench", stations=s, positions=pos, tip_frame=F, length_change=0.0,
                         tendon_tensions=np.asarray(load.actuation.values), tip_twist=0.0,
                         solver=SolverInfo(converged=True, iterations=3))


def model_0ms(robot, load, options):
    return _model(robot, load, options, SPIN["0ms"])


def model_1p5ms(robot, load, options):
    return _model(robot, load, options, SPIN["1.5ms"])


def model_20ms(robot, load, options):
    return _model(robot, load, options, SPIN["20ms"])


def lookup_0ms(name):
    return model_0ms


def lookup_rows(payload):
    """The task of :func:`lookup_kind`: the sweep kind's rows with the payload's model lookup."""
    from workbench.study.evaluate import iter_case_rows

    case_id, params, models, lookup = payload
    return iter_case_rows(case_id, params, models, lookup)


def lookup_kind(lookup):
    """The sweep study kind on the benchmark's models ``lookup(name)`` (module-level: its payloads go to workers)."""
    from workbench.study.kinds import SweepKind

    class LookupKind(SweepKind):
        task = staticmethod(lookup_rows)

        def payload(self, spec, case, models):
            return case.case_id, case.params, tuple(models), lookup

    return LookupKind()


def lookup_1p5ms(name):
    return model_1p5ms


def lookup_20ms(name):
    return model_20ms


LOOKUPS = {"0ms": (lookup_0ms, model_0ms), "1.5ms": (lookup_1p5ms, model_1p5ms), "20ms": (lookup_20ms, model_20ms)}


def make_study(n_cases: int):
    from workbench.study import parse_study

    raw = {
        "study": {"name": "bench", "models": ["cc"], "max_cases": 100000},
        "robot": {"preset": "steel_rod"},
        "load": {"mode": "tension", "tensions": [1.0, 0.0]},
        "solver": {"n_stations": 33},
        "sweep": {"product": {"load.tensions": [[1.0 + 0.01 * i, 0.0] for i in range(n_cases)]}},
    }
    return parse_study(raw, source="<bench>")


def tree_cpu() -> float:
    """CPU seconds (user + system) of this process and every live descendant, with their reaped children.

    A worker that exits during a run is counted through its parent's ``children_*`` times, so the
    difference of two calls is the CPU the whole process tree spent in between (Dask nannies,
    workers, their sandboxes and the runner's own sandbox included).
    """
    import psutil

    me = psutil.Process()
    total = 0.0
    for p in [me, *me.children(recursive=True)]:
        try:
            t = p.cpu_times()
        except psutil.Error:  # exited between listing and reading
            continue
        total += t.user + t.system + t.children_user + t.children_system
    return total


def bare_loop(study, model) -> tuple[float, float]:
    """Wall and CPU seconds of the model calls alone (robot, loads and options built beforehand)."""
    from workbench.study import expand
    from workbench.study.build import build_load, build_options, build_robot

    cases = expand(study)
    c0 = cases[0].params
    robot = build_robot(c0["robot"], c0["derived"])
    options = build_options(c0["solver"])
    loads = [build_load(robot, c.params["load"]) for c in cases]
    c, t0 = time.process_time(), time.perf_counter()
    for load in loads:
        model(robot, load, options)
    return time.perf_counter() - t0, time.process_time() - c


def through_runner(study, executor, lookup) -> tuple[float, float, float]:
    """Wall seconds, CPU seconds of this (the runner's) process, CPU seconds of the whole process tree."""
    from workbench.study import RunConfig, run_cases

    with tempfile.TemporaryDirectory() as d:
        tree0, c0, t0 = tree_cpu(), time.process_time(), time.perf_counter()
        s = run_cases(lookup_kind(lookup), study, Path(d) / "out", executor, RunConfig(progress=False))
        dt, dc, dtree = time.perf_counter() - t0, time.process_time() - c0, tree_cpu() - tree0
        assert s.n_ok == s.n_cases, s
    return dt, dc, dtree


def _load() -> str:
    return "load average " + " / ".join(f"{x:.1f}" for x in os.getloadavg()) + " (1 / 5 / 15 min)"


def _marginal(study_n, study_2n, make, lookup, repeats: int, n: int) -> tuple[float, ...]:
    """Best-of-``repeats`` T(N) and T(2N) (wall, runner CPU, tree CPU); per extra case and the fixed part."""
    a = [through_runner(study_n, make(), lookup) for _ in range(repeats)]
    b = [through_runner(study_2n, make(), lookup) for _ in range(repeats)]
    best = [min(x[k] for x in a) for k in range(3)]
    best2 = [min(x[k] for x in b) for k in range(3)]
    per = [(best2[k] - best[k]) / n for k in range(3)]
    return best[0], per[0], best[0] - n * per[0], per[1], per[2]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    # per case = (T(2N) - T(N)) / N: a run's fixed costs (child and cluster start-up) scatter by
    # ~0.1 s, i.e. by 0.25 ms per case at N = 400 but 0.07 ms at N = 1500 (benchmarks/README.md)
    ap.add_argument("--cases", type=int, default=1500)
    ap.add_argument("--quick", action="store_true", help="skip the 20 ms speed-up part")
    ap.add_argument("--repeats", type=int, default=3, help="best of R runs for the overhead part")
    args = ap.parse_args()

    from workbench.study import IsolatedExecutor, SerialExecutor

    n = args.cases
    small, large = make_study(n), make_study(2 * n)
    print(f"{n} cases (and {2 * n} to separate the fixed per-run cost), 1 model each; {_load()}")
    spins = ("0ms", "1.5ms") + (() if args.quick else ("20ms",))
    rows = []
    # no cluster exists while the bare loop and the serial paths run: a LocalCluster's scheduler
    # lives in this process and its background CPU would be charged to them
    for spin in spins:
        lookup, model = LOOKUPS[spin]
        reps = args.repeats if spin != "20ms" else 1
        bare = [bare_loop(small, model) for _ in range(reps)]
        bw, bc = min(b[0] for b in bare) / n, min(b[1] for b in bare) / n
        rows.append((spin, "bare loop", bw * n, bw, 0.0, bc, bc))
        for path, make in (("runner serial in-process", SerialExecutor), ("runner serial isolated", IsolatedExecutor)):
            if spin == "20ms" and make is SerialExecutor:
                continue
            through_runner(make_study(8), make(), lookup)  # warm-up
            # best of `repeats` (the machine is shared: the minimum is the least disturbed run)
            rows.append((spin, path, *_marginal(small, large, make, lookup, reps, n)))
    for w in (1, 2):  # one cluster at a time (its scheduler's CPU is part of its cost)
        rows += _dask_rows(w, spins, small, large, n, args.repeats)
    _print([r for r in rows if r[0] != "20ms"], [r[1:] for r in rows if r[0] == "20ms"], n)


def _dask_rows(w: int, spins, small, large, n: int, repeats: int) -> list[tuple]:
    import dask
    from distributed import LocalCluster

    from workbench.study import DaskExecutor
    from workbench.study.executors import DASK_SETTINGS

    path = f"runner dask {w} worker" + ("s" if w > 1 else "")
    with dask.config.set(DASK_SETTINGS):  # the cluster the executor would start itself
        t0 = time.perf_counter()
        cluster = LocalCluster(n_workers=w, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=logging.CRITICAL)
        print(f"LocalCluster start-up with {w} worker(s): {time.perf_counter() - t0:.2f} s (not in the times below)")
    out = []
    try:
        make = lambda: DaskExecutor(scheduler=cluster.scheduler_address)  # noqa: E731
        for spin in spins:
            lookup, _ = LOOKUPS[spin]
            through_runner(make_study(8), make(), lookup)  # warm-up (worker imports)
            out.append((spin, path, *_marginal(small, large, make, lookup, repeats if spin != "20ms" else 1, n)))
    finally:
        cluster.close()
    return out


def _print(rows, speed, n) -> None:
    print(f"\n{'case':>5}  {'path':<26} {'T(N) [s]':>8}  {'wall/case [ms]':>14}  {'fixed/run [s]':>13}  "
          f"{'wall ovh/case':>13} {'/ 1.5 ms':>8}  {'runner CPU/case':>15}  {'tree CPU/case':>13}  "
          f"{'CPU ovh/case':>12} {'/ 1.5 ms':>8}")
    bare = {r[0]: r for r in rows if r[1] == "bare loop"}
    for spin, path, t, per_case, fixed, cpu_runner, cpu_tree in rows:
        # per case = marginal time per extra case (fixed per-run cost removed); with 2 workers the
        # wall time gains from parallelism, so its wall overhead can be negative.  CPU overhead:
        # CPU of every process of the run per case minus the bare loop's CPU per case.
        ovh = (per_case - bare[spin][3]) * 1e3
        covh = (cpu_tree - bare[spin][6]) * 1e3
        print(f"{spin:>5}  {path:<26} {t:8.3f}  {per_case * 1e3:14.3f}  {fixed:13.3f}  {ovh:13.3f} {ovh / 1.5:8.1%}  "
              f"{cpu_runner * 1e3:15.3f}  {cpu_tree * 1e3:13.3f}  {covh:12.3f} {covh / 1.5:8.1%}")
    if speed:
        print(f"\n20 ms cases: T(N) with fixed costs, per extra case (T(2N) - T(N)) / N, CPU of all processes")
        base_total, base_case, base_cpu = speed[0][1], speed[0][2], speed[0][5]
        for path, t, per_case, fixed, cpu_runner, cpu_tree in speed:
            ceiling = 2 * base_cpu / cpu_tree if cpu_tree > 0 else float("nan")
            print(f"  {path:<24} T(N) {t:7.3f} s ({base_total / t:4.2f}x)  per case {per_case * 1e3:6.2f} ms "
                  f"({base_case / per_case:4.2f}x)  fixed {fixed:6.3f} s  runner CPU/case {cpu_runner * 1e3:5.2f} ms  "
                  f"all CPU/case {cpu_tree * 1e3:6.2f} ms (2-core CPU-bound ceiling {ceiling:4.2f}x)")
        d = {p: r for p, *r in speed}
        print(f"  dask 2 workers vs 1 worker: T(N) {d['runner dask 1 worker'][0] / d['runner dask 2 workers'][0]:.2f}x, "
              f"per case {d['runner dask 1 worker'][1] / d['runner dask 2 workers'][1]:.2f}x")
        print("  (speed-ups vs the bare loop's wall time; the ceiling is the bare loop's CPU per case x 2 cores / all "
              "CPU per case: what a quiet 2-core machine allows)")
    print(_load())


if __name__ == "__main__":
    main()
