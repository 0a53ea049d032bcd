"""Warm starts in sweeps and chains (:mod:`workbench.models.warm`, ``[solver] warm_start``).

References: cold solves of the same loads, and a 40-step continuation of the Cosserat rod from the
unloaded state (independent of the load ramp) on the branch-jump robot of
``tests/physics/test_load_path.py``.  Checks: the key is off by default and keeps the case ids,
is validated and recorded (``p.solver.warm_start``, ``warm_from``), warm rows agree with cold rows
within the Newton tolerance, and the pool picks the nearest solved fraction of a load.
"""

from __future__ import annotations

import sys
import textwrap
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from workbench.models import SolverOptions
from workbench.models.warm import WarmPool, load_vector, on_ray, solve_chain, warm_key
from workbench.physics.cosserat import Shooter, rod_problem, run
from workbench.physics.cosserat.rod import integrate_segments
from workbench.physics.cosserat.shooting import straight_rod_base_wrench
from workbench.robot import LoadCase, TendonActuation
from workbench.study import RunConfig, SerialExecutor, StudyError, evaluate_case, expand, load_study, run_cases
from workbench.study.evaluate import WARM
from workbench.study.kinds import SWEEP

sys.path.insert(0, str(Path(__file__).parent))
from test_warm_cosserat import JUMP_TENSIONS, OPTS, _jump_load, _robot  # noqa: E402

SCALES = (0.25, 0.5, 1.0, 1.5)  # the load ray of the study below
STUDY = textwrap.dedent("""\
    [study]
    name = "warm"
    models = ["cosserat"]

    [robot]
    preset = "rao_2021"

    [load]
    mode = "tension"

    [solver]
    n_stations = 9
    error_estimate = "none"
    {solver}

    [sweep.zip]
    "load.tensions" = [{tensions}]
    "load.tip_force" = [{forces}]
    """)


def _study(tmp_path: Path, solver: str = "", scales=SCALES) -> Path:
    tensions = ", ".join(f"[{2 * s}, {2 * s}, 0.0, 0.0, {3 * s}, 0.0]" for s in scales)
    forces = ", ".join(f"[0.0, {0.1 * s}, 0.0]" for s in scales)
    p = tmp_path / f"warm{abs(hash(solver))}.toml"
    p.write_text(STUDY.format(solver=solver, tensions=tensions, forces=forces))
    return p


def _continuation_tip(robot, load, tensions, steps: int = 40) -> np.ndarray:
    pb = rod_problem(robot, load)
    sh = Shooter(pb, 1e-10)
    T = np.asarray(tensions, dtype=float)
    prev, x = None, np.zeros(6)
    for k in range(1, steps + 1):
        lam = k / steps
        guess = straight_rod_base_wrench(pb, lam) if prev is None else 2.0 * x - prev
        prev, x = x, sh.newton(guess, lam, lam * T)
    tip, _ = integrate_segments(pb, x[None], T, 1.0, sh.rtol)
    return tip[0, 0:3]


def test_solve_chain_follows_the_load_path_and_matches_cold_solves():
    robot = _robot(3)
    scales = (0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4)
    chain = solve_chain(run, robot, [_jump_load(s) for s in scales], OPTS)
    assert [r.extras.get("warm_started") for r in chain] == [None] + [1.0] * (len(scales) - 1)
    for s, r in zip(scales[:5], chain[:5]):  # where the cold ramp follows the path (continuation checked there)
        cold = run(robot, _jump_load(s), OPTS)
        assert np.abs(r.positions - cold.positions).max() < 1e-8 * robot.length
    ref = _continuation_tip(robot, _jump_load(1.4), 1.4 * JUMP_TENSIONS)
    assert np.linalg.norm(chain[-1].positions[-1] - ref) < 1e-6 * robot.length


def test_a_chain_on_a_model_without_warm_starts_solves_cold():
    robot = _robot(1)
    loads = [LoadCase(actuation=TendonActuation("tension", (t, 0.0, 0.0))) for t in (0.5, 1.0)]
    calls = []

    def cold_model(robot, load, options):
        calls.append(options.warm_state)
        return run(robot, load, replace(options, warm_state=None))

    chain = solve_chain(cold_model, robot, loads, OPTS)
    assert calls[0] is None and calls[1] is not None  # offered; the model ignored it
    assert all("warm_started" not in r.extras for r in chain)


def test_pool_offers_the_nearest_solved_fraction_of_the_load():
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 0.0)), tip_force=(0.0, 0.1, 0.0))
    frac = [replace(load, actuation=TendonActuation("tension", (2.0 * c, 0.0)), tip_force=(0.0, 0.1 * c, 0.0))
            for c in (0.25, 0.5, 1.5)]
    off = replace(load, actuation=TendonActuation("tension", (1.9, 0.0)))
    pool = WarmPool()
    robot = _robot(1)
    key = warm_key("m", robot, load, OPTS)
    for i, f in enumerate(frac):
        pool.add(key, f, f"c{i}", np.full(3, float(i)))
    pool.add(key, off, "off", np.zeros(3))
    pool.add(key, load, "none", None)  # a result without a state is not kept
    assert pool.nearest(key, load)[0] == "c1"  # 0.5 x: nearer than 0.25 x; 1.5 x and the off-ray load excluded
    assert pool.nearest(key, load, ray=False)[0] == "off"
    assert pool.nearest(warm_key("other", robot, load, OPTS), load) is None
    assert warm_key("m", robot, load, replace(OPTS, warm_state=np.ones(3))) == key
    assert warm_key("m", robot, load, replace(OPTS, newton_tolerance=1e-8)) != key
    assert warm_key("m", robot, frac[0], OPTS) == key  # only the load vector differs
    assert on_ray(load_vector(frac[1]), load_vector(load)) and not on_ray(load_vector(frac[2]), load_vector(load))


def test_warm_start_is_off_by_default_and_keeps_the_case_ids(tmp_path):
    cold = load_study(_study(tmp_path))
    off = load_study(_study(tmp_path, "warm_start = false"))
    on = load_study(_study(tmp_path, "warm_start = true"))
    assert "warm_start" not in cold.base["solver"]
    assert [c.case_id for c in expand(cold)] == [c.case_id for c in expand(off)]
    assert on.base["solver"]["warm_start"] is True
    assert not set(c.case_id for c in expand(on)) & set(c.case_id for c in expand(cold))


@pytest.mark.parametrize("bad, message", [
    ('warm_start = "yes"', "solver.warm_start"),
    ("[solver.by_model.cosserat]\nwarm_start = true", "warm_start"),
])
def test_a_bad_warm_start_key_is_one_line_naming_it(tmp_path, bad, message):
    with pytest.raises(StudyError) as err:
        load_study(_study(tmp_path, bad))
    text = str(err.value)
    assert message in text and "Traceback" not in text


def test_sweep_rows_record_the_warm_source_and_agree_with_cold_rows(tmp_path):
    WARM.clear()
    run_cases(SWEEP, load_study(_study(tmp_path)), tmp_path / "cold", SerialExecutor(), RunConfig(progress=False))
    run_cases(SWEEP, load_study(_study(tmp_path, "warm_start = true")), tmp_path / "warm", SerialExecutor(),
              RunConfig(progress=False))
    cold = pd.read_parquet(tmp_path / "cold")
    warm = pd.read_parquet(tmp_path / "warm")
    assert "warm_from" not in cold and "p.solver.warm_start" not in cold
    assert warm["p.solver.warm_start"].all() and (warm["status"] == "ok").all()
    cold["s"] = cold["p.load.tip_force"].map(lambda v: round(float(str(v).strip("[]").split(",")[1]) / 0.1, 6))
    warm["s"] = warm["p.load.tip_force"].map(lambda v: round(float(str(v).strip("[]").split(",")[1]) / 0.1, 6))
    by_s = warm.set_index("s")
    # each case starts from the nearest solved fraction of its load (the cases run in sweep order)
    assert by_s.loc[0.25, "warm_from"] == ""
    for s, src in ((0.5, 0.25), (1.0, 0.5), (1.5, 1.0)):
        assert by_s.loc[s, "warm_from"] == by_s.loc[src, "case_id"]
    c = cold.set_index("s")
    for s in SCALES:
        a, b = np.asarray(by_s.loc[s, "positions"], float), np.asarray(c.loc[s, "positions"], float)
        assert np.abs(a - b).max() < 1e-8 * 0.4  # Newton tolerance 1e-9 on the scaled residual; L = 0.4 m
    WARM.clear()
    # the report's Assumptions table says so; a cold study's does not
    from workbench.report.assumptions import assumption_rows
    from workbench.report.load import load_results

    row = [r for r in assumption_rows(load_results(tmp_path / "warm")) if r.key == "solver.warm_start"]
    assert len(row) == 1 and row[0].source.startswith("3 of 4 rows started")
    assert not [r for r in assumption_rows(load_results(tmp_path / "cold")) if r.key == "solver.warm_start"]


def test_evaluate_without_warm_start_neither_reads_nor_fills_the_pool(tmp_path):
    WARM.clear()
    cases = expand(load_study(_study(tmp_path)))
    rows = [evaluate_case(c.case_id, c.params, ["cosserat"])[0] for c in cases]
    assert len(WARM) == 0 and all("warm_from" not in r for r in rows)
