"""Benchmark: solve time vs resolution at equal accuracy for the spring-link chain (default
kinematic-tree backend), the Cosserat rod (continuum tendons, shooting) and the planar ANCF model.

Run from the repository root::

    python benchmarks/bench_reach.py [--repeats 2] [--quick]

Cases (issue 14's validation matrix, EA and GA x 100 so that the inextensible references hold):

* ``alpha``: 0.8 m, 6 mm steel rod, horizontal base, tip load alpha = P L^2 / EI = 5 against
  gravity's direction; reference the clamped elastica (:mod:`workbench.reference.elastica`).
* ``spatial``: issue 14's 2-section NiTi robot (tensions 4, 0, 0, 0, 2, 0 N, continuum tendons);
  reference the exact constant-curvature arcs (with the tendon compression).

For each model and resolution (links / elements; the Cosserat residual tolerance) it prints the
best wall and CPU time of ``--repeats`` and the tip error / L; then, for every spring-link N, the
cheapest ANCF mesh and the loosest Cosserat tolerance at least as accurate, with the CPU time
ratios measured in this run (CPU time: the machine is shared, wall time is noisy).  ``--quick`` runs the smallest resolutions only (a smoke test of the script).
"""

from __future__ import annotations

import argparse
import math
from dataclasses import replace

import numpy as np

from workbench.kinematics import forward_kinematics
from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.reference.elastica import clamped_elastica
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.orientation import base_rotation_for
from _timing import best_of

L = 0.8
TIGHT = dict(newton_tolerance=1e-10, max_load_steps=2000)


def _stiff(cs: CrossSection) -> CrossSection:
    return replace(cs, EA=100.0 * cs.EA, GA=100.0 * (cs.GA if cs.GA is not None else cs.EA))


def _alpha():
    cs = _stiff(CrossSection.circular(6e-3))
    robot = Robot(sections=(Section(L, cs, TendonGroup(angles=(0.0, math.pi), offset=0.02), n_disks=8),),
                  base_rotation=base_rotation_for("horizontal"))
    P = 5.0 * cs.EI / L**2
    ref = clamped_elastica(L, cs.EI, tip_force=(0.0, -P), stations=2, n_continuation=12)
    return robot, LoadCase(tip_force=(-P, 0.0, 0.0)), np.array([ref.tip[1], 0.0, ref.tip[0]]), L


def _spatial():
    cs = _stiff(CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33))
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    robot = Robot(sections=(Section(0.2, cs, tg, n_disks=10), Section(0.2, cs, tg, n_disks=10)))
    T = (4.0, 0.0, 0.0, 0.0, 2.0, 0.0)
    kap, phi, ell = [], [], []
    for j, sec in enumerate(robot.sections):
        m, comp = np.zeros(2), 0.0
        for (k, sig, grp), t in zip(robot.tendon_table(), T):
            if k >= j:
                m += t * grp.offset * np.array([math.cos(sig), math.sin(sig)])
                comp += t
        eps = comp / sec.cross_section.EA
        kap.append(np.linalg.norm(m) / sec.cross_section.EI / (1.0 - eps))
        phi.append(math.atan2(m[1], m[0]))
        ell.append(sec.length * (1.0 - eps))
    tip = forward_kinematics(np.asarray(kap), np.asarray(phi), np.asarray(ell))[:3, 3]
    return robot, LoadCase(actuation=TendonActuation("tension", T)), tip, 0.4


def _sweep(model, robot, load, ref, length, resolutions, repeats, cosserat=False):
    run, out = get_model(model), {}
    for n in resolutions:
        opts = SolverOptions(newton_tolerance=n, max_load_steps=2000) if cosserat else SolverOptions(n_elements=n, **TIGHT)
        wall, cpu, res = best_of(lambda: run(robot, load, opts), repeats)
        out[n] = (cpu, float(np.linalg.norm(res.tip_position - ref) / length))
        label = f"{n:>8.0e}" if cosserat else f"{n:>8d}"
        print(f"{model:>12} {label} {1e3 * wall:>10.1f} {1e3 * cpu:>10.1f} {out[n][1]:>12.2e}", flush=True)
    return out


def _equal(name, sl, other):
    for n, (t, e) in sl.items():
        ok = [k for k, (_, e2) in other.items() if e2 <= e]
        if not ok:
            print(f"  spring_link N={n:>3} ({e:.1e}): no {name} resolution reaches it")
            continue
        k = ok[0]
        print(f"  spring_link N={n:>3} ({e:.1e} L, {1e3 * t:.1f} ms CPU) vs {name} {k:g} "
              f"({other[k][1]:.1e} L, {1e3 * other[k][0]:.1f} ms CPU): CPU time ratio {t / other[k][0]:.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="smallest resolutions only")
    args = ap.parse_args()
    links = (8, 16) if args.quick else (8, 16, 32, 64, 128)
    tols = (1e-4, 1e-6) if args.quick else (1e-4, 1e-6, 1e-8, 1e-10)
    for name, build in (("alpha", _alpha), ("spatial", _spatial)):
        robot, load, ref, length = build()
        print(f"\n=== {name}: static solve; wall time (best of {args.repeats}), tip error / L ===")
        print(f"{'model':>12} {'N / tol':>8} {'wall [ms]':>10} {'CPU [ms]':>10} {'error / L':>12}")
        sl = _sweep("spring_link", robot, load, ref, length, links, args.repeats)
        co = _sweep("cosserat", robot, load, ref, length, tols, args.repeats, cosserat=True)
        an = None
        if name == "alpha":  # ANCF is planar: the spatial robot is not its case
            an = _sweep("ancf", robot, load, ref, length, (2, 4, 8) if args.quick else (2, 4, 8, 16, 32), args.repeats)
        print("equal accuracy (the cheapest resolution at least as accurate as spring-link N):")
        if an is not None:
            _equal("ancf", sl, an)
        _equal("cosserat", sl, co)


if __name__ == "__main__":
    main()
