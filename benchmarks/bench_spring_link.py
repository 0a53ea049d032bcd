"""Benchmark: spring-link static solve time vs N (2-D and 3-D) against the planar ANCF model at
equal accuracy.

Run from the repository root::

    /work/venv/bin/python benchmarks/bench_spring_link.py [--repeats 3]

Two reference cases on the 0.8 m / 6 mm steel rod (EI = 13.36 N m^2):

* ``arc``: tip moment M = (pi/2) EI / L: the exact answer is a quarter circle for both models (a
  continuum tendon would add the compression T, which the extensible ANCF rod feels and the
  inextensible chain does not, so a pure moment keeps the comparison exact);
* ``sag``: the rod mounted horizontally under self-weight with gamma = q L^3 / EI = 4 (density
  scaled): reference = the clamped inextensible elastica BVP (:mod:`workbench.reference.elastica`).

For every spring-link N (4..64) it prints wall time (best of ``--repeats``) and tip error for the
planar and the spatial chain, built from rigid bodies (the registered model) and as an
``ObjectKinematicTree`` (:mod:`workbench.physics.spring_link.tree`); then, for each N, the cheapest ANCF mesh (1..64 elements) that is at
least as accurate, and the time ratio spring-link / ANCF measured in this run.  A further block
times the eyelet tendon variants (constant-force rope chain and length-controlled reeving) at N =
16, for the rigid-body and the kinematic-tree backend (3-D: Cardan joints, torsion locked).
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.physics.spring_link.tree import tree_tip_position
from workbench.physics.spring_link import SpringLinkParams, solve
from workbench.reference.elastica import clamped_elastica
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset
from _timing import best_of

L = 0.8
D = 0.02


def _cases():
    rod = build_preset("steel_rod")
    EI = rod.sections[0].cross_section.EI
    theta = math.pi / 2
    R = L / theta
    arc_tip = np.array([R * (1 - math.cos(theta)), 0.0, R * math.sin(theta)])
    arc = (rod, LoadCase(tip_torque=(0.0, theta * EI / L, 0.0)), arc_tip)

    area = math.pi * 0.006**2 / 4
    rho = 4.0 * EI / L**3 / (area * 9.81)
    heavy = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal", density=rho)
    q = heavy.sections[0].cross_section.mass_per_length * 9.81
    # elastica coordinates: a = base z (along the rod), b = base x (up); gravity along -b
    ref = clamped_elastica(L, EI, distributed_load=(0.0, -q), stations=2, n_continuation=8)
    sag_tip = np.array([ref.tip[1], 0.0, ref.tip[0]])
    sag = (heavy, LoadCase(), sag_tip)
    return {"arc": arc, "sag": sag}


def _best(fn, repeat):
    wall, _, out = best_of(fn, repeat)
    return wall, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    ancf = get_model("ancf")
    Ns = (4, 8, 16, 32, 64)
    ancf_ns = (1, 2, 4, 8, 16, 32, 64)
    for name, (robot, load, tip) in _cases().items():
        print(f"\n=== case {name}: static solve, tip error vs exact ===")
        sl = {}
        for dim in ("2d", "3d"):
            for n in Ns:
                opts = SolverOptions(n_elements=n, tendon_model="continuum")
                t, res = _best(lambda: solve(robot, load, opts, SpringLinkParams(dimension=dim, backend="bodies")),
                               args.repeats)
                sl[dim, n] = (t, float(np.linalg.norm(res.tip_position - tip)))
        kt = {}
        for dim in ("2d", "3d"):
            for n in Ns:
                opts = SolverOptions(n_elements=n)
                t, tp = _best(lambda: tree_tip_position(robot, load, opts, dim), args.repeats)
                kt[dim, n] = (t, float(np.linalg.norm(tp - tip)))
        an = {}
        for n in ancf_ns:
            opts = SolverOptions(n_elements=n, tendon_model="continuum")
            t, res = _best(lambda: ancf(robot, load, opts), args.repeats)
            an[n] = (t, float(np.linalg.norm(res.tip_position - tip)))
        print(f"{'model':>14} {'N':>4} {'time [ms]':>10} {'tip error [m]':>14}")
        for (dim, n), (t, e) in sl.items():
            print(f"{'spring_link ' + dim:>14} {n:>4} {1e3 * t:>10.2f} {e:>14.3e}")
        for (dim, n), (t, e) in kt.items():
            print(f"{'tree ' + dim:>14} {n:>4} {1e3 * t:>10.2f} {e:>14.3e}")
        for n, (t, e) in an.items():
            print(f"{'ancf':>14} {n:>4} {1e3 * t:>10.2f} {e:>14.3e}")
        print("rigid bodies vs ObjectKinematicTree (same chain, same answer): time ratio bodies/tree")
        for dim in ("2d", "3d"):
            print(f"  {dim}: " + "  ".join(f"N={n}: {sl[dim, n][0] / kt[dim, n][0]:.2f}" for n in Ns))
        errs = np.array([sl["2d", n][1] for n in Ns])
        order = np.log2(errs[:-1] / errs[1:])
        print("spring_link 2d observed order per doubling:", " ".join(f"{o:.2f}" for o in order))
        print("equal accuracy (cheapest ANCF mesh at least as accurate as spring-link N):")
        for dim in ("2d", "3d"):
            for n in Ns:
                t, e = sl[dim, n]
                ok = [m for m in ancf_ns if an[m][1] <= e]
                if not ok:
                    print(f"  spring_link {dim} N={n:>2}: no ANCF mesh in {ancf_ns} reaches {e:.2e}")
                    continue
                m = ok[0]
                print(f"  spring_link {dim} N={n:>2} ({e:.2e} m, {1e3 * t:.2f} ms) vs ancf {m:>2} el. "
                      f"({an[m][1]:.2e} m, {1e3 * an[m][0]:.2f} ms): time ratio spring_link/ancf = {t / an[m][0]:.2f}")

    print("\n=== eyelet tendons at N = 16 (steel rod, 2 tendons) ===")
    rod = build_preset("steel_rod")
    cases = {
        "tension, rope chain": LoadCase(actuation=TendonActuation("tension", (300.0, 0.0))),
        "length, reeving": LoadCase(actuation=TendonActuation("length", (-0.01, 0.0), pretension=10.0)),
    }
    base = {}
    for dim in ("2d", "3d"):
        t, _ = _best(lambda: solve(rod, cases["tension, rope chain"], SolverOptions(n_elements=16, tendon_model="continuum"),
                                   SpringLinkParams(dimension=dim, backend="bodies")), args.repeats)
        base[dim] = t
        print(f"  {dim} continuum tension (reference): {1e3 * t:8.2f} ms")
        t2, _ = _best(lambda: solve(rod, cases["tension, rope chain"], SolverOptions(n_elements=16, tendon_model="continuum"),
                                    SpringLinkParams(dimension=dim, backend="tree", torsion="locked")), args.repeats)
        print(f"  {dim} continuum tension, tree backend: {1e3 * t2:8.2f} ms (ratio to bodies {t2 / t:.2f})")
        for label, ld in cases.items():
            variants = [("bodies", "spring"), ("tree", "locked")] if dim == "2d" else [
                ("bodies", "spring"), ("bodies", "locked"), ("tree", "locked")]
            for be, tors in variants:
                t, res = _best(lambda: solve(rod, ld, SolverOptions(n_elements=16, tendon_model="eyelets"),
                                             SpringLinkParams(dimension=dim, backend=be, torsion=tors)), args.repeats)
                be = be if dim == "2d" else f"{be}/{tors}"
                print(f"  {dim} {be:<14} eyelets {label:<20}: {1e3 * t:8.2f} ms, {res.solver.iterations:4d} Newton its, "
                      f"ratio to continuum {t / base[dim]:.1f}")
    for label, ld in cases.items():
        t, _ = _best(lambda: ancf(rod, ld, SolverOptions(n_elements=16, tendon_model="eyelets")), args.repeats)
        # the ANCF model controls length by its own outer tension iteration, not by reeving
        print(f"  ancf 16 el. eyelets {label.split(',')[0]:<20}: {1e3 * t:8.2f} ms")


if __name__ == "__main__":
    main()
