"""Decimated backbone positions over time of a dynamic run (``series.backbone``), shared by every model.

A dynamic run records its scalar time series at every output step; storing the whole backbone
there would be hundreds of kB a row.  The models keep every ``stride``-th sample
(:func:`frame_stride`: at most :data:`MAX_FRAMES` frames, the first and the final state always)
and return them as ``series["backbone"]`` (k, n_stations, 3) [m, base frame] at the times
``series["backbone_time"]`` (k,) [s] (:func:`backbone_series`); the report's 3-D viewer animates
them.  Checked by ``tests/physics/test_backbone_frames.py``.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MAX_FRAMES", "backbone_series", "frame_stride"]

#: Most backbone frames a dynamic run stores (first and last state included).
MAX_FRAMES = 61


def frame_stride(n_samples: int, max_frames: int = MAX_FRAMES) -> int:
    """Keep every ``stride``-th of ``n_samples`` recorded samples so that at most ``max_frames - 1`` remain.

    The final state is appended separately by the caller, so the total stays <= ``max_frames``.
    """
    if max_frames < 2:
        raise ValueError(f"max_frames must be >= 2, got {max_frames}")
    return max(1, math.ceil(max(int(n_samples), 1) / (max_frames - 1)))


def backbone_series(times, frames) -> dict[str, np.ndarray]:
    """``{"backbone_time": (k,), "backbone": (k, m, 3)}`` from frame times and backbone positions.

    Parameters
    ----------
    times : array_like, shape (k,)
        Times of the kept frames [s], increasing.
    frames : array_like, shape (k, m, 3)
        Backbone positions at the result stations [m], base frame.
    """
    t = np.asarray(times, dtype=float).reshape(-1)
    p = np.asarray(frames, dtype=float)
    if p.ndim != 3 or p.shape[0] != t.size or p.shape[2] != 3:
        raise ValueError(f"frames must have shape (k, m, 3) with k = len(times) = {t.size}, got {p.shape}")
    return {"backbone_time": t, "backbone": p}
