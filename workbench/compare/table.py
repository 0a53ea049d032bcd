"""Table-level comparison: one metric row per case and compared model pair.

Input is the study result table (one row per ``(case_id, model)``, schema in
``docs/architecture.md``); array columns are flattened lists (``positions`` is ``(m, 3)``
row-major, ``tip_frame`` is a row-major 4x4).

Derived (dimensionless) columns
-------------------------------
:func:`add_derived_columns` adds, when the needed columns exist:

``kappaL``
    Total bending angle ``kappa L`` [rad] = ``p.load.bend_angle``, or
    ``p.load.curvature * robot_length``, or an existing ``p.*.kappaL`` parameter.
``gamma``
    Gravity parameter ``q L^3 / EI`` from a ``p.*gamma`` or ``p.*gravity_parameter``
    parameter (the study runner's ``derived.gravity_parameter``), or from columns whose
    names end in ``.q`` (weight per length [N/m]) and ``.EI`` [N m^2].
``d_over_L``
    Tendon offset over robot length from a column ending in ``tendon_offset`` or
    ``tendons.offset``.

A study can define more, in its resolved spec: ``spec["report"]["derived"]`` maps a new
column name to a :meth:`pandas.DataFrame.eval` expression over the result columns (dotted
names in backticks), e.g. ``{"gamma": "`p.robot.q` * robot_length**3 / `p.robot.EI`"}``.
"""

from __future__ import annotations

import itertools
from typing import Any, Iterable, Mapping, Sequence

import numpy as np
import pandas as pd

from ..study.params import section_params
from .convergence import convergence_metrics
from .metrics import (
    compression_split,
    orientation_error_deg,
    out_of_plane_distance,
    section_curvatures,
    shape_error,
    tip_position_error,
)

__all__ = [
    "REQUIRED_COLUMNS",
    "DERIVED_LABELS",
    "array_cell",
    "row_positions",
    "row_tip_frame",
    "ok_rows",
    "add_derived_columns",
    "compare_table",
    "section_ends_from_row",
    "section_ends_with_reason",
]

REQUIRED_COLUMNS = ("case_id", "model", "status")

#: Axis labels (matplotlib mathtext) of the built-in derived columns.
DERIVED_LABELS = {
    "kappaL": r"bending angle $\kappa L$ [rad]",
    "gamma": r"gravity parameter $\gamma = qL^3/EI$",
    "d_over_L": r"tendon offset $d/L$",
}


def array_cell(value: Any) -> np.ndarray | None:
    """A flattened list cell as a float array (``None`` for missing / empty / scalar NaN)."""
    if value is None:
        return None
    if isinstance(value, float) and np.isnan(value):
        return None
    arr = np.asarray(value, dtype=float).reshape(-1)
    return arr if arr.size else None


def row_positions(row: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray] | None:
    """``(stations (m,), positions (m, 3))`` of a result row, or ``None`` if absent.

    Raises ``ValueError`` if the sizes disagree (positions must hold 3 m values).
    """
    pos = array_cell(row.get("positions"))
    if pos is None:
        return None
    if pos.size % 3:
        raise ValueError(f"positions of case {row.get('case_id')!r} / {row.get('model')!r} must hold 3 m values, got {pos.size}")
    pos = pos.reshape(-1, 3)
    st = array_cell(row.get("stations"))
    if st is None:
        L = float(row.get("robot_length", 1.0))
        st = np.linspace(0.0, L, pos.shape[0])
    if st.size != pos.shape[0]:
        raise ValueError(
            f"case {row.get('case_id')!r} / {row.get('model')!r}: stations has {st.size} entries "
            f"but positions has shape {pos.shape}"
        )
    return st, pos


def row_tip_frame(row: Mapping[str, Any]) -> np.ndarray | None:
    """``(4, 4)`` tip transform of a result row, or ``None``."""
    T = array_cell(row.get("tip_frame"))
    if T is None:
        return None
    if T.size != 16:
        raise ValueError(f"tip_frame must hold 16 values (row-major 4x4), got {T.size}")
    return T.reshape(4, 4)


def _row_tip(row: Mapping[str, Any]) -> np.ndarray:
    if all(k in row and pd.notna(row[k]) for k in ("tip_x", "tip_y", "tip_z")):
        return np.array([row["tip_x"], row["tip_y"], row["tip_z"]], dtype=float)
    T = row_tip_frame(row)
    if T is not None:
        return T[:3, 3]
    bp = row_positions(row)
    if bp is not None:
        return bp[1][-1]
    return np.full(3, np.nan)


def _check(df: pd.DataFrame) -> None:
    if not isinstance(df, pd.DataFrame):
        raise TypeError(f"expected a pandas DataFrame, got {type(df).__name__}")
    missing = [c for c in REQUIRED_COLUMNS if c not in df.columns]
    if missing:
        raise ValueError(f"result table lacks required column(s) {missing}; has {list(df.columns)}")


def ok_rows(df: pd.DataFrame) -> pd.DataFrame:
    """Rows with ``status == "ok"``."""
    _check(df)
    return df[df["status"].astype(str) == "ok"]


def _find_column(columns: Iterable[str], suffixes: Sequence[str]) -> str | None:
    cols = [c for c in columns if c.startswith(("p.", "x."))]
    for suf in suffixes:
        for c in cols:
            if c == suf or c.endswith("." + suf.lstrip(".")) or c.endswith(suf):
                return c
    return None


def add_derived_columns(df: pd.DataFrame, derived: Mapping[str, str] | None = None) -> pd.DataFrame:
    """Return a copy of ``df`` with the dimensionless columns described in the module doc.

    Parameters
    ----------
    df : DataFrame
        Result or comparison table.
    derived : mapping of str to str, optional
        Extra ``name -> pandas eval expression`` (``spec["report"]["derived"]``).  An
        expression that cannot be evaluated raises ``ValueError`` naming it.
    """
    out = df.copy()
    cols = list(out.columns)
    L = out["robot_length"].astype(float) if "robot_length" in cols else None
    if "kappaL" not in cols:
        c = _find_column(cols, ["kappaL"])
        if c is not None:
            out["kappaL"] = pd.to_numeric(out[c], errors="coerce")
        elif "p.load.bend_angle" in cols:
            out["kappaL"] = pd.to_numeric(out["p.load.bend_angle"], errors="coerce")
        elif "p.load.curvature" in cols and L is not None:
            out["kappaL"] = pd.to_numeric(out["p.load.curvature"], errors="coerce") * L
    if "gamma" not in cols:
        c = _find_column(cols, ["gamma", "gravity_parameter"])
        if c is not None:
            out["gamma"] = pd.to_numeric(out[c], errors="coerce")
        else:
            cq, cei = _find_column(cols, [".q"]), _find_column(cols, [".EI"])
            if cq is not None and cei is not None and L is not None:
                out["gamma"] = pd.to_numeric(out[cq], errors="coerce") * L**3 / pd.to_numeric(out[cei], errors="coerce")
    if "d_over_L" not in cols and L is not None:
        c = _find_column(cols, ["tendon_offset", "tendons.offset"])
        if c is not None:
            out["d_over_L"] = pd.to_numeric(out[c], errors="coerce") / L
    for name, expr in (derived or {}).items():
        try:
            out[name] = out.eval(str(expr))
        except Exception as exc:  # pandas raises many types here
            raise ValueError(f"derived column {name!r}: cannot evaluate {expr!r}: {exc}") from exc
    return out


def section_ends_from_row(row: Mapping[str, Any]) -> np.ndarray | None:
    """Reference section ends [m] of a result row, or ``None`` when unknown.

    The ends of :func:`section_ends_with_reason` without the reason.  Checked by
    ``tests/compare/test_section_ends.py``.
    """
    return section_ends_with_reason(row)[0]


def section_ends_with_reason(row: Mapping[str, Any]) -> tuple[np.ndarray | None, str]:
    """Reference section ends [m] of a result row and where they come from (or why they are unknown).

    From a ``section_ends`` list column if present; else by rebuilding a description-form robot
    (``p.robot.sections``, :func:`workbench.robot.spec.robot_from_params`) or the robot preset named
    in ``p.robot.preset`` with the row's ``p.robot.*`` parameters (un-flattened by
    :func:`workbench.study.params.section_params`; parameters the preset does not take are
    ignored).  Only the errors a rebuild is documented to raise (``KeyError``: unknown preset;
    ``TypeError``: a parameter the preset does not take; ``ValueError``: an invalid value, e.g.
    :class:`~workbench.robot.description.RobotDescriptionError`) give ``None`` with the error as
    the reason; anything else is a bug and propagates.  Checked by
    ``tests/compare/test_section_ends.py``.

    Returns
    -------
    (ndarray or None, str)
        The ends and ``"section_ends column"`` / ``"preset <name>"``, or ``None`` and the reason.
    """
    ends = array_cell(row.get("section_ends"))
    if ends is not None:
        return ends, "section_ends column"
    from ..robot.presets import build_preset, preset_parameters
    from ..robot.spec import is_description, robot_from_params

    name = row.get("p.robot.preset")
    params = section_params(row, "robot")
    if "sections" in params and is_description(params):  # description form (on a data preset or not)
        try:
            return np.asarray(robot_from_params(params).section_ends, dtype=float), "robot description"
        except ValueError as exc:
            return None, f"robot description not rebuilt ({exc})"
    if not isinstance(name, str) or not name:
        return None, "no section_ends column and no p.robot.preset"
    try:
        known = preset_parameters(name)
        params = {k: v for k, v in params.items() if k in known}
        return np.asarray(build_preset(name, **params).section_ends, dtype=float), f"preset {name}"
    except (KeyError, TypeError, ValueError) as exc:
        msg = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)
        return None, f"preset {name!r} not rebuilt ({type(exc).__name__}: {msg})"


def _pair_metrics(ref: Mapping[str, Any], row: Mapping[str, Any], section_ends, cc_baseline: bool) -> dict[str, float]:
    L = float(ref.get("robot_length", np.nan))
    if not np.isfinite(L) or L <= 0:
        L = float(row.get("robot_length", np.nan))
    m: dict[str, float] = {}
    e = tip_position_error(_row_tip(ref), _row_tip(row))
    m["tip_error"] = e
    m["tip_error_pct"] = 100.0 * e / L
    Ta, Tb = row_tip_frame(ref), row_tip_frame(row)
    m["orientation_error_deg"] = orientation_error_deg(Ta, Tb) if Ta is not None and Tb is not None else np.nan
    ba, bb = row_positions(ref), row_positions(row)
    if ba is not None and bb is not None:
        mx, rms = shape_error(ba[1], bb[1], ba[0], bb[0])
        m["shape_error_max"], m["shape_error_rms"] = mx, rms
        m["shape_error_max_pct"], m["shape_error_rms_pct"] = 100 * mx / L, 100 * rms / L
        ends, source = _curvature_sections(ref, section_ends, float(ba[0][-1]))
        m["kappa_sections"] = source
        ka = section_curvatures(ba[0], ba[1], ends)
        kb = section_curvatures(bb[0], bb[1], ends)
        for j, (x, y) in enumerate(zip(ka, kb)):
            m[f"kappa_ref_{j}"] = x
            m[f"kappa_{j}"] = y
            m[f"kappa_error_{j}"] = y - x
        m["out_of_plane"] = out_of_plane_distance(bb[1])
        m["out_of_plane_pct"] = 100 * m["out_of_plane"] / L
    dl_ref = float(ref.get("length_change", np.nan))
    dl = float(row.get("length_change", np.nan))
    m["length_change_ref"] = dl_ref
    m["length_change"] = dl
    m["length_change_pct"] = 100.0 * dl / L
    m["tip_twist_deg"] = float(np.degrees(float(row.get("tip_twist", np.nan))))
    m["compression_virtual"] = np.nan
    m["compression_backbone"] = np.nan
    m["compression_tendon_stretch"] = np.nan
    m["compression_shape"] = np.nan
    length_mode = str(ref.get("p.load.mode", "length")) == "length"
    if cc_baseline and length_mode and np.isfinite(dl_ref) and np.isfinite(dl):
        stretch = _mean_tendon_stretch(row)
        if np.isfinite(stretch):
            sp = compression_split(dl_ref, dl, stretch)
            m["compression_virtual"] = sp.virtual
            m["compression_backbone"] = sp.backbone
            m["compression_tendon_stretch"] = sp.tendon_stretch
            m["compression_shape"] = sp.shape
    m["wall_time_ref"] = float(ref.get("wall_time", np.nan))
    m["wall_time"] = float(row.get("wall_time", np.nan))
    # dynamic analyses: tip error over time when both rows carry a tip-position series
    m["tip_error_max_over_time"] = _max_tip_error_over_time(ref, row)
    return m


def _curvature_sections(ref: Mapping[str, Any], section_ends: Sequence[float] | None,
                        length: float) -> tuple[np.ndarray, str]:
    """Section ends for the per-section curvature fit and the ``kappa_sections`` note saying where they come from.

    The given ``section_ends``, else those of :func:`section_ends_with_reason`; when neither is
    known, or they do not end at the backbone's arc ``length``, one section spans the robot and the
    note says why (the ``kappa_*`` values are then whole-robot curvatures).  Checked by
    ``tests/compare/test_section_ends.py``.
    """
    if section_ends is not None:
        ends, source = np.asarray(section_ends, dtype=float), "given section_ends"
    else:
        ends, source = section_ends_with_reason(ref)
    if ends is None:
        return np.array([length]), f"whole robot: {source}"
    if abs(ends[-1] - length) > 1e-6 * max(length, 1e-12):
        return (np.array([length]),
                f"whole robot: {source} ends at {ends[-1]:.6g} m, the backbone at {length:.6g} m")
    return ends, source


def _mean_tendon_stretch(row: Mapping[str, Any]) -> float:
    """Mean elastic tendon stretch [m]: ``x.tendon_stretch_mean``, else ``mean_i T_i L / EA_t``
    with ``EA_t`` from a ``p.*axial_stiffness`` / ``p.*tendon_stiffness`` column (loaded tendon
    length approximated by L: first order in the strain)."""
    v = row.get("x.tendon_stretch_mean")
    if v is not None and pd.notna(v):
        return float(v)
    T = array_cell(row.get("tendon_tensions"))
    if T is None:
        return np.nan
    ea_col = next((k for k in row.keys() if str(k).startswith(("p.", "x."))
                   and str(k).endswith(("axial_stiffness", "tendon_stiffness"))), None)
    if ea_col is None or pd.isna(row.get(ea_col)):
        return np.nan
    L = float(row.get("robot_length", np.nan))
    return float(np.mean(T * L / float(row[ea_col])))


def _series(row: Mapping[str, Any], name: str) -> tuple[np.ndarray, np.ndarray] | None:
    t = array_cell(row.get("time"))
    v = array_cell(row.get(f"series.{name}"))
    if t is None or v is None or v.size % t.size:
        return None
    return t, v.reshape(t.size, -1)


def _max_tip_error_over_time(ref: Mapping[str, Any], row: Mapping[str, Any]) -> float:
    a, b = _series(ref, "tip_position"), _series(row, "tip_position")
    if a is None or b is None or a[1].shape[1] != 3 or b[1].shape[1] != 3:
        return np.nan
    ta, pa = a
    tb, pb = b
    lo, hi = max(ta[0], tb[0]), min(ta[-1], tb[-1])
    sel = (ta >= lo) & (ta <= hi)
    if not np.any(sel):
        return np.nan
    pb_on_a = np.stack([np.interp(ta[sel], tb, pb[:, k]) for k in range(3)], axis=-1)
    return float(np.max(tip_position_error(pa[sel], pb_on_a)))


def compare_table(
    df: pd.DataFrame,
    baseline: str = "cc",
    *,
    pairs: str = "all",
    section_ends: Sequence[float] | None = None,
    derived: Mapping[str, str] | None = None,
) -> pd.DataFrame:
    """Metric table: one row per case and compared model pair.

    Parameters
    ----------
    df : DataFrame
        Study result table (``case_id``, ``model``, ``status`` required; failed rows are
        ignored).
    baseline : str
        Baseline model name (default ``"cc"``): every other model is compared with it.  The
        table's ``reference`` column names the compared-against side of each pair.
    pairs : {"all", "baseline"}
        ``"all"`` also compares each pair of non-baseline (physics) models, first in order
        of appearance as the compared-against side of the pair.
    section_ends : sequence of float, optional
        Reference arc lengths of the section ends [m] for the per-section curvature fit;
        default: :func:`section_ends_from_row` of the baseline row, else one section
        spanning the robot.
    derived : mapping, optional
        Extra derived columns (see :func:`add_derived_columns`).

    Returns
    -------
    DataFrame
        Columns ``case_id, reference, model``, every ``p.*`` parameter column,
        ``robot_length``, derived dimensionless columns, and the metrics:
        ``tip_error`` [m], ``tip_error_pct`` [% L], ``orientation_error_deg``,
        ``shape_error_max``/``_rms`` [m] and ``_pct`` [% L], ``kappa_ref_j``, ``kappa_j``,
        ``kappa_error_j`` [1/m] per section ``j``, ``kappa_sections`` (where the section ends
        come from, or ``"whole robot: <reason>"`` when one section spans the robot), ``out_of_plane`` [m] / ``_pct``,
        ``length_change_ref``/``length_change`` [m], ``length_change_pct`` [% L],
        ``tip_twist_deg``, ``compression_virtual``/``_backbone``/``_tendon_stretch``/``_shape``
        [m] (see :func:`~workbench.compare.metrics.compression_split`; only for pairs against
        a CC baseline with a known tendon stretch and, if ``p.load.mode`` exists, length-mode
        actuation; else NaN), ``wall_time_ref``/``wall_time`` [s],
        ``tip_error_max_over_time`` [m] (dynamic cases with ``series.tip_position``),
        ``judged_error``, ``disc_error`` [m], ``disc_error_pct``, ``disc_fraction``,
        ``not_converged`` (:mod:`workbench.compare.convergence`).
        Empty (with the identifying columns) when nothing can be compared.
    """
    if pairs not in ("all", "baseline"):
        raise ValueError(f"pairs must be 'all' or 'baseline', got {pairs!r}")
    ok = ok_rows(df)
    models = list(dict.fromkeys(ok["model"].astype(str)))
    others = [m for m in models if m != baseline]
    pair_list = [(baseline, m) for m in others] if baseline in models else []
    if pairs == "all":
        pair_list += list(itertools.combinations(others, 2))
    pcols = [c for c in df.columns if str(c).startswith("p.")]
    rows = []
    for case_id, grp in ok.groupby("case_id", sort=False):
        by_model = {str(r["model"]): r for _, r in grp.iterrows()}
        for a, b in pair_list:
            if a not in by_model or b not in by_model:
                continue
            ra, rb = by_model[a].to_dict(), by_model[b].to_dict()
            rec: dict[str, Any] = {"case_id": case_id, "reference": a, "model": b}
            for c in pcols:
                rec[c] = ra.get(c)
            rec["robot_length"] = ra.get("robot_length", np.nan)
            rec.update(_pair_metrics(ra, rb, section_ends, cc_baseline=(a == baseline == "cc")))
            rec.update(convergence_metrics(ra, rb, rec))  # error bars and the not-converged mark
            rows.append(rec)
    if not rows:
        return pd.DataFrame(columns=["case_id", "reference", "model", *pcols, "robot_length"])
    out = pd.DataFrame(rows)
    return add_derived_columns(out, derived)
