"""Regression tier: every small study reproduces its golden table within the tolerances."""

from __future__ import annotations

import pytest

from tests.regression.golden import (
    GOLDEN_DIR, compare_to_golden, load_tolerances, read_golden, run_small_study, small_study_paths,
    tolerances_for,
)

pytestmark = pytest.mark.regression


@pytest.mark.parametrize("path", small_study_paths(), ids=lambda p: p.stem)
def test_small_study_matches_golden(path, tmp_path):
    golden_path = GOLDEN_DIR / f"{path.stem}.csv"
    assert golden_path.exists(), f"no golden for {path.stem}: run python -m tests.regression.bless {path.stem}"
    got = run_small_study(path, tmp_path / path.stem)
    problems = compare_to_golden(got, read_golden(golden_path), tolerances_for(path.stem, load_tolerances()))
    assert not problems, f"{path.stem}: {len(problems)} mismatch(es) with the golden:\n" + "\n".join(problems)
