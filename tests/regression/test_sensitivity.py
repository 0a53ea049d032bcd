"""The regression tier detects a deliberate 1 % change of a material parameter.

The quickstart small study states its load dimensionlessly: the tendon tension comes from the CC
command (T = EI kappa / d) and gravity from gamma = q L^3 / EI.  Both scale with EI, so changing
Young's modulus alone changes nothing physical there (the deflection in units of L is the same).
To change the *material* of a physically loaded robot, the test first converts every case to its
physical load -- explicit tendon tensions [N] and gravity g [m/s^2] computed for the nominal robot
-- checks that this equivalent study reproduces the golden (the unmodified run reports no
problems), then stiffens the rod by 1 % (youngs_modulus x 1.01) under the same physical load and
checks that :func:`compare_to_golden` reports mismatches in the tip position.
"""

from __future__ import annotations

import copy
import dataclasses

import pytest

from tests.regression.golden import (
    GOLDEN_DIR, STUDIES_DIR, compare_to_golden, golden_frame, load_tolerances, read_golden,
    run_study_object, tolerances_for,
)

pytestmark = pytest.mark.regression

STEM = "quickstart"


def physical_load_study(study, youngs_factor: float):
    """``study`` with every case's load made physical (tensions, g) and E scaled by ``youngs_factor``."""
    from workbench.study import build_load, build_robot, expand

    cases = []
    for c in expand(study):
        robot = build_robot(c.params["robot"], c.params["derived"])
        load = build_load(robot, c.params["load"])
        assert load.actuation.mode == "tension"
        cases.append({"load.tensions": [float(t) for t in load.actuation.values],
                      "robot.gravity": float(abs(robot.gravity[2]))})
    base = copy.deepcopy(study.base)
    base["robot"]["youngs_modulus"] = base["robot"]["youngs_modulus"] * youngs_factor
    base["derived"]["gravity_parameter"] = None
    base["load"]["bend_angle"] = None
    return dataclasses.replace(study, base=base, sweep={"cases": cases})


def _run_against_golden(youngs_factor: float, tmp_path) -> list[str]:
    from workbench.study import expand, load_study

    study = load_study(str(STUDIES_DIR / f"{STEM}.toml"))
    # the small study must exercise gravity, or the test would not test what it says
    assert all(c.params["derived"]["gravity_parameter"] > 0 for c in expand(study))
    variant = physical_load_study(study, youngs_factor)
    frame = golden_frame(run_study_object(variant, tmp_path / f"E{youngs_factor}"))
    ids = {a.case_id: b.case_id for a, b in zip(expand(variant), expand(study), strict=True)}
    frame["case_id"] = frame["case_id"].map(ids)
    frame = frame.sort_values(["case_id", "model"]).reset_index(drop=True)
    return compare_to_golden(frame, read_golden(GOLDEN_DIR / f"{STEM}.csv"),
                             tolerances_for(STEM, load_tolerances()))


def test_equivalent_physical_load_reproduces_golden(tmp_path):
    assert _run_against_golden(1.0, tmp_path) == []


def test_one_percent_stiffer_rod_fails_the_tier(tmp_path):
    problems = _run_against_golden(1.01, tmp_path)
    tip = [p for p in problems if " ancf tip_" in p]
    # every ANCF case moves: the stiffer rod bends further under the same tension and sags less
    assert len({p.split()[0] for p in tip}) == 4, "\n".join(problems)
    # CC ignores gravity, but its commanded curvature T d / EI changes too
    assert any(" cc tip_" in p for p in problems), "\n".join(problems)
