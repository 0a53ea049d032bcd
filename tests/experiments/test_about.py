"""workbench/experiments/about.py: question, assumptions (values read from the rows) and findings as one text."""

from __future__ import annotations

import pandas as pd
import pytest

from workbench.assumptions import Assumption
from workbench.experiments.about import StudyAbout, about_summary, assumption_values, from_preset

ABOUT = StudyAbout("does it work?", (Assumption("robot.k", what="spring [N m/rad]", source="assumed"),
                                     Assumption("", what="Cardan joints", source="modelling choice"),
                                     Assumption("robot.missing", what="gone", source="assumed")), ("paper row 1",))


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


def test_a_value_given_as_text_is_stated_with_its_source():
    about = StudyAbout("q?", (Assumption("", "the paper gives none", what="object", value="rigid cylinder"),
                              Assumption("", "", what="self-contact", value="not modelled")))
    assert assumption_values(about, pd.DataFrame()) == ["object: rigid cylinder (the paper gives none)",
                                                        "self-contact: not modelled"]


def test_a_preset_assumption_is_referenced_not_restated():
    a = from_preset("hannan_walker", "tendon_stiffness", "cable stiffness EA_t [N]", note="swept")
    assert (a.key, a.source) == ("robot.tendon_stiffness", "assumed, preset hannan_walker, swept")
    with pytest.raises(KeyError, match="declares no assumption 'gravity'"):
        from_preset("hannan_walker", "gravity", "gravity")  # a study setting, not an assumption
