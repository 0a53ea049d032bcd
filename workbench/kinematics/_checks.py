"""Input validation shared by the kinematics modules (checked once, at the public boundary)."""

from __future__ import annotations

import numpy as np


def as_float(name: str, x, *, finite: bool = True) -> np.ndarray:
    """Convert ``x`` to a float64 array; raise ``TypeError``/``ValueError`` naming ``name``."""
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be array-like of real numbers; got {type(x).__name__}") from exc
    if finite and not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must contain only finite values (no NaN/inf)")
    return a


def broadcast_named(**arrays: np.ndarray) -> list[np.ndarray]:
    """Broadcast named arrays together, with an error message that lists their shapes."""
    try:
        return list(np.broadcast_arrays(*arrays.values()))
    except ValueError as exc:
        shapes = ", ".join(f"{k}{np.shape(v)}" for k, v in arrays.items())
        raise ValueError(f"arrays do not broadcast together: {shapes}") from exc


def section_arrays(**named) -> list[np.ndarray]:
    """Check and broadcast per-section arrays of shape ``(..., n_sections)``.

    Every argument must have at least one dimension (the trailing one is the section axis,
    ``n_sections >= 1``) and all must broadcast to a common shape.
    """
    arrays = {k: as_float(k, v) for k, v in named.items()}
    for k, a in arrays.items():
        if a.ndim == 0:
            raise ValueError(
                f"{k} must have shape (..., n_sections) with at least one dimension; got a scalar"
            )
    out = broadcast_named(**arrays)
    if out[0].shape[-1] == 0:
        raise ValueError("n_sections must be >= 1; got arrays with an empty last axis")
    return out


def require_nonnegative(name: str, a: np.ndarray) -> None:
    if np.any(a < 0):
        raise ValueError(f"{name} must be >= 0 (lengths in metres); got min {np.min(a):.6g}")


def require_positive(name: str, a: np.ndarray) -> None:
    if np.any(a <= 0):
        raise ValueError(f"{name} must be > 0; got min {np.min(a):.6g}")
