"""Interrupted runs keep what finished: SIGTERM (like a batch scheduler) exits 143 with the resume hint,
an in-process crash keeps the cases before it, rows are flushed on a timer, and --resume then
completes a table identical to an uninterrupted run."""

from __future__ import annotations

import signal
import subprocess
import time

import pandas as pd
import pytest

import study_fakes as fakes
from runs_util import KILL_STUDY, cli_args, env, parts, same_table
from workbench.study import RunConfig, SerialExecutor, expand, load_study, read_manifest, run_cases
from workbench.study.session import RunSession


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted table of the 30-case study (fake models, in-process)."""
    tmp = tmp_path_factory.mktemp("ref")
    study = tmp / "killme.toml"
    study.write_text(KILL_STUDY)
    run_cases(fakes.sweep_kind(fakes.lookup), load_study(study), tmp / "ref", SerialExecutor(),
              RunConfig(progress=False))
    return pd.read_parquet(tmp / "ref")


@pytest.mark.parametrize("in_process", [True, False], ids=["in-process", "isolated"])
def test_sigterm_stores_finished_cases_exits_143_and_resume_completes(tmp_path, reference, in_process):
    study = tmp_path / "killme.toml"
    study.write_text(KILL_STUDY)
    out = tmp_path / "o"
    proc = subprocess.Popen(cli_args(study, out, in_process=in_process), env=env(), cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    t_end = time.monotonic() + 60
    while time.monotonic() < t_end and proc.poll() is None and len(parts(out)) < 2:
        time.sleep(0.01)
    assert proc.poll() is None, "the run finished before it could be terminated"
    proc.send_signal(signal.SIGTERM)
    rc = proc.wait(timeout=60)
    err = proc.stderr.read().strip().splitlines()
    assert rc == 143 and err[-1].startswith("terminated (SIGTERM); finished cases are stored in "), err
    assert "--resume" in err[-1]
    stored = pd.read_parquet(out)
    assert 0 < len(stored) < 60 and not stored.duplicated(["case_id", "model"]).any()
    assert set(stored["failure"]) <= {"", "model"}  # the interrupted case was not recorded as a crash
    run = read_manifest(out)["runs"][0]
    assert run["outcome"] == "interrupted (Terminated)" and run["end"] is not None
    r = subprocess.run(cli_args(study, out, "--resume"), env=env(), cwd=tmp_path, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 1, r.stderr  # the 13 N cases fail (raise) by design
    assert same_table(pd.read_parquet(out), reference)


def test_in_process_crash_keeps_the_cases_before_it(tmp_path, write_study):
    """--in-process has no isolation: os._exit in case 4 ends the command; cases 0-3 survive in the
    rows journal (not in parts yet: a part per case costs ~4 ms), the next run stores them first and
    computes only the rest."""
    from study_fakes import GOOD

    from workbench.study.store import JOURNAL

    p = write_study('\n[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0], '
                    '[66.0, 0.0], [6.0, 0.0]] }\n', base=GOOD)
    out = tmp_path / "o"
    r = subprocess.run(cli_args(p, out, "--flush-rows", "1000", lookup="study_fakes:lookup", in_process=True),
                       env=env(), cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert r.returncode == 3  # the fake's os._exit(3): the process is gone
    assert (out / JOURNAL).stat().st_size > 0
    # the default executor then finishes the run; the crashing case is stored as a crash
    r = subprocess.run(cli_args(p, out, "--resume", lookup="study_fakes:lookup", in_process=False), env=env(),
                       cwd=tmp_path, capture_output=True, text=True, timeout=120)
    df = pd.read_parquet(out)
    assert r.returncode == 1 and len(df) == 12 and not df.duplicated(["case_id", "model"]).any()
    assert read_manifest(out)["runs"][1]["cases_to_run"] == 2  # cases 0-3 came from the journal
    assert (df[df["p.load.tensions"] == "[66.0,0.0]"]["failure"] == "crash").all()
    assert not (out / JOURNAL).exists()


def test_a_journal_torn_by_a_kill_keeps_its_whole_records_and_never_duplicates(tmp_path):
    """Records after a torn one are never written (the writer died there); rows already in a part are
    skipped (killed between a part's rename and the journal's truncation)."""
    from workbench.study.store import JOURNAL, ResultStore

    row = {"case_id": "c0", "model": "cc", "status": "ok", "error": "", "wall_time": 0.0}
    store = ResultStore(tmp_path / "o", flush_rows=1000, flush_seconds=1e9, journal=True)
    for k in range(3):
        store.add([{**row, "case_id": f"c{k}"}])
    store.flush()  # c0-c2 in a part, the journal emptied
    store.add([{**row, "case_id": "c3"}])
    store.add([{**row, "case_id": "c4"}])
    journal = (tmp_path / "o" / JOURNAL).read_bytes()
    # as if killed while writing c4's record, and c1 had been journaled again before a lost truncation
    ResultStore(tmp_path / "x", journal=True).add([{**row, "case_id": "c1"}])
    again = (tmp_path / "x" / JOURNAL).read_bytes()
    (tmp_path / "o" / JOURNAL).write_bytes(again + journal[:-5])
    fresh = ResultStore(tmp_path / "o")
    assert fresh.recover_journal() == 1  # c3 (c1 is stored, c4 torn)
    ids = sorted(pd.read_parquet(tmp_path / "o")["case_id"])
    assert ids == ["c0", "c1", "c2", "c3"] and not (tmp_path / "o" / JOURNAL).exists()


def test_rows_are_flushed_on_a_timer(tmp_path, write_study):
    """A finished case waits at most flush_seconds in memory, even when no further case finishes."""
    study = load_study(write_study())
    cases = expand(study)
    session = RunSession.open(tmp_path / "o", study, cases, ({} for _ in cases), "test",
                              RunConfig(progress=False, flush_rows=1000, flush_seconds=0.3), models=("cc",))
    with session:
        session.record(cases[0].case_id, [{"case_id": cases[0].case_id, "model": "cc", "status": "ok",
                                           "error": "", "wall_time": 0.0}])
        assert not parts(tmp_path / "o")
        t_end = time.monotonic() + 10
        while not parts(tmp_path / "o") and time.monotonic() < t_end:
            time.sleep(0.05)
        assert parts(tmp_path / "o"), "the timer did not flush"
