"""The numbers a report headlines: per CC comparison the largest error, with its error bar.

Pure pandas on the comparison table (:func:`workbench.compare.compare_table`, with the columns of
:mod:`workbench.compare.convergence`).  Cases that vary a sensitivity assumption
(``[report] sensitivity``, values other than the baseline of the study's base section) are left
out of the headlines (:func:`baseline_cases`) and shown in the report's Sensitivity section.
The headline of a comparison is the case with the largest judged error (the tip error; for
dynamics its peak over time), reported with its discretisation error bar, its final value
(dynamics) and whether it is converged.  Checked by ``tests/report/test_findings.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd

from ..compare.convergence import is_cc_pair
from .load import ResultSet, numeric

__all__ = ["Headline", "sensitivity_keys", "baseline_value", "baseline_cases", "headlines", "summary_columns"]


@dataclass(frozen=True)
class Headline:
    """The headline of one comparison.

    Attributes
    ----------
    baseline, model : str
        The pair: the compared-against model (the table's ``reference`` column) and the model.
    error, error_pct : float
        Largest judged error [m] and [% L] over the baseline cases.
    disc, disc_pct : float
        Its discretisation error bar [m], [% L] (NaN: no estimate).
    disc_exempt : bool
        A side of the pair is exempt from the estimate (:mod:`workbench.compare.convergence`).
    final_pct : float
        Dynamics: the tip error at the end of that case [% L] (NaN for statics).
    case_id : str
        The case it comes from.
    converged : bool
        The headline's own mark (:mod:`workbench.compare.convergence`); True for non-CC pairs.
    n_cases, n_not_converged : int
        Baseline cases compared, and how many of them are not converged.
    dynamic : bool
    cc_pair : bool
    """

    baseline: str
    model: str
    error: float
    error_pct: float
    disc: float
    disc_pct: float
    final_pct: float
    case_id: str
    converged: bool
    n_cases: int
    n_not_converged: int
    dynamic: bool
    cc_pair: bool
    disc_exempt: bool = False

    @property
    def exempt_only(self) -> bool:
        """No bar at all because of an exempt side (the bar is 0): reports say "exempt", not "± 0"."""
        return self.disc_exempt and self.disc_pct == 0.0


def sensitivity_keys(study: ResultSet) -> list[str]:
    """``[report] sensitivity`` as result columns (``p.<section>.<key>``) present in the table."""
    rep = study.spec.get("report") if isinstance(study.spec.get("report"), Mapping) else {}
    keys = [f"p.{k}" for k in (rep.get("sensitivity") or [])]
    return [k for k in keys if k in study.results.columns]


def baseline_value(study: ResultSet, column: str) -> Any:
    """The baseline of a sensitivity column: its value in the resolved spec's base section.

    Sweep studies record ``{section: {key: value}}``; series-parallel studies their geometry
    under ``"geometry"``.  The column names a key path (``p.load.tensions[0]``: the element of the
    base value, :mod:`workbench.study.keypath`).  ``None`` when the spec does not hold it.
    """
    from ..study.keypath import KeyPathError, get_value

    path = column[2:]
    section = path.split(".", 1)[0]
    for root in (study.spec, study.spec.get("base")):
        if isinstance(root, Mapping) and isinstance(root.get(section), Mapping):
            try:
                return get_value(root, path)
            except KeyPathError:
                continue
    return None


def _same(values: pd.Series, target: Any) -> np.ndarray:
    if isinstance(target, (int, float)) and not isinstance(target, bool):
        return np.isclose(numeric(values), float(target), rtol=1e-12, atol=0.0)
    return (values.astype(str) == str(target)).to_numpy()


def baseline_cases(study: ResultSet, table: pd.DataFrame, keys: Sequence[str] | None = None) -> pd.DataFrame:
    """Rows of ``table`` whose sensitivity columns (or just ``keys``) hold their baseline value.

    All rows when the study has no sensitivity keys.
    """
    keep = np.ones(len(table), dtype=bool)
    for col in (sensitivity_keys(study) if keys is None else keys):
        base = baseline_value(study, col)
        if base is not None and col in table:
            keep &= _same(table[col], base) | table[col].isna().to_numpy()
    return table[keep]


def _final_pct(study: ResultSet, ref: str, model: str, case_id: str) -> float:
    from ..compare.table import array_cell

    ok = study.ok
    rows = {str(r["model"]): r for _, r in ok[ok["case_id"] == case_id].iterrows()}
    if ref not in rows or model not in rows:
        return float("nan")
    a, b = rows[ref], rows[model]
    ta, tb = array_cell(a.get("time")), array_cell(b.get("time"))
    pa, pb = array_cell(a.get("series.tip_position")), array_cell(b.get("series.tip_position"))
    if ta is None or tb is None or pa is None or pb is None:
        return float("nan")
    pa, pb = pa.reshape(ta.size, 3), pb.reshape(tb.size, 3)
    t_end = min(ta[-1], tb[-1])
    pa_end = np.array([np.interp(t_end, ta, pa[:, k]) for k in range(3)])
    pb_end = np.array([np.interp(t_end, tb, pb[:, k]) for k in range(3)])
    return 100.0 * float(np.linalg.norm(pa_end - pb_end)) / float(a["robot_length"])


def headlines(study: ResultSet, cmp: pd.DataFrame, pairs: Sequence[tuple[str, str]] | None = None) -> list[Headline]:
    """One :class:`Headline` per compared pair (CC pairs first), over the baseline cases."""
    if cmp.empty or "judged_error" not in cmp:
        return []
    base = baseline_cases(study, cmp)
    found = list(dict.fromkeys(zip(base["reference"].astype(str), base["model"].astype(str))))
    order = sorted(found if pairs is None else pairs, key=lambda p: not is_cc_pair(*p))
    out = []
    for ref, m in order:
        g = base[(base["reference"] == ref) & (base["model"] == m)]
        e = numeric(g["judged_error"])
        if not np.isfinite(e).any():
            continue
        i = int(np.nanargmax(e))
        row = g.iloc[i]
        L = float(row["robot_length"])
        dynamic = np.isfinite(float(row.get("tip_error_max_over_time", np.nan)))
        nc = g["not_converged"].astype(bool).to_numpy()
        out.append(Headline(
            baseline=ref, model=m, error=float(e[i]), error_pct=100.0 * float(e[i]) / L,
            disc=float(row["disc_error"]), disc_pct=float(row["disc_error_pct"]),
            final_pct=_final_pct(study, ref, m, row["case_id"]) if dynamic else float("nan"),
            case_id=str(row["case_id"]), converged=not bool(row["not_converged"]), n_cases=int(np.isfinite(e).sum()),
            n_not_converged=int(nc[np.isfinite(e)].sum()), dynamic=bool(dynamic), cc_pair=is_cc_pair(ref, m),
            disc_exempt=bool(row.get("disc_exempt", False)),
        ))
    return out


def _bar_cell(g: pd.DataFrame, i: int) -> float | str:
    """The summary table's error-bar cell: the bar [% L], or ``exempt`` where an exempt side makes it 0."""
    bar = float(g["disc_error_pct"].iloc[i])
    exempt = "disc_exempt" in g and bool(g["disc_exempt"].iloc[i])
    return "exempt" if exempt and bar == 0.0 else bar


def summary_columns(g: pd.DataFrame) -> dict[str, Any]:
    """Error-bar columns of the report's summary table for the rows ``g`` of one comparison.

    ``largest judged error [% L]`` (tip error; dynamics: its peak over time), its
    ``± discretisation [% L]`` and ``not converged`` (cases marked, or ``n/a`` for a pair without CC).
    """
    if "judged_error" not in g or g.empty:
        return {}
    e = numeric(g["judged_error"])
    if not np.isfinite(e).any():
        return {}
    i = int(np.nanargmax(e))
    L = float(g["robot_length"].iloc[i])
    cc = is_cc_pair(str(g["reference"].iloc[0]), str(g["model"].iloc[0]))
    return {
        "largest judged error [% L]": 100.0 * float(e[i]) / L,
        "± discretisation [% L]": _bar_cell(g, i),
        "not converged": f"{int(g['not_converged'].astype(bool).sum())} of {len(g)}" if cc else "n/a (no CC)",
    }
