"""The "not converged" rule: a deliberately coarse case is marked, a converged one is not."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from workbench.compare import compare_table
from workbench.compare.convergence import AGREEMENT_FLOOR, convergence_metrics
from workbench.study import RunConfig, SerialExecutor, load_study, read_table, run_study

STUDY = """
[study]
name = "coarse"
models = ["cc", "ancf"]

[robot]
preset = "steel_rod"
base_orientation = "horizontal"

[load]
mode = "tension"
bend_angle = 3.0

[derived]
gravity_parameter = 0.01

[solver]
n_elements = 16

[sweep]
product = { "solver.n_elements" = [4, 16] }
"""


def test_coarse_case_is_marked_not_converged(tmp_path):
    path = tmp_path / "coarse.toml"
    path.write_text(STUDY)
    run_study(load_study(path), tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    cmp = compare_table(read_table(tmp_path / "out"), baseline="cc").set_index("p.solver.n_elements")
    # gamma = 0.01: CC's own error (the sag) is ~1 mm; 4 ANCF elements at kappa L = 3 carry a
    # discretisation error of the same order, 16 elements a far smaller one
    assert bool(cmp.loc[4, "not_converged"]) and cmp.loc[4, "disc_fraction"] > 0.1
    assert not bool(cmp.loc[16, "not_converged"]) and cmp.loc[16, "disc_fraction"] < 0.01
    assert cmp.loc[16, "judged_error"] == pytest.approx(cmp.loc[16, "tip_error"])


def _rows(err_model="ancf", disc=1e-4, L=1.0):
    ref = {"model": "cc", "robot_length": L}
    row = {"model": err_model, "robot_length": L, "x.disc_tip_error": disc}
    return ref, row


def test_rule_on_numbers():
    ref, row = _rows(disc=1e-4)
    assert not convergence_metrics(ref, row, {"tip_error": 2e-3})["not_converged"]  # 5 %
    assert convergence_metrics(ref, row, {"tip_error": 5e-4})["not_converged"]  # 20 %
    # dynamics: the peak over time is judged
    m = convergence_metrics(ref, row, {"tip_error": 1e-9, "tip_error_max_over_time": 2e-3})
    assert m["judged_error"] == 2e-3 and not m["not_converged"]
    # CC exact: error and error bar both tiny -> agreement below the floor, whatever their ratio
    ref, row = _rows(disc=3e-6 * AGREEMENT_FLOOR)
    assert not convergence_metrics(ref, row, {"tip_error": 4e-6 * AGREEMENT_FLOOR})["not_converged"]
    # no estimate -> not certified
    ref, row = _rows(disc=float("nan"))
    assert convergence_metrics(ref, row, {"tip_error": 1e-2})["not_converged"]
    # two physics models: an error bar (the sum), never a mark
    a = {"model": "ancf", "robot_length": 1.0, "x.disc_tip_error": 1e-3}
    b = {"model": "spring_link", "robot_length": 1.0, "x.disc_tip_error": 2e-3}
    m = convergence_metrics(a, b, {"tip_error": 1e-4})
    assert m["disc_error"] == pytest.approx(3e-3) and not m["not_converged"]
    # a model that estimates the CC error itself (series-parallel) is judged by that estimate
    c = {"model": "series_parallel", "robot_length": 1.0, "x.disc_tip_error": 1e-3, "x.disc_cc_error": 1e-9}
    m = convergence_metrics({"model": "cc_fit", "robot_length": 1.0}, c, {"tip_error": 1e-5})
    assert m["disc_error"] == 1e-9 and not m["not_converged"]
    assert math.isclose(convergence_metrics({"model": "target", "robot_length": 1.0}, c,
                                            {"tip_error": 1e-11})["disc_error"], 1e-3)


def test_compare_table_columns_present_without_estimates():
    df = pd.DataFrame([
        {"case_id": "a", "model": "cc", "status": "ok", "tip_x": 0.0, "tip_y": 0.0, "tip_z": 1.0, "robot_length": 1.0},
        {"case_id": "a", "model": "ancf", "status": "ok", "tip_x": 0.1, "tip_y": 0.0, "tip_z": 1.0, "robot_length": 1.0},
    ])
    cmp = compare_table(df)
    assert bool(cmp["not_converged"].iloc[0]) and math.isnan(cmp["disc_error"].iloc[0])  # no estimate


def test_an_exempt_side_is_flagged_and_reports_say_exempt_not_plus_minus_zero():
    from workbench.report.findings import _pm
    from workbench.report.headline import Headline
    from workbench.study.estimate import EXEMPT_STATUS

    cc = {"model": "cc", "robot_length": 1.0}
    links = {"model": "spring_link", "robot_length": 1.0, "x.disc_tip_error": 0.0, "disc_status": EXEMPT_STATUS}
    m = convergence_metrics(cc, links, {"tip_error": 2e-3})
    assert m["disc_exempt"] and m["disc_error"] == 0.0 and not m["not_converged"]
    assert not convergence_metrics(cc, {**links, "disc_status": "ok"}, {"tip_error": 2e-3})["disc_exempt"]

    def headline(disc_pct, exempt):
        return Headline(baseline="cc", model="spring_link", error=2e-3, error_pct=0.2, disc=disc_pct / 100,
                        disc_pct=disc_pct, final_pct=float("nan"), case_id="c", converged=True, n_cases=1,
                        n_not_converged=0, dynamic=False, cc_pair=True, disc_exempt=exempt)

    assert "exempt from the error estimate" in _pm(headline(0.0, True)) and "±" not in _pm(headline(0.0, True))
    assert _pm(headline(0.0, False)).endswith("± 0 % L")
    assert _pm(headline(0.01, True)).endswith("± 0.01 % L (one side exempt)")


def test_a_headline_case_is_titled_by_its_own_models_row():
    # spring_link ran 128 links where the case's other rows say 64 elements (solver.by_model):
    # the title of a spring_link finding must show the 128
    import pandas as pd

    from workbench.report import findings

    class Study:
        axes = ["p.solver.n_elements"]
        labels: dict = {}
        ok = pd.DataFrame({"case_id": ["a", "a"], "model": ["ancf", "spring_link"], "p.solver.n_elements": [64, 128]})

    assert "128" in findings._case_text(Study(), "a", "spring_link")
    assert "64" in findings._case_text(Study(), "a", "ancf")
    assert "64" in findings._case_text(Study(), "a")
