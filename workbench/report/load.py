"""A study result folder as the report reads it: a :class:`ResultSet`.

:func:`load_results` reads the folder with :func:`workbench.study.folder.read_folder` (the one
read path, shared with :func:`workbench.results.load`: ``_manifest.json`` and the Parquet parts the
study runner writes) and adds what the report needs.  Conventions (every key is optional):

- the resolved spec is ``manifest["study"]``; the study name its ``[study] name``, else the
  folder name;
- ``spec["sweep"]``: the swept axes, the keys its blocks name (``product``, ``zip``, ``cases``,
  ``random``, ...; :func:`workbench.study.expand.sweep_keys`).  Axis ``k`` is the result column
  ``p.<k>``.  Axes with a dimensionless counterpart are plotted as that group
  (:data:`DIMENSIONLESS_AXES`): ``load.bend_angle`` -> ``kappaL``,
  ``derived.gravity_parameter`` -> ``gamma``, ``robot.tendon_offset`` -> ``d_over_L``;
- ``spec["report"]`` (optional):
  ``axes``: list of column names to plot against instead of the raw sweep axes (may name
  derived columns such as ``gamma``, ``kappaL``, ``d_over_L``);
  ``derived``: ``{name: pandas eval expression}`` extra derived columns;
  ``labels``: ``{column: axis label}``;
  ``reference``: the baseline model, compared against every other model (default ``"cc"``);
  ``frame``: ``"world"`` (default) or ``"base"``, the frame of the shape figures and 3-D view.
- provenance (:mod:`.sections`): ``config_hash``, ``versions`` (mapping), ``git``
  (``{"commit", "dirty"}``), ``runs`` (list of ``{"host", "start", "end", "wall_time"}``).

Without a usable sweep entry the axes are the numeric ``p.*`` columns that vary.  Checked by
``tests/report/test_report_build.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import pandas as pd

from ..compare.table import REQUIRED_COLUMNS, add_derived_columns
from ..study.expand import sweep_keys
from ..study.folder import read_folder
from ..study.store import current_name

__all__ = ["DIMENSIONLESS_AXES", "ResultSet", "canonical_order", "category_label", "load_results", "numeric"]

#: swept parameter column -> dimensionless column plotted instead (when it exists).
DIMENSIONLESS_AXES = {
    "p.load.bend_angle": "kappaL",
    "p.derived.gravity_parameter": "gamma",
    "p.robot.tendon_offset": "d_over_L",
}


@dataclass(frozen=True)
class ResultSet:
    """The results of one study folder, ready for the report.

    Attributes
    ----------
    name : str
    path : Path
    results : DataFrame
        All rows (failed included), with derived columns added.
    manifest : dict
    axes : tuple of str
        Result columns that were swept (plot axes), in sweep order.
    baseline : str
        Baseline model: the one every other model is compared against (study key
        ``[report] reference``; the comparison table's ``reference`` column).
    models : tuple of str
        Models present in the table, in order of appearance.
    """

    name: str
    path: Path
    results: pd.DataFrame
    manifest: Mapping[str, Any]
    axes: tuple[str, ...]
    baseline: str
    models: tuple[str, ...]
    derived: Mapping[str, str] = field(default_factory=dict)
    labels: Mapping[str, str] = field(default_factory=dict)
    categories: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    """Non-numeric swept axes (e.g. ``solver.tendon_model``) -> their values, in plot order."""
    expected_cases: int | None = None
    """Cases the study defines (manifest ``n_cases``); ``None`` when the manifest does not say."""
    frame: str = "world"
    """Frame of the shape figures and the 3-D view: ``"world"`` (default) or ``"base"`` (``[report] frame``)."""

    @property
    def missing_cases(self) -> int:
        """Cases of the study with no row in the table (a partial run); 0 when unknown."""
        if self.expected_cases is None:
            return 0
        return max(0, int(self.expected_cases) - int(self.results["case_id"].nunique()))

    @property
    def spec(self) -> Mapping[str, Any]:
        return _spec_of(self.manifest)

    @property
    def failed(self) -> pd.DataFrame:
        return self.results[self.results["status"].astype(str) != "ok"]

    @property
    def ok(self) -> pd.DataFrame:
        return self.results[self.results["status"].astype(str) == "ok"]

    @property
    def is_dynamic(self) -> bool:
        return "time" in self.results.columns and self.ok["time"].map(_has_values).any()


def _spec_of(manifest: Mapping[str, Any]) -> Mapping[str, Any]:
    s = manifest.get("study")
    return s if isinstance(s, Mapping) else {}


def _has_values(v: Any) -> bool:
    if v is None:
        return False
    try:
        return len(v) > 0
    except TypeError:
        return False


def _varies(df: pd.DataFrame, ok: pd.DataFrame, col: str) -> bool:
    """A numeric column with more than one value among the ok rows."""
    if col not in df.columns:
        return False
    v = pd.to_numeric(ok[col], errors="coerce").dropna()
    return v.nunique() > 1


def _varies_categorical(df: pd.DataFrame, ok: pd.DataFrame, col: str) -> bool:
    """A non-numeric column with more than one value among the ok rows."""
    if col not in df.columns or not pd.to_numeric(ok[col], errors="coerce").isna().all():
        return False
    return ok[col].dropna().astype(str).nunique() > 1


def _plot_axes(df: pd.DataFrame, ok: pd.DataFrame, spec: Mapping[str, Any], rep: Mapping[str, Any]) -> list[str]:
    """The plotted axes: ``report.axes``, else the varying sweep keys, else varying ``p.*`` columns."""
    def varies(col: str) -> bool:
        return _varies(df, ok, col)

    def any_varies(col: str) -> bool:
        return varies(col) or _varies_categorical(df, ok, col)

    axes: list[str] = []
    for a in rep.get("axes") or []:
        # numeric or categorical (e.g. robot.base_orientation) axes, named with or without "p."
        # (a column renamed since the folder was written: by its current name, as the table)
        for col in (current_name(str(a)), current_name(f"p.{a}")):
            if col in df.columns and any_varies(col):
                axes.append(col)
                break
    if not axes:
        for k in sweep_keys(spec.get("sweep")):
            col = k if k in df.columns else f"p.{k}"
            if any_varies(col):
                axes.append(col)
    if not axes:
        axes = [c for c in df.columns if str(c).startswith("p.") and varies(c)]
        if len(axes) > 3:  # e.g. random sweeps varying many keys: keep the first three
            axes = axes[:3]
    if not rep.get("axes"):
        axes = [DIMENSIONLESS_AXES[a] if varies(DIMENSIONLESS_AXES.get(a, "")) else a for a in axes]
    return axes


def load_results(data_dir: str | Path) -> ResultSet:
    """Load ``data/<study>/`` (a study runner's result folder) for the report.

    Raises
    ------
    FileNotFoundError
        The folder, its ``_manifest.json`` or its Parquet parts are missing.
    ValueError
        The table lacks ``case_id``/``model``/``status``, the manifest is not a JSON object
        (:class:`~workbench.study.messages.StudyError`) or a part is unreadable
        (:class:`~workbench.study.store.CorruptPart`).
    """
    read = read_folder(data_dir)
    path, df, manifest = read.path, read.table, read.manifest
    missing = [c for c in REQUIRED_COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"result table in {path} lacks required column(s) {missing}")
    if "error" not in df.columns:
        df["error"] = ""
    spec = read.spec
    rep = spec.get("report") if isinstance(spec.get("report"), Mapping) else {}
    derived = dict(rep.get("derived") or {})
    df = add_derived_columns(df, derived)
    name = read.name
    models = _model_order(df, spec)
    ok = df[df["status"].astype(str) == "ok"]
    axes = _plot_axes(df, ok, spec, rep)
    df = canonical_order(df, axes, models)
    ok = df[df["status"].astype(str) == "ok"]
    frame = str(rep.get("frame") or "world")
    if frame not in ("world", "base"):
        raise ValueError(f"{path}: [report] frame must be 'world' or 'base', got {frame!r}")
    categories = {a: _category_order(ok[a].dropna().map(category_label).unique()) for a in axes
                  if _varies_categorical(df, ok, a)}
    return ResultSet(
        name=name,
        path=path,
        results=df,
        manifest=manifest,
        axes=tuple(dict.fromkeys(axes)),
        baseline=str(rep.get("reference") or "cc"),
        models=models,
        derived=derived,
        labels={current_name(str(k)): str(v) for k, v in (rep.get("labels") or {}).items()},
        categories=categories,
        expected_cases=_expected_cases(manifest),
        frame=frame,
    )


def _vector(text: str) -> tuple[float, ...] | None:
    """A readable label ``(1, 0.5)`` back to its numbers, else ``None``."""
    if not (text.startswith("(") and text.endswith(")")):
        return None
    try:
        return tuple(float(x) for x in text[1:-1].split(", "))
    except ValueError:
        return None


def category_label(value: Any) -> str:
    """The label of a categorical axis value: a swept vector (stored as JSON ``[1.0,0.5]``) as ``(1, 0.5)``.

    Whole-vector sweeps (``load.tensions = [[1.0, 0.0], [2.0, 0.0]]``) are categorical axes; their
    labels are the numbers in ``%g``, not the stored JSON.  Any other value is its text.
    """
    import json

    text = str(value)
    if text[:1] != "[":
        return text
    try:
        v = json.loads(text)
    except ValueError:
        return text
    if isinstance(v, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
        return "(" + ", ".join(f"{float(x):g}" for x in v) + ")"
    return text


def _category_order(labels) -> tuple[str, ...]:
    """Categories in plot order: vectors by their numbers (``(2, 0)`` before ``(10, 0)``), else alphabetical."""
    labels = [str(x) for x in labels]
    vectors = [_vector(x) for x in labels]
    if labels and all(v is not None for v in vectors):
        return tuple(x for _, x in sorted(zip(vectors, labels)))
    return tuple(sorted(labels))


def _model_order(df: pd.DataFrame, spec: Mapping[str, Any]) -> tuple[str, ...]:
    """The models of the table: in the study's ``models`` order, then any other (sorted)."""
    inner = spec.get("study") if isinstance(spec.get("study"), Mapping) else spec
    listed = [str(m) for m in (inner.get("models") or [])] if isinstance(inner, Mapping) else []
    present = set(df["model"].astype(str))
    return tuple([m for m in dict.fromkeys(listed) if m in present] + sorted(present - set(listed)))


def canonical_order(df: pd.DataFrame, axes, models) -> pd.DataFrame:
    """The rows sorted by the plotted axes, ``case_id`` and model order (index reset).

    Rows are stored in completion order (a Dask run differs from a serial one); every figure,
    caption and table of the report reads this order, so none depends on how the rows were stored
    (checked by ``tests/report/test_report_order.py``).
    """
    rank = {m: i for i, m in enumerate(models)}
    keys = pd.DataFrame(index=df.index)
    for i, a in enumerate(axes):
        if a in df.columns:
            v = pd.to_numeric(df[a], errors="coerce")
            keys[f"_k{i}"] = v if v.notna().any() else df[a].astype(str)
    keys["_cid"] = df["case_id"].astype(str)
    keys["_m"] = df["model"].astype(str).map(rank).fillna(len(rank))
    order = keys.sort_values(list(keys.columns), kind="mergesort", na_position="last").index
    return df.loc[order].reset_index(drop=True)


def _expected_cases(manifest: Mapping[str, Any]) -> int | None:
    n = manifest.get("n_cases")
    return int(n) if isinstance(n, (int, float)) and not isinstance(n, bool) and n >= 0 else None


def numeric(series: pd.Series) -> np.ndarray:
    """Float array of a column (non-numeric -> NaN)."""
    return pd.to_numeric(series, errors="coerce").to_numpy(dtype=float)
