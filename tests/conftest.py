"""Fixtures shared across test folders."""

from __future__ import annotations

from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def small_study_run(tmp_path_factory):
    """``small_study_run(path) -> data folder``: each small study runs once per test session.

    The regression tier (golden comparison) and the report browser tests read the same run, so
    the default suite pays for each small study once.
    """
    from tests.regression.golden import run_small_study

    root = tmp_path_factory.mktemp("small_study_runs")
    done: dict[Path, Path] = {}

    def _run(path: str | Path) -> Path:
        path = Path(path).resolve()
        if path not in done:
            out = root / path.stem
            run_small_study(path, out)
            done[path] = out
        return done[path]

    return _run
