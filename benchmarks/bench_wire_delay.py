"""Speed of Cojocaru's wire-delay case (issues 18, 31): 10 s simulated, one tronconic section, 3 s delay.

Target (issue 31): 10 s simulated in <= 3.3 s CPU, i.e. >= 3x faster than real time (issue 18's was
<= 10 s wall), at the converged resolution (the committed study's: 40
beam3d elements with the 5 disks on element boundaries, 2.5 ms, stiffness-proportional damping
beta = 2.7e-4 s, ``studies/wire_delay.toml``).  Each configuration is run once in this process and
printed with CPU time (``time.process_time``), wall time, the load average, steps taken, Newton
iterations and Jacobians, the CPU ratio to the target, and the headline quantities (peak tip-to-CC
error, backbone compression, largest wire tension) so that a speed setting can be judged against
what it changes in the answer.

Default configurations:

* ``committed``: the study's settings (sparse LU, damped);
* ``dense``: the same with Exudyn's dense solver (beam3d used it before issue 18);
* ``undamped``: damping 0 (the snap then needs step reductions and Newton restarts);
* ``half``: 20 elements at 5 ms (the estimate's first coarse solve).

Named on the command line (40 elements / 2.5 ms unless ``half_``): ``num9`` / ``num7`` (every ODE2
Jacobian term numerical, relative epsilon 1e-9 / 1e-7), ``full`` (no modified Newton), ``jacstep``
(a Jacobian every step), ``num9full``, ``contract3`` / ``contract8`` (modified-Newton contractivity),
``anaconn`` (analytic connector Jacobians), ``ana_c8``, ``threads2`` (two threads), ``half_num9``,
``half_anaconn``, ``half_ana_c8``, ``half_c8``, ``half_threads2``, ``40_5ms_num9``, ``mnewton8`` /
``mnewton20`` (at most 8 -- Exudyn's default, the setting before the fourth session -- or 20 modified-Newton
iterations per Jacobian; beam3d commits 15), ``abs12`` / ``abs7`` (Newton's absolute tolerance 1e-12 -- the
setting before issue 31 -- or 1e-7 instead of beam3d's ``1e3 x newton_tolerance`` = 1e-6).

The code before a change runs from an exported tree of the older commit (``git archive <commit> | tar -x -C
DIR``; ``PYTHONPATH=DIR python benchmarks/bench_wire_delay.py committed``), alternated with the new one.

Run from the repository root (minutes)::

    python benchmarks/bench_wire_delay.py
    python benchmarks/bench_wire_delay.py committed half full contract8
    python benchmarks/bench_wire_delay.py committed mnewton8   # the fourth session's change, in one run
"""

from __future__ import annotations

import contextlib
import os
import sys
import time

TARGET = 3.3  # [s] CPU for 10 s simulated (issue 31: >= 3x faster than real time)


def _dense(sim) -> None:
    import exudyn as exu

    sim.linearSolver.solverType = exu.LinearSolverType.EXUdense


def _numerical(eps: float):
    """Every ODE2 Jacobian term by numerical differentiation at relative epsilon ``eps``."""

    def tweak(sim) -> None:
        nd = sim.timeIntegration.newton.numericalDifferentiation
        nd.forODE2 = True
        nd.relativeEpsilon = eps

    return tweak


def _full_newton(sim) -> None:
    sim.timeIntegration.newton.useModifiedNewton = False


def _jac_per_step(sim) -> None:
    sim.timeIntegration.newton.modifiedNewtonJacUpdatePerStep = True


def _analytic_connectors(sim) -> None:
    sim.timeIntegration.newton.numericalDifferentiation.forODE2Connectors = False


def _contractivity(c: float):
    """Modified Newton: a new Jacobian when the residual contracts by less than ``c`` per iteration."""

    def tweak(sim) -> None:
        sim.timeIntegration.newton.modifiedNewtonContractivity = c

    return tweak


def _modified_iterations(n: int):
    """Modified Newton: at most ``n`` iterations per Jacobian (beam3d commits 15; Exudyn's default is 8)."""

    def tweak(sim) -> None:
        sim.timeIntegration.newton.maxModifiedNewtonIterations = n

    return tweak


def _absolute_tolerance(tol: float):
    """Newton's absolute tolerance (RMS of the increment per coordinate) ``tol`` instead of beam3d's."""

    def tweak(sim) -> None:
        sim.timeIntegration.newton.absoluteTolerance = tol

    return tweak


def _threads2(sim) -> None:
    sim.parallel.numberOfThreads = 2


def _both(*tweaks):
    def tweak(sim) -> None:
        for t in tweaks:
            t(sim)

    return tweak


@contextlib.contextmanager
def _solver_probe(tweak, stats: dict):
    """Wrap ``exudyn.SolveDynamic``: apply ``tweak(sim)`` (a setting under test); record Newton counters."""
    import exudyn as exu

    original = exu.SolveDynamic

    def wrapped(mbs, sim, **kw):
        if tweak is not None:
            tweak(sim)
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

    b = 2.7e-4
    configs = {
        "committed": ("committed (40 el, 2.5 ms, beta 2.7e-4 s, sparse)", opts(40, 2.5e-3, b), None),
        "dense": ("dense LU  (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _dense),
        "undamped": ("undamped  (40 el, 2.5 ms, beta 0)", opts(40, 2.5e-3, 0.0), None),
        "half": ("half      (20 el, 5 ms)", opts(20, 5e-3, b), None),
        "num9": ("numerical Jacobian eps 1e-9 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _numerical(1e-9)),
        "num7": ("numerical Jacobian eps 1e-7 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _numerical(1e-7)),
        "full": ("full Newton (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _full_newton),
        "jacstep": ("Jacobian every step (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _jac_per_step),
        "num9full": ("numerical eps 1e-9, full Newton (40 el, 2.5 ms)", opts(40, 2.5e-3, b),
                     _both(_numerical(1e-9), _full_newton)),
        "anaconn": ("analytic connector Jacobians (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _analytic_connectors),
        "contract8": ("modified Newton contractivity 0.8 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _contractivity(0.8)),
        "contract3": ("modified Newton contractivity 0.3 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _contractivity(0.3)),
        "half_anaconn": ("half, analytic connectors (20 el, 5 ms)", opts(20, 5e-3, b), _analytic_connectors),
        "ana_c8": ("analytic connectors, contractivity 0.8 (40 el, 2.5 ms)", opts(40, 2.5e-3, b),
                   _both(_analytic_connectors, _contractivity(0.8))),
        "half_ana_c8": ("half, analytic connectors, contractivity 0.8 (20 el, 5 ms)", opts(20, 5e-3, b),
                        _both(_analytic_connectors, _contractivity(0.8))),
        "half_c8": ("half, contractivity 0.8 (20 el, 5 ms)", opts(20, 5e-3, b), _contractivity(0.8)),
        "mnewton8": ("modified Newton 8 its per Jacobian (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _modified_iterations(8)),
        "mnewton20": ("modified Newton 20 its per Jacobian (40 el, 2.5 ms)", opts(40, 2.5e-3, b),
                      _modified_iterations(20)),
        "abs12": ("Newton absolute tolerance 1e-12 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _absolute_tolerance(1e-12)),
        "abs7": ("Newton absolute tolerance 1e-7 (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _absolute_tolerance(1e-7)),
        "threads2": ("2 threads (40 el, 2.5 ms)", opts(40, 2.5e-3, b), _threads2),
        "half_threads2": ("half, 2 threads (20 el, 5 ms)", opts(20, 5e-3, b), _threads2),
        "half_num9": ("half, numerical eps 1e-9 (20 el, 5 ms)", opts(20, 5e-3, b), _numerical(1e-9)),
        "40_5ms_num9": ("numerical eps 1e-9 (40 el, 5 ms)", opts(40, 5e-3, b), _numerical(1e-9)),
    }
    chosen = sys.argv[1:] or ["committed", "dense", "undamped", "half"]
    unknown = [c for c in chosen if c not in configs]
    if unknown:
        raise SystemExit(f"bench_wire_delay.py: unknown configuration(s) {unknown}; choose from {list(configs)}")
    print(f"wire-delay benchmark: 10 s simulated (3 s delay, 4 s moves), target <= {TARGET:.1f} s CPU; "
          f"load average {os.getloadavg()[0]:.1f}")
    for key in chosen:
        name, o, tweak = configs[key]
        stats: dict = {}
        c0, w0 = time.process_time(), time.perf_counter()
        with _solver_probe(tweak, stats):
            r = simulate_wire_delay(options=o, delay=3.0, duration=10.0)
        cpu, wall = time.process_time() - c0, time.perf_counter() - w0
        H = r.section_length
        print(f"{name:50s}: CPU {cpu:6.2f} s (x{cpu / TARGET:4.2f} the target)  wall {wall:6.1f} s  "
              f"steps {stats['steps']:5d}  Newton/step {stats['newton'] / stats['steps']:4.1f}  "
              f"Jacobians/step {stats['jacobians'] / stats['steps']:4.2f}  | peak tip error "
              f"{r.tip_error.max() * 1e3:8.4f} mm  min dL {100 * r.length_change.min() / H:8.5f} % H  "
              f"max T {r.tendon_tensions.max():8.2f} N  load {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
