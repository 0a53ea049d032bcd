"""Benchmark: warm starts along load rays (issue 31), cold vs :func:`workbench.models.warm.solve_chain`.

Run from the repository root::

    python benchmarks/bench_warm.py [--models cosserat] [--scales 0.25,0.5,0.75,1] [--repeats 3] [--jump]

The Rao et al. 2021 robot and its 12 load cases (:mod:`bench_peer`, ``../shared/notes/peer-benchmark.md``);
each case is swept along its load ray (tensions and tip force times each of ``--scales``, in growing
order): a sweep that scales one load pattern, as ``[solver] warm_start`` serves it.  ``--jump``: instead,
the branch-jump load of ``tests/physics/test_load_path.py`` (3 sections; tensions (0, 0.69, 0 / 0, 0, 0 /
3.11, 0, 0) N, tip force (0, -0.259, 0) N), where the cold ramp needs several steps, as one ray.  Cold: every load
solved on its own.  Warm: each ray solved by ``solve_chain`` (its first load cold, each further one from
the nearest smaller one).  Printed per model: solves, warm-started solves, median / total wall and CPU
time per solve (the best of ``--repeats`` passes over all rays), the largest tip and backbone distance
/ L between the warm and cold answers, and of each to a cold solve at a 100x tighter ``newton_tolerance``
(the accuracy each keeps).
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

import numpy as np

from bench_peer import CASES, load, robot, setups
from workbench.models import get_model
from workbench.models.warm import solve_chain
from workbench.robot import LoadCase, Robot, TendonActuation


def ray_loads(base: LoadCase, scales: list[float]):
    """The loads ``s x base`` for each ``s`` of ``scales``."""
    return [replace(base, actuation=replace(base.actuation, values=tuple(s * v for v in base.actuation.values)),
                    tip_force=tuple(s * f for f in base.tip_force)) for s in scales]


def timed(fn):
    """(wall [s], CPU [s], result) of one call."""
    c0, t0 = time.process_time(), time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def jump_problem():
    """The 3-section robot and the branch-jump load (``tests/physics/test_load_path.py``)."""
    rb = robot()
    ld = LoadCase(actuation=TendonActuation("tension", (0.0, 0.69, 0.0, 0.0, 0.0, 0.0, 3.11, 0.0, 0.0)),
                  tip_force=(0.0, -0.259, 0.0))
    return Robot(sections=rb.sections + rb.sections[:1]), ld


def bench(name: str, scales: list[float], repeats: int, jump: bool = False) -> None:
    model, r = get_model(name), robot()
    options = setups(4)[name].options
    model(r, load(1), options)  # compile / import outside the timers
    rays = {case: ray_loads(load(case), scales) for case in range(len(CASES))}
    if jump:
        r, ld = jump_problem()
        rays = {"jump": ray_loads(ld, scales)}
    length = r.length
    per = {"cold": ([], []), "warm": ([], [])}
    results = {}
    for case, loads in rays.items():
        best = {"cold": None, "warm": None}
        for _ in range(max(1, repeats)):
            for how in ("cold", "warm"):
                if how == "cold":
                    solves = [timed(lambda ld=ld: model(r, ld, options)) for ld in loads]
                    w, c = [s[0] for s in solves], [s[1] for s in solves]
                    res = [s[2] for s in solves]
                else:  # per-solve times of a chain: each load timed inside the chain
                    stamps = []

                    def run(rb, ld, op):
                        t = timed(lambda: model(rb, ld, op))
                        stamps.append(t[:2])
                        return t[2]

                    res = solve_chain(run, r, loads, options)
                    w, c = [s[0] for s in stamps], [s[1] for s in stamps]
                if best[how] is None or sum(w) < sum(best[how][0]):
                    best[how] = (w, c, res)
        for how in ("cold", "warm"):
            per[how][0].extend(best[how][0])
            per[how][1].extend(best[how][1])
        results[case] = (best["cold"][2], best["warm"][2])
    n = sum(len(v[0]) for v in results.values())
    warm_n = sum(int(x.extras.get("warm_started", 0.0)) for _, ws in results.values() for x in ws)
    tip = max(float(np.linalg.norm(a.tip_position - b.tip_position)) for cs, ws in results.values()
              for a, b in zip(cs, ws)) / length
    shape = max(float(np.abs(a.positions - b.positions).max()) for cs, ws in results.values()
                for a, b in zip(cs, ws)) / length
    print(f"{name}: {n} solves ({len(rays)} rays x scales {scales}), {warm_n} warm-started")
    for how in ("cold", "warm"):
        w, c = np.asarray(per[how][0]), np.asarray(per[how][1])
        print(f"  {how}: median wall {1e3 * np.median(w):7.2f} ms, CPU {1e3 * np.median(c):7.2f} ms per solve; "
              f"total wall {w.sum():6.2f} s, CPU {c.sum():6.2f} s")
    cw, ww = np.asarray(per["cold"][0]).sum(), np.asarray(per["warm"][0]).sum()
    print(f"  warm / cold total wall {ww / cw:.2f}; max warm-cold distance / L: tip {tip:.1e}, backbone {shape:.1e}")
    tight = replace(options, newton_tolerance=options.newton_tolerance / 100)
    for how, k in (("cold", 0), ("warm", 1)):
        err = max(float(np.abs(res[k][i].positions - model(r, ld, tight).positions).max())
                  for case, res in results.items() for i, ld in enumerate(rays[case])) / length
        print(f"  {how}: max backbone distance / L to a cold solve at newton_tolerance / 100: {err:.1e}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--models", default="cosserat")
    ap.add_argument("--scales", default="0.25,0.5,0.75,1")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--jump", action="store_true")
    a = ap.parse_args()
    scales = [float(s) for s in a.scales.split(",")]
    for name in a.models.split(","):
        bench(name, scales, a.repeats, a.jump)


if __name__ == "__main__":
    main()
