"""Scenarios: the [scenario] section (validation, sweep, case ids) and the scenario functions."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from workbench.study import StudyError, expand, load_study
from workbench.study.build import build_load, build_robot
from workbench.study.evaluate import evaluate_case
from workbench.experiments.hannan_walker.scenario import hannan_walker_line
from workbench.experiments.wire_delay.scenario import wire_delay
from workbench.study.scenarios import SCENARIOS, load_with_scenario, scenario_parameters

WD = textwrap.dedent("""\
    [study]
    name = "wd"
    models = ["cc"]

    [robot]
    preset = "cojocaru_tronconic"
    n_sections = 1

    [scenario]
    name = "wire_delay"
    delay = 1.0

    [load]
    mode = "length"
    analysis = "dynamic"
    duration = 1.0

    [solver]
    tendon_model = "eyelets"
    """)


def _study(tmp_path, text):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return load_study(p)


def _problems(tmp_path, text):
    with pytest.raises(StudyError) as ei:
        _study(tmp_path, text)
    return ei.value.problems


# ---------------------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------------------
def test_scenario_resolved_with_defaults(tmp_path):
    st = _study(tmp_path, WD)
    sc = st.base["scenario"]
    assert sc["name"] == "wire_delay" and sc["delay"] == 1.0
    assert set(sc) == {"name", *scenario_parameters("wire_delay")}


def test_unknown_scenario_one_line_with_suggestion(tmp_path):
    (p,) = _problems(tmp_path, WD.replace('name = "wire_delay"', 'name = "wire_dealy"'))
    assert "scenario.name: unknown scenario 'wire_dealy'; did you mean 'wire_delay'?" in p
    assert "\n" not in p


def test_unknown_and_mistyped_parameters(tmp_path):
    probs = _problems(tmp_path, WD.replace("delay = 1.0", 'delya = 1.0\ndelayed_wire = 1.5\nmove_time = "4"'))
    text = "\n".join(probs)
    assert "scenario.delya: unknown parameter of scenario 'wire_delay'; did you mean 'delay'?" in text
    assert "scenario.delayed_wire: must be an integer" in text
    assert "scenario.move_time: must be a number" in text
    assert len(probs) == 3


def test_infeasible_scenario_reported_before_running(tmp_path):
    probs = _problems(tmp_path, WD.replace("n_sections = 1", "n_sections = 2"))
    assert len(probs) == 1 and "scenario: scenario wire_delay needs a one-section robot with 3 tendons" in probs[0]
    probs = _problems(tmp_path, WD.replace("delay = 1.0", "delay = -1.0"))
    assert len(probs) == 1 and "delay >= 0" in probs[0]


def test_scenario_sweep_axis_and_case_ids(tmp_path):
    st = _study(tmp_path, WD + '\n[sweep]\nproduct = { "scenario.delay" = [0.0, 2.0, 3] }\n')
    cases = expand(st)
    assert [c.params["scenario"]["delay"] for c in cases] == [0.0, 2.0, 3.0]
    assert len({c.case_id for c in cases}) == 3
    # the same parameters without a sweep give the same id (ids depend on values only)
    one = expand(_study(tmp_path, WD.replace("delay = 1.0", "delay = 2.0")))[0]
    assert one.case_id == cases[1].case_id


def test_scenario_name_cannot_be_swept_and_unknown_axis(tmp_path):
    probs = _problems(tmp_path, WD + '\n[sweep]\nproduct = { "scenario.name" = ["wire_delay"], "scenario.dlay" = [1.0] }\n')
    text = "\n".join(probs)
    assert 'sweep.product["scenario.name"]: the scenario cannot be swept' in text
    assert 'sweep.product["scenario.dlay"]: unknown axis; did you mean \'scenario.delay\'?' in text


def test_study_without_scenario_has_no_scenario_section(tmp_path):
    from study_fakes import GOOD

    st = _study(tmp_path, GOOD)
    assert "scenario" not in st.base
    assert "scenario" not in expand(st)[0].params


def test_missing_name(tmp_path):
    (p,) = _problems(tmp_path, WD.replace('name = "wire_delay"\n', ""))
    assert "scenario.name: missing required key" in p


def test_evaluate_case_passes_scenario_load_to_models(tmp_path):
    st = _study(tmp_path, WD + '\n[sweep]\nproduct = { "scenario.delay" = [2.5] }\n')
    c = expand(st)[0]
    seen = {}

    def lookup(name):
        def run(robot, load, options):
            seen["load"] = load
            raise RuntimeError("stop here")
        return run

    rows = evaluate_case(c.case_id, c.params, ["fake"], model_lookup=lookup)
    assert rows[0]["status"] == "failed" and rows[0]["p.scenario.delay"] == 2.5
    load = seen["load"]
    assert load.analysis == "dynamic" and math.isclose(load.duration, 2.5 + 4.0 + 1.0)
    assert load.actuation.mode == "length"
    assert load.actuation.start_times == (2.5, 0.0, 0.0)
    assert load.actuation.ramp_durations == (4.0, 4.0, 4.0)


# ---------------------------------------------------------------------------------------
# scenario functions against independent facts
# ---------------------------------------------------------------------------------------
def test_wire_delay_cylindrical_section_mean_wire_change_is_zero():
    # Eq 12 (mean of consistent wire lengths = H) holds exactly for D1 = D2
    robot = build_robot({"preset": "cojocaru_tronconic", "n_sections": 1, "disk_diameter_step": 1e-9})
    f = wire_delay(robot, theta=0.6, alpha=0.3)
    assert abs(np.mean(f["length_changes"])) < 1e-9
    # three equally spaced wires on a CC arc: dl_i = -d theta cos(sigma_i - phi)
    d = robot.sections[0].tendons.offset
    sig = np.asarray(robot.sections[0].tendons.angles)
    np.testing.assert_allclose(f["length_changes"], -d * 0.6 * np.cos(sig - (0.3 + math.pi)), atol=1e-9)


def test_wire_delay_virtual_compression_at_three_seconds():
    from workbench.experiments.wire_delay.analysis import arc_from_wire_lengths_tronconic_workbench, wire_lengths_tronconic_workbench

    robot = build_robot({"preset": "cojocaru_tronconic", "n_sections": 1})
    load = build_load(robot, load_with_scenario(robot, {"mode": "length"}, {"name": "wire_delay", **scenario_parameters("wire_delay"), "delay": 3.0}))
    sec = robot.sections[0]
    g = sec.tendons
    sigma = np.asarray(g.angles)
    L0 = wire_lengths_tronconic_workbench(0.0, 0.0, sec.length, g.offset, g.offset_tip, sigma)
    Lcmd = L0 + load.actuation.command_at(3.0, load.ramp_time)
    _, _, e = arc_from_wire_lengths_tronconic_workbench(Lcmd, sec.length, g.offset, g.offset_tip, sigma)
    assert -0.02 < float(e) / sec.length < -0.015  # the paper's "approximately 2 %" (-1.78 %)
    # without delay the commands stay a CC configuration
    load0 = build_load(robot, load_with_scenario(robot, {"mode": "length"}, {"name": "wire_delay", **scenario_parameters("wire_delay")}))
    _, _, e0 = arc_from_wire_lengths_tronconic_workbench(L0 + load0.actuation.command_at(3.0, 4.0), sec.length, g.offset, g.offset_tip, sigma)
    assert abs(float(e0)) < 1e-5


@pytest.mark.parametrize("shape", ["line", "grasp"])
def test_hannan_walker_line_commands_put_the_cc_tip_on_the_line(shape):
    from workbench.kinematics import planar_forward_kinematics
    from workbench.experiments.hannan_walker.replay import joint_angles_from_cable_changes

    robot = build_robot({"preset": "hannan_walker"})
    ell = robot.section_lengths
    for k in (0, 3, 5):
        f = hannan_walker_line(robot, shape=shape, n_samples=6, sample=k, grasp_bend_angles=[-0.3, 0.3, 1.0, 1.6])
        q = joint_angles_from_cable_changes(np.asarray(f["length_changes"]), robot, 16)
        kappa = q * 4 / ell  # per-section joint angle, 4 joints per section (Eq 2-3)
        A = planar_forward_kinematics(kappa, ell)
        tip = np.array([-A[0, 3], A[1, 3]])  # planar -> base (x, z)
        target = np.array([0.25, 0.70]) + (np.array([0.35, 0.60]) - np.array([0.25, 0.70])) * k / 5
        assert np.linalg.norm(tip - target) < 1e-6


def test_hannan_walker_grasp_differs_from_line_and_bad_inputs():
    robot = build_robot({"preset": "hannan_walker"})
    a = hannan_walker_line(robot, sample=2)["length_changes"]
    b = hannan_walker_line(robot, shape="grasp", sample=2, grasp_bend_angles=[-0.3, 0.3, 1.0, 1.6])["length_changes"]
    assert np.max(np.abs(np.subtract(a, b))) > 1e-3
    with pytest.raises(ValueError, match="grasp_bend_angles with 4 entries"):
        hannan_walker_line(robot, shape="grasp")
    with pytest.raises(ValueError, match="0 <= sample < n_samples"):
        hannan_walker_line(robot, sample=9, n_samples=9)
    with pytest.raises(ValueError, match="out of reach"):
        hannan_walker_line(robot, end_x=2.0, end_z=2.0)


def test_registry_functions_are_keyword_only():
    for name in SCENARIOS:
        assert scenario_parameters(name)
