"""Throughput (cases/s) of the study runner against the number of Dask workers, and what limits it.

    python benchmarks/bench_scaling.py [--workers 1,2,4] [--repeats 2] [--studies zero,cheap,heavy] [--slurm | --slurm-only]

Studies (each through ``run_cases`` with a ``DaskExecutor`` on an already running ``LocalCluster``
of 1, 2, 4 single-threaded worker processes; cluster start-up and the workers' first imports
are timed separately and left out):

- ``zero``  -- 1000 cases of a model that returns at once (a full 33-station result), batched as
  the runner does (32 cases a task), and 200 cases one per task: the runner's own per-case cost
  (expansion, pickling, flattening, Parquet) and the per-task cost (Dask, the executor loop);
- ``cheap`` -- ``studies/sag_validity.toml`` (135 cases, cc + ANCF 32 el., ~20 ms a case);
- ``heavy`` -- ``studies/bending.toml`` (75 cases, cc + ANCF + spring-link, ~0.45 s a case).

Printed per run: wall time (best of ``--repeats``, with the spread max - min as its error bar),
cases/s, speed-up over 1 worker, the summed model time of the table over the wall time (the
parallelism the models actually got) and the overhead per case, ``(workers x wall - model
time) / cases`` -- what is not model time: runner, Dask, storage and, past the core count, the
time-slicing of an oversubscribed machine -- and the CPU time of this (the client) process per
case, which holds the runner, the result store and the Dask scheduler: one core of it is the
ceiling of a run's throughput however many workers it has (for long runs it includes the
scheduler's time-driven work, printed as the idle client CPU per second).  A breakdown follows (expansion and
recorded parameters before the first submission, store writes, reading many parts).  ``--slurm`` adds the local SLURM cluster of
``tests/cluster`` (``SLURM_CONF`` must point at a running one): the cheap study on 1 and 2 worker
jobs, the time from submission to the first worker, and the idle client CPU with 1-8 worker jobs
(the scheduler's per-worker heartbeat cost; ``--slurm-only`` runs just these).  The machine is shared: compare the
numbers of one run; the load average is printed.  Results: ``benchmarks/README.md``, "Scaling".
"""

from __future__ import annotations

import argparse
import logging
import os
import pickle
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from workbench.models.result import PhysicsResult, SolverInfo  # noqa: E402


def model_zero(robot, load, options):
    """A model that costs nothing: a straight 33-station result."""
    s = np.linspace(0.0, robot.length, options.n_stations)
    pos = np.column_stack([0 * s, 0 * s, s])
    F = np.eye(4)
    F[:3, 3] = pos[-1]
    return PhysicsResult(model="zero", stations=s, positions=pos, tip_frame=F, length_change=0.0,
                         tendon_tensions=np.asarray(load.actuation.values), tip_twist=0.0,
                         solver=SolverInfo(converged=True, iterations=1))


def lookup_zero(name):
    return model_zero


def zero_study(n: int):
    from workbench.study import parse_study

    return parse_study({
        "study": {"name": "zero", "models": ["cc"], "max_cases": 100000},
        "robot": {"preset": "steel_rod"},
        "load": {"mode": "tension", "tensions": [1.0, 0.0]},
        "solver": {"n_stations": 33},
        "sweep": {"product": {"load.tensions": [[1.0 + 1e-4 * i, 0.0] for i in range(n)]}},
    }, source="<bench zero>")


def _warm():
    """Import what the real studies' workers import (Exudyn models), so no run pays for it."""
    import workbench.physics.ancf  # noqa: F401
    import workbench.physics.spring_link  # noqa: F401
    from workbench.models import get_model

    for m in ("cc", "ancf", "spring_link"):
        get_model(m)
    return os.getpid()


def _lookup_rows(payload):
    """The sweep kind's rows with the payload's model lookup (the task of :func:`_lookup_kind`)."""
    from workbench.study.evaluate import iter_case_rows

    case_id, params, models, lookup = payload
    return iter_case_rows(case_id, params, models, lookup)


def _lookup_kind(lookup):
    """The sweep study kind on the models ``lookup(name)`` (here: :func:`lookup_zero`)."""
    from workbench.study.kinds import SweepKind

    class LookupKind(SweepKind):
        task = staticmethod(_lookup_rows)

        def payload(self, spec, case, models):
            return case.case_id, case.params, tuple(models), lookup

    return LookupKind()


def _one_run(kind, spec, make_executor, lookup=None, batch_size=None):
    import pandas as pd

    from workbench.study import RunConfig, run_cases

    if lookup is not None:
        kind = _lookup_kind(lookup)
    with tempfile.TemporaryDirectory() as d:
        c0, t0 = time.process_time(), time.perf_counter()
        s = run_cases(kind, spec, Path(d) / "out", make_executor(), RunConfig(progress=False, batch_size=batch_size))
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        model = float(pd.read_parquet(Path(d) / "out", columns=["wall_time"])["wall_time"].sum())
    assert s.n_ok + s.n_failed == s.n_cases, s
    return wall, model, s.n_cases, cpu


def _measure(kind, spec, make_executor, repeats, lookup=None, batch_size=None):
    runs = [_one_run(kind, spec, make_executor, lookup, batch_size) for _ in range(repeats)]
    walls = [r[0] for r in runs]
    best = min(range(len(runs)), key=lambda i: walls[i])
    cpus = [r[3] / r[2] for r in runs]
    return {"wall": walls[best], "spread": max(walls) - min(walls), "model": runs[best][1], "n": runs[best][2],
            "cpu": min(cpus), "cpu_spread": max(cpus) - min(cpus)}


HEADER = (f"  {'study':<24} {'wkr':>3}  {'wall [s]':>15}  {'cases/s':>8}  {'speed':>6}  {'model/wall':>10}  "
          f"{'ovh/case [ms]':>13}  {'client CPU/case [ms]':>20}")


def _row(label, workers, m, base_wall):
    ovh = (workers * m["wall"] - m["model"]) / m["n"]
    print(f"  {label:<24} {workers:>3}  {m['wall']:7.2f} ± {m['spread']:5.2f}  {m['n'] / m['wall']:8.1f}"
          f"  {base_wall / m['wall']:5.2f}x  {m['model'] / m['wall']:10.2f}  {ovh * 1e3:13.2f}"
          f"  {m['cpu'] * 1e3:11.3f} ± {m['cpu_spread'] * 1e3:6.3f}")


def _idle_cpu(seconds: float = 5.0) -> float:
    """CPU of this process per second of wall while the cluster idles (scheduler heartbeats, monitors)."""
    c0, t0 = time.process_time(), time.perf_counter()
    time.sleep(seconds)
    return (time.process_time() - c0) / (time.perf_counter() - t0)


def _studies(names):
    from workbench.study import SWEEP, get_kind, kind_of

    out = {}
    for name in names:
        if name == "zero":
            out[name] = (SWEEP, None, lookup_zero)
        else:
            path = ROOT / "studies" / {"cheap": "sag_validity.toml", "heavy": "bending.toml"}[name]
            kind = get_kind(kind_of(path))
            out[name] = (kind, kind.load(path), None)
    return out


def bench_local(names, worker_counts, repeats):
    import dask
    from distributed import Client, LocalCluster

    from workbench.study import DaskExecutor

    studies = _studies(names)
    print(HEADER)
    results = {}
    for w in worker_counts:
        with dask.config.set({"distributed.scheduler.worker-saturation": 1.0,
                              "distributed.scheduler.work-stealing": False}):
            t0 = time.perf_counter()
            cluster = LocalCluster(n_workers=w, threads_per_worker=1, processes=True,
                                   dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL)
            start = time.perf_counter() - t0
        try:
            with Client(cluster) as c:
                t0 = time.perf_counter()
                c.run(_warm)
                warm = time.perf_counter() - t0
            idle = _idle_cpu()
            print(f"  -- {w} worker(s): LocalCluster start {start:.2f} s, first imports {warm:.2f} s (not counted); "
                  f"idle client CPU {idle * 1e3:.1f} ms/s")

            def make(addr=cluster.scheduler_address):
                return DaskExecutor(scheduler=addr)

            for name, (kind, spec, lookup) in studies.items():
                if name == "zero":
                    net = {}
                    for batch, n in ((None, 1000), (1, 200)):
                        label = "zero" + (", 32 cases/task" if batch is None else ", 1 case/task")
                        m = _measure(kind, zero_study(n), make, repeats, lookup, batch)
                        results[(label, w)] = m
                        _row(f"{label} ({n})", w, m, results[(label, worker_counts[0])]["wall"])
                        net[batch] = m["cpu"] - idle * m["wall"] / m["n"]
                    task = (net[1] - net[None]) * 32 / 31
                    print(f"  {'':<24} {'':>3}  client CPU net of the idle rate: {net[None] * 1e3:.3f} ms/case at "
                          f"32 cases/task, {net[1] * 1e3:.3f} ms at 1 -> per task {task * 1e3:.3f} ms, "
                          f"per case {(net[None] - task / 32) * 1e3:.3f} ms")
                    continue
                m = _measure(kind, spec, make, repeats, lookup)
                results[(name, w)] = m
                _row(f"{name} ({m['n']})", w, m, results[(name, worker_counts[0])]["wall"])
        finally:
            cluster.close()
    return results


def _cpu(fn, repeats=3):
    """Best CPU time of ``fn()`` in this process [s] (insensitive to other jobs on a shared machine)."""
    best = float("inf")
    for _ in range(repeats):
        c0 = time.process_time()
        fn()
        best = min(best, time.process_time() - c0)
    return best


def bench_breakdown():
    """Client-process CPU per case of the parts of a run that do not parallelise."""
    import pandas as pd

    from workbench.study import ResultStore
    from workbench.study.evaluate import evaluate_batch
    from workbench.study.params import flatten_params

    print("\nclient-process CPU per case (best of 3), the parts that do not parallelise:")
    for name, (kind, spec, _) in _studies(["cheap", "heavy"]).items():
        cases = kind.expand(spec)
        t_exp = _cpu(lambda: kind.expand(spec)) / len(cases)
        t_rec = _cpu(lambda: [kind.recorded_params(spec, c) for c in cases]) / len(cases)
        print(f"  {name:<6} expansion {t_exp * 1e3:.3f} ms, recorded parameters {t_rec * 1e3:.3f} ms "
              f"(both before the first case is submitted)")
    print("  rows of the real studies (8 cases each, computed here): unpickling them as the client receives them, "
          "then storing them in 256-row parts:")
    for name, (kind, spec, _) in _studies(["cheap", "heavy"]).items():
        cases = kind.expand(spec)[:8]
        rows = evaluate_batch(([(c.case_id, c.params) for c in cases], spec.models, None))
        blob = pickle.dumps(rows, protocol=pickle.HIGHEST_PROTOCOL)
        n_rows = sum(len(r) for r in rows)
        t_unpickle = _cpu(lambda: pickle.loads(blob)) / n_rows
        params = [flatten_params(kind.recorded_params(spec, c)) for c in cases]
        with tempfile.TemporaryDirectory() as d:
            def store_real(folder=Path(d), rows=rows, params=params):
                st = ResultStore(folder / f"s{time.perf_counter_ns()}", params, flush_rows=256, flush_seconds=1e9)
                for _ in range(32):  # 256 rows or more: whole parts
                    for r in pickle.loads(blob):
                        st.add(r)
                st.close()

            t_store = (_cpu(store_real) - 32 * t_unpickle * n_rows) / (32 * n_rows)
        print(f"  {name:<6} {len(blob) / n_rows / 1e3:.1f} kB per row pickled ({n_rows // len(cases)} rows a case): "
              f"unpickle {t_unpickle * 1e3:.3f} ms, store {t_store * 1e3:.3f} ms per row")
    kind, _, lookup = _studies(["zero"])["zero"]
    spec = zero_study(1024)
    cases = kind.expand(spec)
    rows = evaluate_batch(([(c.case_id, c.params) for c in cases], spec.models, lookup))
    params = [flatten_params(kind.recorded_params(spec, c)) for c in cases]
    with tempfile.TemporaryDirectory() as d:
        def store(flush_rows, folder=Path(d)):
            sub = folder / f"s{time.perf_counter_ns()}"
            st = ResultStore(sub, params, flush_rows=flush_rows, flush_seconds=1e9)
            for r in rows:
                st.add([dict(x) for x in r])
            st.close()
            return sub

        t256 = _cpu(lambda: store(256)) / len(rows)
        t2 = _cpu(lambda: store(2)) / len(rows)
        many = store(2)
        n_parts = len(list(many.glob("part-*.parquet")))
        t0 = time.perf_counter()
        pd.read_parquet(many)
        t_read = time.perf_counter() - t0
    print(f"  store: {t256 * 1e3:.3f} ms per case (1 row) with 256-row parts, {t2 * 1e3:.3f} ms with a part "
          f"per 2 rows (atomic write + fsync of each part)")
    print(f"  reading a folder of {n_parts} parts: {t_read:.2f} s ({t_read / n_parts * 1e3:.2f} ms per part, wall)")


def bench_slurm(repeats):
    from workbench.study.cluster import JobQueueExecutor
    from workbench.study.cluster_config import resolve_cluster

    kind, spec, _ = _studies(["cheap"])["cheap"]
    print("\nlocal SLURM (tests/cluster/slurm-local.sh), cheap study, 1 core per job:")
    print(HEADER)
    base = None
    for jobs in (1, 2):
        cfg = resolve_cluster("slurm", overrides={"jobs": jobs, "memory": "1GB", "walltime": "00:20:00",
                                                  "queue_timeout": 120.0})
        firsts = []

        def make():
            ex = JobQueueExecutor(cfg, log=lambda line: firsts.append(line) if "first worker after" in line else None)
            return ex

        m = _measure(kind, spec, make, repeats)
        base = base or m["wall"]
        _row(f"slurm {jobs} job(s)", jobs, m, base)
        waits = [float(x.split("after ")[1].split(" s")[0]) for x in firsts]
        print(f"  {'':<18} submission -> first worker: {statistics.mean(waits):.1f} s "
              f"(min {min(waits):.1f}, max {max(waits):.1f}, {len(waits)} runs; included in the wall time)")


def bench_slurm_idle(job_counts=(1, 2, 4, 8), seconds: float = 10.0):
    """Client CPU per second of an idle jobqueue cluster against its worker count (the scheduler's fixed cost).

    Unlike a ``LocalCluster`` (whose nannies live in the client process) the client here holds only
    the Dask scheduler and the executor's job keeper, as on a real batch system; with ``n <= 10``
    workers Dask's heartbeat interval is 0.5 s, so ``(rate(n) - rate(1)) / (n - 1) / 2`` is the
    scheduler's CPU per heartbeat.
    """
    from workbench.study.cluster import JobQueueExecutor
    from workbench.study.cluster_config import resolve_cluster

    print(f"\nlocal SLURM, idle client CPU against the number of 1-worker jobs ({seconds:g} s each, best of 2):")
    rates = {}
    for jobs in job_counts:
        cfg = resolve_cluster("slurm", overrides={"jobs": jobs, "memory": "500MB", "walltime": "00:10:00",
                                                  "queue_timeout": 120.0})
        with JobQueueExecutor(cfg, log=lambda line: None) as ex:
            t0 = time.monotonic()
            while len(ex._client.scheduler_info()["workers"]) < jobs:
                if time.monotonic() - t0 > 180:
                    raise RuntimeError(f"only {len(ex._client.scheduler_info()['workers'])} of {jobs} workers joined")
                time.sleep(0.5)
            joined = time.monotonic() - t0
            time.sleep(3.0)  # let the workers' start-up traffic settle
            rates[jobs] = min(_idle_cpu(seconds) for _ in range(2))
        print(f"  {jobs} worker job(s): {rates[jobs] * 1e3:6.1f} ms/s (all joined {joined:.1f} s after the first)")
    n = list(rates)
    if len(n) > 1:
        per = (rates[n[-1]] - rates[n[0]]) / (n[-1] - n[0])
        print(f"  -> {per * 1e3:.2f} ms/s per worker, {per / 2 * 1e3:.2f} ms per heartbeat (0.5 s interval); "
              f"fixed {(rates[n[0]] - per * n[0]) * 1e3:.1f} ms/s")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", default="1,2,4")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--studies", default="zero,cheap,heavy")
    ap.add_argument("--slurm", action="store_true", help="also the local SLURM cluster (SLURM_CONF)")
    ap.add_argument("--slurm-only", action="store_true", help="only the local SLURM measurements")
    ap.add_argument("--idle-only", action="store_true", help="with --slurm-only: only the idle client CPU")
    args = ap.parse_args()
    print(f"{os.cpu_count()} CPUs; load average at start {os.getloadavg()[0]:.1f}; repeats {args.repeats}")
    if args.slurm_only:
        args.slurm = True
    else:
        bench_local(args.studies.split(","), [int(w) for w in args.workers.split(",")], args.repeats)
        bench_breakdown()
    if args.slurm:
        if not args.idle_only:
            bench_slurm(args.repeats)
        bench_slurm_idle()
    print(f"load average at end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
