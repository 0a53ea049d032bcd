"""The seeded split: disjoint, covering, deterministic, physics subsamples nested (workbench.measure.split)."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.measure.split import fold_rows, held_out_size, n_folds, train_sizes
from workbench.measure.types import Split


@pytest.mark.parametrize("n, split", [(40, Split(1, 0.25, None, 12)), (41, Split(3, None, 5, 7)),
                                      (7, Split(0, None, 7, 3)), (1000, Split(9, 0.1, None, 200))])
def test_disjoint_sorted_subsets(n, split):
    folds = fold_rows(n, split)
    assert [f.fold for f in folds] == list(range(n_folds(split)))
    assert [len(f.train) for f in folds] == train_sizes(n, split)
    for f in folds:
        assert not set(f.train) & set(f.test)
        assert sorted(set(f.train) | set(f.test)) == list(range(n))
        for a in (f.train, f.test, f.physics_train, f.physics_test):
            assert np.all(np.diff(a) > 0)
        assert set(f.physics_train) <= set(f.train) and set(f.physics_test) <= set(f.test)
        assert len(f.physics_train) == min(split.physics_rows, len(f.train))
        assert len(f.physics_test) == min(split.physics_rows, len(f.test))


def test_k_folds_hold_out_every_row_exactly_once_in_parts_of_near_equal_size():
    folds = fold_rows(41, Split(3, None, 5, 7))
    tests = np.concatenate([f.test for f in folds])
    assert sorted(tests.tolist()) == list(range(41))
    assert sorted(len(f.test) for f in folds) == [8, 8, 8, 8, 9]


def test_a_fraction_holds_out_that_share():
    assert held_out_size(40, 0.25) == 10 and held_out_size(3, 0.01) == 1 and held_out_size(3, 0.99) == 2
    (f,) = fold_rows(40, Split(1, 0.25, None, 12))
    assert len(f.test) == 10 and len(f.train) == 30


def test_the_same_seed_gives_the_same_rows_and_another_seed_other_rows():
    a, b, c = (fold_rows(100, Split(s, None, 4, 10)) for s in (5, 5, 6))
    for x, y in zip(a, b):
        for name in ("train", "test", "physics_train", "physics_test"):
            np.testing.assert_array_equal(getattr(x, name), getattr(y, name))
    assert any(not np.array_equal(x.test, z.test) for x, z in zip(a, c))


def test_physics_subsamples_are_nested_in_physics_rows():
    small = fold_rows(200, Split(2, None, 4, 10))
    large = fold_rows(200, Split(2, None, 4, 30))
    for s, g in zip(small, large):
        np.testing.assert_array_equal(s.train, g.train)
        assert set(s.physics_train) < set(g.physics_train) and set(s.physics_test) < set(g.physics_test)


def test_the_physics_subsample_is_spread_over_the_rows():
    """A seeded shuffle, not the first rows: the subsample's mean row index is near the middle."""
    (f,) = fold_rows(10_000, Split(0, 0.2, None, 500))
    assert abs(f.physics_train.mean() - 5000) < 5 * 10_000 / np.sqrt(12 * 500)


@pytest.mark.parametrize("n, split, match", [(1, Split(0, 0.5, None, 1), "at least 2 rows"),
                                             (5, Split(0, None, 6, 1), r"folds must be in \[2, n = 5\]"),
                                             (5, Split(0, 0.5, 2, 1), "exactly one"),
                                             (5, Split(0, None, None, 1), "exactly one")])
def test_impossible_splits_raise(n, split, match):
    with pytest.raises(ValueError, match=match):
        fold_rows(n, split)
