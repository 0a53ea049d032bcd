"""Timing of the series-parallel module (Huang et al.): one FK static solve and one IK.

Run: ``/work/venv/bin/python benchmarks/bench_series_parallel.py``.  Prints wall times measured in
this run (best of ``--repeat``) and their ratios, including the cost of the IK branch check
(``check_branch=True`` vs ``False``); no assertions.
"""

from __future__ import annotations

import argparse

import numpy as np

from workbench.physics.series_parallel import (
    ModuleGeometry,
    home_pose,
    module_forward,
    module_inverse,
    pose_from_xyz_rotvec,
    stack_forward,
    stack_inverse,
)
from _timing import best_of


def _best(fn, repeat):
    wall, _, out = best_of(fn, repeat)
    return wall, out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--elements", type=int, nargs="+", default=[8, 16])
    ap.add_argument("--stack", action="store_true", help="also time a 3-module IK and FK")
    args = ap.parse_args(argv)
    geo = ModuleGeometry()
    target = home_pose(geo) @ pose_from_xyz_rotvec([0.05, -0.03, 0.05], [0.1, 0.2, 0.15])
    print(f"{'n_el':>5} {'IK [s]':>9} {'IK its':>7} {'leg solves':>10} {'FK [s]':>9} {'FK its':>7} {'IK/FK':>6}"
          f" {'IK unchecked [s]':>17} {'check cost':>10}")
    for n in args.elements:
        t_ik, ik = _best(lambda: module_inverse(geo, target, n_elements=n), args.repeat)
        t_raw, _ = _best(lambda: module_inverse(geo, target, n_elements=n, check_branch=False), args.repeat)
        t_fk, fk = _best(lambda: module_forward(geo, ik.lengths, n_elements=n), args.repeat)
        ok = ik.success and fk.converged
        print(f"{n:>5} {t_ik:>9.3f} {ik.iterations:>7} {ik.leg_solves:>10} {t_fk:>9.3f} {fk.iterations:>7} "
              f"{t_ik / t_fk:>6.2f} {t_raw:>17.3f} {t_ik / t_raw:>9.2f}x"
              f"{'' if ok else '  (FAILED: ' + (ik.reason or fk.reason) + ')'}")
    if args.stack:
        geos = [geo] * 3
        poses = np.stack([home_pose(geo)] * 3)
        for k in range(3):
            poses[k, 2, 3] = (k + 1) * geo.height
        poses[2] = poses[2] @ pose_from_xyz_rotvec([0.05, 0.0, 0.0], [0.0, 0.2, 0.0])
        t_ik, ik = _best(lambda: stack_inverse(geos, poses), 1)
        t_fk, fk = _best(lambda: stack_forward(geos, ik.lengths), 1)
        print(f"3 modules (8 el.): IK {t_ik:.3f} s, FK {t_fk:.3f} s, ratio {t_ik / t_fk:.2f}, "
              f"ok={ik.success and fk.converged}")


if __name__ == "__main__":
    main()
