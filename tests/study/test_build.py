"""study/build.py and the recorded parameters: a stored row rebuilds exactly the robot (and load) that ran."""

from __future__ import annotations

import numpy as np
import pytest

import study_fakes as fakes
from workbench.study import (RunConfig, SerialExecutor, build_load, build_robot, expand, load_study, read_table,
                             run_cases)
from workbench.study.build import gravity_from_parameter, resolve_robot
from workbench.study.params import section_params

GAMMA_SWEEP = '''
[derived]
gravity_parameter = 0.0

[sweep]
product = { "derived.gravity_parameter" = [0.0, 1.0, 4.0], "load.tensions" = [[1.0, 0.0], [2.0, 0.0]] }
'''


def test_resolve_robot_returns_the_parameters_it_built_with():
    params = {"preset": "steel_rod", "length": 0.8, "diameter": 6e-3}
    robot, ran = resolve_robot(params, {"gravity_parameter": 1.0})
    cs = robot.sections[0].cross_section
    assert ran == {**params, "gravity": gravity_from_parameter(1.0, cs.EI, cs.mass_per_length, 0.8)}
    assert build_robot(ran) == robot  # no derived parameters needed to rebuild it
    assert float(np.linalg.norm(robot.gravity)) == ran["gravity"]
    plain, same = resolve_robot(params)
    assert same == params and plain == build_robot(params)


def test_a_stored_row_rebuilds_the_robot_and_load_that_ran(tmp_path, write_study):
    study = load_study(write_study(GAMMA_SWEEP))
    ran = []

    def lookup(name):
        def run(robot, load, options):
            if options.n_elements == study.base["solver"]["n_elements"]:  # not the estimate's coarse solves
                ran.append((robot, load))
            return fakes.arc(robot, load, options)
        return run

    run_cases(fakes.sweep_kind(lookup), study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    df = read_table(tmp_path / "out")
    assert len(df) == 12 and len(ran) == 12 and (df["status"] == "ok").all()
    # case ids are still the hashes of the parameters as configured
    assert set(df["case_id"]) == {c.case_id for c in expand(study)}
    robots = [r for r, _ in ran]
    for _, row in df.iterrows():
        robot = build_robot(section_params(row, "robot"))  # p.robot.* alone, no derived parameters
        assert robot in robots
        assert row["p.robot.gravity"] == row["robot_gravity"] == float(np.linalg.norm(robot.gravity))
        load = build_load(robot, section_params(row, "load"))
        assert any(r == robot and ld == load for r, ld in ran)
    gamma = df.groupby("p.derived.gravity_parameter")["p.robot.gravity"].first()
    assert gamma[0.0] == 0.0 and gamma[4.0] == pytest.approx(4.0 * gamma[1.0], rel=1e-12)


def test_a_case_that_cannot_be_built_records_its_configured_parameters(write_study):
    from workbench.study import evaluate_case

    case = expand(load_study(write_study(GAMMA_SWEEP)))[0]
    params = {**case.params, "robot": {**case.params["robot"], "poisson_ratio": 0.7}}
    rows = evaluate_case(case.case_id, params, ("cc",), fakes.lookup)
    assert rows[0]["status"] == "failed" and rows[0]["p.robot.gravity"] == case.params["robot"]["gravity"]


WIRE_DELAY = '''
[study]
name = "wd"
models = ["cc"]

[robot]
preset = "cojocaru_tronconic"
n_sections = 1

[scenario]
name = "wire_delay"
move_time = 2.0

[load]
mode = "length"
pretension = 20.0
analysis = "dynamic"
duration = 8.0

[sweep]
product = { "scenario.delay" = [0.0, 1.5] }
'''


def test_a_stored_row_records_the_load_a_scenario_made(tmp_path):
    p = tmp_path / "wd.toml"
    p.write_text(WIRE_DELAY)
    study = load_study(p)
    ran = []

    def lookup(name):
        def run(robot, load, options):
            if options.n_elements == study.base["solver"]["n_elements"]:  # not the estimate's coarse solves
                ran.append((robot, load))
            return fakes.arc(robot, load, options)
        return run

    run_cases(fakes.sweep_kind(lookup), study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    df = read_table(tmp_path / "out").sort_values("p.scenario.delay")
    assert set(df["case_id"]) == {c.case_id for c in expand(study)}
    # the scenario's fields, not the configured [load] (duration 8.0, no length changes)
    assert df["p.load.duration"].tolist() == [3.0, 4.5] and df["p.load.ramp_time"].tolist() == [2.0, 2.0]
    assert df["p.load.start_delays"].tolist() == ["[0.0,0.0,0.0]", "[1.5,0.0,0.0]"]
    for _, row in df.iterrows():
        robot = build_robot(section_params(row, "robot"))
        load = build_load(robot, section_params(row, "load"))  # no scenario needed to rebuild it
        assert any(r == robot and ld == load for r, ld in ran)
