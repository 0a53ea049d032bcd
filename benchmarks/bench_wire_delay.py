"""Speed of Cojocaru's wire-delay case (issue 18): 10 s simulated, one tronconic section, 3 s delay.

Target: 10 s simulated in <= 10 s wall at the converged resolution (the committed study's: 40
beam3d elements with the 5 disks on element boundaries, 2.5 ms, stiffness-proportional damping
beta = 2.7e-4 s, ``studies/wire_delay.toml``).  Each configuration is run once in this process and
printed with CPU time (``time.process_time``), wall time, the load average, steps taken, Newton
iterations and Jacobians, the ratios to the target, and the headline quantities (peak tip-to-CC
error, backbone compression, largest wire tension) so that a speed setting can be judged against
what it changes in the answer.  Configurations:

* ``committed``: the study's settings (sparse LU, damped);
* ``dense LU``: the same with Exudyn's dense solver (beam3d used it before issue 18);
* ``undamped``: damping 0 (the snap then needs step reductions and Newton restarts);
* ``half``: 20 elements at 5 ms (the estimate's first coarse solve).

Run from the repository root (minutes)::

    python benchmarks/bench_wire_delay.py
"""

from __future__ import annotations

import contextlib
import os
import time

TARGET = 10.0  # [s] wall for 10 s simulated


@contextlib.contextmanager
def _solver_probe(dense: bool, stats: dict):
    """Wrap ``exudyn.SolveDynamic``: optionally force the dense LU; record Newton counters."""
    import exudyn as exu

    original = exu.SolveDynamic

    def wrapped(mbs, sim, **kw):
        if dense:
            sim.linearSolver.solverType = exu.LinearSolverType.EXUdense
        out = original(mbs, sim, **kw)
        it = mbs.sys["dynamicSolver"].it
        stats.update(steps=it.currentStepIndex, newton=it.newtonStepsCount, jacobians=it.newtonJacobiCount)
        return out

    exu.SolveDynamic = wrapped
    try:
        yield
    finally:
        exu.SolveDynamic = original


def main() -> None:
    from workbench.experiments.wire_delay.analysis import simulate_wire_delay
    from workbench.models import SolverOptions

    def opts(n, dt, beta):
        return SolverOptions(n_elements=n, tendon_model="eyelets", time_step=dt, damping=beta, spectral_radius=0.8)

    configs = [
        ("committed (40 el, 2.5 ms, beta 2.7e-4 s, sparse)", opts(40, 2.5e-3, 2.7e-4), False),
        ("dense LU  (40 el, 2.5 ms, beta 2.7e-4 s)        ", opts(40, 2.5e-3, 2.7e-4), True),
        ("undamped  (40 el, 2.5 ms, beta 0, sparse)       ", opts(40, 2.5e-3, 0.0), False),
        ("half      (20 el, 5 ms, beta 2.7e-4 s, sparse)  ", opts(20, 5e-3, 2.7e-4), False),
    ]
    print(f"wire-delay benchmark: 10 s simulated (3 s delay, 4 s moves), target <= {TARGET:.0f} s wall; "
          f"load average {os.getloadavg()[0]:.1f}")
    for name, o, dense in configs:
        stats: dict = {}
        c0, w0 = time.process_time(), time.perf_counter()
        with _solver_probe(dense, stats):
            r = simulate_wire_delay(options=o, delay=3.0, duration=10.0)
        cpu, wall = time.process_time() - c0, time.perf_counter() - w0
        H = r.section_length
        print(f"{name}: CPU {cpu:6.1f} s (x{cpu / TARGET:4.1f})  wall {wall:6.1f} s (x{wall / TARGET:4.1f})  "
              f"steps {stats['steps']:5d}  Newton/step {stats['newton'] / stats['steps']:4.1f}  "
              f"Jacobians/step {stats['jacobians'] / stats['steps']:4.2f}  | peak tip error "
              f"{r.tip_error.max() * 1e3:6.2f} mm  min dL {100 * r.length_change.min() / H:7.4f} % H  "
              f"max T {r.tendon_tensions.max():7.1f} N  load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
