"""Shao's harvester scoop: fluidic vs tendon plans, the fruit in the scoop, the grasp-centre controller."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from workbench.models import SolverOptions
from workbench.robot.presets import build_preset

from workbench.experiments.fruit_harvester.scoop import grasp_case, harvester_scoop
from workbench.experiments.whole_arm_grasp.tasks import cc_result, run_task


@pytest.fixture(scope="module")
def shao():
    return build_preset("shao_harvester")


def test_fluidic_plan_lengthens_tendon_plan_does_not(shao):
    f, _ = grasp_case(shao, {"actuation": "fluidic"})
    t, _ = grasp_case(shao, {"actuation": "tendon"})
    assert f.wrap_angle == pytest.approx(1.5 * math.pi) and t.wrap_angle == pytest.approx(1.5 * math.pi)
    assert f.ell[0] == pytest.approx(0.4 * (1 + 2 * 0.5355e6 * 3e-4 / 2e3), rel=1e-3)  # chambers: + sum F L / EA
    assert t.ell[0] == 0.4  # CC of a tendon section keeps its length (the physics shortens it)
    p = f.pressures[0]
    assert p[0] == pytest.approx(0.0, abs=1e-6) and max(p) <= 0.6e6  # least pressure, within the paper's limit
    # the fruit sits at the CC centre of arc (Shao Eq 2) of each plan
    assert f.circle.centre == pytest.approx((1.0 / f.kappa[0], 0.0))
    assert cc_result(shao, f, SolverOptions()).length_change == pytest.approx(f.ell[0] - 0.4)
    assert harvester_scoop(shao, actuation="fluidic") == {}  # no tendon load: the chambers drive it
    assert len(harvester_scoop(shao, actuation="tendon")["tensions"]) == 3


def test_bad_scoop_parameters(shao):
    with pytest.raises(ValueError, match="MPa"):
        grasp_case(shao, {"chamber_area": 1e-4})
    with pytest.raises(ValueError, match="tip"):
        grasp_case(shao, {"payload": "tip", "object_mass": 0.1})
    with pytest.raises(ValueError, match="onto itself"):
        grasp_case(shao, {"bend_angle": 1.95 * math.pi, "chamber_area": 1e-3})


def test_centre_controller_removes_the_horizontal_error_only(shao):
    plan, task = grasp_case(shao, {"actuation": "fluidic", "object_mass": 0.1, "control_iterations": 3,
                                   "contact_stiffness": 1e7, "friction_stiffness": 1e5})
    res = run_task(shao, plan, task, SolverOptions(n_elements=16))
    x = res.extras
    assert x["held"] == 1.0 and x["settle_dz"] > 0.01  # the fruit sinks into the scoop (base +z = down)
    E = res.series["control_error"]
    assert abs(E[-1, 0]) < 0.1 * abs(E[0, 0])  # x error corrected (J_v's k column)
    assert abs(E[-1, 1]) > 0.5 * abs(E[0, 1])  # z error stays: J_v has no z row


def test_hanging_scoop_stays_on_the_clamped_branch():
    """The ANCF clamp fixes y' only; a one-step solve of the 100 g tip case once landed on x' = -1 (the scoop
    point-mirrored through the base).  The contact system refuses that state, the ramp halves the step."""
    robot = build_preset("shao_harvester", payload_mass=0.1)
    plan, task = grasp_case(robot, {"actuation": "fluidic", "payload": "tip", "object_mass": 0.0})
    res = run_task(robot, plan, task, SolverOptions(n_elements=16))
    assert res.positions[1, 2] > 0.0  # leaves the clamp along base +z, as clamped
    assert res.positions[:, 0].max() > 0.15  # bends towards base +x, as commanded (CC: 2 / kappa = 0.197 m)


def test_centre_controller_saturates_at_the_pressure_limit(shao):
    """50 g fruit, fluidic: the fruit sits 6 mm short of the centre of arc (x), so the controller asks for more
    bend; with the pressure limit at the plan's own pressure that step cannot be realised: the loop stops,
    flagged, and the row is a result, not a failure."""
    kw = {"actuation": "fluidic", "object_mass": 0.05, "control_iterations": 4, "contact_stiffness": 1e7,
          "friction_stiffness": 1e5}
    plan, _ = grasp_case(shao, kw)
    plan, task = grasp_case(shao, {**kw, "max_pressure": 1.0001 * plan.pressures[0].max()})
    res = run_task(shao, plan, task, SolverOptions(n_elements=16))
    x = res.extras
    assert x["control_saturated"] == 1.0 and x["control_steps"] == 0.0
    assert x["grasp_centre_error_x"] < -1e-3  # uncorrected
    assert "above the limit of" in res.solver.message


@pytest.mark.slow  # ~5 s alone; the browser test (regression tier) builds this report too
def test_small_study_report_has_the_scoop_figures(small_study_run, tmp_path):
    from workbench.report.build import build_report
    from workbench.study import read_table

    from workbench.experiments.fruit_harvester.scoop_notes import ABOUT

    out = small_study_run(Path(__file__).resolve().parents[2] / "tests/regression/studies/fruit_harvester_fluidic.toml")
    df = read_table(out)
    assert set(df["status"]) == {"ok"}, df[["model", "error"]]
    ph = df[df["model"] == "contact"].set_index("p.scenario.actuation")
    assert ph.at["fluidic", "length_change"] > 0.05 > 0 > ph.at["tendon", "length_change"]  # chambers lengthen
    html = build_report(out, tmp_path / "report", formats=()).read_text()
    for name in ("scoop_shapes", "scoop_centre", "scoop_length", "scoop_control"):
        assert f"data-figure='{name}'" in html, name
    import html as _html

    text = _html.unescape(html)
    assert ABOUT.question[:40] in text and all(a.what in text for a in ABOUT.assumptions)
    assert "Findings: fluidic: the section's length changes by 16.1 % of L in the physics" in text
