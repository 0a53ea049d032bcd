"""Wall time of Cojocaru's wire-delay case: 10 s simulated, one tronconic section.

The delayed case (3 s) is the benchmark; the delay-free move is printed for comparison
(between t ~ 2 s and 5 s the delayed case snaps into a strongly bent shape that is not a
constant-curvature arc, at ~1.7 kN per wire; that phase is what costs).

Run from the repository root::

    /work/venv/bin/python benchmarks/bench_wire_delay.py

Prints, for each configuration, the wall time, the element count, the number of time steps,
the ratio to the 10 s target and a few physical outputs (peak virtual compression, peak
backbone compression, peak tension, peak tip error) so that speed settings can be judged
against what they change in the answer.
"""

from __future__ import annotations

import time


def main() -> None:
    from workbench.models import SolverOptions
    from workbench.physics.wire_delay import default_options, simulate_wire_delay

    target = 10.0
    coarse = SolverOptions(n_elements=4, tendon_model="eyelets", time_step=1e-2, damping=0.0, spectral_radius=0.8)
    configs = [
        ("3 s delay, default (8 el., h = 5 ms)", default_options(), 3.0),
        ("3 s delay, coarse  (4 el., h = 10 ms)", coarse, 3.0),
        ("no delay,  default (8 el., h = 5 ms)", default_options(), 0.0),
    ]
    print("wire-delay benchmark: 10 s simulated (3 s delay, 4 s moves), target <= %.0f s wall" % target)
    for name, opts, delay in configs:
        t0 = time.perf_counter()
        r = simulate_wire_delay(options=opts, delay=delay, duration=10.0)
        wall = time.perf_counter() - t0
        print(
            f"{name}: wall {wall:7.2f} s  elements {r.n_elements:2d}  steps {r.n_steps:5d}  "
            f"wall/target {wall / target:5.2f}  | min e {r.virtual_compression.min() * 1e3:7.3f} mm  "
            f"min dL {r.length_change.min() * 1e3:7.4f} mm  max T {r.tendon_tensions.max():7.1f} N  "
            f"max tip error {r.tip_error.max() * 1e3:6.1f} mm  max |twist| {abs(r.tip_twist).max():.2e} rad"
        )


if __name__ == "__main__":
    main()
