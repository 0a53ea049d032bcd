"""Warm starts of the Cosserat shooting: continue the load ramp from a solve at a fraction of the same load.

A cold solve ramps every load -- tip force and torque, tendon tensions and the weights -- along
the straight path ``lam (W, F, M, T)``, ``lam`` from 0 to 1 (:meth:`~.shooting.Shooter.go_to`).  A warm
start takes the converged state of an earlier solve of the same rod whose load was ``c (W, F, M, T)``
for some ``0 < c <= 1`` (the same load ray) and continues the same ramp from ``lam = c`` to 1: the
path is the tail of the cold path (from the unloaded rod, through the neighbour's load), so the
answer is the one the load path from the unloaded state reaches.  Other states are refused
(:func:`decode` returns ``None``).  Off the ray, a straight path between two loads can reach another
stable equilibrium than the cold ramp without any event on the way (on the branch-jump robot of
``tests/physics/test_load_path.py``, Newton from an off-ray neighbour's state lands on a curled
branch: ``tests/models/test_warm_cosserat.py``).  From a larger load
(``c > 1``) the path runs backwards and inherits whatever branch the larger load's solve reached.
With gravity on a rod with mass the weights fix ``c = 1`` (the same load).  Tendons alone (no
weight, tip force or torque) are solved cold: the base wrench is then 0, the cold Newton's first
guess exact.

Load-path safety: a state is offered (:func:`encode`, called by
:func:`~workbench.physics.cosserat.model.run`) only from a solve whose load path had no event and
whose shooting Jacobian kept the straight rod's sign; the warm ramp starts there with that sign and
the same path checks, its first step checked against the secant of the cold path
(:class:`RayShooter`: the ramp has no secant for a first step, and one long step along the ray
can land on another branch; ``tests/models/test_warm.py`` chains the branch-jump load to 1.4 x and
compares with a continuation), and the model solves cold when it fails or records an event.

The state: ``[1, L, n_t, fingerprint, W (3), F (3), M (3), T (n_t), x (6)]`` with ``W`` the total
weight of rod, disks and payload, ``fingerprint`` the sum of the stiffnesses and tendon offsets (a
different rod is refused) and ``x`` the base wrench.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...models.warm import leaves_secant, ray_fraction
from .._stepping import RampPolicy
from .problem import RodProblem
from .shooting import Shooter, ShootingFailure

__all__ = ["RayShooter", "WarmAbandoned", "encode", "decode", "go_from"]

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


def decode(pb: RodProblem, state: np.ndarray | None,
           tensions: np.ndarray) -> tuple[float, np.ndarray, np.ndarray] | None:
    """``(c, neighbour's tensions, neighbour's base wrench)`` when ``state`` is of the same rod at
    ``c`` times this load (``pb`` under ``tensions``), ``0 < c <= 1``; ``None`` otherwise."""
    if state is None:
        return None
    s = np.asarray(state, dtype=float).reshape(-1)
    n = pb.n_tendons
    if s.size != 19 + n or not np.all(np.isfinite(s)) or not np.array_equal(s[:4], _head(pb)):
        return None
    v = _load(pb, tensions)
    if not np.any(v[:9]):  # tendons alone: the base wrench is 0, the cold solve exact in one Newton check
        return None
    c = ray_fraction(s[4:13 + n], v, _RAY_RTOL)
    if c is None:
        return None
    return c, s[13:13 + n], s[13 + n:]


class WarmAbandoned(RuntimeError):
    """The first warm step kept leaving the secant of the cold path: solve cold."""


class RayShooter(Shooter):
    """A :class:`~.shooting.Shooter` that starts at a neighbour's state ``c x`` the load and checks
    the first step from there.

    The ramp (:func:`workbench.physics._stepping.load_ramp`) checks a step against the secant of the
    last two accepted points and has only one (the start) before the first step; the cold path
    gives the second: the unloaded straight rod at ``lam = 0``.  A first step whose path measure
    lands farther than ``max(jump_ratio |predicted move|, jump_floor)`` (the ramp's own rule) from
    that secant is a failed attempt (the ramp halves it); after ``tries`` such attempts the warm
    start is abandoned (:class:`WarmAbandoned`).
    """

    tries = 3

    def __init__(self, pb: RodProblem, tol: float, c: float, compiled: bool | None = None) -> None:
        super().__init__(pb, tol, compiled)
        self.c = float(c)
        self.rejected = 0
        self._m0 = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 1.0])  # the straight rod: tip / L, tip tangent
        self._mc: np.ndarray | None = None

    def start_at(self, start: tuple[float, np.ndarray, np.ndarray]) -> None:
        """Make the neighbour's equilibrium ``start`` (:func:`decode`) the converged point."""
        c, tau, x = start
        self.point = dataclasses.replace(self.point, lam=c, tau=np.array(tau), x=np.array(x))
        self.sign = 1  # the neighbour kept the straight rod's sign (encode is only called then)
        self._mc = None  # measured by go_to's shot at its start point, before the first Newton

    def newton(self, x: np.ndarray, lam: float, tau: np.ndarray) -> np.ndarray:
        """:meth:`Shooter.newton`; while the ramp is still at its start, from the secant predictor
        through the unloaded rod (``x(lam) = x(c) lam / c``) and followed by the secant check."""
        first = self.point.lam == self.c
        if first and self._mc is None:  # the last shot is go_to's of the start point
            self._mc = np.asarray(self.path_point().measure)
        x = super().newton(self.point.x * (lam / self.c) if first else x, lam, tau)
        if not first:
            return x
        rule = RampPolicy()
        if leaves_secant(self._m0, self._mc, self.c, lam, self.path_point().measure, rule.jump_ratio, rule.jump_floor):
            self.rejected += 1
            if self.rejected >= self.tries:
                raise WarmAbandoned("the first warm step left the cold path's secant")
            raise ShootingFailure("the first warm step left the cold path's secant")
        return x


def go_from(shooter: RayShooter, start: tuple[float, np.ndarray, np.ndarray], tensions: np.ndarray,
            max_attempts: int) -> int:
    """Ramp ``shooter`` (a fresh one) from the neighbour's equilibrium ``start`` (:func:`decode`) to
    its full load under ``tensions``; returns the ramp attempts (:meth:`~.shooting.Shooter.go_to`).

    Raises
    ------
    ShootingFailure, WarmAbandoned
        The ramp failed, or its first step kept leaving the cold path (the caller solves cold).
    """
    shooter.start_at(start)
    return shooter.go_to(tensions, max_attempts)
