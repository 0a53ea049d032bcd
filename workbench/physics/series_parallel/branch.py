"""Which IK solution branch a converged state lies on: the sign of ``det d(balance)/dL``.

A sign change of the determinant along a path marks a fold or bifurcation of the IK branch
(the workspace boundary of the branch connected to home).  Checked by
``test_rx_limit_is_a_fold_of_the_ik_branch`` and ``test_ik_stops_at_the_fold_instead_of_changing_branch``
(``tests/physics/test_series_parallel.py``); the measured folds are in ``docs/models.md``.
"""

from __future__ import annotations

import numpy as np

from .leg import _leg_solve
from .newton import _balance


class _BranchCheckError(RuntimeError):
    pass


def _branch_sign(geometry, T, L, legs, kw, counter, with_smin=False):
    """Sign of ``det d(balance)/dL`` at a converged IK state (which IK solution branch it is on);
    with ``with_smin`` also the smallest singular value of ``diag(1, 1, 1, 1/r, 1/r, 1/r) J`` [N/m]."""
    try:
        J = _ik_jacobian(geometry, T, L, legs, wrench=kw["w"], gravity=kw["g"], n_elements=kw["n_el"],
                         leg_tolerance=kw["leg_tolerance"], fd_step=kw["fd_step"])
    except RuntimeError as e:
        raise _BranchCheckError(f"branch check: Jacobian at a converged state: {e}") from None
    counter[0] += 6
    sign, _ = np.linalg.slogdet(J)
    if not with_smin:
        return float(sign)
    S = np.diag([1.0, 1.0, 1.0] + [1.0 / geometry.platform_radius] * 3)
    return float(sign), float(np.linalg.svd(S @ J, compute_uv=False)[-1])


def _ik_jacobian(geometry, T, L, legs, *, wrench=None, gravity=None, n_elements=8, leg_tolerance=1e-11, fd_step=1e-7):
    """``(6, 6)`` Jacobian ``d(balance)/dL`` (Eq 22) at a converged IK state, by forward differences.

    ``legs`` are the converged :class:`LegSolution` of the six legs at pose ``T`` and lengths
    ``L``; column i re-solves leg i at ``L_i + fd_step`` warm-started from ``legs[i]``.  Used to
    locate folds (turning points) of the IK solution branch, where this matrix is singular.
    """
    F = np.stack([lg.tip_force for lg in legs])
    M = np.stack([lg.tip_moment for lg in legs])
    r = _balance(geometry, T, F, M, wrench, gravity)
    J = np.empty((6, 6))
    for i in range(6):
        lg = _leg_solve(geometry, i, L[i] + fd_step, T, gravity, n_elements, leg_tolerance, 50, guess=legs[i],
                        guess_length=L[i])
        if not lg.converged:
            raise RuntimeError(f"leg {i} solve failed at L = {L[i] + fd_step:.6g} m: {lg.reason}")
        F2, M2 = F.copy(), M.copy()
        F2[i], M2[i] = lg.tip_force, lg.tip_moment
        J[:, i] = (_balance(geometry, T, F2, M2, wrench, gravity) - r) / fd_step
    return J
