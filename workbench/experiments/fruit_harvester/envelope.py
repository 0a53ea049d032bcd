"""Shao's fruit harvester: the assumed grasp envelope and the grasp centre of a backbone.

Shao et al. (papers/002_, Sec. 4) state that the arc length ``s`` and curvature ``kappa`` limits
bound the object sizes that can be scooped (up to 100 mm, 200 g) but give no numbers.
**Assumed** here (a physical assumption of this study, plotted as such): the skin of a section of
outer diameter ``D`` wraps an object of diameter ``d = 2 / kappa - D``; holding it needs a wrap
angle ``kappa s >= 3 pi / 2``; the section can contract to ``s_min = 0.34 m`` (15 %) and not
elongate beyond ``0.40 m``; the actuators limit the curvature to ``kappa <= 25 1/m``.  Then
``d in [2 / kappa_max - D, 2 s / (3 pi / 2) - D]``, i.e. 20 ... 110 mm at s = 0.40 m.

Pure numpy.  Checked by ``tests/experiments/test_fruit_harvester.py`` (the envelope reaches the
paper's 100 mm; the circle fit is exact on an arc and finds the CC centre of arc).
"""

from __future__ import annotations

import math
from typing import Mapping

import numpy as np

__all__ = ["HARVESTER_LIMITS", "circle_fit", "grasp_envelope"]

#: Assumed limits of the harvester grasp envelope (see the module docstring).
HARVESTER_LIMITS = {"s_min": 0.34, "s_max": 0.40, "kappa_max": 25.0, "wrap_angle": 1.5 * math.pi}


def circle_fit(points: np.ndarray) -> tuple[np.ndarray, float]:
    """Least-squares circle (Kasa) through planar points ``(m, 2)``: ``(centre (2,), radius)``."""
    p = np.asarray(points, dtype=float)
    A = np.column_stack([2 * p[:, 0], 2 * p[:, 1], np.ones(len(p))])
    b = (p ** 2).sum(axis=1)
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    c = sol[:2]
    return c, float(np.sqrt(sol[2] + c @ c))


def grasp_envelope(s, outer_diameter: float,
                   limits: Mapping[str, float] = HARVESTER_LIMITS) -> tuple[np.ndarray, np.ndarray]:
    """Smallest and largest wrappable object diameter [m] at arc lengths ``s`` [m] (shape of ``s``).

    ``d_lo = 2 / kappa_max - D`` (curvature limit), ``d_hi = 2 s / wrap_angle - D`` (wrap angle).
    """
    s = np.asarray(s, dtype=float)
    d_lo = np.full_like(s, 2.0 / limits["kappa_max"] - outer_diameter)
    d_hi = 2.0 * s / limits["wrap_angle"] - outer_diameter
    return d_lo, d_hi
