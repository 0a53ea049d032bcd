"""Shooting for the clamped tendon rod: Newton on the base wrench, the load ramp (numpy/scipy).

Unknowns: the total force and moment at the clamp, ``x = (N(0), M(0))``.  Residual: the tip
conditions ``N(L) = F_tip + W``, ``M(L) = M_tip + (R(L) o) x W_p`` (tip loads, the weight ``W``
of the payload ``W_p`` at offset ``o`` in the tip frame and of a disk at the tip), scaled by a
force scale ``F_s`` and by ``F_s L``.  One Newton iteration integrates seven shots as one batch
(the iterate and six forward-difference perturbations share every integration step, so the
difference quotients see one discretisation); the step is backtracked until the residual norm
falls.  With eyelets (:mod:`.eyelets`: the unknowns are the rod's own clamp wrench, a shot iterates
its chords) the Jacobian is kept and updated by Broyden's rank-one formula while steps halve the
residual (one shot per iteration), and a fresh one is taken otherwise.  Large loads are reached with the common load ramp (:func:`workbench.physics._stepping.load_ramp`:
external loads and tendon tensions move together along a straight path from the last converged
point; the first attempt is the whole way, a failure halves the increment, growth is capped at the
load still to go), each Newton started from a secant predictor.  Each accepted solve reports its
load-path measure (:meth:`Shooter.path_point`: tip position / L, tip tangent, and the sign of the
shooting Jacobian's determinant, which changes where the rod's tangent stiffness loses
definiteness); the ramp rejects a step that jumps or flips that sign (no cap on the motion of a
step: the sign catches a first step that lands on a curled, unstable branch), so the solve follows
the branch loaded from the straight rod.  Checked by ``tests/physics/test_cosserat_model.py`` and
``tests/physics/test_load_path.py`` (the branch-jump case of issue 28).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._stepping import LoadRampInfo, PathPoint, RampExhausted, RampPolicy, RampStalled, load_ramp
from .eyelets import EyeletRoute, integrate_eyelets, straight_tendon_wrench
from .problem import RodProblem
from .rod import cross, integrate_segments

__all__ = ["Shooter", "ShootingFailure", "straight_rod_base_wrench"]

_POLICY = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="remaining", min_increment=1e-6,
                     max_motion=math.inf)
_MAX_NEWTON = 15


class ShootingFailure(RuntimeError):
    """A shooting solve or the load ramp did not converge."""


@dataclass(frozen=True)
class _Point:
    """A converged state: external-load factor, applied tensions [N], base wrench (6,)."""

    lam: float
    tau: np.ndarray
    x: np.ndarray


def straight_rod_base_wrench(pb: RodProblem, lam: float) -> np.ndarray:
    """``(6,)`` clamp reaction ``(N(0), M(0))`` of the straight rod under ``lam`` x the external
    loads (tendons are internal: they do not change it).  The Newton predictor at the first step."""
    e3 = np.array([0.0, 0.0, pb.length])
    Wp = pb.payload_mass * pb.gravity
    F = pb.tip_force + Wp + pb.point_forces.sum(0)
    M = pb.tip_torque + cross(e3, pb.tip_force) + cross(e3 + pb.payload_offset, Wp)
    arms = np.zeros((pb.breakpoints.size, 3))
    arms[:, 2] = pb.breakpoints
    M = M + cross(arms, pb.point_forces).sum(0)
    for s0, ls, m0, m1 in zip(pb.section_starts, pb.section_lengths, pb.mass_per_length0, pb.mass_per_length1):
        mass = 0.5 * (m0 + m1) * ls
        first = ls / 6.0 * (s0 * m0 + 4.0 * (s0 + 0.5 * ls) * 0.5 * (m0 + m1) + (s0 + ls) * m1)  # Simpson
        F = F + mass * pb.gravity
        M = M + cross(np.array([0.0, 0.0, first]), pb.gravity)
    return lam * np.concatenate([F, M])


class Shooter:
    """The shooting state of one solve: the converged points of the current load path.

    Parameters
    ----------
    pb : RodProblem
    tol : float
        Required max-norm of the scaled tip residual; DOP853 runs at ``rtol = tol / 10``
        (not below 1e-13).
    compiled : bool, optional
        Right-hand side by the numba kernel (default: where numba is installed) or numpy
        (:func:`~workbench.physics.cosserat.rod.integrate_segments`).
    route : EyeletRoute, optional
        Eyelet routing (:mod:`.eyelets`): the unknowns are then the rod's own clamp wrench and the
        shots are :func:`~workbench.physics.cosserat.eyelets.integrate_eyelets`; ``None``: continuous
        tendons.
    """

    def __init__(self, pb: RodProblem, tol: float, compiled: bool | None = None,
                 route: EyeletRoute | None = None) -> None:
        self.pb = pb
        self.route = route
        self.compiled = compiled
        self.tol = float(tol)
        self.rtol = max(1e-13, 0.1 * self.tol)
        self.point = _Point(0.0, np.zeros(pb.n_tendons), np.zeros(6))
        self.newton_iterations = 0
        self.shots = 0
        self.attempts = 0  # load-ramp attempts of every go_to, failed ones included
        self.sign = 0  # sign of det of the shooting Jacobian at the last converged Newton solve
        self.ramps: list[LoadRampInfo] = []  # every go_to's ramp outcome, in order
        self._tip = np.zeros(0)

    def _scales(self, lam: float, tau: np.ndarray) -> tuple[float, float]:
        pb = self.pb
        g = float(np.abs(pb.gravity).max())
        weight = g * (float(np.sum(pb.mass_per_length0 * pb.section_lengths)) + pb.payload_mass)
        fs = max(lam * (weight + float(np.abs(pb.point_forces).sum()) + float(np.abs(pb.tip_force).max())),
                 float(np.sum(tau)), lam * float(np.abs(pb.tip_torque).max()) / pb.length,
                 1e-6 * float(pb.stiffness0[:, 3].min()) / pb.length**2)
        return fs, fs * pb.length

    def residual(self, X: np.ndarray, lam: float, tau: np.ndarray) -> np.ndarray:
        """Scaled tip residuals ``(B, 6)`` of base wrenches ``X`` ``(B, 6)`` at load ``(lam, tau)``."""
        if self.route is None:
            tip, _ = integrate_segments(self.pb, X, tau, lam, self.rtol, compiled=self.compiled)
        else:
            tip, _, _ = integrate_eyelets(self.pb, self.route, X, tau, lam, self.rtol, compiled=self.compiled)
        self.shots += X.shape[0]
        self._tip = tip[0]
        return self.tip_residual(tip, lam, tau)

    def tip_residual(self, tip: np.ndarray, lam: float, tau: np.ndarray) -> np.ndarray:
        """Scaled tip residuals ``(B, 6)`` of integrated tip states ``tip`` ``(B, n_state)``."""
        pb = self.pb
        Wp = lam * pb.payload_mass * pb.gravity
        arm = np.einsum("bij,j->bi", tip[:, 3:12].reshape(-1, 3, 3), pb.payload_offset)
        F = lam * (pb.tip_force + pb.point_forces[-1]) + Wp
        M = lam * pb.tip_torque + cross(arm, Wp)
        fs, ms = self._scales(lam, tau)
        return np.concatenate([(tip[:, 12:15] - F) / fs, (tip[:, 15:18] - M) / ms], axis=1)

    def newton(self, x: np.ndarray, lam: float, tau: np.ndarray) -> np.ndarray:
        """Base wrench ``(6,)`` meeting the tip conditions at ``(lam, tau)``, from the guess ``x``.

        Raises
        ------
        ShootingFailure
            No convergence in 15 iterations, a failed line search or a failed integration.
        """
        fs, ms = self._scales(lam, tau)
        scale = np.array([fs, fs, fs, ms, ms, ms])
        if self.route is not None:
            return self._broyden(x, lam, tau, scale)
        try:
            for _ in range(_MAX_NEWTON):
                h = 1e-7 * np.maximum(np.abs(x), scale)
                res = self.residual(np.vstack([x, x + np.diag(h)]), lam, tau)
                r0 = res[0]
                if not np.all(np.isfinite(res)):
                    raise ShootingFailure("non-finite tip residual")
                J = ((res[1:] - r0) / h[:, None]).T
                if np.max(np.abs(r0)) <= self.tol:
                    self.sign = int(np.sign(np.linalg.det(J)))
                    return x
                self.newton_iterations += 1
                dx = np.linalg.solve(J, -r0)
                x = self._line_search(x, dx, r0, lam, tau)
        except (RuntimeError, np.linalg.LinAlgError) as err:
            raise ShootingFailure(str(err)) from err
        raise ShootingFailure(f"no convergence in {_MAX_NEWTON} Newton iterations")

    def _jacobian(self, x: np.ndarray, lam: float, tau: np.ndarray, scale: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Residual and forward-difference Jacobian at ``x`` (seven shots in one batch)."""
        h = 1e-7 * np.maximum(np.abs(x), scale)
        res = self.residual(np.vstack([x, x + np.diag(h)]), lam, tau)
        if not np.all(np.isfinite(res)):
            raise ShootingFailure("non-finite tip residual")
        return res[0], ((res[1:] - res[0]) / h[:, None]).T

    def _broyden(self, x: np.ndarray, lam: float, tau: np.ndarray, scale: np.ndarray) -> np.ndarray:
        """Newton with Broyden's (good) rank-one updates of the difference Jacobian: a step that at
        least halves the residual norm updates the Jacobian (one shot per iteration instead of seven);
        any other step falls back to a fresh difference Jacobian and the backtracking line search.
        Used with eyelets, whose shots cost more (the chords are iterated per segment)."""
        try:
            r0, J = self._jacobian(x, lam, tau, scale)
            fresh = True
            for _ in range(3 * _MAX_NEWTON):
                if np.max(np.abs(r0)) <= self.tol:
                    self.sign = int(np.sign(np.linalg.det(J)))
                    return x
                self.newton_iterations += 1
                dx = np.linalg.solve(J, -r0)
                ra = self.residual((x + dx)[None], lam, tau)[0]
                if np.all(np.isfinite(ra)) and np.linalg.norm(ra) <= 0.5 * np.linalg.norm(r0):
                    J = J + np.outer(ra - r0 - J @ dx, dx) / (dx @ dx)
                    x, r0, fresh = x + dx, ra, False
                    continue
                if fresh:
                    x = self._line_search(x, dx, r0, lam, tau)
                r0, J = self._jacobian(x, lam, tau, scale)
                fresh = True
        except (RuntimeError, np.linalg.LinAlgError) as err:
            raise ShootingFailure(str(err)) from err
        raise ShootingFailure(f"no convergence in {3 * _MAX_NEWTON} Broyden iterations")

    def _line_search(self, x, dx, r0, lam, tau) -> np.ndarray:  # noqa: ANN001
        n0 = np.linalg.norm(r0)
        a = 1.0
        for _ in range(8):
            xa = x + a * dx
            ra = self.residual(xa[None], lam, tau)[0]
            if np.all(np.isfinite(ra)) and np.linalg.norm(ra) < (1.0 - 1e-4 * a) * n0:
                return xa
            a *= 0.5
        raise ShootingFailure("line search failed to reduce the tip residual")

    def straight(self, lam: float, tau: np.ndarray) -> np.ndarray:
        """``(6,)`` the unknowns on the straight rod under ``lam`` x the external loads and tensions
        ``tau`` (the tendons count only with eyelets, where the unknowns are the rod's own wrench)."""
        x = straight_rod_base_wrench(self.pb, lam)
        return x if self.route is None else x + straight_tendon_wrench(self.route, tau)

    def path_point(self) -> PathPoint:
        """The load-path measure of the last converged state: tip position / L and tip tangent,
        with the sign of the shooting Jacobian's determinant (the last integrated shot's tip)."""
        tip = self._tip
        return PathPoint(tuple(np.concatenate([tip[0:3] / self.pb.length, tip[3:12].reshape(3, 3)[:, 2]])),
                         self.sign)

    def go_to(self, tau: np.ndarray, max_attempts: int, guess: np.ndarray | None = None) -> int:
        """Follow the straight load path from the last converged point to the full external
        load with tensions ``tau`` [N]; returns the number of ramp attempts.  ``guess``: the
        unknowns' predictor for a first attempt that goes the whole way (else the straight rod's).

        Raises
        ------
        ShootingFailure
            More than ``max_attempts`` attempts, or the increment fell below 1e-6.
        """
        start = self.point
        tau = np.asarray(tau, dtype=float)
        path: list[tuple[float, np.ndarray]] = [(0.0, start.x)]

        def predict(t: float, lam: float, ta: np.ndarray) -> np.ndarray:
            if guess is not None and len(path) == 1 and t == 1.0:
                return np.asarray(guess, dtype=float)
            if len(path) >= 2:
                (ta, xa), (tb, xb) = path[-2], path[-1]
                return xb + (t - tb) / (tb - ta) * (xb - xa)
            return start.x + self.straight(lam, ta) - self.straight(start.lam, start.tau)

        def attempt(t: float) -> bool | PathPoint:
            lam = start.lam + t * (1.0 - start.lam)
            ta = start.tau + t * (tau - start.tau)
            self.attempts += 1
            try:
                x = self.newton(predict(t, lam, ta), lam, ta)
            except ShootingFailure:
                return False
            path.append((t, x))
            self.point = _Point(lam, ta, x)
            return self.path_point()

        def restore(saved) -> None:  # noqa: ANN001
            n, point = saved
            del path[n:]
            self.point = point

        try:
            info = load_ramp(attempt, lambda: (len(path), self.point), restore, max_attempts=max_attempts,
                             policy=_POLICY, start=self._start_point())
        except RampExhausted as err:
            raise ShootingFailure(f"load ramp exceeded max_load_steps={max_attempts} "
                                  f"(reached {err.lam:.4g} of the way)") from None
        except RampStalled as err:
            raise ShootingFailure(f"load ramp stalled at {err.lam:.4g} of the way (increment below 1e-6)") from None
        self.ramps.append(info)
        return info.attempts

    def _start_point(self) -> PathPoint:
        """The path measure of the current point (one shot; the straight rod at the unloaded start)."""
        p = self.point
        if p.lam == 0.0 and not np.any(p.tau) and not np.any(p.x):
            return PathPoint((0.0, 0.0, 1.0, 0.0, 0.0, 1.0), 1)
        self.residual(p.x[None], p.lam, p.tau)
        return self.path_point()

    @property
    def x(self) -> np.ndarray:
        """The last converged base wrench ``(6,)``."""
        return self.point.x
