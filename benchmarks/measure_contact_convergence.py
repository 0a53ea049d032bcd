"""Convergence of the contact model's held state under mesh refinement: a measurement, not a test.

Run from the repository root: ``python benchmarks/measure_contact_convergence.py [n1,n2,...]``
(default ``8,16,32,64,128``).  For a few cases of ``studies/whole_arm_grasp.toml`` (H&W trunk
wrapped round a cylinder) and ``studies/fruit_harvester_fluidic.toml`` (Shao's scoop) it solves
the held state alone (close and release; no pull-out, carry or control: the state whose tip the
CC comparison judges) at each element count, with the study's contact law (8 contact segments
per element, so refining the mesh refines the contact too), and prints per mesh the tip (base
x, z), its distance to CC's tip, the settled object offset, the normal force, ``|tip(n) -
tip(n/2)|`` and the observed order ``log2`` of successive differences, and the CPU / wall time.
The contact model's declared order (``registry.MODELS["contact"].order``) is read off this:
results in ``docs/models.md``, "Planar contact" (convergence under refinement).
"""

from __future__ import annotations

import copy
import math
import os
import sys
import time

import numpy as np

CASES = [  # study, scenario values that pick the case, overrides of the held-state task
    ("studies/whole_arm_grasp.toml", {"object_radius": 0.06, "squeeze": 1.2, "friction": 0.3}),
    ("studies/whole_arm_grasp.toml", {"object_radius": 0.06, "squeeze": 1.0, "friction": 0.0}),
    ("studies/whole_arm_grasp.toml", {"object_radius": 0.07, "squeeze": 1.5, "friction": 0.6}),
    ("studies/whole_arm_grasp.toml", {"object_radius": 0.07, "squeeze": 1.0, "friction": 0.6}),
    ("studies/fruit_harvester_fluidic.toml", {"actuation": "fluidic", "payload": "object", "object_mass": 0.2}),
    ("studies/fruit_harvester_fluidic.toml", {"actuation": "tendon", "payload": "object", "object_mass": 0.2}),
]
#: per scenario: the held state only
HELD = {"whole_arm_wrap": {"pull_distance": 0.0, "carry_samples": 0}, "harvester_scoop": {"control_iterations": 0}}


def _case(study: str, pick: dict):
    from workbench.experiments.whole_arm_grasp.kind import load_grasp_study
    from workbench.study.expand import expand

    for c in expand(load_grasp_study(study)):
        sc = c.params["scenario"]
        base = sc.get("contact_stiffness") in (None, 1.0e7, 1.0e8)
        if base and all(sc.get(k) == v for k, v in pick.items()):
            return c
    raise LookupError(f"{study}: no case with {pick}")


def _held_tip(params: dict, n: int):
    from workbench.experiments.whole_arm_grasp.tasks import cc_result, run_task
    from workbench.experiments.whole_arm_grasp.worker import plan_function
    from workbench.study.build import build_options, resolve_case

    p = copy.deepcopy(params)
    p["solver"]["n_elements"] = n
    p["scenario"].update(HELD[p["scenario"]["name"]])
    robot, ran = resolve_case(p)
    opt = build_options(ran["solver"])
    scen = {k: v for k, v in ran["scenario"].items() if k not in ("error_estimate", "penalty_estimate")}
    plan, task = plan_function(scen["name"])(robot, scen)
    res = run_task(robot, plan, task, opt)
    cc = cc_result(robot, plan, opt)
    return res, float(np.linalg.norm(res.tip_position - cc.tip_position))


def main(argv: list[str]) -> int:
    ns = [int(v) for v in argv[0].split(",")] if argv else [8, 16, 32, 64, 128]
    print(f"load average {os.getloadavg()[0]:.1f}; meshes {ns}")
    for study, pick in CASES:
        case = _case(study, pick)
        print(f"\n{study} {pick}")
        prev, d_prev = None, None
        for n in ns:
            t0, c0 = time.perf_counter(), time.process_time()
            try:
                res, cc_err = _held_tip(case.params, n)
            except Exception as e:  # noqa: BLE001 - a failed mesh is a result here
                print(f"  n={n:4d} failed: {type(e).__name__}: {str(e)[:120]}")
                prev, d_prev = None, None
                continue
            tip = res.tip_position[[0, 2]]
            e = res.extras
            d = float(np.linalg.norm(tip - prev)) if prev is not None else math.nan
            order = math.log2(d_prev / d) if d_prev and d and d > 0 else math.nan
            print(f"  n={n:4d} tip=({tip[0]:.6f}, {tip[1]:.6f}) m  CC error {cc_err * 1e3:8.3f} mm  "
                  f"settle ({e.get('settle_dx', math.nan) * 1e3:7.3f}, {e.get('settle_dz', math.nan) * 1e3:7.3f}) mm  "
                  f"F_n {e.get('normal_force', math.nan):8.3f} N  |tip(n)-tip(n/2)| {d * 1e3:8.4f} mm  "
                  f"order {order:5.2f}  cpu {time.process_time() - c0:5.1f} s  wall {time.perf_counter() - t0:5.1f} s")
            prev, d_prev = tip, (d if math.isfinite(d) else None)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
