"""Read a study result folder back: its manifest, its table and the swept axes -- the one read path.

:func:`read_folder` is what :func:`workbench.results.load` (the notebook-facing table) and
:func:`workbench.report.load.load_results` (the report's :class:`~workbench.report.load.ResultSet`)
both start from.  A result folder is what the study runner writes (:mod:`workbench.study.store`):
``_manifest.json`` and Parquet parts whose columns the zero-row schema part lists.  The table is
read with the schema part's columns (:func:`~workbench.study.store.read_columns`: an unreadable
part raises :class:`~workbench.study.store.CorruptPart` naming it).  Parts are never concatenated
with mixed schemas: :func:`check_part_schemas` first compares every part's columns with the
schema part's and raises :class:`PartSchemaMismatch` naming the files and columns when a part has
a column the schema part does not list (it would be dropped) or a column of another type (it
would be cast).  The one alignment done is documented: a part written before a column existed
lacks it, and its rows read that column as missing (``None`` / NaN).  The swept axes are the ``p.<key>`` columns of the ``[sweep]`` keys
(:func:`workbench.study.expand.sweep_keys`).  Checked by ``tests/study/test_results.py`` and
``tests/report/test_report_build.py``; the schema check by ``tests/study/test_part_schemas.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import pyarrow as pa
import pyarrow.parquet as pq

from .expand import sweep_keys
from .session import read_manifest, study_name
from .store import MANIFEST, SCHEMA_FILE, CorruptPart, current_name, read_columns, read_table

__all__ = ["StudyFolder", "PartSchemaMismatch", "add_element_columns", "check_part_schemas", "read_folder",
           "swept_columns"]


class PartSchemaMismatch(CorruptPart):
    """Parts of a result folder whose columns disagree with the folder's schema (``problems``: one line each).

    A :class:`~workbench.study.store.CorruptPart` of the folder (``path``) whose reason lists the parts and columns.
    """

    def __init__(self, folder: Path, problems: list[str]):
        self.folder, self.problems = Path(folder), list(problems)
        shown = "; ".join(self.problems[:5]) + (f" (+{len(self.problems) - 5} more)" if len(self.problems) > 5 else "")
        super().__init__(folder, f"parts with mixed schemas cannot be read as one table: {shown}")


def _same_type(a: pa.DataType, b: pa.DataType) -> bool:
    """Types equal, list types by their value type (the item field's name does not matter)."""
    if pa.types.is_list(a) and pa.types.is_list(b):
        return _same_type(a.value_type, b.value_type)
    return a.equals(b)


def check_part_schemas(folder: str | Path) -> None:
    """Raise :class:`PartSchemaMismatch` when a part's columns disagree with the folder's schema.

    The reference is the schema part (:data:`~workbench.study.store.SCHEMA_FILE`), else the first
    part.  A part may lack a column (written before the column existed: read as missing); it may
    not hold a column the reference lacks (a read with the reference's columns drops it) nor a
    column of another type (a read casts it, e.g. a string ``"7"`` to ``7.0``).  Columns are
    compared by their current names (:func:`~workbench.study.store.current_name`); an all-null
    column matches any type.  Only the Parquet footers are read.  Checked by
    ``tests/study/test_part_schemas.py``.
    """
    path = Path(folder)
    parts = sorted(p for p in path.glob("part-*.parquet") if p.name != SCHEMA_FILE)
    ref_path = path / SCHEMA_FILE if (path / SCHEMA_FILE).exists() else (parts[0] if parts else None)
    if ref_path is None:
        return
    ref = {current_name(f.name): f.type for f in _schema(ref_path)}
    problems = []
    for part in parts:
        extra, other = [], []
        for f in _schema(part):
            name = current_name(f.name)
            if name not in ref:
                extra.append(name)
            elif not (pa.types.is_null(f.type) or pa.types.is_null(ref[name]) or _same_type(f.type, ref[name])):
                other.append(f"{name} is {f.type} there, {ref[name]} in {ref_path.name}")
        if extra:
            problems.append(f"{part.name} has column(s) {', '.join(extra)} that {ref_path.name} lacks")
        if other:
            problems.append(f"{part.name}: " + ", ".join(other))
    if problems:
        raise PartSchemaMismatch(path, problems)


def _schema(part: Path) -> pa.Schema:
    try:
        return pq.read_schema(part)
    except (OSError, pa.ArrowException) as e:
        raise CorruptPart(part, str(e).splitlines()[0] if str(e) else type(e).__name__) from None


@dataclass(frozen=True)
class StudyFolder:
    """A study result folder as read: ``path``, ``manifest`` (the run's ``_manifest.json``), ``table``.

    ``table`` holds one row per (case, model), failed rows included, cells as Parquet stores them
    (array columns as flat arrays, list parameters as JSON strings).
    """

    path: Path
    manifest: Mapping[str, Any]
    table: Any  # pandas.DataFrame (imported lazily)

    @property
    def spec(self) -> Mapping[str, Any]:
        """The resolved study spec (``manifest["study"]``; ``{}`` when absent)."""
        spec = self.manifest.get("study")
        return spec if isinstance(spec, Mapping) else {}

    @property
    def name(self) -> str:
        """The study's name (``[study] name``), else the folder's name."""
        return str(study_name(self.manifest) or self.path.name)


def read_folder(folder: str | Path) -> StudyFolder:
    """The manifest and result table of a study result folder.

    Raises
    ------
    FileNotFoundError
        ``folder`` does not exist, holds no ``_manifest.json`` or no Parquet part.
    CorruptPart
        A part file is not readable Parquet.
    PartSchemaMismatch
        A part's columns disagree with the schema part's (:func:`check_part_schemas`).
    StudyError
        The manifest is not a JSON object.
    """
    path = Path(folder)
    if not path.is_dir():
        raise FileNotFoundError(f"study folder {path} does not exist")
    if not (path / MANIFEST).exists():
        raise FileNotFoundError(f"{path}: not a study result folder (no {MANIFEST})")
    manifest = read_manifest(path)
    check_part_schemas(path)
    schema = path / SCHEMA_FILE
    if not schema.exists():  # written by hand or by an old version: the parts' own schema
        if not any(path.glob("part-*.parquet")):
            raise FileNotFoundError(f"{path}: no Parquet parts (no stored rows)")
        return StudyFolder(path, manifest, add_element_columns(read_table(path), _spec(manifest)))
    try:
        names = pq.read_schema(schema).names
    except (OSError, pa.ArrowException) as e:
        raise CorruptPart(schema, str(e).splitlines()[0] if str(e) else type(e).__name__) from None
    table = read_columns(path, names)
    return StudyFolder(path, manifest, add_element_columns(table, _spec(manifest)))


def swept_columns(spec: Mapping[str, Any], columns) -> list[str]:
    """The ``p.*`` columns of the keys the spec's ``[sweep]`` names (:func:`sweep_keys`) that ``columns`` holds."""
    have = set(columns)
    return [f"p.{k}" for k in sweep_keys(spec.get("sweep")) if f"p.{k}" in have]


def _spec(manifest: Mapping[str, Any]) -> Mapping[str, Any]:
    spec = manifest.get("study")
    return spec if isinstance(spec, Mapping) else {}


def _element(cell: Any, parts: tuple) -> Any:
    """The element ``parts`` of a stored ``p.<section>.<key>`` cell (JSON text of a list / table), else ``None``."""
    import json

    from .keypath import KeyPathError, format_key_path, get_value

    if isinstance(cell, str) and cell[:1] in "[{":
        cell = json.loads(cell)
    try:
        v = get_value({"v": cell}, format_key_path(("v", *parts)))
    except KeyPathError:
        return None
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v


def add_element_columns(table, spec: Mapping[str, Any]):
    """``table`` with a column ``p.<path>`` for every swept key path below ``section.key`` (``load.tensions[0]``).

    The rows store a case's parameters by section key (``p.load.tensions`` holds the whole list,
    as JSON text); a sweep over one element gets its own column of that element's values (numbers
    as floats), so it is an axis like any other: a number in the table, the report and
    :func:`workbench.results.to_xarray`.  Existing columns are left as they are.
    """
    from .keypath import KeyPathError, parse_key_path

    for axis in sweep_keys(spec.get("sweep")):
        col = f"p.{axis}"
        try:
            parts = parse_key_path(axis)
        except KeyPathError:
            continue
        source = f"p.{parts[0]}.{parts[1]}" if len(parts) > 2 and isinstance(parts[1], str) else None
        if col in table.columns or source is None or source not in table.columns:
            continue
        table[col] = table[source].map(lambda cell, rest=parts[2:]: _element(cell, rest))
    return table
