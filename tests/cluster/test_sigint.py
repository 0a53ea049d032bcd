"""Loading dask-jobqueue leaves the process's Ctrl-C (SIGINT) handler as it was (issue 31, "Ctrl-C stops the tests").

dask-jobqueue's ``runner`` module installs ``lambda *_: sys.exit()`` as SIGINT handler when imported, so a
Ctrl-C during pytest became a ``SystemExit`` that failed the running test while the suite carried on.
:func:`workbench.study.cluster.cluster_class` (the only place the package is imported) puts the previous
handler back.  Nothing is submitted or started here.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from workbench.study.cluster import cluster_class

ROOT = Path(__file__).resolve().parents[2]


def _sentinel(signum, frame):  # pragma: no cover - never called: only its identity is checked
    raise AssertionError("the test's SIGINT handler was called")


@pytest.mark.parametrize("scheduler", ["slurm", "pbs", "sge", "lsf"])
def test_loading_the_jobqueue_class_keeps_the_sigint_handler(scheduler, monkeypatch):
    """A fresh import of dask_jobqueue (earlier tests may have imported it) keeps the handler in place."""
    for name in [m for m in sys.modules if m == "dask_jobqueue" or m.startswith("dask_jobqueue.")]:
        monkeypatch.delitem(sys.modules, name)  # put back afterwards
    before = signal.signal(signal.SIGINT, _sentinel)
    try:
        cls = cluster_class(scheduler)
        after = signal.getsignal(signal.SIGINT)
    finally:
        signal.signal(signal.SIGINT, before)
    assert cls.__name__ == f"{scheduler.upper()}Cluster"
    assert after is _sentinel, f"importing dask_jobqueue replaced the SIGINT handler with {after!r}"


_CHILD = """
import os, signal
# Python's own handler, whatever the parent left (a shell's background job starts with SIGINT ignored)
signal.signal(signal.SIGINT, signal.default_int_handler)
from workbench.study.cluster import job_script
from workbench.study.cluster_config import resolve_cluster
script = job_script(resolve_cluster("slurm", {}, "c.toml", {"jobs": 1}))  # what --dry-run prints
assert "#SBATCH" in script
assert signal.getsignal(signal.SIGINT) is signal.default_int_handler, signal.getsignal(signal.SIGINT)
try:
    os.kill(os.getpid(), signal.SIGINT)
    for _ in range(1000):  # the handler runs between bytecodes, at once
        pass
except KeyboardInterrupt:
    print("KeyboardInterrupt")
"""


def test_ctrl_c_after_a_dry_run_job_script_is_a_keyboard_interrupt():
    """In a fresh interpreter: the job script of a dry run, then a real SIGINT raises KeyboardInterrupt."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    r = subprocess.run([sys.executable, "-c", _CHILD], capture_output=True, text=True, timeout=120, env=env,
                       cwd=ROOT)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.strip() == "KeyboardInterrupt", (r.stdout, r.stderr[-2000:])
