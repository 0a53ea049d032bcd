"""Which IK solution branch a converged state lies on, and the walk from home that stays on it.

The sign of ``det d(balance)/dL`` names the branch; a sign change along a path marks a fold or
bifurcation of the IK branch (the workspace boundary of the branch connected to home).
:class:`HomeReference` is that sign (and the IK) at the home pose; :func:`walk_from_home` is the
pose continuation home -> target of :func:`~workbench.physics.series_parallel.module_inverse`,
rejecting steps that land on another branch.  Checked by ``test_rx_limit_is_a_fold_of_the_ik_branch``,
``test_ik_stops_at_the_fold_instead_of_changing_branch`` and ``test_home_cache_gives_the_same_answer_with_fewer_leg_solves``
(``tests/physics/test_series_parallel.py``); the measured folds are in ``docs/models.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, NamedTuple

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from .._stepping import continuation
from .geometry import interp_pose, home_pose, rotation_vector
from .leg import leg_solve
from .newton import platform_balance, ik_newton
from .predictor import hermite_lengths


class BranchCheckError(RuntimeError):
    """A branch check could not be made (the home IK or a Jacobian leg solve failed)."""


class HomeReference(NamedTuple):
    """The branch check's reference: the IK of the home pose under the same loads and settings.

    A tuple, as the values of ``module_inverse(..., home_cache=)`` always were.

    Attributes
    ----------
    lengths : ndarray, shape (6,)
        Home insertion lengths [m].
    legs : list of LegSolution
        The six legs at home.
    sign : float
        Sign of ``det d(balance)/dL`` at home (names the branch).
    smallest_singular_value : float
        Of ``diag(1, 1, 1, 1/r, 1/r, 1/r) d(balance)/dL`` at home [N/m].
    """

    lengths: np.ndarray
    legs: list
    sign: float
    smallest_singular_value: float


def home_reference(geometry, kw, max_iterations: int, cache: dict) -> HomeReference:
    """The :class:`HomeReference` for these loads and settings, from ``cache`` or solved and stored there.

    ``kw`` are the Newton settings of :func:`ik_newton` (``w``, ``g``, ``n_el``, tolerances,
    ``fd_step``, ``counter``); the cache key is the geometry, the loads and those settings.
    Raises :class:`BranchCheckError` when the home IK fails (nothing is stored then).
    """
    key = (geometry, None if kw["w"] is None else kw["w"].tobytes(), None if kw["g"] is None else kw["g"].tobytes(),
           kw["n_el"], kw["length_tolerance"], kw["leg_tolerance"], kw["fd_step"])
    if key not in cache:
        H = home_pose(geometry)
        Lh, legs_h, okh, _, _, msgh = ik_newton(geometry, H, hermite_lengths(geometry, H), None,
                                                max_iterations=max_iterations, **kw)
        if not okh:
            raise BranchCheckError(f"branch check: IK of the home pose failed: {msgh}")
        cache[key] = HomeReference(Lh, legs_h, *branch_sign(geometry, H, Lh, legs_h, kw, kw["counter"], with_smin=True))
    return cache[key]


@dataclass(frozen=True)
class Walk:
    """Outcome of :func:`walk_from_home`.

    Attributes
    ----------
    success : bool
    lengths : ndarray, shape (6,) or None
        Insertion lengths at the target [m] (None unless ``success``).
    legs : list of LegSolution or None
    residual : ndarray, shape (6,) or None
        Platform balance at the target [N, N m].
    iterations : int
        Newton iterations of all steps.
    reason : str
        Failure reason, "" on success.
    """

    success: bool
    lengths: np.ndarray | None
    legs: list | None
    residual: np.ndarray | None
    iterations: int
    reason: str


def walk_from_home(geometry, T, kw, *, home: Callable[[], HomeReference] | None, path_steps: int | None,
                   max_iterations: int) -> Walk:
    """Pose continuation of the module IK along the SE(3) path from the home pose to ``T``.

    Every step solves :func:`ik_newton` at the next pose on the path (rotation by slerp,
    translation linear), started from the last lengths shifted by the change of the Hermite
    lengths and from the last legs (:func:`workbench.physics._stepping.continuation`: first step ``1/n``, growing by
    1.5 up to ``2/n``, stall below ``1/(16 n)``; ``n = path_steps`` or about one step per 40 mm
    and 0.1 rad).  With ``home`` (the branch check on) the walk starts from the home IK and a
    converged step whose branch sign differs from home's is a failed step (a smaller one may stay
    on the branch); without it, from the Hermite home lengths.
    """
    H = home_pose(geometry)
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([H[:3, :3], T[:3, :3]])))
    n_steps = path_steps if path_steps else max(
        2, int(math.ceil(np.linalg.norm(T[:3, 3] - H[:3, 3]) / 0.04 + np.linalg.norm(rotation_vector(H[:3, :3].T @ T[:3, :3])) / 0.1))
    )
    try:
        ref = home() if home is not None else HomeReference(hermite_lengths(geometry, H), None, 0.0, 0.0)
    except BranchCheckError as e:
        return Walk(False, None, None, None, 0, str(e))
    Lc, legs_c, r_c = ref.lengths, ref.legs, None
    its, msgn, off_branch_seen = 0, "", False  # off_branch_seen: the last step converged on another branch

    def step(lam, lt):
        nonlocal Lc, legs_c, r_c, its, msgn, off_branch_seen
        Tt = interp_pose(H, T, slerp, lt)
        # predictor: previous L shifted by the change of the Hermite lengths
        Lg = Lc + (hermite_lengths(geometry, Tt) - hermite_lengths(geometry, interp_pose(H, T, slerp, lam)))
        Ln, legs_n, okn, itn, rn, msgn = ik_newton(geometry, Tt, Lg, legs_c, legs0_L=Lc, max_iterations=max_iterations, **kw)
        its += itn
        # a converged step on another branch is a failed step: a smaller one may stay on ours
        if okn and home is not None and branch_sign(geometry, Tt, Ln, legs_n, kw, kw["counter"]) != ref.sign:
            okn, msgn, off_branch_seen = False, "converged on another branch", True
        if okn:
            Lc, legs_c, r_c, off_branch_seen = Ln, legs_n, rn, False
        return okn

    try:
        walk = continuation(step, first=1.0 / n_steps, max_step=2.0 / n_steps, min_step=1.0 / (16 * n_steps),
                                      growth=1.5)
    except BranchCheckError as e:
        return Walk(False, None, None, None, its, str(e))
    if walk.completed:
        return Walk(True, Lc, legs_c, r_c, its, "")
    lam = walk.reached
    where = (f"{lam:.3f} of the way from home to the target (rotation "
             f"{math.degrees(lam * np.linalg.norm(rotation_vector(H[:3, :3].T @ T[:3, :3]))):.1f} deg, "
             f"translation {1e3 * lam * np.linalg.norm(T[:3, 3] - H[:3, 3]):.0f} mm)")
    if off_branch_seen:
        msg = (f"the IK solution branch connected to home ends near {where}: det d(balance)/dL changes "
               f"sign (fold or bifurcation), the target lies outside the workspace of that branch")
    else:
        msg = f"pose continuation stalled at {where}: {msgn}"
        if home is not None and legs_c is not None:
            msg += _fold_note(geometry, interp_pose(H, T, slerp, lam), Lc, legs_c, kw, ref.smallest_singular_value)
    return Walk(False, None, None, None, its, msg)


def _fold_note(geometry, T, L, legs, kw, smin_home) -> str:
    """The stall message's note on the IK Jacobian's smallest singular value there (relative to home)."""
    try:
        _, smin = branch_sign(geometry, T, L, legs, kw, kw["counter"], with_smin=True)
    except BranchCheckError:
        return ""
    return (f"; smallest singular value of the IK Jacobian there {smin / smin_home:.2g} x its "
            f"home value" + (" (near a fold of the IK branch: workspace boundary)" if smin < 1e-2 * smin_home else ""))


def branch_sign(geometry, T, L, legs, kw, counter, with_smin=False):
    """Sign of ``det d(balance)/dL`` at a converged IK state (which IK solution branch it is on);
    with ``with_smin`` also the smallest singular value of ``diag(1, 1, 1, 1/r, 1/r, 1/r) J`` [N/m]."""
    try:
        J = ik_jacobian(geometry, T, L, legs, wrench=kw["w"], gravity=kw["g"], n_elements=kw["n_el"],
                         leg_tolerance=kw["leg_tolerance"], fd_step=kw["fd_step"])
    except RuntimeError as e:
        raise BranchCheckError(f"branch check: Jacobian at a converged state: {e}") from None
    counter[0] += 6
    sign, _ = np.linalg.slogdet(J)
    if not with_smin:
        return float(sign)
    S = np.diag([1.0, 1.0, 1.0] + [1.0 / geometry.platform_radius] * 3)
    return float(sign), float(np.linalg.svd(S @ J, compute_uv=False)[-1])


def ik_jacobian(geometry, T, L, legs, *, wrench=None, gravity=None, n_elements=8, leg_tolerance=1e-11, fd_step=1e-7):
    """``(6, 6)`` Jacobian ``d(balance)/dL`` (Eq 22) at a converged IK state, by forward differences.

    ``legs`` are the converged :class:`LegSolution` of the six legs at pose ``T`` and lengths
    ``L``; column i re-solves leg i at ``L_i + fd_step`` warm-started from ``legs[i]``.  Used to
    locate folds (turning points) of the IK solution branch, where this matrix is singular.
    """
    F = np.stack([lg.tip_force for lg in legs])
    M = np.stack([lg.tip_moment for lg in legs])
    r = platform_balance(geometry, T, F, M, wrench, gravity)
    J = np.empty((6, 6))
    for i in range(6):
        lg = leg_solve(geometry, i, L[i] + fd_step, T, gravity, n_elements, leg_tolerance, 50, guess=legs[i],
                        guess_length=L[i])
        if not lg.converged:
            raise RuntimeError(f"leg {i} solve failed at L = {L[i] + fd_step:.6g} m: {lg.reason}")
        F2, M2 = F.copy(), M.copy()
        F2[i], M2[i] = lg.tip_force, lg.tip_moment
        J[:, i] = (platform_balance(geometry, T, F2, M2, wrench, gravity) - r) / fd_step
    return J
