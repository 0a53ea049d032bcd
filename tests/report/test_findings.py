"""The report's Question / Findings / Assumptions / Sensitivity sections on a small real study.

A deliberately coarse case (4 ANCF elements at kappa L = 3) must be marked not converged in the
findings, the summary and the error-bar figure; the sensitivity key gets its figure and sentence;
the assumptions table carries the preset's assumed values and the study's own.
"""

from __future__ import annotations

import re

import pandas as pd
import pytest

from workbench.report.build import build_report
from workbench.study import RunConfig, SerialExecutor, load_study, run_study

STUDY = """
[study]
name = "findings"
models = ["cc", "ancf"]

[robot]
preset = "steel_rod"
base_orientation = "horizontal"
diameter = 0.006

[load]
mode = "tension"
bend_angle = 3.0

[derived]
gravity_parameter = 0.01

[solver]
n_elements = 16

[sweep]
cases = [
    { "solver.n_elements" = 4, "robot.diameter" = 0.006 },
    { "solver.n_elements" = 16, "robot.diameter" = 0.006 },
    { "solver.n_elements" = 16, "robot.diameter" = 0.008 },
]

[report]
question = "Does the coarse mesh show?"
assumptions = { "solver.n_elements" = "4 and 16 elements (the test's choice)" }
sensitivity = ["robot.diameter"]
"""


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    d = tmp_path_factory.mktemp("findings")
    (d / "s.toml").write_text(STUDY)
    run_study(load_study(d / "s.toml"), d / "out", SerialExecutor(), RunConfig(progress=False))
    path = build_report(d / "out", d / "rep")
    return path.read_text(encoding="utf-8"), pd.read_csv(d / "rep" / "summary.csv")


def _section(html: str, sid: str) -> str:
    m = re.search(rf'<section id="{sid}"[^>]*>(.*?)</section>', html, re.S)
    assert m, f"no section {sid}"
    return m.group(1)


def test_four_sections_first_with_exact_headings(page):
    html, _ = page
    ids = re.findall(r'<section id="([^"]+)"', html)
    assert ids[:4] == ["question", "findings", "assumptions", "sensitivity"]
    for sid, title in (("question", "Question"), ("findings", "Findings"), ("assumptions", "Assumptions"),
                       ("sensitivity", "Sensitivity")):
        body = _section(html, sid)
        assert f"<h2>{title}</h2>" in body
        assert len(re.sub(r"<[^>]+>", "", body).replace(title, "").strip()) > 20
    assert "Does the coarse mesh show?" in _section(html, "question")


def test_coarse_case_marked_not_converged(page):
    html, summary = page
    text = _section(html, "findings")
    # the sensitivity case (8 mm) is left out of the headline: 2 baseline cases, the coarse one marked
    assert "1 of 2 cases are not converged" in text or "NOT CONVERGED" in text
    row = summary[summary["comparison"].str.contains("ANCF")].iloc[0]
    assert row["not converged"] == "1 of 2"
    assert "± discretisation [% L]" in summary.columns
    assert 'data-figure="error_bars"' in html or "data-figure='error_bars'" in html
    assert "not converged" in html


def test_assumptions_and_sensitivity_from_data(page):
    html, _ = page
    a = _section(html, "assumptions")
    assert "robot.youngs_modulus" in a and "robot.yield_strength" in a  # the preset's ASSUMED
    assert "4 and 16 elements" in a and "Richardson" in a
    s = _section(html, "sensitivity")
    assert "sensitivity_robot_diameter" in s and "(baseline)" in s
    assert "error bar" in s


# issue 28: on main the cosserat rows had no error bar, so the findings said "no error estimate" and
# "NOT CONVERGED" for every CC-vs-cosserat comparison; now the bar is its solver-tolerance estimate.
def test_cosserat_headline_has_a_tolerance_error_bar(tmp_path):
    study = STUDY.replace('models = ["cc", "ancf"]', 'models = ["cc", "cosserat"]').replace(
        '{ "solver.n_elements" = 4, "robot.diameter" = 0.006 },\n', '')
    (tmp_path / "s.toml").write_text(study)
    run_study(load_study(tmp_path / "s.toml"), tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    html = build_report(tmp_path / "out", tmp_path / "rep").read_text(encoding="utf-8")
    findings = html[html.index('<section id="findings"'):html.index('<section id="assumptions"')]
    sentence = re.search(r"CC[^<]*Cosserat rod[^<]*largest tip error[^<]*", findings)
    assert sentence, findings[:2000]
    text = sentence.group(0)
    assert "no error estimate" not in text and "NOT CONVERGED" not in text
    assert re.search(r"± \S+ % L \(Cosserat rod: solver-tolerance estimate\)", text), text
