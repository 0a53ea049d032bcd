"""The folder lock: one run per result folder; a second is refused with one line; stale locks are taken over."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pandas as pd
import pytest

from runs_util import KILL_STUDY, ROOT, cli_args, env, parts
from workbench.study.lock import LOCK_FILE, FolderLock, FolderLocked, lock_holder


def test_a_second_lock_is_refused_naming_the_holder(tmp_path):
    first = FolderLock(tmp_path / "o").acquire("2026-01-01T00:00:00+00:00")
    assert first.created_folder and lock_holder(tmp_path / "o")[0] == "running"
    with pytest.raises(FolderLocked) as ei:
        FolderLock(tmp_path / "o").acquire()
    (line,) = ei.value.problems
    assert line.startswith(f"{tmp_path / 'o'}: another run is writing into this folder (pid {os.getpid()} on host ")
    assert "started 2026-01-01T00:00:00+00:00" in line and line.endswith("or choose another --out")
    first.release()
    assert lock_holder(tmp_path / "o") == ("free", {})
    again = FolderLock(tmp_path / "o").acquire()
    assert again.stale is None  # released properly: nothing stale
    again.release(remove_folder=True)
    assert (tmp_path / "o").exists()  # it did not create the folder: kept
    fresh = FolderLock(tmp_path / "new" / "o").acquire()
    fresh.release(remove_folder=True)  # a run that failed before writing anything leaves no folder
    assert not (tmp_path / "new" / "o").exists()


def test_a_lock_of_a_killed_process_is_taken_over_and_recorded(tmp_path):
    folder = tmp_path / "o"
    code = (f"import sys, time; sys.path.insert(0, {str(ROOT)!r}); from workbench.study.lock import FolderLock; "
            f"FolderLock({str(folder)!r}).acquire('t'); print('locked', flush=True); time.sleep(60)")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "locked"
    with pytest.raises(FolderLocked):
        FolderLock(folder).acquire()
    proc.kill()
    proc.wait()
    state, holder = lock_holder(folder)
    assert state == "dead" and holder["pid"] == proc.pid  # show can say "the last run was killed"
    lock = FolderLock(folder).acquire()
    assert lock.stale["pid"] == proc.pid
    lock.release()
    assert (folder / LOCK_FILE).exists()  # never deleted (that would let two processes hold it)


def _wait_locked(folder, proc, timeout=60.0):
    t_end = time.monotonic() + timeout
    while time.monotonic() < t_end and proc.poll() is None:
        if lock_holder(folder)[0] == "running":
            return True
        time.sleep(0.01)
    return False


@pytest.mark.parametrize("second", ["fresh", "resume"])
def test_two_runs_into_one_folder_exactly_one_runs(tmp_path, second):
    """A run plus a second run (or a concurrent --resume) into the same --out: the second is refused
    with one line, the first completes, no row is stored twice."""
    study = tmp_path / "killme.toml"
    study.write_text(KILL_STUDY)
    out = tmp_path / "o"
    first = subprocess.Popen(cli_args(study, out), env=env(), cwd=tmp_path, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    assert _wait_locked(out, first), "the first run never took the lock"
    r = subprocess.run(cli_args(study, out, *(["--resume"] if second == "resume" else [])), env=env(), cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    rc1 = first.wait(timeout=120)
    assert rc1 == 1, first.stderr.read()  # the 13 N cases fail by design
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "another run is writing into this folder" in r.stderr and f"pid {first.pid}" in r.stderr
    df = pd.read_parquet(out)
    assert len(df) == 60 and not df.duplicated(["case_id", "model"]).any()
    assert parts(out)
