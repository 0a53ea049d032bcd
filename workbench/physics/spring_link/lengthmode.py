"""Planar continuum tendons in length mode on the extensible (``axial=True``) chain.

A frictionless continuum tendon's path length on the planar chain is

    L = L_ref - c d beta_m + sum_{k < m} g_k

(``beta_m`` the rotation of its terminating link, ``c = +-1`` its side, ``g_k`` the axial gaps of
the joints it passes): the integral of ``(1 + eps) - d kappa`` of the rod the chain stands for,
shear gaps neglected.  While taut, ``T = EA_t (L - L_0) / L_0``.  The chain carries the tendon as a
rotational spring on ``beta_m`` (stiffness ``EA_t d^2 / L_0``, exact for the inextensible chain)
whose rest angle includes the gap sum, and the backbone compression ``T`` of every joint it passes
as a rest-length offset of that joint's axial spring.  Both couplings use given (lagged) gap sums
and tensions; Newton on those values (:func:`settle_lagged`) repeats the equilibrium until the
state reproduces them.  Checked by ``tests/physics/test_spring_link_crossexam.py``
(length-mode tensions against ``ancf`` and ``cosserat``).
"""

from __future__ import annotations

import numpy as np

from ...models.result import ModelFailure

__all__: list[str] = []

_MAX_ITERATIONS = 100
_TOLERANCE = 1e-12   # on the gap sums, relative to the robot length


def joint_gaps(model) -> np.ndarray:  # noqa: ANN001
    """Axial joint gaps ``(N,)`` [m] of a planar chain (zeros for the inextensible one)."""
    if not model.axial:
        return np.zeros(model.geo.n_links)
    exu, mbs = model.exu, model.mbs
    _, beta = model.link_states()
    out = np.zeros(model.geo.n_links)
    for k, (m0, m1) in enumerate(model.joint_markers):
        p0 = np.asarray(mbs.GetMarkerOutput(m0, exu.OutputVariableType.Position))[:2]
        p1 = np.asarray(mbs.GetMarkerOutput(m1, exu.OutputVariableType.Position))[:2]
        out[k] = float(np.dot(p1 - p0, [np.sin(beta[k]), np.cos(beta[k])]))
    return out


def gap_sums(model) -> np.ndarray:  # noqa: ANN001
    """Sum of the axial gaps of the joints every tendon passes, ``(n_tendons,)`` [m]."""
    g = joint_gaps(model)
    return np.array([float(np.sum(g[: t.end_eyelet])) for t in model.tendons])


def _state(model) -> np.ndarray:  # noqa: ANN001
    return np.concatenate([gap_sums(model), model.tensions()])


def _lagged(model) -> np.ndarray:  # noqa: ANN001
    return np.concatenate([model.lag_gaps, model.lag_tensions])


def settle_lagged(model, resolve) -> int:  # noqa: ANN001
    """Newton on the lagged values ``x = (gap sums, tensions)`` until the equilibrium they give
    reproduces them (gap sums to 1e-12 L, tensions to 1e-9 relative); returns the equilibria.

    ``resolve(old, new)`` is an equilibrium moving the lagged values from ``old`` to ``new``
    (pairs of arrays).  The Jacobian of ``x -> state(x)`` is taken by finite differences (one
    equilibrium per lagged value); the map is nearly linear, so two or three iterations do.

    Raises
    ------
    ModelFailure
        Not settled within 100 equilibria.
    """
    n = len(model.tendons)
    scale = np.concatenate([np.full(n, model.robot.length * _TOLERANCE), np.full(n, 1e-9)])

    def go(x: np.ndarray) -> np.ndarray:
        old = _lagged(model)
        resolve((old[:n], old[n:]), (x[:n], x[n:]))
        return _state(model)

    count = 0
    x = _lagged(model)
    y = _state(model)
    while count < _MAX_ITERATIONS:
        r = y - x
        if np.all(np.abs(r) <= scale * np.maximum(1.0, np.abs(np.concatenate([np.zeros(n), y[n:]])))):
            return count
        J = -np.eye(2 * n)
        for j in range(2 * n):
            h = 1e-7 * model.robot.length if j < n else 1e-4 * max(1.0, abs(x[j]))
            xj = x.copy()
            xj[j] += h
            J[:, j] += (go(xj) - y) / h
            count += 1
        x = x - np.linalg.solve(J, r)
        y = go(x)
        count += 1
    raise ModelFailure("spring_link: length-mode coupling of tendons and axial springs did not settle "
                       f"within {_MAX_ITERATIONS} equilibria")
