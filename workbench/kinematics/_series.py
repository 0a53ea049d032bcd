"""Numerically stable trigonometric ratios used by the constant-curvature formulas.

All functions are elementwise, accept any array shape, never divide by zero and are
accurate to a few ulps for every argument: a Taylor branch is used where the closed form
suffers from cancellation (``|x|`` below a threshold), the closed form elsewhere.

Notation (``x`` real):

=================  =========================================  ===================================
function           closed form                                series about 0
=================  =========================================  ===================================
``sinc``           ``sin(x)/x``                               ``1 - x^2/6 + x^4/120 - ...``
``dsinc``          ``d/dx sin(x)/x = (x cos x - sin x)/x^2``  ``-x/3 + x^3/30 - x^5/840 + ...``
``versinc``        ``(1 - cos x)/x``                          ``x/2 - x^3/24 + x^5/720 - ...``
``dversinc``       ``(x sin x - 1 + cos x)/x^2``              ``1/2 - x^2/8 + x^4/144 - ...``
=================  =========================================  ===================================
"""

from __future__ import annotations

from math import factorial

import numpy as np

_SINC_SMALL = 1e-4  # series to x^4: truncation x^6/5040 < 2e-28
_DERIV_SMALL = 0.3  # closed forms lose ~3 eps/x^2 relative accuracy; 6-term series below (< 1e-16)


def sinc(x: np.ndarray) -> np.ndarray:
    """``sin(x)/x`` (unnormalised), 1 at 0."""
    x = np.asarray(x, dtype=np.float64)
    return sinc_given_sin(x, np.sin(x))


def sinc_given_sin(x: np.ndarray, sin_x: np.ndarray) -> np.ndarray:
    """``sin(x)/x`` when ``sin(x)`` is already known (saves one transcendental call)."""
    small = np.abs(x) < _SINC_SMALL
    if not np.any(small):
        return sin_x / x
    xs = np.where(small, 1.0, x)
    out = np.divide(sin_x, xs, out=np.empty(np.shape(x)))
    xm = x[small]
    x2 = xm * xm
    out[small] = 1.0 - x2 / 6.0 + x2 * x2 / 120.0
    return out


def _poly_series(x: np.ndarray, coeffs: list[float], first_power: int) -> np.ndarray:
    x2 = x * x
    acc = np.zeros_like(x)
    for c in reversed(coeffs):
        acc = acc * x2 + c
    return acc * x**first_power if first_power else acc


# d/dx (sin x / x) = sum_{k>=1} (-1)^k 2k x^(2k-1) / (2k+1)!
_DSINC_C = [(-1) ** k * 2 * k / factorial(2 * k + 1) for k in range(1, 7)]
# (1 - cos x)/x = sum_{k>=1} (-1)^(k+1) x^(2k-1) / (2k)!
_VERSINC_C = [(-1) ** (k + 1) / factorial(2 * k) for k in range(1, 7)]
# d/dx (1 - cos x)/x = sum_{k>=1} (-1)^(k+1) (2k-1) x^(2k-2) / (2k)!
_DVERSINC_C = [(-1) ** (k + 1) * (2 * k - 1) / factorial(2 * k) for k in range(1, 7)]


def dsinc(x: np.ndarray) -> np.ndarray:
    """``d/dx [sin(x)/x] = (x cos x - sin x)/x^2``; 0 at 0."""
    x = np.asarray(x, dtype=np.float64)
    small = np.abs(x) < _DERIV_SMALL
    xs = np.where(small, 1.0, x)
    closed = (xs * np.cos(xs) - np.sin(xs)) / (xs * xs)
    return np.where(small, _poly_series(x, _DSINC_C, 1), closed)


def versinc(x: np.ndarray) -> np.ndarray:
    """``(1 - cos x)/x = 2 sin^2(x/2)/x``; 0 at 0 (no cancellation)."""
    x = np.asarray(x, dtype=np.float64)
    h = 0.5 * x
    return np.sin(h) * sinc(h)


def dversinc(x: np.ndarray) -> np.ndarray:
    """``d/dx [(1 - cos x)/x] = (x sin x - 1 + cos x)/x^2``; 1/2 at 0."""
    x = np.asarray(x, dtype=np.float64)
    small = np.abs(x) < _DERIV_SMALL
    xs = np.where(small, 1.0, x)
    closed = (xs * np.sin(xs) - 2.0 * np.sin(0.5 * xs) ** 2) / (xs * xs)
    return np.where(small, _poly_series(x, _DVERSINC_C, 0), closed)
