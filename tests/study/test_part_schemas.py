"""study.folder.check_part_schemas: parts whose columns disagree with the schema part are an error naming
the files and columns, not a silent drop or cast (issue 28, "What else a verdict needs": the report's read
of a result folder concatenated parts with mixed schemas)."""

from __future__ import annotations

import json

import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from workbench.study import ResultStore
from workbench.study.folder import PartSchemaMismatch, check_part_schemas, read_folder
from workbench.study.store import MANIFEST, SCHEMA_FILE


def _row(case, **extra):
    return {"case_id": case, "model": "cc", "status": "ok", "error": "", "wall_time": 0.1, **extra}


def _folder(tmp_path):
    """A folder the store wrote: a part before x.b existed, one after (the documented alignment)."""
    store = ResultStore(tmp_path, flush_rows=1)
    store.add([_row("a", tip_x=1.0)])
    store.add([_row("b", tip_x=2.0, **{"x.b": 3.0})])
    store.flush()
    (tmp_path / MANIFEST).write_text(json.dumps({"study": {"name": "t"}}))
    return tmp_path


def test_store_written_folder_reads_with_missing_cells(tmp_path):
    table = read_folder(_folder(tmp_path)).table.sort_values("case_id")
    assert table["tip_x"].tolist() == [1.0, 2.0]
    assert table["x.b"].isna().tolist() == [True, False]


def test_part_with_a_column_the_schema_lacks_is_an_error(tmp_path):
    folder = _folder(tmp_path)
    # on main this column was silently dropped by the read with the schema part's columns
    pq.write_table(pa.table({"case_id": ["c"], "model": ["cc"], "status": ["ok"], "x.c": [5.0]}),
                   folder / "part-9999999999999999999-1-000000.parquet")
    with pytest.raises(PartSchemaMismatch, match=r"part-9999999999999999999-1-000000.parquet has column\(s\) x.c"):
        read_folder(folder)


def test_part_with_another_type_is_an_error(tmp_path):
    folder = _folder(tmp_path)
    # on main the string "7" was silently cast to 7.0
    pq.write_table(pa.table({"case_id": ["c"], "model": ["cc"], "status": ["ok"], "tip_x": ["7"]}),
                   folder / "part-9999999999999999999-1-000000.parquet")
    with pytest.raises(PartSchemaMismatch, match=rf"tip_x is string there, double in {SCHEMA_FILE}"):
        check_part_schemas(folder)


def test_without_schema_part_the_first_part_is_the_reference(tmp_path):
    pq.write_table(pa.table({"case_id": ["a"], "x.b": [1.0]}), tmp_path / "part-1.parquet")
    pq.write_table(pa.table({"case_id": ["b"], "x.b": [2.0], "x.c": [3.0]}), tmp_path / "part-2.parquet")
    with pytest.raises(PartSchemaMismatch, match=r"part-2.parquet has column\(s\) x.c that part-1.parquet lacks"):
        check_part_schemas(tmp_path)
