"""Warm starts of the Cosserat shooting: continue the load ramp from a solve at a smaller or larger
multiple of the same load.

A cold solve ramps every load -- tip force and torque, tendon tensions and the weights -- along
the straight path ``lam (W, F, M, T)``, ``lam`` from 0 to 1 (:meth:`~.shooting.Shooter.go_to`).  A warm
start takes the converged state of an earlier solve of the same rod whose load was ``c (W, F, M, T)``
for some ``c > 0`` (the same load ray) and continues the same ramp from ``lam = c`` to 1: the path
is the cold path's own (from the unloaded rod, through the neighbour's load), so the answer is the
one the load path from the unloaded state reaches.  A neighbour off the ray is refused
(:func:`decode` returns ``None``): between two loads on different rays a straight path can reach
another stable equilibrium than the cold ramp without any event on the way (measured on the
branch-jump robot of ``tests/physics/test_load_path.py``: random neighbours led Newton and the
ramp to a state 0.8 L from the load-path answer; ``tests/models/test_warm_cosserat.py``).  With
gravity on a rod with mass the weights fix ``c = 1`` (the same load).

Load-path safety: a state is offered (:func:`encode`, called by
:func:`~workbench.physics.cosserat.model.run`) only from a solve whose load path had no event and
whose shooting Jacobian kept the straight rod's sign; the warm ramp starts there with that sign and
the same path checks, and the model solves cold when it fails or records an event.

The state: ``[1, L, n_t, fingerprint, W (3), F (3), M (3), T (n_t), x (6)]`` with ``W`` the total
weight of rod, disks and payload, ``fingerprint`` the sum of the stiffnesses and tendon offsets (a
different rod is refused) and ``x`` the base wrench.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .problem import RodProblem
from .shooting import Shooter

__all__ = ["encode", "decode", "go_from"]

_VERSION = 1.0
_RAY_RTOL = 1e-9


def _weight(pb: RodProblem) -> np.ndarray:
    mass = float(np.sum(0.5 * (pb.mass_per_length0 + pb.mass_per_length1) * pb.section_lengths)) + pb.payload_mass
    return mass * pb.gravity + pb.point_forces.sum(0)


def _head(pb: RodProblem) -> np.ndarray:
    fingerprint = float(np.sum(pb.stiffness0) + np.sum(pb.stiffness1) + np.sum(pb.tendon_offsets))
    return np.array([_VERSION, pb.length, pb.n_tendons, fingerprint])


def _load(pb: RodProblem, tensions: np.ndarray) -> np.ndarray:
    return np.concatenate([_weight(pb), pb.tip_force, pb.tip_torque, np.asarray(tensions, dtype=float)])


def encode(pb: RodProblem, tensions: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The warm state of the equilibrium with base wrench ``x`` of ``pb`` under ``tensions``."""
    return np.concatenate([_head(pb), _load(pb, tensions), np.asarray(x, dtype=float)])


def decode(pb: RodProblem, state: np.ndarray | None, tensions: np.ndarray) -> tuple[float, np.ndarray, np.ndarray] | None:
    """``(c, neighbour's tensions, neighbour's base wrench)`` when ``state`` is of the same rod at
    ``c > 0`` times this load (``pb`` under ``tensions``); ``None`` otherwise."""
    if state is None:
        return None
    s = np.asarray(state, dtype=float).reshape(-1)
    n = pb.n_tendons
    if s.size != 19 + n or not np.all(np.isfinite(s)) or not np.array_equal(s[:4], _head(pb)):
        return None
    v, w = _load(pb, tensions), s[4:13 + n]
    vv = float(v @ v)
    if vv == 0.0:
        return None
    c = float(w @ v) / vv
    if not c > 0.0 or np.linalg.norm(w - c * v) > _RAY_RTOL * np.linalg.norm(w):
        return None
    return c, s[13:13 + n], s[13 + n:]


def go_from(shooter: Shooter, start: tuple[float, np.ndarray, np.ndarray], tensions: np.ndarray,
            max_attempts: int) -> int:
    """Ramp ``shooter`` (a fresh one) from the neighbour's equilibrium ``start`` (:func:`decode`) to
    its full load under ``tensions``; returns the ramp attempts (:meth:`~.shooting.Shooter.go_to`,
    whose :class:`~.shooting.ShootingFailure` propagates)."""
    c, tau, x = start
    shooter.point = dataclasses.replace(shooter.point, lam=c, tau=np.array(tau), x=np.array(x))
    shooter.sign = 1  # the neighbour kept the straight rod's sign (encode is only called then)
    return shooter.go_to(tensions, max_attempts)
