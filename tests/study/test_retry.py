"""Resume and retries: infrastructure failures are retried by default, model failures with --retry-failed;
duplicated rows are detected and recomputed; nothing is ever stored twice."""

from __future__ import annotations

import shutil
from dataclasses import dataclass

import pandas as pd

import study_fakes as fakes
from runs_util import same_table
from workbench.cli import main
from workbench.study import IsolatedExecutor, RunConfig, SerialExecutor, load_study, read_manifest, run_cases, summarize
from workbench.study.expand import Case
from workbench.study.outcomes import CaseLimits
from workbench.study.plan import plan_units


@dataclass(frozen=True)
class _Row:
    case_id: str
    model: str
    status: str
    failure: str = ""


def _cases(*ids):
    return [Case(case_id=i, index=k, params={}, swept={}) for k, i in enumerate(ids)]


def test_plan_computes_missing_models_and_retries_by_failure_kind():
    stored = [_Row("a", "cc", "ok"), _Row("a", "ancf", "failed", "model"),
              _Row("b", "cc", "failed", "killed"), _Row("b", "ancf", "ok"),
              _Row("c", "cc", "failed", "timeout"),
              _Row("d", "cc", "ok"), _Row("d", "cc", "ok"), _Row("d", "ancf", "ok")]
    plan = plan_units(_cases("a", "b", "c", "d", "e"), ("cc", "ancf"), stored)
    assert [(u.case.case_id, u.models) for u in plan.units] == [
        ("b", ("cc",)), ("c", ("cc", "ancf")), ("d", ("cc",)), ("e", ("cc", "ancf"))]
    assert plan.remove == {("b", "cc"), ("c", "cc"), ("d", "cc")}
    assert plan.retried == {"killed": 1, "timeout": 1, "duplicate": 2}
    again = plan_units(_cases("a"), ("cc", "ancf"), stored, retry_failed=True)
    assert [(u.case.case_id, u.models) for u in again.units] == [("a", ("ancf",))] and again.retried == {"model": 1}
    whole = plan_units(_cases("b"), ("cc", "ancf"), stored, separable=False)
    assert whole.units[0].models == ("cc", "ancf") and whole.remove == {("b", "cc"), ("b", "ancf")}


def _study(write_study, tensions):
    from study_fakes import GOOD

    axis = ", ".join(f"[{t}, 0.0]" for t in tensions)
    return load_study(write_study(f"""
        [sweep]
        product = {{ "load.tensions" = [{axis}] }}
        """, base=GOOD))


def test_resume_retries_a_killed_model_and_keeps_the_model_failure(tmp_path, write_study, monkeypatch):
    """cc of the 2 N case is killed from outside once (infrastructure); the 13 N case raises (a model failure)."""
    monkeypatch.setenv("WB_KILL_ONCE", str(tmp_path / "killed-once"))
    study = _study(write_study, [1.0, 2.0, fakes.RAISE, 3.0])
    out = tmp_path / "o"
    first = run_cases(fakes.sweep_kind(fakes.lookup_kill_once), study, out, IsolatedExecutor(),
                      RunConfig(progress=False))
    df = pd.read_parquet(out)
    assert first.failures == {"killed": 1, "model": 2} and first.exit_code == 3  # 3: infrastructure failed
    t2 = df[df["p.load.tensions"] == "[2.0,0.0]"].set_index("model")
    assert t2.loc["cc", "failure"] == "killed" and t2.loc["ancf", "status"] == "ok"  # ancf kept, not redone

    second = run_cases(fakes.sweep_kind(fakes.lookup_kill_once), study, out, IsolatedExecutor(),
                       RunConfig(progress=False, resume=True))
    assert second.n_run == 1 and second.failures == {"model": 2} and second.exit_code == 1
    assert read_manifest(out)["runs"][1]["retried"] == {"killed": 1}
    ref = tmp_path / "ref"
    run_cases(fakes.sweep_kind(fakes.lookup), study, ref, SerialExecutor(), RunConfig(progress=False))
    assert same_table(pd.read_parquet(out), pd.read_parquet(ref))

    third = run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(),
                      RunConfig(progress=False, resume=True))
    assert third.n_run == 0  # model failures are results: not retried by default
    fourth = run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(),
                       RunConfig(progress=False, resume=True, retry_failed=True))
    assert fourth.n_run == 1 and read_manifest(out)["runs"][3]["retried"] == {"model": 2}
    assert same_table(pd.read_parquet(out), pd.read_parquet(ref))


def test_resume_retries_timeouts(tmp_path, write_study):
    study = _study(write_study, [1.0, fakes.HANG])
    out = tmp_path / "o"
    run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(),
              RunConfig(progress=False, limits=CaseLimits(seconds=0.5)))
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(),
                  RunConfig(progress=False, resume=True, limits=CaseLimits(seconds=0.5)))
    assert s.n_run == 1 and s.failures == {"timeout": 2}
    assert read_manifest(out)["runs"][1]["retried"] == {"timeout": 2}
    assert not pd.read_parquet(out).duplicated(["case_id", "model"]).any()


def test_duplicate_rows_are_reported_then_recomputed(tmp_path, write_study, capsys):
    study = _study(write_study, [1.0, 2.0])
    out = tmp_path / "o"
    run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(), RunConfig(progress=False, flush_rows=2))
    part = sorted(p for p in out.glob("part-*.parquet") if "schema" not in p.name)[0]
    shutil.copy(part, part.with_name(part.name.replace("part-", "part-9")))  # as two unlocked runs wrote it
    n = len(pd.read_parquet(part))  # rows of the copied part (one case: a part per 2 rows)
    assert n == 2 and summarize(out).n_duplicates == n
    assert main(["show", str(out)]) == 0
    assert f"WARNING: {n} duplicate (case_id, model) rows" in capsys.readouterr().out
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, out, SerialExecutor(), RunConfig(progress=False, resume=True))
    assert s.n_duplicates == 0 and s.n_run == 1
    assert read_manifest(out)["runs"][1]["retried"] == {"duplicate": 2 * n}
    assert len(pd.read_parquet(out)) == 4


def test_resume_records_a_changed_description_and_report(tmp_path, write_study):
    p = write_study()
    out = tmp_path / "o"
    run_cases(fakes.sweep_kind(fakes.lookup), load_study(p), out, SerialExecutor(), RunConfig(progress=False))
    p.write_text(p.read_text().replace('name = "good"', 'name = "good"\ndescription = "new words"')
                 + '\n[report]\nreference = "cc"\n')
    run_cases(fakes.sweep_kind(fakes.lookup), load_study(p), out, SerialExecutor(),
              RunConfig(progress=False, resume=True))
    man = read_manifest(out)
    assert man["runs"][1]["changed"] == {"study.description": ["", "new words"], "report": [{}, {"reference": "cc"}]}
    assert man["study"]["study"]["description"] == "new words" and man["study"]["report"] == {"reference": "cc"}
