"""Study kinds: kind_of / get_kind choose the kind once, run_cases runs any kind the same way."""

from __future__ import annotations

import pandas as pd
import pytest

import study_fakes as fakes
from workbench import registry
from workbench.study import RunConfig, SWEEP, SerialExecutor, get_kind, kind_of, load_study, read_manifest, run_cases

SP_TINY = """
[study]
kind = "series_parallel"
name = "tiny"
[solver]
n_elements = 4
[motions]
module = [ { axis = "z", amplitude = 0.01, samples = 2 } ]
"""


@pytest.mark.parametrize("text,kind", [
    ('[study]\nname = "x"\nmodels = ["cc"]\n', "sweep"),
    ('[study]\nkind = "series_parallel"\n', "series_parallel"),
    ('[study]\nkind = "sweep"\n', "sweep"),
    ('[study]\nkind = "no_such_kind"\n', "sweep"),  # the sweep loader reports study.kind as unknown
    ("[study]\nkind = 3\n", "sweep"),
    ("study = 3\n", "sweep"),
    ("[study\n", "sweep"),  # invalid TOML: the sweep loader reports it
])
def test_kind_of(tmp_path, text, kind):
    p = tmp_path / "s.toml"
    p.write_text(text)
    assert kind_of(p) == kind


def test_kind_of_an_unreadable_file_is_sweep(tmp_path):
    assert kind_of(tmp_path / "missing.toml") == "sweep"


def test_get_kind_resolves_the_registry():
    assert get_kind("sweep") is SWEEP
    sp = get_kind("series_parallel")
    assert sp.name == "series_parallel" and sp is registry.resolve(registry.KINDS["series_parallel"].target)
    assert set(registry.KINDS) == {"sweep", "series_parallel", "grasp", "closed_loop", "calibration"}
    with pytest.raises(KeyError, match="unknown study kind 'nope'; known kinds: sweep, series_parallel"):
        get_kind("nope")


def test_a_kind_missing_a_method_cannot_be_made():
    from workbench.study import StudyKind

    class Partial(StudyKind):
        name = "partial"

        def load(self, path, max_cases=None, overrides=()):
            return None

    with pytest.raises(TypeError, match="abstract"):
        Partial()


def test_sweep_batch_sizes():
    assert SWEEP.batch_size(1, 1) == 1
    assert SWEEP.batch_size(100, 1) == 13  # ceil(100 / 8)
    assert SWEEP.batch_size(10_000, 2) == 32
    assert SWEEP.batch_size(100, 0) == 13  # no slots reported: one


def test_run_cases_sweep_equals_run_study(tmp_path, write_study):
    study = load_study(write_study('[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0]] }\n'))
    a = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "a", SerialExecutor(), RunConfig(progress=False))
    b = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "b", SerialExecutor(), RunConfig(progress=False))
    assert (a.n_cases, a.n_ok, a.n_failed) == (b.n_cases, b.n_ok, b.n_failed) == (2, 2, 0)
    ta = pd.read_parquet(tmp_path / "a").drop(columns="wall_time").sort_values(["case_id", "model"])
    tb = pd.read_parquet(tmp_path / "b").drop(columns="wall_time").sort_values(["case_id", "model"])
    assert ta.reset_index(drop=True).equals(tb.reset_index(drop=True))


def test_series_parallel_kind_loads_and_expands(tmp_path):
    p = tmp_path / "sp.toml"
    p.write_text(SP_TINY)
    kind = get_kind(kind_of(p))
    spec = kind.load(p)
    assert kind.models(spec) == ("target", "series_parallel", "cc_fit")
    assert len(kind.expand(spec)) == 2 and kind.batch_size(2, 4) == 1


def test_crashed_series_parallel_case_gets_one_failed_row_per_model(tmp_path):
    """A worker crash (here: the executor reports it) is a failed row for each of the kind's models
    (they are computed together: no model is blamed alone, nothing is rerun)."""
    from workbench.study.outcomes import Crash, Outcome

    class Crashing(SerialExecutor):
        def imap_unordered(self, fn, payloads, limits=None, chunk_size=1):
            for i, _ in enumerate(payloads):
                yield i, Outcome([], Crash("crash", "worker died (test)"))

    p = tmp_path / "sp.toml"
    p.write_text(SP_TINY)
    kind = get_kind("series_parallel")
    summary = run_cases(kind, kind.load(p), tmp_path / "out", Crashing(), RunConfig(progress=False))
    df = pd.read_parquet(tmp_path / "out")
    assert summary.n_failed == 2 and len(df) == 6
    assert set(df["model"]) == {"target", "series_parallel", "cc_fit"}
    assert (df["error"] == "worker died (test)").all() and (df["failure"] == "crash").all()
    assert read_manifest(tmp_path / "out")["runs"][0]["cases_done"] == 2
