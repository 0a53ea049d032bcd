"""The per-case result cache: a study with an added sweep value or an added model computes only the new
(case, model) pairs; cached rows are bit-identical; only results are cached; a code change invalidates."""

from __future__ import annotations

import pandas as pd

from runs_util import same_table
from study_fakes import GOOD
from workbench.cli import main
from workbench.study import RunConfig, SerialExecutor, load_study, read_manifest, run_study
from workbench.study import cache as cache_mod
from workbench.study.cache import ResultCache, code_version


def _study(write_study, tensions, models='"cc"'):
    axis = ", ".join(f"[{t}, 0.0]" for t in tensions)
    return load_study(write_study(f'\n[sweep]\nproduct = {{ "load.tensions" = [{axis}] }}\n',
                                  base=GOOD.replace('models = ["cc", "ancf"]', f"models = [{models}]")))


def test_an_added_sweep_value_computes_only_the_new_case(tmp_path, write_study):
    cache = tmp_path / "_cache"
    first = run_study(_study(write_study, [1.0, 2.0]), tmp_path / "a", SerialExecutor(),
                      RunConfig(progress=False, cache=cache))
    assert first.n_cached == 0 and read_manifest(tmp_path / "a")["runs"][0]["cache"]["writes"] == 2
    second = run_study(_study(write_study, [1.0, 2.0, 3.0]), tmp_path / "b", SerialExecutor(),
                       RunConfig(progress=False, cache=cache))
    rec = read_manifest(tmp_path / "b")["runs"][0]["cache"]
    assert second.n_cached == 2 and rec == {"folder": str(cache), "hits": 2, "writes": 1}  # one case computed
    assert first.n_computed == 2 and second.n_computed == 1 and second.n_run == 3
    a, b = pd.read_parquet(tmp_path / "a"), pd.read_parquet(tmp_path / "b")
    old = b[b["case_id"].isin(a["case_id"])]
    assert same_table(old, a) and old.sort_values("case_id")["wall_time"].tolist() == \
        a.sort_values("case_id")["wall_time"].tolist()  # the very rows, wall time included
    ref = run_study(_study(write_study, [1.0, 2.0, 3.0]), tmp_path / "ref", SerialExecutor(), RunConfig(progress=False))
    assert ref.n_cached == 0 and same_table(b, pd.read_parquet(tmp_path / "ref"))  # same table as without cache


def test_an_added_model_computes_only_that_model(tmp_path, write_study):
    cache = tmp_path / "_cache"
    run_study(_study(write_study, [1.0]), tmp_path / "a", SerialExecutor(), RunConfig(progress=False, cache=cache))
    s = run_study(_study(write_study, [1.0], models='"cc", "ancf"'), tmp_path / "b", SerialExecutor(),
                  RunConfig(progress=False, cache=cache))
    assert s.n_cached == 1 and read_manifest(tmp_path / "b")["runs"][0]["cache"]["writes"] == 1
    assert s.n_computed == 1  # the case is submitted for its new model
    assert set(pd.read_parquet(tmp_path / "b")["model"]) == {"cc", "ancf"} and s.n_ok == 1


def test_only_results_are_cached_and_a_code_change_invalidates(tmp_path, monkeypatch):
    c = ResultCache(tmp_path)
    base = {"case_id": "abc", "model": "cc", "status": "failed", "error": "x"}
    for failure in ("crash", "timeout", "memory", "killed", "lost"):
        c.put({**base, "failure": failure})
    assert c.writes == 0 and c.get("abc", "cc") is None
    c.put({**base, "failure": "model"})  # a model failure is a result
    c.put({**base, "case_id": "ok1", "status": "ok", "failure": ""})
    assert c.writes == 2 and c.get("ok1", "cc")["status"] == "ok" and c.get("abc", "cc")["failure"] == "model"
    assert code_version("cc") != code_version("ancf")
    assert any(p.name == "ancf.py" and p.parent.name == "physics" for _, p in cache_mod._sources("ancf"))
    assert any(p.name == "cc.py" and p.parent.name == "models" for _, p in cache_mod._sources("cc"))
    monkeypatch.setattr(cache_mod, "code_version", lambda model: "0" * 16)  # as after an edit of the model
    assert c.get("ok1", "cc") is None


def test_cli_caches_next_to_the_output_folder(tmp_path, write_study, capsys):
    p = write_study('\n[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0]] }\n',
                    base=GOOD.replace('models = ["cc", "ancf"]', 'models = ["cc"]'))
    run = ["run", str(p), "--in-process", "--no-report", "--progress", "off", "--out"]
    assert main(run + [str(tmp_path / "a")]) == 0 and (tmp_path / "_cache" / "cc").is_dir()
    capsys.readouterr()
    assert main(run + [str(tmp_path / "b")]) == 0
    assert "(this run: 0 computed, 2 from the cache (2 model rows), 0 already stored)" in capsys.readouterr().out
    assert main(run + [str(tmp_path / "c"), "--no-cache"]) == 0
    assert "cache" not in read_manifest(tmp_path / "c")["runs"][0]


def test_retry_failed_recomputes_a_cached_model_failure(tmp_path, write_study):
    cache = tmp_path / "_cache"
    study = _study(write_study, [1.0])
    run_study(study, tmp_path / "a", SerialExecutor(), RunConfig(progress=False, cache=cache))
    c = ResultCache(cache)
    (cid,) = pd.read_parquet(tmp_path / "a")["case_id"].tolist()
    good = c.get(cid, "cc")
    c.put({**good, "status": "failed", "failure": "model", "error": "ModelFailure: planted"})  # as if it had failed
    b = run_study(study, tmp_path / "b", SerialExecutor(), RunConfig(progress=False, cache=cache))
    assert b.n_failed == 1 and b.n_cached == 1 and b.n_computed == 0  # a model failure is a result: reused
    again = run_study(study, tmp_path / "b", SerialExecutor(),
                      RunConfig(progress=False, cache=cache, resume=True, retry_failed=True))
    assert again.n_ok == 1 and again.n_failed == 0 and again.n_cached == 0 and again.n_computed == 1
    assert ResultCache(cache).get(cid, "cc")["status"] == "ok"  # the recomputed row replaced the failure
