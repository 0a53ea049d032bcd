"""Regression tier: every small study reproduces its golden table within the tolerances."""

from __future__ import annotations

import pytest

from tests.regression.golden import (
    GOLDEN_DIR, compare_to_golden, golden_frame, load_tolerances, read_golden, small_study_paths, tolerances_for,
)
from workbench.study import read_table

pytestmark = pytest.mark.regression


@pytest.mark.parametrize("path", small_study_paths(), ids=lambda p: p.stem)
def test_small_study_matches_golden(path, small_study_run):
    golden_path = GOLDEN_DIR / f"{path.stem}.csv"
    assert golden_path.exists(), f"no golden for {path.stem}: run python -m tests.regression.bless {path.stem}"
    got = golden_frame(read_table(small_study_run(path)))  # one run per session, shared with the report tests
    problems = compare_to_golden(got, read_golden(golden_path), tolerances_for(path.stem, load_tolerances()))
    assert not problems, f"{path.stem}: {len(problems)} mismatch(es) with the golden:\n" + "\n".join(problems)
