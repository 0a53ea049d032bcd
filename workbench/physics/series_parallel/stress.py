"""Leg stresses of a solved module from its end reactions (pure numpy).

A leg carries no distributed load in the series-parallel studies (no gravity), so the statics of
its distal part ``[s, L]`` give the section force and moment exactly (Eq 19 with ``f = l = 0``)::

    n(s) = n(L),    m(s) = m(L) + (p(L) - p(s)) x n(L),

with ``n(L)``, ``m(L)`` the force and moment the platform exerts on the rod tip
(:class:`~workbench.physics.series_parallel.ModuleIK` ``tip_forces`` / ``tip_moments``).  At every
node the axial force is ``N = n . t`` and the bending moment the part of ``m`` normal to the
tangent ``t`` (central differences of the node positions), and the outer-fibre stress is
``|N| / A + |M_b| / W`` (:func:`workbench.models.stress.combined_stress`; torsion not included).
With gravity the rod's own weight would add a moment of order ``rho A g L^2 / 2`` that this leaves
out (the studies run without gravity).  Checked by ``tests/physics/test_series_parallel_stress.py``
(a straight leg under an axial load, a cantilevered leg under a tip force).
"""

from __future__ import annotations

import numpy as np

from ...models.stress import combined_stress
from ...robot.description import circular_section

__all__ = ["leg_stress", "module_leg_stress"]


def leg_stress(positions, tip_force, tip_moment, rod_diameter: float) -> np.ndarray:
    """Outer-fibre stress [Pa] at every node of one leg.

    Parameters
    ----------
    positions : array_like, shape (N+1, 3)
        Node positions [m], hole first.
    tip_force, tip_moment : array_like, shape (3,)
        ``n(L)`` [N], ``m(L)`` [N m] in the frame of ``positions``.
    rod_diameter : float
        [m] (solid circular section).

    Returns
    -------
    ndarray, shape (N+1,)
    """
    p = np.asarray(positions, dtype=float)
    n = np.asarray(tip_force, dtype=float)
    m = np.asarray(tip_moment, dtype=float)[None, :] + np.cross(p[-1] - p, n)
    t = np.gradient(p, axis=0)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    N = t @ n
    mb = np.linalg.norm(m - np.sum(m * t, axis=1, keepdims=True) * t, axis=1)
    A, I, _ = circular_section(rod_diameter)
    return combined_stress(N, mb, A, I / (0.5 * rod_diameter))


def module_leg_stress(geometry, modules) -> float:
    """Largest leg stress [Pa] over every leg of the given module solutions (``ModuleIK`` / ``ModulePose``)."""
    worst = 0.0
    for mod in modules:
        for i in range(6):
            s = leg_stress(mod.leg_positions[i], mod.tip_forces[i], mod.tip_moments[i], geometry.rod_diameter)
            worst = max(worst, float(np.max(s)))
    return worst
