"""study/rows.py: one non-finite rule and one failed-row builder for every study kind."""

from __future__ import annotations

import math

import numpy as np

from workbench.study.rows import fail_non_finite, failed_rows, non_finite_cells


def _ok(**cells):
    return {"case_id": "c", "model": "m", "status": "ok", "error": "", "positions": [0.0, 0.0, 1.0],
            "tip_frame": [1.0] * 16, "length_change": 0.0, "tip_twist": 0.0, **cells}


def test_a_finite_row_stays_ok():
    row = fail_non_finite(_ok(**{"x.a": 1.0, "series.s": [1.0, 2.0]}))
    assert row["status"] == "ok" and row["error"] == ""


def test_non_finite_cells_in_rule_order():
    row = _ok(**{"x.b": math.nan, "series.s": [1.0, math.inf], "tip_twist": math.nan})
    row["positions"] = [math.nan, 0.0, 0.0]
    assert non_finite_cells(row) == ["positions", "tip_twist", "series.s", "x.b"]
    fail_non_finite(row)
    assert row["status"] == "failed"
    assert row["error"] == "non-finite result in positions, tip_twist, series.s, x.b"


def test_tendon_tensions_all_nan_means_no_forces_partly_nan_is_broken():
    assert non_finite_cells(_ok(tendon_tensions=[math.nan, math.nan])) == []
    assert non_finite_cells(_ok(tendon_tensions=[1.0, math.nan])) == ["tendon_tensions"]
    assert non_finite_cells(_ok(tendon_tensions=None)) == []


def test_a_failed_row_keeps_its_reason():
    row = _ok(**{"x.a": math.nan})
    row.update(status="failed", error="IK: no solution")
    assert fail_non_finite(row)["error"] == "IK: no solution"


def test_failed_rows_one_per_model_with_extra_cells():
    rows = failed_rows("c1", {"robot": {"length": 0.8}}, ("a", "b"), "boom", wall_time=0.0,
                       extra={"robot_length": 0.8})
    assert [r["model"] for r in rows] == ["a", "b"]
    assert rows[0] == {"case_id": "c1", "model": "a", "p.robot.length": 0.8, "robot_length": 0.8,
                       "status": "failed", "error": "boom", "failure": "model", "wall_time": 0.0}
    assert math.isnan(failed_rows("c1", {}, ("a",), "crash")[0]["wall_time"])


def test_the_finite_check_of_list_cells_matches_numpys():
    from workbench.study.rows import _not_finite

    nan, inf = float("nan"), float("inf")
    cases = [[0.0, 1.0], [1e308, 1e308], [1.0, nan], [inf, -inf], [[1.0, nan]], [[1.0, 2.0]], [], (1.0, nan), 2.0, nan]
    for c in cases:
        assert _not_finite(c) == (not np.isfinite(np.asarray(c, dtype=float)).all()), c
    assert _not_finite(None) is False
