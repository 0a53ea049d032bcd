"""Fixtures shared across test folders, and the parallel run's grouping (pytest-xdist).

The default run is parallel (``-n 2 --dist loadgroup`` in ``pyproject.toml``; ``-n 0``: one process).
A test that uses a module- or session-scoped fixture of the tests (a Dask LocalCluster, the plug-in's
pip install, the SLURM test cluster, a study run read by a module) gets the ``xdist_group`` of that
fixture, so one worker builds it once and runs all its tests (:func:`pytest_collection_modifyitems`).
The small studies are shared across workers by a file lock instead (:func:`small_study_run`), so the
regression tier still spreads over both workers.
"""

from __future__ import annotations

import fcntl
import os
import shutil
from pathlib import Path

import pytest


def _shared_root(tmp_path_factory, name: str) -> Path:
    """A folder every worker of this run sees (the run's base temp folder; this process's without xdist)."""
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = tmp_path_factory.getbasetemp().parent / name  # <basetemp>/popen-gwN -> <basetemp>
    else:
        root = tmp_path_factory.getbasetemp() / name
    root.mkdir(parents=True, exist_ok=True)
    return root


#: wider fixtures that are not grouped: shared across workers by other means
_UNGROUPED = {"small_study_run", "tmp_path_factory", "worker_id", "testrun_uid"}


def pytest_collection_modifyitems(config, items):
    """Group the tests of each module/session fixture defined under ``tests/`` (see the module docstring)."""
    for item in items:
        defs = getattr(item, "_fixtureinfo", None)
        for name in item.fixturenames:
            fixturedefs = defs.name2fixturedefs.get(name) if defs else None
            if not fixturedefs or name in _UNGROUPED:
                continue
            fd = fixturedefs[-1]
            if fd.scope in ("module", "package", "session") and "tests" in Path(fd.baseid or ".").parts[:1]:
                item.add_marker(pytest.mark.xdist_group(f"{fd.baseid}::{name}"))
                break


@pytest.fixture(scope="session")
def small_study_run(tmp_path_factory):
    """``small_study_run(path) -> data folder``: each small study runs once per test run.

    The regression tier (golden comparison) and the report browser tests read the same run, so
    the default suite pays for each small study once, also when two workers run the suite: the
    first worker that needs a study runs it while holding ``<stem>.lock`` (``fcntl.flock``), the
    other waits and reads the finished folder (``<stem>.done`` beside it marks it; a run that raised
    leaves none, so the next test runs it again and reports its own error).
    """
    from tests.regression.golden import run_small_study

    root = _shared_root(tmp_path_factory, "small_study_runs")

    def _run(path: str | Path) -> Path:
        path = Path(path).resolve()
        out = root / path.stem
        with open(root / f"{path.stem}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            done = root / f"{path.stem}.done"
            if not done.exists():
                shutil.rmtree(out, ignore_errors=True)
                run_small_study(path, out)
                done.write_text("", encoding="utf-8")
        return out

    return _run
