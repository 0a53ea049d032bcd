"""Results as data: one call loads a study's result folder into a tidy table with arrays in their shapes.

::

    from workbench import results
    df = results.load("data/quickstart")            # one row per case and model
    df.loc[0, "positions"].shape                     # (n_stations, 3), metres, base frame
    df.attrs["units"]["tip_x"], df.attrs["frames"]["tip_x"]   # 'm', 'base'

What :func:`load` does to the stored table (read by :func:`workbench.study.folder.read_folder`, the
read the report starts from too):

- array cells become numpy arrays of their stored per-row shape (``workbench.shapes`` in the
  schema part: ``positions`` ``(n_stations, 3)``, ``tip_frame`` ``(4, 4)``, ``series.tip_position``
  ``(n_t, 3)`` beside ``time`` ``(n_t,)``); a ``-1`` axis takes what the row has;
- list parameters stored as JSON strings (``p.load.tensions = '[1.0,0.0]'``) become lists;
- ``attrs``: ``units`` and ``frames`` per column (the Parquet field metadata, else
  :mod:`workbench.study.columns` and the report's unit table; a unit not known stays out -- never
  guessed), ``manifest`` (the run's ``_manifest.json``), ``sweep_axes`` (the swept ``p.*`` columns,
  :func:`workbench.study.folder.swept_columns`).

It lives at the top of the package (beside the CLI) because it is the notebook-facing face of
two layers: the store's format (``workbench.study``) and the report's unit table.
:func:`to_xarray` (optional, needs ``xarray``) turns the table into an ``xarray.Dataset`` over the
sweep axes and the model.  Checked by ``tests/study/test_results.py`` (every column type
round-trips; every row at its place in the Dataset).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["ARRAY_DIMS", "load", "to_xarray"]


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

    from .study.columns import column_meta
    from .study.store import SCHEMA_FILE
    from .units import unit_of

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

    from .study.folder import read_folder, swept_columns
    from .study.store import SCHEMA_FILE, array_shapes

    read = read_folder(folder)
    folder, df = read.path, read.table
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
    units, frames = _meta(folder, list(df.columns))
    df.attrs.update(units=units, frames=frames, manifest=read.manifest, sweep_axes=swept_columns(read.spec, df.columns))
    return df


# ---------------------------------------------------------------------------------------
# optional: an xarray.Dataset over the sweep axes
# ---------------------------------------------------------------------------------------
#: Names of the per-row axes of the array columns (``to_xarray`` dimensions); others are ``<col>_dim<i>``.
ARRAY_DIMS: dict[str, tuple[str, ...]] = {
    "positions": ("station", "xyz"), "stations": ("station",), "tip_frame": ("row", "col"),
    "tendon_tensions": ("tendon",), "joint_angles": ("joint",), "time": ("t",),
}


def _label(v: Any) -> Any:
    """A coordinate label: lists (list parameters) as their canonical JSON, scalars unchanged."""
    return json.dumps(v, separators=(",", ":")) if isinstance(v, (list, tuple, np.ndarray)) else v


def _array_dims(col: str, shape: tuple[int, ...], sizes: dict[str, int]) -> tuple[str, ...]:
    names = ARRAY_DIMS.get(col) or (("t", "xyz" if shape[-1:] == (3,) else f"{col}_k") if col.startswith("series.")
                                    else ())
    if len(names) != len(shape):
        names = tuple(f"{col}_dim{i}" for i in range(len(shape)))
    # a shared name (station, t) must mean the same length in every variable
    return tuple(n if sizes.get(n, k) == k else f"{col}_{n}" for n, k in zip(names, shape))


def to_xarray(table, axes: list[str] | None = None):
    """An ``xarray.Dataset`` of a result table over the sweep axes and the model (needs ``xarray``).

    Parameters
    ----------
    table : pandas.DataFrame
        What :func:`load` returns (its ``attrs`` give the axes, units and frames).
    axes : list of str, optional
        The ``p.*`` columns to use as dimensions (default ``table.attrs["sweep_axes"]``).

    Returns
    -------
    xarray.Dataset
        Dimensions ``(*axes, "model")`` when the cases form the full grid of the axes' values
        (``product`` sweeps), else ``("case_id", "model")`` with the axes as coordinates along
        ``case_id`` (``zip``, ``cases``, sampled sweeps).  List-valued axes (``p.load.tensions``)
        are labelled by their JSON (``"[1.0,0.0]"``); a swept element (``p.load.tensions[0]``) is a
        float column of the table (:func:`workbench.study.folder.add_element_columns`): a float
        coordinate.  Scalar columns are variables over those
        dimensions (NaN / missing where a (case, model) has no row); array columns of one shape
        in every row get their own trailing dimensions (``positions``: ``station``, ``xyz``;
        series: ``t``, ...), others stay object variables of arrays.  ``units`` and ``frame`` of
        every variable are in its ``attrs`` (from ``table.attrs``).

    Raises
    ------
    ImportError
        xarray is not installed (``pip install xarray``).
    ValueError
        An axis is not a column, or two rows share a (case, model).
    """
    try:
        import xarray as xr
    except ImportError as e:
        raise ImportError("workbench.results.to_xarray needs xarray, which is not installed: pip install xarray") from e
    axes = list(table.attrs.get("sweep_axes", []) if axes is None else axes)
    missing = [a for a in axes if a not in table.columns]
    if missing:
        raise ValueError(f"to_xarray: no column {', '.join(missing)} in the table (columns p.*: the sweep axes)")
    if table.duplicated(["case_id", "model"]).any():
        raise ValueError("to_xarray: several rows share a (case_id, model): load one result folder")
    frame = table.copy()
    for a in axes:
        frame[a] = frame[a].map(_label)
    per_case = frame.drop_duplicates("case_id")
    grid = bool(axes) and not per_case.duplicated(axes).any() and \
        int(np.prod([per_case[a].nunique() for a in axes])) == len(per_case)
    dims = [*axes, "model"] if grid else ["case_id", "model"]
    arrays = [c for c in frame.columns if c not in dims and frame[c].map(lambda v: isinstance(v, np.ndarray)).any()]
    scalars = [c for c in frame.columns if c not in dims and c not in arrays and (grid or c not in axes)]
    ds = frame.set_index(dims)[scalars].to_xarray()
    if not grid:
        by_case = per_case.set_index("case_id").reindex(ds["case_id"].values)
        ds = ds.assign_coords({a: ("case_id", by_case[a].to_numpy()) for a in axes})
    for c in arrays:
        _add_array(ds, frame, c, dims)
    units, frames = table.attrs.get("units", {}), table.attrs.get("frames", {})
    for name in list(ds.variables):
        if name in units:
            ds[name].attrs["units"] = units[name]
        if name in frames:
            ds[name].attrs["frame"] = frames[name]
    ds.attrs["sweep_axes"] = axes
    ds.attrs["layout"] = "grid" if grid else "cases"
    return ds


def _add_array(ds, frame, col: str, dims: list[str]) -> None:
    """Array column ``col`` into ``ds``: stacked with trailing dimensions when every cell has one shape."""
    cells = [v for v in frame[col] if isinstance(v, np.ndarray)]
    shapes = {v.shape for v in cells}
    lead = [ds.sizes[d] for d in dims]
    index = [ds.indexes[d] for d in dims]
    pos = [tuple(ix.get_loc(k) for ix, k in zip(index, key)) for key in frame[dims].itertuples(index=False)]
    if len(shapes) == 1:
        shape = shapes.pop()
        out = np.full(lead + list(shape), np.nan)
        for p, v in zip(pos, frame[col]):
            if isinstance(v, np.ndarray):
                out[p] = v
        ds[col] = ([*dims, *_array_dims(col, shape, dict(ds.sizes))], out)
    else:  # rows of different lengths (a swept resolution): one array per cell
        out = np.full(lead, None, dtype=object)
        for p, v in zip(pos, frame[col]):
            out[p] = v
        ds[col] = (dims, out)
