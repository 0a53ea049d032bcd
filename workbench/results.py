"""Results as data: one call loads a study's result folder into a tidy table with arrays in their shapes.

::

    from workbench import results
    df = results.load("data/quickstart")            # one row per case and model
    df.loc[0, "positions"].shape                     # (n_stations, 3), metres, base frame
    df.attrs["units"]["tip_x"], df.attrs["frames"]["tip_x"]   # 'm', 'base'

What :func:`load` does to the stored table (``pandas.read_parquet`` of the folder):

- array cells become numpy arrays of their stored per-row shape (``workbench.shapes`` in the
  schema part: ``positions`` ``(n_stations, 3)``, ``tip_frame`` ``(4, 4)``, ``series.tip_position``
  ``(n_t, 3)`` beside ``time`` ``(n_t,)``); a ``-1`` axis takes what the row has;
- list parameters stored as JSON strings (``p.load.tensions = '[1.0,0.0]'``) become lists;
- ``attrs``: ``units`` and ``frames`` per column (the Parquet field metadata, else
  :mod:`workbench.study.columns` and the report's unit table; a unit not known stays out -- never
  guessed), ``manifest`` (the run's ``_manifest.json``), ``sweep_axes`` (the swept ``p.*`` columns).

It lives at the top of the package (beside the CLI) because it is the notebook-facing face of
two layers: the store's format (``workbench.study``) and the report's unit table.  Checked by
``tests/study/test_results.py`` (every column type round-trips).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["load"]


def _shape_cell(cell: Any, shape: list[int]) -> Any:
    if cell is None or (isinstance(cell, float) and np.isnan(cell)):
        return None
    a = np.asarray(cell, dtype=float)
    if not shape:
        return a
    try:
        return a.reshape([-1 if s < 0 else s for s in shape])
    except ValueError:  # a row whose length does not fit the declared shape: keep it flat
        return a


def _json_cell(cell: Any) -> Any:
    if isinstance(cell, str) and cell[:1] in "[{":
        try:
            return json.loads(cell)
        except json.JSONDecodeError:
            return cell
    return cell


def _meta(folder: Path, columns: list[str]) -> tuple[dict[str, str], dict[str, str]]:
    import pyarrow.parquet as pq

    from .report.units import unit_of
    from .study.columns import column_meta
    from .study.store import SCHEMA_FILE

    units: dict[str, str] = {}
    frames: dict[str, str] = {}
    schema = pq.read_schema(folder / SCHEMA_FILE) if (folder / SCHEMA_FILE).exists() else None
    for c in columns:
        md = {}
        if schema is not None and c in schema.names:
            md = {k.decode(): v.decode() for k, v in (schema.field(c).metadata or {}).items()}
        unit, frame = column_meta(c)
        unit = md.get("unit", unit)
        if unit is None and c.startswith("p."):
            unit = unit_of(c)
        frame = md.get("frame", frame)
        if unit is not None:
            units[c] = unit
        if frame is not None:
            frames[c] = frame
    return units, frames


def load(folder: str | Path, *, ok_only: bool = False):
    """The result table of ``folder`` with arrays in their shapes, lists as lists, units and frames in ``attrs``.

    Parameters
    ----------
    folder : path-like
        A study result folder (``data/<study>``).
    ok_only : bool
        Keep only rows with ``status == "ok"``.

    Returns
    -------
    pandas.DataFrame
        One row per (case, model); see the module docstring for the conversions and ``attrs``.

    Raises
    ------
    FileNotFoundError
        ``folder`` holds no result table.
    """
    import pandas as pd

    from .study.session import read_manifest
    from .study.store import MANIFEST, array_shapes, read_columns

    folder = Path(folder)
    if not (folder / MANIFEST).exists():
        raise FileNotFoundError(f"{folder}: not a study result folder (no {MANIFEST})")
    import pyarrow.parquet as pq

    from .study.store import SCHEMA_FILE

    names = pq.read_schema(folder / SCHEMA_FILE).names if (folder / SCHEMA_FILE).exists() else None
    df = read_columns(folder, names) if names else pd.read_parquet(folder)
    if ok_only:
        df = df[df["status"] == "ok"].reset_index(drop=True)
    shapes = array_shapes(folder) if (folder / SCHEMA_FILE).exists() else {}
    for c in df.columns:
        if pd.api.types.is_numeric_dtype(df[c]) or pd.api.types.is_bool_dtype(df[c]):
            continue
        if c.startswith("p."):
            if df[c].map(lambda v: isinstance(v, str) and v[:1] in "[{").any():
                df[c] = df[c].astype(object).map(_json_cell)
        elif c in shapes or (len(df) and any(isinstance(v, (list, np.ndarray)) for v in df[c].head(50))):
            df[c] = df[c].astype(object).map(lambda v, s=shapes.get(c, []): _shape_cell(v, s))
    manifest = read_manifest(folder)
    units, frames = _meta(folder, list(df.columns))
    swept = _sweep_axes(manifest, df)
    df.attrs.update(units=units, frames=frames, manifest=manifest, sweep_axes=swept)
    return df


def _sweep_axes(manifest: dict, df) -> list[str]:
    """The ``p.*`` columns the study swept (in the order of the ``[sweep]`` section)."""
    sweep = (manifest.get("study") or {}).get("sweep") or {}
    out: list[str] = []
    for block, body in sweep.items():
        entries = body if isinstance(body, list) else [body]
        for entry in entries:
            if isinstance(entry, dict):
                out += [f"p.{k}" for k in entry if k != "n" and f"p.{k}" in df.columns]
    return list(dict.fromkeys(out))
