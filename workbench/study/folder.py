"""Read a study result folder back: its manifest, its table and the swept axes -- the one read path.

:func:`read_folder` is what :func:`workbench.results.load` (the notebook-facing table) and
:func:`workbench.report.load.load_results` (the report's :class:`~workbench.report.load.ResultSet`)
both start from.  A result folder is what the study runner writes (:mod:`workbench.study.store`):
``_manifest.json`` and Parquet parts whose columns the zero-row schema part lists.  The table is
read with the schema part's columns (:func:`~workbench.study.store.read_columns`: an unreadable
part raises :class:`~workbench.study.store.CorruptPart` naming it; parts are never concatenated
with mixed schemas); the swept axes are the ``p.<key>`` columns of the ``[sweep]`` keys
(:func:`workbench.study.expand.sweep_keys`).  Checked by ``tests/study/test_results.py`` and
``tests/report/test_report_build.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import pyarrow as pa
import pyarrow.parquet as pq

from .expand import sweep_keys
from .session import read_manifest, study_name
from .store import MANIFEST, SCHEMA_FILE, CorruptPart, read_columns, read_table

__all__ = ["StudyFolder", "read_folder", "swept_columns"]


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
    StudyError
        The manifest is not a JSON object.
    """
    path = Path(folder)
    if not path.is_dir():
        raise FileNotFoundError(f"study folder {path} does not exist")
    if not (path / MANIFEST).exists():
        raise FileNotFoundError(f"{path}: not a study result folder (no {MANIFEST})")
    manifest = read_manifest(path)
    schema = path / SCHEMA_FILE
    if not schema.exists():  # written by hand or by an old version: the parts' own schema
        if not any(path.glob("part-*.parquet")):
            raise FileNotFoundError(f"{path}: no Parquet parts (no stored rows)")
        return StudyFolder(path, manifest, read_table(path))
    try:
        names = pq.read_schema(schema).names
    except (OSError, pa.ArrowException) as e:
        raise CorruptPart(schema, str(e).splitlines()[0] if str(e) else type(e).__name__) from None
    table = read_columns(path, names)
    return StudyFolder(path, manifest, table)


def swept_columns(spec: Mapping[str, Any], columns) -> list[str]:
    """The ``p.*`` columns of the keys the spec's ``[sweep]`` names (:func:`sweep_keys`) that ``columns`` holds."""
    have = set(columns)
    return [f"p.{k}" for k in sweep_keys(spec.get("sweep")) if f"p.{k}" in have]
