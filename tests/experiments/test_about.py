"""workbench/experiments/about.py: question, assumptions (values read from the rows) and findings as one text."""

from __future__ import annotations

import pandas as pd

from workbench.experiments.about import Assumption, StudyAbout, about_summary, assumption_values

ABOUT = StudyAbout("does it work?", (Assumption("p.robot.k", "spring [N m/rad]", "assumed"),
                                     Assumption("", "Cardan joints", "modelling choice"),
                                     Assumption("p.robot.missing", "gone", "assumed")), ("paper row 1",))


def test_assumption_values_come_from_the_rows():
    ok = pd.DataFrame({"p.robot.k": [120.0, 120.0]})
    assert assumption_values(ABOUT, ok) == ["spring [N m/rad] = 120.0 (assumed)", "Cardan joints (modelling choice)",
                                            "gone (assumed)"]
    swept = pd.DataFrame({"p.robot.k": [1.0, 2.0, 1.0]})
    assert assumption_values(ABOUT, swept)[0] == "spring [N m/rad] = swept: 1.0, 2.0 (assumed)"


def test_summary_states_question_findings_assumptions_and_paper_rows():
    text = about_summary(ABOUT, pd.DataFrame({"p.robot.k": [3.0]}), ["error 1 mm", "twist 0"])
    assert text.startswith("Question: does it work? Findings: error 1 mm; twist 0. Assumptions: spring")
    assert text.endswith("Answers (seed papers): paper row 1.")
    assert "Findings: no successful case to report." in about_summary(ABOUT, pd.DataFrame(), [])
