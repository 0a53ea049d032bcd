"""Benchmark: the 12 load cases of the Rao et al. 2021 two-section robot through the workbench's models, with
the ratio to the C++ peer's recorded medians (issue 31).

Run from the repository root::

    python benchmarks/bench_peer.py [--models cosserat,cosserat_eyelets,beam3d,spring_link,cc] [--cases 0,1,2]
                                    [--repeats 1]
                                    [--no-reference] [--ref-scale 4]

Robot and cases (``../shared/notes/peer-benchmark.md``): 2 x 0.2 m NiTi (E 54 GPa, nu 0.3, d 1.4 mm, density
6450 kg/m^3), 10 disks per section, 3 tendons per section at 90 / -30 / 210 deg, offset 10 mm, tendon EA 1e7 N,
no gravity; tensions (section 1's three tendons, then section 2's) and a tip force in the base frame
(:data:`CASES`).  Models: ``cosserat`` (continuous tendons, the peer's CR), ``cosserat_eyelets`` (the
``cosserat`` model with ``tendon_model = "eyelets"``: the peer's SSCR, the same physics), ``beam3d`` with
eyelets at 20 elements (also compared with the SSCR), ``spring_link`` with eyelets at 40 links (the peer's PRB), ``cc`` (the peer's CC;
it ignores the tip force by design).

Printed per model: the median over the solved cases of each case's best wall (and CPU) time of
``--repeats`` solves; cases solved / failed with the reasons; the tip distance / L to a reference solve of
the same model and physics (max and median over the cases): ``cosserat`` and ``cosserat_eyelets`` at a
100x tighter ``newton_tolerance`` (as the study pipeline's estimate), ``beam3d`` at ``--ref-scale`` times the elements
(an underestimate by ``ref-scale^-2``, 6 % at 4, for its order 2), ``spring_link`` against the independent
eyelet model, ``beam3d`` at ``--ref-scale`` x 20 elements (the same eyelet physics: tendons straight
between the disks, point loads at the disks; beam3d's extensibility is ~1e-4 L here), ``cc`` exact (no
discretisation); and the speed-up ``peer median / workbench median`` from
``benchmarks/peer_timings.toml`` (the peer's own timer readings on this machine, with their source).
The reference solves are slow: ``--no-reference`` skips them.  With a
``--cases`` subset the medians are over other cases than the peer's: the ratio is then indicative only.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import time
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from workbench.models import get_model
from workbench.models.result import SolverOptions
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

HERE = Path(__file__).resolve().parent
LENGTH = 0.4

#: (tensions in N: section 1's t1 t2 t3, section 2's t1 t2 t3; tip force in N, base frame), cases 0..11
CASES = (
    ((4, 0, 0, 0, 2, 0), (0, 0, 0)), ((2, 0, 0, 0, 1, 0), (0, 0, 0)), ((0, 3, 0, 0, 0, 3), (0, 0, 0)),
    ((5, 0, 0, 0, 0, 5), (0, 0, 0)), ((3, 0, 0, 0, 0, 0), (0, 0, 0)), ((0, 0, 0, 4, 0, 0), (0, 0, 0)),
    ((4, 0, 0, 0, 2, 0), (0.1, 0, 0)), ((4, 0, 0, 0, 2, 0), (0, 0, -0.2)), ((2, 2, 0, 0, 3, 0), (0, 0.1, 0)),
    ((0, 0, 0, 0, 0, 0), (0.1, 0, 0)), ((6, 0, 0, 6, 0, 0), (0, 0, 0)), ((1, 1, 1, 1, 1, 1), (0, 0, 0)),
)


@dataclass(frozen=True)
class Setup:
    """How one model is run: its options, the reference options (``None``: exact), a label, the
    reference's model (``None``: the same model) and the registered model run (``None``: the row's name)."""

    options: SolverOptions
    reference: SolverOptions | None
    label: str
    reference_model: str | None = None
    model: str | None = None


def setups(ref_scale: int) -> dict[str, Setup]:
    """The models at the issue's resolutions, with their same-physics references."""
    cos = SolverOptions(tendon_model="continuum")
    cey = SolverOptions(tendon_model="eyelets")
    b3 = SolverOptions(n_elements=20, tendon_model="eyelets")
    sl = SolverOptions(n_elements=40, tendon_model="eyelets", model_settings={"spring_link": {"richardson": True}})
    return {
        "cosserat": Setup(cos, replace(cos, newton_tolerance=cos.newton_tolerance / 100),
                          f"tol {cos.newton_tolerance:g}; ref tol {cos.newton_tolerance / 100:g}"),
        "cosserat_eyelets": Setup(cey, replace(cey, newton_tolerance=cey.newton_tolerance / 100),
                                  f"eyelets; tol {cey.newton_tolerance:g}; ref tol {cey.newton_tolerance / 100:g}",
                                  model="cosserat"),
        "beam3d": Setup(b3, replace(b3, n_elements=ref_scale * b3.n_elements),
                        f"eyelets, 20 el.; ref {ref_scale * 20} el."),
        "spring_link": Setup(sl, replace(b3, n_elements=ref_scale * b3.n_elements),
                             f"eyelets, Richardson 20+40 links; ref beam3d {ref_scale * 20} el.", "beam3d"),
        "cc": Setup(SolverOptions(), None, "closed form (exact)"),
    }


def robot() -> Robot:
    """The Rao et al. 2021 two-section NiTi robot of ``../shared/notes/peer-benchmark.md``."""
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.3)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, rod, tg, n_disks=10), Section(0.2, rod, tg, n_disks=10)))


def load(case: int) -> LoadCase:
    tensions, force = CASES[case]
    return LoadCase(actuation=TendonActuation("tension", tuple(map(float, tensions))),
                    tip_force=tuple(map(float, force)))


def solve(model, r: Robot, case: int, options: SolverOptions, repeats: int):
    """(best wall [s], best CPU [s], tip position) of ``repeats`` solves, or the failure as a one-line string."""
    wall, cpu, tip = math.inf, math.inf, None
    for _ in range(max(1, repeats)):
        c0, t0 = time.process_time(), time.perf_counter()
        try:
            res = model(r, load(case), options)
        except Exception as e:  # noqa: BLE001 - a failed case is a result of the benchmark
            return f"{type(e).__name__}: {' '.join(str(e).split())[:140]}"
        wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
        if not res.solver.converged:
            return f"not converged: {res.solver.message[:140]}"
        tip = np.asarray(res.tip_position, dtype=float)
        if not np.all(np.isfinite(tip)):
            return "non-finite tip"
    return wall, cpu, tip


@dataclass(frozen=True)
class Summary:
    """One model's results over the cases run."""

    walls: tuple[float, ...]
    cpus: tuple[float, ...]
    errors: tuple[float, ...]
    failures: tuple[tuple[int, str], ...]
    ref_failures: tuple[tuple[int, str], ...]


def run_model(name: str, setup: Setup, cases: list[int], repeats: int, reference: bool) -> Summary:
    """Every case through ``name`` (and its reference), one line per case as it finishes."""
    model, r = get_model(setup.model or name), robot()
    ref_model = get_model(setup.reference_model or setup.model or name)
    walls, cpus, errors, failures, ref_failures = [], [], [], [], []
    for case in cases:
        out = solve(model, r, case, setup.options, repeats)
        if isinstance(out, str):
            failures.append((case, out))
            print(f"  {name:>16} case {case:>2}: FAILED {out}", flush=True)
            continue
        wall, cpu, tip = out
        walls.append(wall)
        cpus.append(cpu)
        err = ""
        if reference and setup.reference is None:
            errors.append(0.0)
            err = "exact"
        elif reference:
            ref = solve(ref_model, r, case, setup.reference, 1)
            if isinstance(ref, str):
                ref_failures.append((case, ref))
                err = f"reference FAILED {ref}"
            else:
                errors.append(float(np.linalg.norm(tip - ref[2])) / LENGTH)
                err = f"{errors[-1]:.2e} L from the reference"
        print(f"  {name:>16} case {case:>2}: {1e3 * wall:9.1f} ms wall {1e3 * cpu:9.1f} ms CPU  "
              f"tip {np.array2string(tip, precision=5)}  {err}", flush=True)
    return Summary(tuple(walls), tuple(cpus), tuple(errors), tuple(failures), tuple(ref_failures))


def peer_rows() -> tuple[dict, dict[str, dict]]:
    """The peer's recorded timings: (source, {workbench model: peer row (with its key)})."""
    data = tomllib.loads((HERE / "peer_timings.toml").read_text())
    by_model = {}
    for key, row in data["models"].items():
        names = row["workbench_model"]
        for name in [names] if isinstance(names, str) else names:
            if name:
                by_model[name] = dict(row, key=key)
    return data["source"], by_model


def report(results: dict[str, Summary], labels: dict[str, str], peers: dict[str, dict], n_cases: int) -> None:
    """The summary table: medians, solved / failed, accuracy, speed-up over the peer."""
    print(f"\n{'model':>16} {'resolution':<34} {'wall [ms]':>9} {'CPU [ms]':>9} {'solved':>7} {'max err':>9} "
          f"{'med err':>9}  {'peer':>5} {'peer [ms]':>9} {'peer ok':>7} {'speed-up':>9}")
    for name, s in results.items():
        wall = 1e3 * float(np.median(s.walls)) if s.walls else math.nan
        cpu = 1e3 * float(np.median(s.cpus)) if s.cpus else math.nan
        emax = f"{max(s.errors):.1e}" if s.errors else "-"
        emed = f"{float(np.median(s.errors)):.1e}" if s.errors else "-"
        p = peers.get(name)
        if p is None:
            peer = f"{'-':>5} {'-':>9} {'-':>7} {'-':>9}"
        else:
            ratio = p["median_ms"] / wall
            bound = "<" if p.get("upper_bound") else ""
            peer = (f"{p['key']:>5} {bound + format(p['median_ms'], 'g'):>9} {p['solved']:>4}/12 "
                    f"{bound + format(ratio, '.3g') + 'x':>9}")
        print(f"{name:>16} {labels[name]:<34} {wall:9.1f} {cpu:9.1f} {len(s.walls):>3}/{n_cases:<3} {emax:>9} "
              f"{emed:>9}  {peer}")
    for name, s in results.items():
        for case, why in s.failures:
            print(f"  {name} case {case} failed: {why}")
        for case, why in s.ref_failures:
            print(f"  {name} case {case}: reference solve failed: {why}")
    print("errors: tip distance / L to the reference solve; speed-up: peer median / workbench median wall time")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--models", default="cosserat,cosserat_eyelets,beam3d,spring_link,cc",
                    help="comma-separated model names")
    ap.add_argument("--cases", default=",".join(map(str, range(len(CASES)))), help="comma-separated case numbers")
    ap.add_argument("--repeats", type=int, default=1, help="solves per case (its best time counts)")
    ap.add_argument("--reference", action=argparse.BooleanOptionalAction, default=True,
                    help="solve each case's reference to measure the accuracy (slow)")
    ap.add_argument("--ref-scale", type=int, default=4, help="mesh factor of the beam3d / spring_link references")
    args = ap.parse_args()
    known = setups(args.ref_scale)
    models = [m.strip() for m in args.models.split(",") if m.strip()]
    cases = [int(c) for c in args.cases.split(",") if c.strip()]
    for m in models:
        if m not in known:
            ap.error(f"--models: {m!r} is not benchmarked here (one of {', '.join(known)})")
    for c in cases:
        if not 0 <= c < len(CASES):
            ap.error(f"--cases: {c} is not a case (0..{len(CASES) - 1})")
    source, peers = peer_rows()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=HERE).stdout
    print(f"commit {commit.strip() or '?'}; load average {os.getloadavg()[0]:.1f}; cases {cases}; repeats "
          f"{args.repeats}; reference {'on' if args.reference else 'off'}\npeer: {source['paper']}; {source['measured']}")
    results = {m: run_model(m, known[m], cases, args.repeats, args.reference) for m in models}
    report(results, {m: known[m].label for m in models}, peers, len(cases))
    print(f"load average at the end {os.getloadavg()[0]:.1f}"
          + ("" if len(cases) == len(CASES) else "; a case subset: the ratios to the peer are indicative only"))


if __name__ == "__main__":
    main()
