"""The pipeline side of the discretisation-error estimate: which rows get one, and the switches."""

from __future__ import annotations

import math

import pytest

from workbench.study import RunConfig, SerialExecutor, load_study, read_table, run_study
from workbench.study.estimate import EXEMPT_STATUS

STUDY = """
[study]
name = "est"
models = ["cc", "ancf", "spring_link"]

[robot]
preset = "steel_rod"
gravity = 0.0

[load]
mode = "tension"
bend_angle = 1.0

[solver]
n_elements = 8
{extra}
"""


def _run(tmp_path, extra=""):
    tmp_path.mkdir(parents=True, exist_ok=True)
    p = tmp_path / "est.toml"
    p.write_text(STUDY.format(extra=extra))
    run_study(load_study(p), tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    return {r["model"]: r for _, r in read_table(tmp_path / "out").iterrows()}


def test_physics_rows_carry_an_estimate_cc_rows_none(tmp_path):
    rows = _run(tmp_path)
    assert all(r["status"] == "ok" for r in rows.values())
    for m in ("ancf", "spring_link"):
        r = rows[m]
        assert r["disc_status"] == "ok" or r["disc_status"].startswith("observed order"), r["disc_status"]
        assert math.isfinite(r["x.disc_tip_error"]) and r["x.disc_tip_error"] >= 0.0
        assert math.isfinite(r["x.disc_order_observed"])
    assert math.isnan(rows["cc"]["x.disc_tip_error"])
    # the chain converges at order 2 only: its estimate at 8 links is far larger than ANCF's
    assert rows["spring_link"]["x.disc_tip_error"] > 10 * rows["ancf"]["x.disc_tip_error"]


def test_error_estimate_none_and_exempt(tmp_path):
    rows = _run(tmp_path / "a", 'error_estimate = "none"')
    assert all(math.isnan(r.get("x.disc_tip_error", float("nan"))) for r in rows.values())
    rows = _run(tmp_path / "b", 'error_estimate_exempt = ["spring_link"]')
    assert rows["spring_link"]["x.disc_tip_error"] == 0.0 and rows["spring_link"]["disc_status"] == EXEMPT_STATUS
    assert rows["ancf"]["x.disc_tip_error"] > 0.0


def test_exempt_model_must_be_a_study_model(tmp_path):
    from workbench.study.spec import StudyError

    p = tmp_path / "bad.toml"
    p.write_text(STUDY.format(extra='error_estimate_exempt = ["beam3d"]'))
    with pytest.raises(StudyError, match="error_estimate_exempt"):
        load_study(p)
