"""The study-kind contract, checked on every kind registered in ``workbench.registry.KINDS``.

Each kind is a :class:`~workbench.study.kinds.StudyKind`; a committed study of that kind (its
regression-size copy in ``tests/regression/studies/``) loads with and without a command-line
override, counts as many cases as it expands, and one case evaluated through the kind's own
``payload`` and ``task`` writes one row per model with the result-table columns that
``docs/architecture.md`` ("Result tables") lists for every row.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from workbench import registry
from workbench.study import StudyKind, get_kind, kind_of

STUDIES = Path(__file__).parents[1] / "regression" / "studies"
#: the regression-size study each registered kind is checked on (its cheapest committed study; a path
#: elsewhere for a kind without a regression study)
EXAMPLES = {
    "sweep": "quickstart.toml",
    "series_parallel": "series_parallel_s_shape.toml",
    "grasp": "whole_arm_grasp.toml",
    "closed_loop": "closed_loop.toml",
    "calibration": Path(__file__).parents[1] / "measure" / "fixtures" / "fit_contract.toml",
}
#: the columns every row has, whatever the kind (docs/architecture.md, "Result tables"); a failed
#: row also says why (``failure``; an ok row may leave it out: the store writes it empty)
ROW_COLUMNS = ("case_id", "model", "status", "error", "wall_time")
OVERRIDE = "solver.n_elements=8"


def test_every_registered_kind_has_an_example():
    assert set(EXAMPLES) == set(registry.KINDS)


@pytest.fixture(scope="module", params=sorted(registry.KINDS))
def loaded(request):
    name = request.param
    path = STUDIES / EXAMPLES[name]
    assert kind_of(path) == name
    kind = get_kind(name)
    return kind, path, kind.load(path, max_cases=None)


def test_kind_is_a_study_kind(loaded):
    kind, _, spec = loaded
    assert isinstance(kind, StudyKind) and kind.name in registry.KINDS
    assert kind.flush_rows > 0 and isinstance(kind.separable_models, bool) and callable(kind.task)
    assert kind.batch_size(10, 2) >= 1
    assert spec.overrides == () and isinstance(spec.notes, tuple) and isinstance(spec.warnings, tuple)
    assert spec.name and isinstance(spec.config_hash, str) and isinstance(spec.resolved(), dict)


def test_load_with_and_without_overrides(loaded):
    kind, path, spec = loaded
    changed = kind.load(path, overrides=(OVERRIDE,))
    assert changed.overrides == (OVERRIDE,)
    assert changed.config_hash != spec.config_hash
    assert kind.count(changed) == kind.count(spec)


def test_count_is_the_number_of_expanded_cases(loaded):
    kind, _, spec = loaded
    cases = kind.expand(spec)
    assert kind.count(spec) == len(cases) > 0
    assert len({c.case_id for c in cases}) == len(cases)
    assert [c.case_id for c in kind.expand(spec)] == [c.case_id for c in cases]  # deterministic


def test_one_case_writes_one_row_per_model(loaded):
    kind, _, spec = loaded
    case = kind.expand(spec)[0]
    models = kind.models(spec)
    recorded = kind.recorded_params(spec, case)
    assert isinstance(recorded, dict) and recorded
    limits = kind.limits(spec)
    assert limits.seconds is None or limits.seconds > 0
    rows = list(kind.task(kind.payload(spec, case, models)))
    assert sorted(r["model"] for r in rows) == sorted(models)
    for r in rows:
        assert set(ROW_COLUMNS) <= set(r), (r["model"], set(ROW_COLUMNS) - set(r))
        assert r["case_id"] == case.case_id
        assert r["status"] in ("ok", "failed")
        assert (r["status"] == "ok") == (r["error"] in ("", None)), (r["model"], r["error"])
        assert r["status"] == "ok" or r.get("failure"), r["model"]
        assert any(k.startswith("p.") for k in r), r["model"]
