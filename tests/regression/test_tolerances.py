"""The regression tolerances follow their rule (``derive_tolerances.RULE``, the header of tolerances.toml).

Issue 28 ("What else a verdict needs") found tolerances as large as the values they guard:
``wire_delay`` ``x.disc_tip_error`` 1.05e-4 with tolerance 2e-4 (measured noise 3.6e-12),
``series_parallel`` ``x.fk_residual`` 1e-10 with tolerance 1e-3, ``fruit_harvester_fluidic``
``x.static_steps`` 20 with tolerance 20.  Reads only committed files (no study runs): default suite.
"""

from __future__ import annotations

import pytest

from tests.regression.derive_tolerances import MULTIPLES, count_slack, floor_of, guarded, is_count, round_up2
from tests.regression.golden import GOLDEN_DIR, KEY_COLUMNS, load_tolerances, read_golden, small_study_paths, \
    tolerances_for

STEMS = [p.stem for p in small_study_paths()]


def _columns(stem, tolerances):
    golden = read_golden(GOLDEN_DIR / f"{stem}.csv")
    ok = golden[golden["status"] == "ok"]
    tol = tolerances_for(stem, tolerances)
    return [(c, ok[c].to_numpy(dtype=float), tol.get(c)) for c in golden.columns if c not in KEY_COLUMNS]


def tolerance_problems(stem: str, tolerances=None) -> list[str]:
    """Every violation of the rule in study ``stem``'s entries (``tolerances``: default the committed file)."""
    out = []
    for c, values, t in _columns(stem, load_tolerances() if tolerances is None else tolerances):
        if t is None:
            out.append(f"{c}: no tolerance")
            continue
        if "noise" not in t:
            out.append(f"{c}: no measured noise (derive it: tests/regression/derive_tolerances.py)")
            continue
        for v in guarded(values, t["noise"], c):
            if t["abs"] + t["rel"] * v >= v:
                out.append(f"{c}: tolerance {t['abs'] + t['rel'] * v:.3g} >= the golden value {v:.3g} it guards")
                break
        if is_count(c):
            slack = count_slack(t["noise"], guarded(values, t["noise"], c))
            if t["rel"] or t["abs"] > slack:
                out.append(f"{c}: count slack {t['abs']:g} / rel {t['rel']:g} beyond the rule's {slack:g}")
            continue
        floor = floor_of(values)
        loosest = round_up2(max(MULTIPLES[0] * t["noise"], floor)) * (1 + 1e-12)
        if t["rel"]:
            if t["rel"] > round_up2(MULTIPLES[0] * t.get("rel_noise", 0.0)) * (1 + 1e-12) \
                    or t["abs"] > round_up2(floor) * (1 + 1e-12):
                out.append(f"{c}: rel {t['rel']:g} > {MULTIPLES[0]:g} x rel_noise or abs {t['abs']:g} > floor {floor:.2g}")
        elif t["abs"] > loosest:
            out.append(f"{c}: abs {t['abs']:g} > {MULTIPLES[0]:g} x noise {t['noise']:g} (floor {floor:.2g})")
    return out


@pytest.mark.parametrize("stem", STEMS)
def test_tolerances_below_the_values_they_guard(stem):
    problems = tolerance_problems(stem)
    assert not problems, f"{stem}:\n" + "\n".join(problems)


def test_the_issue_cases_are_caught():
    """The three cases quoted in issue 28: their old tolerances, with the committed measured noise, fail the check."""
    old = {"wire_delay": ("x.disc_tip_error", 2e-4), "series_parallel": ("x.fk_residual", 1e-3),
           "fruit_harvester_fluidic": ("x.static_steps", 20.0)}
    real = load_tolerances()
    patched = {k: dict(v) for k, v in real.items()}
    for stem, (col, abs_) in old.items():
        patched[stem] = {**patched[stem], col: {**tolerances_for(stem, real)[col], "abs": abs_, "rel": 0.0}}
    for stem, (col, _) in old.items():
        assert any(p.startswith(f"{col}:") for p in tolerance_problems(stem, patched)), stem


def test_rule_on_synthetic_columns():
    """column_tolerance: 10 x noise; relative where an absolute tolerance would reach a small value;
    a lower multiple only when needed (noted); counts exact or 2 x their change; unresolved values flagged."""
    import numpy as np

    from tests.regression.derive_tolerances import column_tolerance

    t = column_tolerance("tip_x", np.array([0.5, 0.2]), np.array([1e-15, 3e-15]), np.array([0.5, 0.2]))
    assert t.abs == pytest.approx(3e-14) and t.rel == 0 and not t.problem
    # rows of 1e-3 and 1e-8 with changes 2e-9 and 1e-16: 10 x 2e-9 would reach 1e-8, 10 x relative does not
    t = column_tolerance("x.bar", np.array([1e-3, 1e-8]), np.array([2e-9, 1e-16]), np.array([1e-3, 1e-8]))
    assert t.rel == pytest.approx(2e-5) and t.note == "relative"
    t = column_tolerance("x.bar", np.array([3e-5, 1.5e-5]), np.array([4.4e-6, 1e-6]), np.array([3e-5, 1.5e-5]))
    assert "noise-limited" in t.note and not t.problem
    t = column_tolerance("x.bar", np.array([1e-5]), np.array([9e-6]), np.array([1e-5]))
    assert t.problem
    t = column_tolerance("x.static_steps", np.array([48.0, 60.0]), np.array([0.0, 2.0]), np.array([48.0, 60.0]))
    assert t.abs == 4 and not t.problem
    assert column_tolerance("x.ik_iterations", np.array([6.0]), np.array([9.0]), np.array([6.0])).abs == 1
    assert column_tolerance("x.static_steps", np.array([20.0]), np.array([0.0]), np.array([20.0])).abs == 0
