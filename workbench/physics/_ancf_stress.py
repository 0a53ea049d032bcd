"""Backbone stresses of the planar ANCF model from its node coordinates (pure numpy; private).

Split from :mod:`workbench.physics.ancf` (which calls :func:`ancf_stress_extras` on its static and dynamic
states): axial strain and bending of the cubic Hermite centreline (:func:`~workbench.physics._ancf_geometry.hermite`)
at five points per element, combined by :mod:`workbench.models.stress`.  Checked by
``tests/models/test_stress.py``.
"""

from __future__ import annotations

import numpy as np

from ..robot import Robot
from ._ancf_geometry import hermite
from ._ancf_problem import AncfProblem

__all__ = ["ancf_stress_extras", "backbone_stress"]


def backbone_stress(pb: AncfProblem, qn: np.ndarray):
    """Backbone stress at five points per element of the states ``qn`` (..., n+1, 4) and the strengths there.

    Axial strain ``|r'| - 1`` and bending ``theta' = (r' x r'') / |r'|^2`` of the material (the
    continuum tendon's reference curvature / strain are the load, not the backbone's strain).
    Returns ``(sigma (..., 5 n), strength (5 n,))`` or ``None`` without stress geometry.
    """
    from ..models.stress import combined_stress, section_arrays

    arrs = section_arrays(pb.cross_sections) if pb.cross_sections else None
    if arrs is None:
        return None
    n = pb.s_nodes.size - 1
    elem = np.repeat(np.arange(n), 5)
    x = np.tile(np.linspace(0.0, 1.0, 5), n) * np.diff(pb.s_nodes)[elem]
    _, dr, ddr = hermite(qn, pb.s_nodes, elem, x)
    nrm2 = np.sum(dr * dr, axis=-1)
    eps = np.sqrt(nrm2) - 1.0
    kap = (dr[..., 0] * ddr[..., 1] - dr[..., 1] * ddr[..., 0]) / nrm2
    A, W, Y = (a[elem] for a in arrs)
    return combined_stress(pb.EA[elem] * eps, pb.EI[elem] * kap, A, W), Y


def ancf_stress_extras(pb: AncfProblem, robot: Robot, qn: np.ndarray, tensions: np.ndarray) -> dict[str, float]:
    """The stress extras (:func:`workbench.models.stress.stress_extras`) of the states ``qn`` and ``tensions``."""
    from ..models.stress import stress_extras

    bs = backbone_stress(pb, qn)
    return stress_extras(None if bs is None else bs[0], None if bs is None else bs[1], robot, tensions)
