"""Constant-curvature (CC) kinematics over many samples at once: the CC model vectorised over commands.

A calibration evaluates CC on every measured sample (tens of thousands) for every trial
parameter vector, so a Python loop over samples (one :func:`workbench.models.cc.run` each) is
too slow.  This module applies the same maps as :mod:`workbench.models.cc` to a whole array of
commands ``(n, n_tendons)`` at once, with a loop over sections and tendons only:

- tension mode: the tendons passing through section ``j`` give the moment
  ``m_j = sum_i T_i d_ij (cos sigma_i, sin sigma_i)``; curvature ``|m_j| / EI_j`` (``EI_j`` at
  mid-section), bending plane ``atan2(m_y, m_x)`` (0 for a straight section), arc length the
  undeformed section length;
- length mode: the sections are peeled from the base outwards, each section's arc from its own
  tendons' lengths (:func:`workbench.kinematics.arc_from_tendon_lengths`, or the planar closed
  form for an antagonistic pair), minus what the section's arcs consume of the outer tendons;
- ``d_ij`` is the mean offset over section ``j`` of a tendon terminating in section ``i``: a
  tapered group's offset varies linearly over the tendon's whole routed length (the rule of
  :mod:`workbench.models.cc`).

Positions are in the robot's base frame [m]; backbone stations are reference arc lengths mapped
section-wise onto the (in length mode stretched) arcs, as ``cc.run`` does.  Gravity, payload
and tip loads are ignored (CC).  Checked row by row against ``cc.run`` by
``tests/models/test_cc_batch.py``; timed by ``benchmarks/bench_cc_batch.py``.
"""

from __future__ import annotations

import numpy as np

from ..kinematics import arc_from_tendon_lengths, forward_kinematics, section_transform
from ..robot import Robot

__all__ = ["cc_arcs", "cc_backbones", "cc_tip_frames", "cc_tip_positions"]

_MODES = ("tension", "length")


def _check(robot: Robot, mode: str, commands) -> np.ndarray:
    """The commands as a float ``(n, n_tendons)`` array; one ``ValueError`` line for bad input."""
    if not isinstance(robot, Robot):
        raise TypeError(f"robot must be a workbench.Robot, got {type(robot).__name__}")
    if mode not in _MODES:
        raise ValueError(f"mode must be 'tension' or 'length', got {mode!r}")
    cmds = np.asarray(commands, dtype=float)
    m = robot.n_tendons
    if cmds.ndim != 2 or cmds.shape[1] != m:
        raise ValueError(f"commands must have shape (n, {m}) (one column per tendon of robot.tendon_table()), "
                         f"got {cmds.shape}")
    bad = ~np.all(np.isfinite(cmds), axis=1)
    if np.any(bad):
        raise ValueError(f"commands must be finite; row {int(np.argmax(bad))} is not")
    return cmds


def _offsets(robot: Robot) -> np.ndarray:
    """``d[i, j]``: mean offset [m] of tendon ``i`` over section ``j`` (0 where the tendon does not pass)."""
    table = robot.tendon_table()
    ends = robot.section_ends
    d = np.zeros((len(table), robot.n_sections))
    for i, (sec, _sigma, group) in enumerate(table):
        for j in range(sec + 1):
            start = ends[j - 1] if j > 0 else 0.0
            d[i, j] = group.offset_at(0.5 * (start + ends[j]) / ends[sec])
    return d


def _tension_arcs(robot: Robot, cmds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    table = robot.tendon_table()
    sig = np.array([t[1] for t in table])
    d = _offsets(robot)
    n = cmds.shape[0]
    kappa = np.zeros((n, robot.n_sections))
    phi = np.zeros((n, robot.n_sections))
    for j in range(robot.n_sections):
        ei = robot.sections[j].cross_section_at(0.5).EI
        mx = cmds @ (d[:, j] * np.cos(sig))
        my = cmds @ (d[:, j] * np.sin(sig))
        kappa[:, j] = np.hypot(mx, my) / ei
        phi[:, j] = np.where(kappa[:, j] > 0, np.arctan2(my, mx), 0.0)
    ell = np.broadcast_to(robot.section_lengths, kappa.shape).copy()
    return kappa, phi, ell


def _length_arcs(robot: Robot, cmds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    table = robot.tendon_table()
    sec_of = np.array([t[0] for t in table])
    sig_all = np.array([t[1] for t in table])
    d = _offsets(robot)
    ell0 = robot.section_lengths
    n, ns = cmds.shape[0], robot.n_sections
    kappa, phi, ell = np.zeros((n, ns)), np.zeros((n, ns)), np.zeros((n, ns))
    consumed = np.zeros_like(cmds)
    for j in range(ns):
        idx = np.flatnonzero(sec_of == j)
        if idx.size == 0:
            raise ValueError(f"length mode needs tendons terminating in every section; section {j} has none")
        sig = sig_all[idx]
        lengths = ell0[j] + cmds[:, idx] - consumed[:, idx]
        if idx.size == 2 and np.isclose(abs(np.angle(np.exp(1j * (sig[1] - sig[0])))), np.pi):
            # antagonistic pair: planar closed form (the out-of-plane component is unobservable)
            ell[:, j] = lengths.mean(axis=1)
            kc = (lengths[:, 1] - lengths[:, 0]) / (2.0 * d[idx[0], j] * ell[:, j])
            kappa[:, j] = np.abs(kc)
            phi[:, j] = np.where(kc >= 0, sig[0], sig[0] + np.pi)
        else:
            try:
                kappa[:, j], phi[:, j], ell[:, j] = arc_from_tendon_lengths(lengths, sig, d[idx[0], j])
            except ValueError as exc:
                raise ValueError(f"section {j}: {exc}") from None
        outer = np.flatnonzero(sec_of > j)
        if outer.size:
            kd = kappa[:, j, None] * d[outer, j]
            if np.any(np.abs(kd) >= 1.0):
                row = int(np.argmax(np.any(np.abs(kd) >= 1.0, axis=1)))
                raise ValueError(f"row {row}: |kappa| * d must be < 1 in section {j}: a tendon cannot reach "
                                 f"the centre of curvature")
            li = ell[:, j, None] * (1.0 - kd * np.cos(sig_all[outer] - phi[:, j, None]))
            consumed[:, outer] += li - ell0[j]
    phi = np.where(kappa > 0, np.angle(np.exp(1j * phi)), 0.0)
    return kappa, phi, ell


def cc_arcs(robot: Robot, mode: str, commands) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The CC arc of every section for every row of commands.

    Parameters
    ----------
    robot : Robot
    mode : {"tension", "length"}
        Tension [N] or change of free length [m] per tendon (:class:`workbench.robot.TendonActuation`).
    commands : array_like, shape (n, n_tendons)
        One row per sample, columns in ``robot.tendon_table()`` order.

    Returns
    -------
    kappa, phi, ell : ndarray, shape (n, n_sections)
        Curvature [1/m], bending-plane angle [rad], arc length [m]: row ``r`` equals
        ``cc.arc_from_actuation(robot, TendonActuation(mode, commands[r]))``.
    """
    cmds = _check(robot, mode, commands)
    return _tension_arcs(robot, cmds) if mode == "tension" else _length_arcs(robot, cmds)


def cc_tip_frames(robot: Robot, mode: str, commands) -> np.ndarray:
    """CC tip frames ``(n, 4, 4)`` in the base frame (translation in m); row ``r`` equals ``cc.run``'s ``tip_frame``."""
    kappa, phi, ell = cc_arcs(robot, mode, commands)
    return forward_kinematics(kappa, phi, ell)


def cc_tip_positions(robot: Robot, mode: str, commands) -> np.ndarray:
    """CC tip positions ``(n, 3)`` [m] in the base frame; row ``r`` equals ``cc.run``'s ``tip_position``."""
    return cc_tip_frames(robot, mode, commands)[:, :3, 3]


def cc_backbones(robot: Robot, mode: str, commands, n_stations: int) -> np.ndarray:
    """CC backbone points ``(n, n_stations, 3)`` [m] in the base frame at evenly spaced reference stations.

    Station ``q`` is the reference arc length ``q L / (n_stations - 1)``, mapped section-wise onto
    the row's arcs (stretched in length mode); row ``r`` equals ``cc.run``'s ``positions`` with
    ``SolverOptions(n_stations=n_stations)``.
    """
    if isinstance(n_stations, bool) or not isinstance(n_stations, (int, np.integer)) or n_stations < 2:
        raise ValueError(f"n_stations must be an integer >= 2, got {n_stations!r}")
    kappa, phi, ell = cc_arcs(robot, mode, commands)
    n, ns = kappa.shape
    stations = np.linspace(0.0, robot.length, int(n_stations))
    starts0 = np.concatenate([[0.0], robot.section_ends[:-1]])
    ell0 = robot.section_lengths
    # a station on a section boundary belongs to the next section (same point either way)
    owner = np.clip(np.sum(starts0[None, :] <= stations[:, None], axis=1) - 1, 0, ns - 1)
    out = np.empty((n, stations.size, 3))
    base = np.broadcast_to(np.eye(4), (n, 4, 4))
    ends = section_transform(kappa, phi, ell)  # (n, ns, 4, 4)
    for j in range(ns):
        q = np.flatnonzero(owner == j)
        if q.size:
            frac = np.clip((stations[q] - starts0[j]) / ell0[j], 0.0, 1.0)
            local = section_transform(kappa[:, j, None], phi[:, j, None], ell[:, j, None] * frac)  # (n, m, 4, 4)
            out[:, q, :] = (np.einsum("rab,rqb->rqa", base[:, :3, :3], local[:, :, :3, 3])
                            + base[:, None, :3, 3])
        base = base @ ends[:, j]
    return out
