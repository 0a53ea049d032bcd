"""The seeded split of a calibration study's samples into training and held-out (test) rows.

:func:`fold_rows` turns ``n`` samples and a :class:`~workbench.measure.types.Split` into the
:class:`~workbench.measure.types.FoldRows` of every fold:

- the rows are shuffled once by ``numpy.random.default_rng(seed).permutation(n)``;
- ``test_fraction``: one fold (fold 0); its test rows are the first ``round(test_fraction * n)``
  rows of the shuffle (at least 1, at most ``n - 1``), the training rows the rest;
- ``folds = k``: the shuffle is cut into ``k`` parts of sizes differing by at most one
  (``numpy.array_split``); fold ``f`` holds out part ``f`` and trains on the others, so every row is
  a test row of exactly one fold;
- the physics subsamples come from a second, independent shuffle of all ``n`` rows
  (``default_rng([seed, 1])``): ``physics_train`` is the first ``physics_rows`` training rows in that
  order, ``physics_test`` the first ``physics_rows`` test rows.  So they are *nested*: with the same
  seed, a larger ``physics_rows`` keeps every row of a smaller one and adds rows; and a row's rank
  does not depend on the fold, so the subsamples of the folds are drawn alike.

The same ``(n, split)`` gives the same rows on every machine (numpy's PCG64 stream is stable across
versions for ``permutation``).  Every index array is sorted.  Checked by
``tests/measure/test_measure_split.py`` (disjointness, coverage, determinism, nesting).
"""

from __future__ import annotations

import numpy as np

from .types import FoldRows, Split

__all__ = ["fold_rows", "n_folds", "held_out_size", "train_sizes"]


def n_folds(split: Split) -> int:
    """Number of folds: 1 with ``test_fraction``, else ``folds``."""
    return 1 if split.test_fraction is not None else int(split.folds)


def held_out_size(n: int, test_fraction: float) -> int:
    """Held-out rows of a ``test_fraction`` split of ``n`` rows: ``round(test_fraction * n)`` within ``[1, n - 1]``."""
    return min(max(1, int(round(test_fraction * n))), n - 1)


def train_sizes(n: int, split: Split) -> list[int]:
    """Training rows of each fold (what :func:`fold_rows` gives, without building the folds)."""
    if split.test_fraction is not None:
        return [n - held_out_size(n, split.test_fraction)]
    return [n - len(part) for part in np.array_split(np.arange(n), int(split.folds))]


def _first(order_rank: np.ndarray, rows: np.ndarray, k: int) -> np.ndarray:
    """The ``k`` rows of ``rows`` that come first in the physics order (``order_rank[row]``), sorted."""
    return np.sort(rows[np.argsort(order_rank[rows], kind="stable")[:k]])


def fold_rows(n: int, split: Split) -> list[FoldRows]:
    """The training and test rows of every fold (module docstring).

    Parameters
    ----------
    n : int
        Number of samples (rows of :class:`~workbench.measure.types.Measurements`).
    split : Split

    Raises
    ------
    ValueError
        Fewer than 2 rows, ``folds`` > ``n``, or neither / both of ``test_fraction`` and ``folds``
        (the study loader refuses these first, in its words).
    """
    if (split.test_fraction is None) == (split.folds is None):
        raise ValueError("set exactly one of test_fraction and folds")
    if n < 2:
        raise ValueError(f"a split needs at least 2 rows, got {n}")
    if split.folds is not None and not 2 <= split.folds <= n:
        raise ValueError(f"folds must be in [2, n = {n}], got {split.folds}")
    perm = np.random.default_rng(split.seed).permutation(n)
    rank = np.empty(n, dtype=int)
    rank[np.random.default_rng([split.seed, 1]).permutation(n)] = np.arange(n)
    if split.test_fraction is not None:
        k = held_out_size(n, split.test_fraction)
        parts = [(perm[:k], perm[k:])]
    else:
        chunks = np.array_split(perm, int(split.folds))
        parts = [(c, np.concatenate([o for j, o in enumerate(chunks) if j != f])) for f, c in enumerate(chunks)]
    out = []
    for f, (test, train) in enumerate(parts):
        out.append(FoldRows(fold=f, train=np.sort(train), test=np.sort(test),
                            physics_train=_first(rank, train, split.physics_rows),
                            physics_test=_first(rank, test, split.physics_rows)))
    return out
