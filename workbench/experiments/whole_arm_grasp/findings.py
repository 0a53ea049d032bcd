"""The whole-arm grasp study's findings, computed from its rows (never typed in): one sentence each.

:func:`findings` takes the ``(cc row, contact row)`` pairs of a result set and states what the
numbers say -- CC's penetration of the object, where the physics holds it, the holding force and
what squeeze and friction do to it, how the object follows a carry, and the size of the error bars.
Kept apart from the figures (as data for a report's "Findings" section); the wraps figure quotes
them.  Checked by ``tests/experiments/test_whole_arm_grasp.py`` (the report of a small study).
"""

from __future__ import annotations

import numpy as np

from ...report.style import fmt

__all__ = ["findings", "column", "span"]


def column(rows, key) -> np.ndarray:
    """Float values of ``key`` in ``rows`` (NaN where missing or not a number)."""
    out = []
    for r in rows:
        try:
            out.append(float(r.get(key, np.nan)))
        except (TypeError, ValueError):
            out.append(np.nan)
    return np.array(out)


def span(v: np.ndarray, scale: float = 1.0) -> str:
    """``"lo-hi"`` (``"lo to hi"`` below 0) of the finite values times ``scale`` (one value when equal, ``n/a`` when none)."""
    v = v[np.isfinite(v)] * scale
    if v.size == 0:
        return "n/a"
    a, b = fmt(v.min()), fmt(v.max())
    return a if a == b else (f"{a} to {b}" if v.min() < 0 else f"{a}-{b}")


def _friction_effect(cc, ph) -> str:
    """Largest relative change of the holding force with friction at fixed object size and squeeze."""
    keys = ("p.scenario.object_radius", "p.scenario.squeeze")
    groups: dict[tuple, list[float]] = {}
    for c, p in zip(cc, ph):
        groups.setdefault(tuple(round(float(c[k]), 12) for k in keys), []).append(float(p.get("x.holding_force", np.nan)))
    rel = [np.ptp(g) / np.mean(g) for g in groups.values() if len(g) > 1 and np.all(np.isfinite(g))]
    return "" if not rel else f"; friction changes it by at most {fmt(100 * max(rel))} % at fixed size and squeeze"


def _squeeze_effect(cc, ph) -> str:
    sq = column(cc, "p.scenario.squeeze")
    F = column(ph, "x.holding_force")
    lo, hi = np.nanmin(sq), np.nanmax(sq)
    if not np.isfinite(lo) or lo == hi:
        return ""
    a, b = np.nanmedian(F[sq == lo]), np.nanmedian(F[sq == hi])
    return f"; squeeze {fmt(lo)} -> {fmt(hi)} raises its median {fmt(a)} -> {fmt(b)} N"


def _contact_patches(row) -> int | None:
    """Number of contiguous runs of touching segments (``series.contact_fn > 0``) of a contact row."""
    from ...compare.table import array_cell

    fn = array_cell(row.get("series.contact_fn"))
    if fn is None or fn.size == 0:
        return None
    on = np.concatenate([[0], (fn > 0).astype(int), [0]])
    return int(np.sum(np.diff(on) == 1))


def findings(pairs) -> tuple[str, ...]:
    """Sentences (no trailing period) stating the study's results; empty without pairs."""
    if not pairs:
        return ()
    cc, ph = [p[0] for p in pairs], [p[1] for p in pairs]
    out = [f"CC's plan ignores the object: its arcs penetrate it by {span(column(cc, 'x.cc_max_penetration'), 1e3)} mm "
           f"(the thinner distal section spirals inwards even at squeeze 1)"]
    held = column(ph, "x.held") > 0
    out.append(f"the physics held the object in {int(held.sum())} of {len(ph)} cases")
    if held.any():
        h = [p for p, k in zip(ph, held) if k]
        out.append(f"it settles {span(-column(h, 'x.settle_dz'), 1e3)} mm lower and {span(column(h, 'x.settle_dx'), 1e3)} mm "
                   f"further out (+x) than CC holds it (gravity and the arm's compliance)")
    patches = [_contact_patches(p) for p, k in zip(ph, held) if k]
    patches = [n for n in patches if n is not None]
    if patches:
        out.append(f"it touches the object in {min(patches)}-{max(patches)} separate patches (a stiff arm wraps by "
                   f"points, not along CC's arc)" if min(patches) != max(patches) else
                   f"it touches the object in {patches[0]} separate patches (a stiff arm wraps by points, not along "
                   f"CC's arc)")
    F = column(ph, "x.holding_force")
    if np.isfinite(F).any():
        lower = int(np.sum(column(ph, "x.pull_peak_resolved") == 0))
        out.append(f"holding force against a straight-down pull {span(F)} N" + _squeeze_effect(cc, ph)
                   + _friction_effect(cc, ph)
                   + (f"; in {lower} case(s) the static path ended before the force peaked (a lower bound)" if lower else ""))
    mv = column(ph, "x.carry_move_error")
    if np.isfinite(mv).any():
        out.append(f"carried along the CC plan, the object's move misses the planned move by {span(mv, 1e3)} mm "
                   f"(the settling offset removed)")
    bars = {k: np.nanmax(column(ph, f"x.{e}_holding_force") / F) for e, k in (("disc", "mesh"), ("pen", "penalty"))
            if np.isfinite(column(ph, f"x.{e}_holding_force")).any()}
    if bars:
        out.append("error bars of the holding force up to " + ", ".join(f"{fmt(100 * v)} % ({k})" for k, v in bars.items()))
    return tuple(out)
