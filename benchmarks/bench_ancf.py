"""Benchmark of the planar ANCF model (one command, numbers measured in this run).

    /work/venv/bin/python benchmarks/bench_ancf.py [--quick]

1. Static: 0.8 m, 6 mm steel cantilever, horizontal under gravity, 16 elements: build+solve
   wall time (median of repeats) and tip error against the heavy elastica
   (:mod:`workbench.reference.elastica`); refinement 4/8/16/32 elements.
2. PyElastica (Cosserat rod, explicit Position-Verlet) on the same cantilever, damped to
   equilibrium, side by side, if ``elastica`` is importable here or in the interpreter named
   by ``$PYELASTICA_PYTHON`` (default ``/work/venv-bench/bin/python``); skipped with a message
   otherwise.  Clamp: ``OneEndFixedBC`` fixes node 0's position and element 0's directors.
3. Dynamics: 10 s simulated, two antagonistic tendons, the second ramped 3 s late,
   generalised-alpha with a 2 ms step; continuum and eyelet tendons, tension and length
   control.

Speed numbers are machine-dependent (2 shared cores here): compare ratios from one run.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import subprocess
import sys
import time

L, DIAM, E, RHO, NU, G = 0.8, 6e-3, 210e9, 7850.0, 0.3, 9.81


def _pyelastica_cantilever(
    n_elem: int, dt: float, damping: float, tol: float, max_time: float, shift_clamp: bool = False
) -> dict:
    """Damped PyElastica cantilever under gravity; returns tip (along, transverse) and timings.

    ``OneEndFixedBC`` fixes node 0 and the directors of element 0, so bending starts at the
    first internal node: the cantilever is effectively ``dx / 2`` shorter (tip deflection
    ``~ (1 - 2 dx / L)`` of the exact one, first order in ``dx``).  ``shift_clamp=True``
    compensates: a rod of length ``L' = L / (1 - 1 / (2 n))`` starting at ``x = -dx'/2``, so
    the effective clamp sits at ``x = 0`` and the free length is ``L``.
    """
    import numpy as np
    import elastica as ea

    class Sim(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping):
        pass

    t0 = time.perf_counter()
    sim = Sim()
    length = L / (1.0 - 0.5 / n_elem) if shift_clamp else L
    start = np.array([-0.5 * length / n_elem if shift_clamp else 0.0, 0.0, 0.0])
    rod = ea.CosseratRod.straight_rod(
        n_elem, start, np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]), length, DIAM / 2, RHO,
        youngs_modulus=E, shear_modulus=E / (2 * (1 + NU)),
    )
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,), constrained_director_idx=(0,))
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, -G, 0.0]))
    sim.dampen(rod).using(ea.AnalyticalLinearDamper, uniform_damping_constant=damping, time_step=dt)
    sim.finalize()
    stepper = ea.PositionVerlet()
    chunk = 0.02
    n_chunk = max(1, int(round(chunk / dt)))
    t, prev = 0.0, None
    steps = 0
    while t < max_time:
        for _ in range(n_chunk):
            t = stepper.step(sim, t, dt)
        steps += n_chunk
        tip = rod.position_collection[:, -1].copy()
        if prev is not None and np.linalg.norm(tip - prev) < tol:
            break
        prev = tip
    wall = time.perf_counter() - t0
    return {"tip": [float(tip[0]), float(tip[1])], "wall": wall, "sim_time": t, "steps": steps, "n_elem": n_elem}


def _run_pyelastica(args: dict) -> dict | str:
    try:
        import elastica  # noqa: F401

        return _pyelastica_cantilever(**args)
    except ImportError:
        pass
    py = os.environ.get("PYELASTICA_PYTHON", "/work/venv-bench/bin/python")
    if not os.path.exists(py):
        return f"PyElastica not importable here and {py} does not exist: skipped"
    code = (
        "import json, sys; sys.path.insert(0, %r); import bench_ancf as b; "
        "print(json.dumps(b._pyelastica_cantilever(**json.loads(sys.argv[1]))))" % os.path.dirname(__file__)
    )
    try:
        out = subprocess.run([py, "-c", code, json.dumps(args)], capture_output=True, text=True, timeout=1800)
    except subprocess.TimeoutExpired:
        return "PyElastica run timed out: skipped"
    if out.returncode != 0:
        return "PyElastica failed: " + out.stderr.strip().splitlines()[-1] if out.stderr.strip() else "PyElastica failed"
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(quick: bool = False) -> None:
    import numpy as np

    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from workbench.models.result import SolverOptions
    from workbench.physics.ancf import run
    from workbench.reference.elastica import clamped_elastica
    from workbench.robot import LoadCase, TendonActuation
    from workbench.robot.presets import build_preset

    robot = build_preset("steel_rod", length=L, diameter=DIAM, gravity=G, base_orientation="horizontal")
    cs = robot.sections[0].cross_section
    q = cs.mass_per_length * G
    t0 = time.perf_counter()
    ref = clamped_elastica(L, cs.EI, distributed_load=(0.0, -q), stations=2).tip
    t_ref = time.perf_counter() - t0
    print(f"rod: L={L} m, d={DIAM * 1e3:.0f} mm steel, EI={cs.EI:.4g} N m^2, EA={cs.EA:.4g} N, "
          f"gamma=qL^3/EI={q * L**3 / cs.EI:.4g}")
    print(f"elastica reference tip (along, transverse) = ({ref[0]:.9f}, {ref[1]:.9f}) m  [{t_ref * 1e3:.0f} ms]")
    print("\n[1] ANCF static, self-weight")
    reps = 3 if quick else 9
    t16 = None
    for n in (4, 8, 16, 32):
        walls = []
        for _ in range(reps):
            t0 = time.perf_counter()
            res = run(robot, LoadCase(), SolverOptions(n_elements=n))
            walls.append(time.perf_counter() - t0)
        err = np.hypot(res.tip_position[2] - ref[0], res.tip_position[0] - ref[1])
        med = statistics.median(walls)
        if n == 16:
            t16, e16 = med, err
        print(f"  {n:3d} el.: build+solve {med * 1e3:7.2f} ms (median of {reps}), tip error {err:.3e} m, "
              f"Newton its {res.solver.iterations}")

    print("\n[2] PyElastica, same cantilever, damped to equilibrium")
    # explicit Verlet: the rotational (shear) mode of a 6 mm steel rod needs dt < ~9e-7 s
    pe_args = dict(n_elem=40, dt=6e-7, damping=60.0, tol=1e-9, max_time=1.5)
    if quick:
        pe_args.update(n_elem=20, max_time=0.1)
    for shift in (False, True):
        pe = _run_pyelastica({**pe_args, "shift_clamp": shift})
        if isinstance(pe, str):
            print("  " + pe)
            break
        err = math.hypot(pe["tip"][0] - ref[0], pe["tip"][1] - ref[1])
        clamp = "clamp shifted by dx/2" if shift else "OneEndFixedBC as is"
        print(f"  {pe['n_elem']} el. ({clamp}), dt={pe_args['dt']:g} s, uniform damping {pe_args['damping']} 1/s: "
              f"{pe['steps']} steps, {pe['sim_time']:.2f} s simulated, wall {pe['wall']:.2f} s, tip error {err:.3e} m")
        print(f"    wall-time ratio PyElastica / ANCF(16 el.) = {pe['wall'] / t16:.0f}  "
              f"(tip errors {err:.2e} vs {e16:.2e} m)")

    print("\n[3] ANCF dynamics: 10 s simulated, h = 2 ms, two antagonistic tendons, second 3 s late")
    robot_t = build_preset("steel_rod", length=L, diameter=DIAM, gravity=G, base_orientation="horizontal",
                           tendon_count=2)
    cases = [
        ("continuum", TendonActuation("tension", (60.0, 60.0), start_times=(0.0, 3.0))),
        ("eyelets", TendonActuation("tension", (60.0, 60.0), start_times=(0.0, 3.0))),
        ("continuum", TendonActuation("length", (-0.01, -0.01), start_times=(0.0, 3.0), pretension=5.0)),
        ("eyelets", TendonActuation("length", (-0.01, -0.01), start_times=(0.0, 3.0), pretension=5.0)),
    ]
    for model, act in cases:
        load = LoadCase(actuation=act, analysis="dynamic", duration=2.0 if quick else 10.0, ramp_time=1.0)
        t0 = time.perf_counter()
        res = run(robot_t, load, SolverOptions(n_elements=16, tendon_model=model, time_step=2e-3, damping=1e-3))
        wall = time.perf_counter() - t0
        print(f"  {model:9s} {act.mode:7s}: wall {wall:6.2f} s for {load.duration:.0f} s, final tip "
              f"({res.tip_position[0]:+.5f}, {res.tip_position[2]:.5f}) m, tensions "
              f"{np.array2string(res.tendon_tensions, precision=1)} N")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
