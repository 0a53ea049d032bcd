"""Benchmark: calibrating CC on 30 000 measured rows, and the cost of a physics model's calibration.

Run:  python benchmarks/bench_calibration.py [--n 30000] [--physics cosserat,beam3d] [--physics-rows 40]

Synthetic measured data (:class:`workbench.measure.predict.Predictor` of the model itself at known
values plus 0.2 mm noise per coordinate) for the Rao et al. 2021 robot in its ``steel_rod`` form
(2 sections of 0.2 m, NiTi 1.4 mm, 3 tendons per section at 10 mm): 13 unknowns (Young's modulus,
a command zero per tendon, the registration's translation and rotation), as in
``examples/measured``.  For CC, one calibration on ``--n`` rows (``calibrate_on``: least squares,
finite-difference Jacobian, intervals); printed: wall and CPU time of the calibration, the residual
evaluations, the time of one evaluation over all rows, the recovered E against the truth, and the
load average.  For each physics model: the time of one sample's solve (after a warm-up that
compiles what needs compiling) and one calibration on ``--physics-rows`` rows.  Issue 30's target:
CC on 30 000 rows within 10 s on this project's 2-core machine.  The CC path is vectorised through
``workbench.models.cc_batch``; without that module (branch not merged) the per-row fallback of
``workbench.measure.predict`` is what runs, and then ``--n`` should be small.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from workbench.measure.calibrate import calibrate_on, diff_step, evaluation_noise  # noqa: E402
from workbench.measure.predict import Predictor, model_options  # noqa: E402
from workbench.measure.types import FitParameter, Measurements  # noqa: E402

ROBOT = {"preset": "steel_rod", "length": 0.4, "n_sections": 2, "diameter": 1.4e-3, "youngs_modulus": 54e9,
         "density": 6450.0, "tendon_count": 3, "tendon_offset": 0.01, "first_tendon_angle": math.pi / 2}
NOISE = 2e-4


def _parameters(n_tendons: int) -> tuple[list[FitParameter], np.ndarray]:
    """The 13 unknowns (start, bounds) and their true values."""
    ps = [FitParameter("robot.youngs_modulus", 54e9, 30e9, 90e9, "Pa", "bench")]
    truth = [60e9]
    for i in range(n_tendons):
        ps.append(FitParameter(f"command_zero[{i}]", 0.0, -0.2, 0.2, "N", "bench"))
        truth.append(0.05 * (-1) ** i)
    for j, t in enumerate((0.01, -0.02, 0.03)):
        ps.append(FitParameter(f"registration.translation[{j}]", 0.0, -0.1, 0.1, "m", "bench"))
        truth.append(t)
    for j, r in enumerate((0.05, -0.1, 0.2)):
        ps.append(FitParameter(f"registration.rotation[{j}]", 0.0, -0.5, 0.5, "rad", "bench"))
        truth.append(r)
    return ps, np.array(truth)


def _data(model: str, n: int, solver: dict, seed: int = 0) -> tuple[Predictor, list[FitParameter], np.ndarray]:
    from workbench.study.build import build_robot

    n_t = build_robot(ROBOT).n_tendons
    rng = np.random.default_rng(seed)
    cmd = rng.uniform(0.0, 3.0, (n, n_t))
    ps, truth = _parameters(n_t)
    names = tuple(p.name for p in ps)
    tables = {"robot": ROBOT, "load": {}, "solver": solver}
    blank = Measurements("bench", "tension", cmd, np.zeros((n, 3)), "measurement", np.arange(1, n + 1))
    tips = Predictor(model, tables, names, blank).tips(truth, np.arange(n)) + rng.normal(0.0, NOISE, (n, 3))
    meas = Measurements("bench", "tension", cmd, tips, "measurement", np.arange(1, n + 1))
    return Predictor(model, tables, names, meas), ps, truth


def _calibrate(model: str, n: int, solver: dict, max_evaluations: int) -> None:
    p, ps, truth = _data(model, n, solver)
    tau = model_options(solver, model).newton_tolerance
    w0, c0 = time.perf_counter(), time.process_time()
    res = calibrate_on(p, ps, p.measurements.tip_position, np.arange(n), 0.95, max_evaluations, diff_step(model, tau),
                       evaluation_noise(model, tau))
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    inside = int(np.sum((res.ci_low <= truth) & (truth <= res.ci_high)))
    per = p.timing.seconds / max(1, p.timing.calls if model == "cc" else p.timing.samples)
    what = "evaluation over all rows" if model == "cc" else "sample solve"
    print(f"{model:9s} {n:6d} rows, {len(ps)} parameters: calibration {wall:7.2f} s wall, {cpu:7.2f} s CPU, "
          f"{res.evaluations} residual evaluations ({p.timing.calls} ran the model), {per * 1e3:.2f} ms per {what}; "
          f"converged {res.success}; "
          f"E {res.values[0] / 1e9:.3f} GPa (true {truth[0] / 1e9:.0f}, interval {res.ci_low[0] / 1e9:.3f}-"
          f"{res.ci_high[0] / 1e9:.3f}); {inside}/{len(ps)} true values inside their intervals; "
          f"s = {res.sigma * 1e3:.3f} mm (noise {NOISE * 1e3:.1f}); load {os.getloadavg()[0]:.1f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=30000, help="CC rows")
    ap.add_argument("--physics", default="cosserat", help="comma-separated physics models ('' for none)")
    ap.add_argument("--physics-rows", type=int, default=40)
    ap.add_argument("--max-evaluations", type=int, default=200)
    a = ap.parse_args()
    try:
        import workbench.models.cc_batch  # noqa: F401
        batched = "vectorised (workbench.models.cc_batch)"
    except ImportError:
        batched = "per-row fallback (cc_batch not merged)"
    print(f"load average {os.getloadavg()[0]:.2f}; CC path: {batched}")
    _calibrate("cc", a.n, {}, a.max_evaluations)
    for model in [m for m in a.physics.split(",") if m]:
        solver = {"n_elements": 16} if model == "cosserat" else {"n_elements": 20, "tendon_model": "eyelets"}
        t0 = time.perf_counter()
        _data(model, 1, solver)  # warm-up: compiles the model's kernels (not timed below)
        print(f"{model:9s} warm-up (first solve, compilation included) {time.perf_counter() - t0:.1f} s")
        _calibrate(model, a.physics_rows, solver, a.max_evaluations)


if __name__ == "__main__":
    main()
