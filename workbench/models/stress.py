"""Backbone and tendon stresses of a solved robot, and their ratio to the declared strengths.

The backbone's largest normal stress at a cross-section is the outer-fibre sum of axial and
bending stress (symmetric section: some fibre always sees both with the same sign)::

    sigma = |N| / A + |M_b| / W,        N = EA eps,   M_b = EI |kappa_b|,

with ``eps`` the axial strain and ``kappa_b`` the bending curvature of the material (not the
reference curvature a continuum-tendon model may use to apply the tendon load), ``A`` the area
and ``W = I / c`` the section modulus (:class:`workbench.robot.CrossSection` ``area``,
``section_modulus``).  Torsion shear is not included.  A tendon's stress is ``T / A_t``
(:class:`workbench.robot.TendonGroup` ``area``).  The stress ratio is the largest
stress / strength over every sample with a known strength (``yield_strength``, ``strength``).

Pure numpy, used by every model's result code (CC included) and the series-parallel worker.
Checked by ``tests/models/test_stress.py`` (cantilever under a tip load against
``sigma = M c / I + N / A``, a straight rod under axial tendon load, every model).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

__all__ = ["combined_stress", "section_arrays", "tendon_arrays", "stress_extras"]


def combined_stress(axial_force, bending_moment, area, section_modulus) -> np.ndarray:
    """Outer-fibre normal stress ``|N| / A + |M| / W`` [Pa] (arrays broadcast).

    Parameters
    ----------
    axial_force : array_like
        ``N`` [N] (sign irrelevant).
    bending_moment : array_like
        Magnitude of the bending moment ``M_b`` [N m].
    area, section_modulus : array_like
        ``A`` [m^2], ``W`` [m^3].
    """
    N = np.abs(np.asarray(axial_force, dtype=float))
    M = np.abs(np.asarray(bending_moment, dtype=float))
    return N / np.asarray(area, dtype=float) + M / np.asarray(section_modulus, dtype=float)


def section_arrays(cross_sections: Sequence) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """``(A, W, yield strength)`` per sample from :class:`CrossSection` objects; ``None`` if any lacks ``A`` or ``W``.

    Unknown strengths are NaN.
    """
    if any(cs.area is None or cs.section_modulus is None for cs in cross_sections):
        return None
    A = np.array([cs.area for cs in cross_sections], dtype=float)
    W = np.array([cs.section_modulus for cs in cross_sections], dtype=float)
    Y = np.array([np.nan if cs.yield_strength is None else cs.yield_strength for cs in cross_sections], dtype=float)
    return A, W, Y


def tendon_arrays(robot) -> tuple[np.ndarray, np.ndarray] | None:
    """``(area, strength)`` per tendon in ``robot.tendon_table()`` order; ``None`` if a tendon has no area."""
    table = robot.tendon_table()
    if not table or any(g.area is None for _, _, g in table):
        return None
    area = np.array([g.area for _, _, g in table], dtype=float)
    strength = np.array([np.nan if g.strength is None else g.strength for _, _, g in table], dtype=float)
    return area, strength


def stress_extras(backbone_stress=None, backbone_strength=None, robot=None, tendon_tensions=None) -> dict[str, float]:
    """The result extras ``max_stress_backbone``, ``max_stress_tendon`` [Pa] and ``stress_ratio`` [-].

    Parameters
    ----------
    backbone_stress : array_like, optional
        Backbone stress per sample [Pa] (``None``: no stress geometry -> no backbone key).
    backbone_strength : array_like, optional
        Yield strength per sample [Pa] (NaN: unknown), broadcastable to ``backbone_stress``.
    robot : Robot, optional
        For the tendon areas and strengths.
    tendon_tensions : array_like, optional
        Tensions [N] in ``robot.tendon_table()`` order (any leading axes: e.g. ``(k, n)`` over
        time); NaN tensions (a model that predicts none) give no tendon key.

    Returns
    -------
    dict
        Keys present only where they are defined; ``stress_ratio`` is the largest stress /
        strength of the samples whose strength is known (absent if none is).
    """
    out: dict[str, float] = {}
    ratios = []
    if backbone_stress is not None:
        sb = np.asarray(backbone_stress, dtype=float)
        if sb.size and np.all(np.isfinite(sb)):
            out["max_stress_backbone"] = float(sb.max())
            if backbone_strength is not None:  # per sample; broadcast over leading (time) axes
                yb = np.broadcast_to(np.asarray(backbone_strength, dtype=float), sb.shape).reshape(-1)
                sb = sb.reshape(-1)
                known = np.isfinite(yb)
                if known.any():
                    ratios.append(float(np.max(sb[known] / yb[known])))
    if robot is not None and tendon_tensions is not None:
        tab = tendon_arrays(robot)
        T = np.asarray(tendon_tensions, dtype=float)
        if tab is not None and T.size and T.shape[-1] == tab[0].size and np.all(np.isfinite(T)):
            st = np.abs(T).reshape(-1, tab[0].size) / tab[0]
            out["max_stress_tendon"] = float(st.max())
            known = np.isfinite(tab[1])
            if known.any():
                ratios.append(float(np.max(st[:, known] / tab[1][known])))
    if ratios:
        out["stress_ratio"] = max(ratios)
    return out
