"""Benchmark: 3-D eyelet statics of issue 18's two-section spatial robot (beam3d, spring_link) against a
planar ANCF eyelet solve of the same rod, timed in one run.

Run from the repository root::

    python benchmarks/bench_eyelet_statics.py [--repeats 2] [--quick] [--baseline] [--stiff]

Robot: 2 x 0.2 m NiTi (E 54 GPa, d 1.4 mm, density 6450 kg/m^3, Poisson 0.33), 10 disks per section,
3 eyelet tendons per section at 90 / -30 / 210 deg, offset 10 mm, EA_t 1e7 N, tensions
(4, 0, 0, 0, 2, 0) N, gravity of the robot description (none).  ``--stiff``: EA and GA x 100 (the
robot of ``benchmarks/bench_reach.py`` and ``tests/physics/validation_matrix.py``).

Printed per model and resolution: best CPU and wall time of ``--repeats`` solves, ``SolveStatic``
calls (attempts / accepted), Newton iterations summed over them, the tip and its distance to the
reference (beam3d at ``--reference`` elements; 160 by default, 80 with ``--quick``).  Then the
Richardson error bars of the beam3d tips (:mod:`workbench.models.discretization`, order 2), and the
CPU ratio beam3d / planar ANCF (same rod, the same tensions in the plane: 4 N on the section-1
tendon, 2 N on the section-2 tendon, both at sigma = 0; 20 elements).  ``--baseline`` also times
the static method before issue 18 (plain load ramp, Exudyn's beam Jacobian), ~20 s CPU per solve.
"""

from __future__ import annotations

import argparse
import math
import os
from contextlib import contextmanager
from dataclasses import replace

import numpy as np

from workbench.models import get_model
from workbench.models.discretization import estimate_from_values
from workbench.models.result import SolverOptions
from workbench.physics import beam3d
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from _timing import best_of

TENSIONS = (4.0, 0.0, 0.0, 0.0, 2.0, 0.0)
LENGTH = 0.4


def robot(stiff: bool, planar: bool = False) -> Robot:
    """The NiTi robot (``planar``: one tendon pair at sigma = 0 / pi per section instead of three)."""
    cs = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33)
    if stiff:
        cs = replace(cs, EA=100.0 * cs.EA, GA=100.0 * cs.GA)
    angles = (0.0, math.pi) if planar else (math.pi / 2, -math.pi / 6, 7 * math.pi / 6)
    tg = TendonGroup(angles=angles, offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, cs, tg, n_disks=10), Section(0.2, cs, tg, n_disks=10)))


@contextmanager
def newton_counter():
    """Count Newton iterations of every ``exudyn.SolveStatic`` inside the block (benchmark only)."""
    import exudyn as exu

    original, counts = exu.SolveStatic, []

    def counted(mbs, settings, **kw):
        kw["storeSolver"] = True
        try:
            return original(mbs, settings, **kw)
        finally:
            counts.append(int(mbs.sys["staticSolver"].it.newtonStepsCount))

    exu.SolveStatic = counted
    try:
        yield counts
    finally:
        exu.SolveStatic = original


def timed(fn, repeats: int):
    """(best wall, best CPU, result, Newton iterations of one solve)."""
    with newton_counter() as counts:
        wall, cpu, res = best_of(fn, repeats)
    return wall, cpu, res, sum(counts) // max(1, repeats)


def row(name, n, wall, cpu, res, newton, ref):
    err = float("nan") if ref is None else float(np.linalg.norm(res.tip_position - ref))
    acc = res.extras.get("load_steps", res.extras.get("static_steps", float("nan")))
    tip = np.array2string(res.tip_position, precision=6)
    print(f"{name:>22} {n:>5d} {1e3 * cpu:>9.1f} {1e3 * wall:>9.1f} {res.solver.iterations:>5d}/{acc:<4.0f} "
          f"{newton:>6d}  {tip}  {err:>9.2e} ({err / LENGTH:.1e} L)", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="reference at 80 elements, spring_link at 20 links only")
    ap.add_argument("--baseline", action="store_true", help="also the pre-issue-18 static method (slow)")
    ap.add_argument("--stiff", action="store_true", help="EA and GA x 100 (bench_reach's robot)")
    ap.add_argument("--reference", type=int, default=None, help="beam3d elements of the reference")
    args = ap.parse_args()
    r3, load = robot(args.stiff), LoadCase(actuation=TendonActuation("tension", TENSIONS))
    opts = lambda n: SolverOptions(n_elements=n, tendon_model="eyelets", newton_tolerance=1e-10, max_load_steps=2000)
    n_ref = args.reference or (80 if args.quick else 160)
    print(f"load average {os.getloadavg()[0]:.1f}; robot {'EA x 100' if args.stiff else 'NiTi'}; reference beam3d "
          f"at {n_ref} elements")
    ref = beam3d.run(r3, load, opts(n_ref)).tip_position
    print(f"{'model':>22} {'N':>5} {'CPU [ms]':>9} {'wall [ms]':>9} {'calls':>10} {'Newton':>6}  tip [m] (base)"
          f"{'':>26} error")
    tips = {}
    for n in (10, 20, 40) if args.quick else (10, 20, 40, 80):
        wall, cpu, res, it = timed(lambda: beam3d.run(r3, load, opts(n)), args.repeats if n <= 40 else 1)
        tips[n] = (cpu, res.tip_position)
        row("beam3d", n, wall, cpu, res, it, ref)
    if args.baseline:
        wall, cpu, res, it = timed(lambda: beam3d.run(r3, load, opts(20), stiffness_stages=(), jacobian="exudyn_beam"), 1)
        row("beam3d (before #18)", 20, wall, cpu, res, it, ref)
        base_cpu = cpu
    wall, cpu, res, it = timed(lambda: beam3d.run(r3, load, opts(20), stiffness_stages=()), 1)
    row("beam3d (plain ramp)", 20, wall, cpu, res, it, ref)
    planar, pload = robot(args.stiff, planar=True), LoadCase(actuation=TendonActuation("tension", (4.0, 0.0, 2.0, 0.0)))
    wall, cpu_a, res, _ = timed(lambda: get_model("ancf")(planar, pload, opts(20)), max(args.repeats, 5))
    row("ancf (planar)", 20, wall, cpu_a, res, -1, None)  # ANCF calls mbs.SolveStatic: Newton not counted
    run_sl = get_model("spring_link")
    for n in (20,) if args.quick else (20, 40):
        wall, cpu, res, it = timed(lambda: run_sl(r3, load, opts(n)), 1)
        row("spring_link (tree)", n, wall, cpu, res, it, ref)
    print("\nRichardson error bars (order 2, workbench.models.discretization), from N, N/2, N/4:")
    for n in sorted(tips)[2:]:
        est = estimate_from_values([tips[n][1], tips[n // 2][1], tips[n // 4][1]], [n, n // 2, n // 4], 2.0, 1e-9)
        print(f"  {n} el.: {est.error:.2e} m (observed order {est.order_observed:.2g}); vs the reference "
              f"{np.linalg.norm(tips[n][1] - ref):.2e} m")
    print(f"  20 el. (1 element per disk interval) vs the reference: {np.linalg.norm(tips[20][1] - ref):.2e} m; "
          f"10 el. puts the eyelets mid-element (not in the asymptotic range)")
    print(f"CPU ratio beam3d / planar ANCF at 20 el.: {tips[20][0] / cpu_a:.1f} "
          f"(beam3d {1e3 * tips[20][0]:.0f} ms, ANCF {1e3 * cpu_a:.1f} ms); target <= 0.25 s and <= 50")
    if args.baseline:
        print(f"speed-up over the method before issue 18 at 20 el.: {base_cpu / tips[20][0]:.0f} x (CPU)")


if __name__ == "__main__":
    main()
