"""Read a study folder (Parquet part files + ``manifest.json``) into a :class:`Study`.

The manifest is ``_manifest.json`` (the study runner's name, ignored by Parquet readers) or
``manifest.json``.  Conventions (every key is optional here):

- the resolved spec is ``manifest["study"]`` (study runner) or ``manifest["spec"]``;
- study name: ``spec["study"]["name"]``, ``spec["name"]`` or ``manifest["name"]``; default:
  the folder name;
- ``spec["sweep"]``: the swept axes: blocks ``{"product": {key: values}, "zip": {...},
  "cases": [{key: value}, ...], "random": {"n": 4, key: {...}}, ...}``, or directly a mapping
  ``{key: values}``, or a list of mappings with a ``"key"``/``"name"``/``"parameter"`` entry.
  Axis ``k`` is the result column ``p.<k>``.  Axes with a dimensionless counterpart are
  plotted as that group (:data:`DIMENSIONLESS_AXES`): ``load.bend_angle`` -> ``kappaL``,
  ``derived.gravity_parameter`` -> ``gamma``, ``robot.tendon_offset`` -> ``d_over_L``;
- ``spec["report"]`` (optional):
  ``axes``: list of column names to plot against instead of the raw sweep axes (may name
  derived columns such as ``gamma``, ``kappaL``, ``d_over_L``);
  ``derived``: ``{name: pandas eval expression}`` extra derived columns;
  ``labels``: ``{column: axis label}``;
  ``reference``: reference model (default ``"cc"``).
- provenance: ``config_hash``, ``versions`` (mapping), ``git`` (``{"commit", "dirty"}``) or
  ``git_commit``, ``runs`` (list of ``{"host", "start", "end", "wall_time"}``) or ``host``,
  ``start_time``, ``end_time`` (ISO 8601).

Without a usable sweep entry the axes are the numeric ``p.*`` columns that vary.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import pandas as pd

from ..compare.table import REQUIRED_COLUMNS, add_derived_columns

__all__ = ["DIMENSIONLESS_AXES", "MANIFEST_NAMES", "Study", "load_study", "sweep_keys"]

MANIFEST_NAMES = ("_manifest.json", "manifest.json")

#: swept parameter column -> dimensionless column plotted instead (when it exists).
DIMENSIONLESS_AXES = {
    "p.load.bend_angle": "kappaL",
    "p.derived.gravity_parameter": "gamma",
    "p.robot.tendon_offset": "d_over_L",
}


@dataclass(frozen=True)
class Study:
    """A loaded study.

    Attributes
    ----------
    name : str
    path : Path
    results : DataFrame
        All rows (failed included), with derived columns added.
    manifest : dict
    axes : tuple of str
        Result columns that were swept (plot axes), in sweep order.
    reference : str
        Reference model name.
    models : tuple of str
        Models present in the table, in order of appearance.
    """

    name: str
    path: Path
    results: pd.DataFrame
    manifest: Mapping[str, Any]
    axes: tuple[str, ...]
    reference: str
    models: tuple[str, ...]
    derived: Mapping[str, str] = field(default_factory=dict)
    labels: Mapping[str, str] = field(default_factory=dict)
    categories: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    """Non-numeric swept axes (e.g. ``solver.tendon_model``) -> their values, in plot order."""

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
    for key in ("study", "spec"):
        s = manifest.get(key)
        if isinstance(s, Mapping):
            return s
    return {}


def _has_values(v: Any) -> bool:
    if v is None:
        return False
    try:
        return len(v) > 0
    except TypeError:
        return False


def sweep_keys(spec: Mapping[str, Any]) -> list[str]:
    """Swept parameter keys from a resolved spec (tolerant of the forms in the module doc)."""
    sw = spec.get("sweep") if isinstance(spec, Mapping) else None
    keys: list[str] = []
    if isinstance(sw, Mapping):
        for k, v in sw.items():
            if k == "cases" and isinstance(v, (list, tuple)):
                for case in v:
                    if isinstance(case, Mapping):
                        keys += [str(c) for c in case if str(c) not in keys]
                continue
            if k == "n" and not isinstance(v, (list, tuple, Mapping)):
                continue
            if k in ("mode", "kind", "type", "product", "zip") and not isinstance(v, (list, tuple, Mapping)):
                continue
            if isinstance(v, Mapping) and not any(x in v for x in ("values", "start", "stop", "num", "min", "max", "low", "high")):
                # nested axes, e.g. {"axes": {...}} or {"grid": {...}}
                keys += sweep_keys({"sweep": v})
            else:
                keys.append(str(k))
    elif isinstance(sw, (list, tuple)):
        for item in sw:
            if isinstance(item, Mapping):
                for name in ("key", "name", "parameter", "param"):
                    if name in item:
                        keys.append(str(item[name]))
                        break
            elif isinstance(item, str):
                keys.append(item)
    return keys


def _read_parquet_folder(path: Path) -> pd.DataFrame:
    files = sorted(p for p in path.rglob("*.parquet") if not p.name.startswith((".", "_")))
    if not files:
        raise FileNotFoundError(f"no Parquet part files (*.parquet) under {path}")
    frames = [pd.read_parquet(f) for f in files]
    frames = [f for f in frames if len(f.columns)]
    return pd.concat(frames, ignore_index=True, sort=False) if frames else pd.DataFrame()


def load_study(data_dir: str | Path) -> Study:
    """Load ``data/<study>/``: Parquet part files and (optional) ``manifest.json``.

    Raises
    ------
    FileNotFoundError
        The folder or its Parquet files are missing.
    ValueError
        The table lacks ``case_id``/``model``/``status`` or the manifest is not JSON.
    """
    path = Path(data_dir)
    if not path.is_dir():
        raise FileNotFoundError(f"study folder {path} does not exist")
    df = _read_parquet_folder(path)
    missing = [c for c in REQUIRED_COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"result table in {path} lacks required column(s) {missing}")
    if "error" not in df.columns:
        df["error"] = ""
    mpath = next((path / n for n in MANIFEST_NAMES if (path / n).exists()), None)
    manifest: dict[str, Any] = {}
    if mpath is not None:
        try:
            manifest = json.loads(mpath.read_text())
        except json.JSONDecodeError as exc:
            raise ValueError(f"{mpath} is not valid JSON: {exc}") from exc
        if not isinstance(manifest, dict):
            raise ValueError(f"{mpath} must hold a JSON object, got {type(manifest).__name__}")
    spec = _spec_of(manifest)
    rep = spec.get("report") if isinstance(spec.get("report"), Mapping) else {}
    derived = dict(rep.get("derived") or {})
    df = add_derived_columns(df, derived)
    inner = spec.get("study") if isinstance(spec.get("study"), Mapping) else {}
    name = str(inner.get("name") or spec.get("name") or manifest.get("name") or path.name)
    ok = df[df["status"].astype(str) == "ok"]

    def varies(col: str) -> bool:
        if col not in df.columns:
            return False
        v = pd.to_numeric(ok[col], errors="coerce").dropna()
        return v.nunique() > 1

    def varies_categorical(col: str) -> bool:
        if col not in df.columns or not pd.to_numeric(ok[col], errors="coerce").isna().all():
            return False
        return ok[col].dropna().astype(str).nunique() > 1

    axes: list[str] = []
    for a in rep.get("axes") or []:
        # numeric or categorical (e.g. robot.base_orientation) axes, named with or without "p."
        for col in (str(a), f"p.{a}"):
            if col in df.columns and (varies(col) or varies_categorical(col)):
                axes.append(col)
                break
    if not axes:
        for k in sweep_keys(spec):
            col = k if k in df.columns else f"p.{k}"
            if varies(col) or varies_categorical(col):
                axes.append(col)
    if not axes:
        axes = [c for c in df.columns if str(c).startswith("p.") and varies(c)]
        if len(axes) > 3:  # e.g. random sweeps varying many keys: keep the first three
            axes = axes[:3]
    if not rep.get("axes"):
        axes = [DIMENSIONLESS_AXES[a] if varies(DIMENSIONLESS_AXES.get(a, "")) else a for a in axes]
    categories = {a: tuple(sorted(ok[a].dropna().astype(str).unique())) for a in axes if varies_categorical(a)}
    models = tuple(dict.fromkeys(df["model"].astype(str)))
    reference = str(rep.get("reference") or "cc")
    labels = {str(k): str(v) for k, v in (rep.get("labels") or {}).items()}
    return Study(
        name=name,
        path=path,
        results=df,
        manifest=manifest,
        axes=tuple(dict.fromkeys(axes)),
        reference=reference,
        models=models,
        derived=derived,
        labels=labels,
        categories=categories,
    )


def numeric(series: pd.Series) -> np.ndarray:
    """Float array of a column (non-numeric -> NaN)."""
    return pd.to_numeric(series, errors="coerce").to_numpy(dtype=float)
