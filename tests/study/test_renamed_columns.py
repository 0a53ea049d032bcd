"""A folder written before a column rename is read under the current names (store.RENAMED_COLUMNS)."""

from __future__ import annotations

import json

import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from workbench.study.store import MANIFEST, SCHEMA_FILE, current_name, read_columns, read_table


@pytest.fixture
def old_folder(tmp_path):
    """A series-parallel folder as written before ``p.motion.*`` became ``p.pose.*``."""
    t = pa.table({"case_id": ["a", "a", "b"], "model": ["target", "series_parallel", "target"],
                  "status": ["ok", "ok", "ok"], "p.motion.kind": ["module", "module", "stack"],
                  "p.motion.shape": ["x", "x", "bending"], "p.motion.value": [0.1, 0.1, 1.0],
                  "tip_z": [0.5, 0.5, 0.9]})
    pq.write_table(t.schema.empty_table(), tmp_path / SCHEMA_FILE)
    pq.write_table(t, tmp_path / "part-1-1-000000.parquet")
    spec = {"study": {"kind": "series_parallel", "name": "old", "models": ["target", "series_parallel"]},
            "report": {"reference": "target", "axes": ["p.motion.value"], "labels": {"p.motion.value": "amplitude"}}}
    (tmp_path / MANIFEST).write_text(json.dumps({"study": spec, "n_cases": 2}))
    return tmp_path


def test_current_name():
    assert current_name("p.motion.value") == "p.pose.value"
    assert current_name("p.pose.value") == "p.pose.value" and current_name("tip_x") == "tip_x"


def test_old_columns_are_read_under_their_current_names(old_folder):
    df = read_table(old_folder)
    assert {"p.pose.kind", "p.pose.shape", "p.pose.value"} <= set(df.columns)
    assert not [c for c in df.columns if c.startswith("p.motion.")]
    assert list(df["p.pose.value"]) == [0.1, 0.1, 1.0]
    # asked for by either name, a column comes back under its current one
    got = read_columns(old_folder, ["case_id", "p.pose.shape", "p.motion.value", "p.pose.pivot"])
    assert list(got.columns) == ["case_id", "p.pose.shape", "p.pose.value", "p.pose.pivot"]
    assert list(got["p.pose.shape"]) == ["x", "x", "bending"] and got["p.pose.pivot"].isna().all()


def test_a_folder_resumed_after_the_rename_merges_old_and_new_rows(old_folder):
    new = pa.table({"case_id": ["c"], "model": ["target"], "status": ["ok"], "p.pose.kind": ["module"],
                    "p.pose.shape": ["y"], "p.pose.value": [0.2], "tip_z": [0.5]})
    old = pq.read_schema(old_folder / SCHEMA_FILE)
    union = pa.unify_schemas([old, new.schema])
    pq.write_table(union.empty_table(), old_folder / SCHEMA_FILE)
    pq.write_table(new, old_folder / "part-2-1-000000.parquet")
    df = read_table(old_folder).sort_values("case_id")
    assert list(df["p.pose.shape"]) == ["x", "x", "bending", "y"]
    assert not [c for c in df.columns if c.startswith("p.motion.")]


def test_the_report_and_results_read_an_old_folder(old_folder):
    from workbench import results
    from workbench.report.load import load_results

    rs = load_results(old_folder)
    assert rs.axes == ("p.pose.value",) and rs.labels == {"p.pose.value": "amplitude"}
    df = results.load(old_folder)
    assert "p.pose.value" in df.columns and "p.motion.value" not in df.columns
