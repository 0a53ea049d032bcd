"""Fixtures shared across test folders.

The default run is parallel (``-n 2 --dist loadfile`` in ``pyproject.toml``; ``-n 0``: one process):
one worker runs all tests of a file, so a module fixture (a Dask LocalCluster, the plug-in's pip
install, a study run read by a module) and the SLURM tests' cluster are built once.  (``--dist
loadgroup`` would group finer, but pytest-xdist 3.8's groups do not reach pytest 9.2's node ids.)
The small studies are read by several files, so :func:`small_study_run` shares them across workers.
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
