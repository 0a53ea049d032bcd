"""The caption statements 'stays below t % of L for x <= a' read right at the edges."""

from __future__ import annotations

import numpy as np

from workbench.report.sweeps import _below_statement


def test_only_the_first_value_below_is_said_so_not_as_x_le_0():
    s = _below_statement(np.array([0.0, 0.05, 0.1]), np.array([7.0, 12.0, 20.0]), "payload mass", "tip error",
                         val=lambda v: f"{v:g} kg")
    assert "≤ 0 kg" not in s and "only at the smallest payload mass swept (0 kg)" in s
    assert s.startswith("tip error stays below 10 % of L only at")


def test_equal_bounds_are_merged_and_worst_per_value_is_used():
    x = np.array([1.0, 1.0, 2.0, 2.0, 3.0])
    e = np.array([0.5, 0.2, 6.0, 0.1, 30.0])          # at x = 2 the worst case (6 %) counts, not 0.1 %
    s = _below_statement(x, e, "x", "err")
    assert s == ("err stays below 1 and 5 % of L only at the smallest x swept (1); "
                 "stays below 10 % of L for x ≤ 2 (max 30 % at x = 3).")
    shuffled = np.random.default_rng(0).permutation(len(x))
    assert _below_statement(x[shuffled], e[shuffled], "x", "err") == s
