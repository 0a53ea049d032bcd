"""Per-case evaluation: robot/load building, derived gravity, rows, per-model failure isolation."""

from __future__ import annotations

import math

import numpy as np
import pytest

import study_fakes as fakes
from workbench.study import build_robot, evaluate_case, expand, gravity_from_parameter, load_study


def _case(write_study, extra="", base=None):
    kw = {} if base is None else {"base": base}
    return expand(load_study(write_study(extra, **kw)))


def test_gravity_parameter_round_trip():
    params = {"preset": "steel_rod", "length": 0.8, "diameter": 6e-3}
    robot = build_robot(params, {"gravity_parameter": 4.0})
    cs = robot.sections[0].cross_section
    g = float(np.linalg.norm(robot.gravity))
    gamma = cs.mass_per_length * g * robot.length**3 / cs.EI
    assert gamma == pytest.approx(4.0, rel=1e-12)
    # independent numbers: steel, d = 6 mm -> EI = 13.3596 N m^2, m' = 0.22195 kg/m
    EI = 210e9 * math.pi * 6e-3**4 / 64
    mpl = 7850 * math.pi * 6e-3**2 / 4
    assert g == pytest.approx(4.0 * EI / (mpl * 0.8**3), rel=1e-12)
    with pytest.raises(ValueError, match="mass per length > 0"):
        gravity_from_parameter(1.0, 13.0, 0.0, 1.0)


def test_rows_schema_and_values(write_study):
    case = _case(write_study)[0]
    rows = evaluate_case(case.case_id, case.params, ("cc", "ancf"), fakes.lookup)
    assert [r["model"] for r in rows] == ["cc", "ancf"]
    r = rows[0]
    assert r["status"] == "ok" and r["error"] == ""
    assert r["case_id"] == case.case_id
    assert r["p.robot.length"] == 0.8 and r["p.solver.n_stations"] == 9
    assert r["p.load.tensions"] == "[1.0,0.0]"
    assert len(r["positions"]) == 3 * 9 and len(r["stations"]) == 9 and len(r["tip_frame"]) == 16
    assert (r["tip_x"], r["tip_y"], r["tip_z"]) == tuple(np.asarray(r["positions"]).reshape(9, 3)[-1])
    kappa = 1.0 * 0.02 / (210e9 * math.pi * 6e-3**4 / 64)
    assert r["tip_x"] == pytest.approx((1 - math.cos(kappa * 0.8)) / kappa, rel=1e-12)
    assert r["x.kappa"] == pytest.approx(kappa)
    assert r["_shapes"]["series.tip_position"] == [-1, 3]
    assert r["robot_length"] == 0.8 and r["converged"] is True


@pytest.mark.parametrize("tension,reason", [(fakes.RAISE, "RuntimeError: fake model exploded"),
                                            (fakes.NAN, "non-finite result in"),
                                            (fakes.NOCONV, "not converged")])
def test_failures_become_failed_rows(write_study, tension, reason):
    from study_fakes import GOOD

    case = _case(write_study, base=GOOD.replace("tensions = [1.0, 0.0]", f"tensions = [{tension}, 0.0]"))[0]
    rows = evaluate_case(case.case_id, case.params, ("cc",), fakes.lookup)
    assert rows[0]["status"] == "failed" and reason in rows[0]["error"]


def test_one_model_failing_does_not_stop_others(write_study):
    case = _case(write_study)[0]

    def lookup(name):
        if name == "ancf":
            def broken(robot, load, options):
                raise ZeroDivisionError("ancf broke")
            return broken
        return fakes.arc

    rows = evaluate_case(case.case_id, case.params, ("ancf", "cc", "spring_link"), lookup)
    assert [r["status"] for r in rows] == ["failed", "ok", "ok"]
    assert "ZeroDivisionError: ancf broke" in rows[0]["error"]


def test_build_failure_fails_every_model(write_study):
    case = _case(write_study)[0]
    params = {**case.params, "robot": {**case.params["robot"], "poisson_ratio": 0.7}}
    rows = evaluate_case(case.case_id, params, ("cc", "ancf"), fakes.lookup)
    assert [r["status"] for r in rows] == ["failed", "failed"]
    assert "building the case failed" in rows[0]["error"] and "poisson_ratio" in rows[0]["error"]


def test_bend_angle_goes_through_arc_actuation(write_study, monkeypatch):
    import workbench.models.cc
    from study_fakes import GOOD

    monkeypatch.setattr(workbench.models.cc, "actuation_from_arc", fakes.fake_arc_actuation)
    base = GOOD.replace("tensions = [1.0, 0.0]", "bend_angle = 1.2\nbend_plane = 0.0")
    case = _case(write_study, base=base)[0]
    rows = evaluate_case(case.case_id, case.params, ("cc",), fakes.lookup)
    r = rows[0]
    assert r["status"] == "ok"
    # fake actuation realises kappa = 1.2 / L exactly with the fake arc model
    assert r["x.kappa"] == pytest.approx(1.2 / 0.8, rel=1e-12)


def test_by_model_runs_each_model_with_its_own_settings(write_study):
    """``[solver.by_model.<model>]``: each model runs (and records) its own settings; without the
    key the case parameters (and so the case ids) do not mention it."""
    from study_fakes import GOOD

    from workbench.study import StudyError

    assert "by_model" not in _case(write_study)[0].params["solver"]
    base = GOOD.replace("n_elements = 8\n", "n_elements = 8\nby_model.ancf = { n_elements = 32, n_stations = 17 }\n")
    case = _case(write_study, base=base)[0]
    seen = {}

    def lookup(name):
        def run(robot, load, options):
            seen.setdefault(name, []).append((options.n_elements, options.n_stations))
            return fakes.arc(robot, load, options)
        return run

    rows = evaluate_case(case.case_id, case.params, ("cc", "ancf"), lookup)
    assert [r["p.solver.n_elements"] for r in rows] == [8, 32]
    assert [r["p.solver.n_stations"] for r in rows] == [9, 17]
    assert seen["cc"] == [(8, 9)] and [n for n, _ in seen["ancf"][:3]] == [32, 16, 8]  # the estimate coarsens it
    with pytest.raises(StudyError, match=r"solver\.by_model\.beam3d: 'beam3d' is not one of study.models"):
        load_study(write_study(base=base.replace("by_model.ancf", "by_model.beam3d")))
    with pytest.raises(StudyError, match=r"solver\.by_model\.ancf\.n_elements: must be >= 1"):
        load_study(write_study(base=base.replace("n_elements = 32", "n_elements = 0")))
