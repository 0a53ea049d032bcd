"""Mesh, frame convention and tendon routes of the spatial beam models (pure numpy).

Used by :mod:`workbench.physics.beam3d` (through :mod:`workbench.physics._beam3d_system`) and
:mod:`workbench.physics.ancf3d`.  Checked through
``tests/physics/test_beam3d*.py`` and ``test_ancf3d.py``.
"""

from __future__ import annotations

import numpy as np

from ..robot import Robot

__all__ = ["R_BASE_MODEL", "element_layout", "tendon_routes", "locate"]

#: base <- model rotation: model x (beam axis) = base z, model y = base x, model z = base y.
R_BASE_MODEL = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])


def element_layout(robot: Robot, n_elements: int) -> tuple[np.ndarray, np.ndarray]:
    """Node arc lengths and the section index of every element.

    Elements are distributed over sections in proportion to their lengths (at least one
    per section), uniform within a section.

    Returns
    -------
    node_s : ndarray, shape (n_el + 1,)
        Reference arc length of every node [m].
    elem_section : ndarray of int, shape (n_el,)
        Section index of every element.
    """
    Ls = robot.section_lengths
    counts = np.maximum(1, np.round(n_elements * Ls / Ls.sum()).astype(int))
    starts = np.concatenate([[0.0], np.cumsum(Ls)[:-1]])
    node_s = [0.0]
    sec = []
    for j, (s0, Lj, nj) in enumerate(zip(starts, Ls, counts)):
        node_s.extend(s0 + Lj * np.arange(1, nj + 1) / nj)
        sec.extend([j] * nj)
    node_s = np.asarray(node_s)
    node_s[-1] = robot.length
    return node_s, np.asarray(sec, dtype=int)


def locate(node_s: np.ndarray, s: float, prefer_left: bool = True) -> tuple[int, float]:
    """Element index and local coordinate (-L_e/2..L_e/2, from the element midpoint) of arc length ``s``."""
    n_el = node_s.size - 1
    if prefer_left:
        e = int(np.searchsorted(node_s, s, side="left")) - 1
    else:
        e = int(np.searchsorted(node_s, s, side="right")) - 1
    e = min(max(e, 0), n_el - 1)
    mid = 0.5 * (node_s[e] + node_s[e + 1])
    return e, float(s - mid)


def tendon_routes(robot: Robot) -> list[list[tuple[float, float]]]:
    """Eyelet route of every tendon: ``[(s, d), ...]`` from the base anchor to the termination.

    The first entry is the anchor on the base plate (s = 0), the last the terminating
    disk.  ``d`` is the tendon offset [m] at that station: linear along the tendon's whole
    routed length, ``TendonGroup.offset_at(s / s_end)`` (the TendonGroup convention).
    """
    routes = []
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    ends = robot.section_ends
    for j, sigma, group in robot.tendon_table():
        # offset linear along the whole routed length [0, ends[j]] (TendonGroup convention)
        route = [(0.0, group.offset_at(0.0))]
        for k in range(j + 1):
            sec = robot.sections[k]
            for sd in sec.disk_positions():
                s = float(starts[k] + sd)
                route.append((s, float(group.offset_at(s / ends[j]))))
        routes.append(route)
    return routes
