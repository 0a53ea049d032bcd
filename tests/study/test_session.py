"""study/session.py: one run session for every study kind (manifest, run record, store, finish)."""

from __future__ import annotations

import json

import pytest

import study_fakes as fakes
from workbench.study import RunConfig, SerialExecutor, expand, load_study, read_manifest, run_cases, study_name
from workbench.study.session import RunSession


def test_study_name_ends_the_manifest_chains():
    assert study_name({"study": {"study": {"name": "q"}}}) == "q"
    assert study_name({}) is None and study_name({}, "?") == "?"
    assert study_name({"study": None}, "d") == "d"


def test_resume_appends_a_run_and_refreshes_the_provenance(tmp_path, write_study):
    study = load_study(write_study())
    out = tmp_path / "out"
    run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(), RunConfig(progress=False))
    man = read_manifest(out)
    man["versions"] = {"numpy": "0"}  # as if an older install had written the folder
    (out / "_manifest.json").write_text(json.dumps(man))
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(), RunConfig(progress=False, resume=True))
    assert s.n_run == 0 and s.n_skipped == 1
    man = read_manifest(out)
    assert len(man["runs"]) == 2 and man["runs"][1]["cases_to_run"] == 0
    assert man["versions"]["numpy"] != "0" and man["runs"][1]["end"] is not None


def test_an_interrupted_run_still_finishes_its_manifest(tmp_path, write_study):
    study = load_study(write_study())
    cases = expand(study)
    out = tmp_path / "out"
    session = RunSession.open(out, study, cases, ({} for _ in cases), "test", RunConfig(progress=False))
    with pytest.raises(KeyboardInterrupt):
        with session:
            session.record(cases[0].case_id, [{"case_id": cases[0].case_id, "model": "cc", "status": "ok",
                                               "error": "", "wall_time": 0.0}])
            raise KeyboardInterrupt
    man = read_manifest(out)
    assert man["runs"][0]["end"] is not None and man["runs"][0]["cases_done"] == 1
    assert session.n_ok == 1 and session.store.finished_case_ids() == {cases[0].case_id}


def test_piped_progress_prints_on_a_timer_while_a_case_runs(tmp_path, write_study, capsys):
    """Without a terminal, a line at least every ``progress_seconds`` while a (slow) case runs, naming it."""
    study = load_study(write_study('[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0]] }\n'))
    first = expand(study)[0].case_id
    run_cases(fakes.sweep_kind(fakes.lookup_sleep_1s), study, tmp_path / "out", SerialExecutor(),
              RunConfig(progress=None, progress_seconds=0.2))
    lines = capsys.readouterr().err.splitlines()
    timed = [ln for ln in lines if "in progress: case" in ln]
    assert len(timed) >= 3, lines  # ~2 s per case (two models), 0.2 s interval: several lines before the first case ends
    assert timed[0].startswith(f"{study.name}: 0/2 cases (ok 0, failed 0), ")
    assert f"in progress: case {first} (models cc, ancf), 1 more to go" in timed[0]
    assert lines[-1].startswith(f"{study.name}: 2/2 cases (ok 2, failed 0), ")
