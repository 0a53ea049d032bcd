"""Shao's grasp-centre controller running on the physics: correct the centre of arc with its Jacobian.

Shao et al. (papers/002_, Sec. 3) control the *centre of the arc* (Eq 2, ``x = (cos phi, sin phi, 0) / k``),
the grasp centre, through the Jacobian of Eq 4-5 (corrected: :func:`workbench.kinematics.centre_of_arc_jacobian`).
Here that resolved-rate law closes the loop on the physics: each step measures the grasp centre of
the physical section (the fruit's centre, or for a tip payload the centre of the least-squares
circle through the backbone), takes the error ``e`` to the commanded centre (the plan's CC centre),
and updates ``q = [s, k, phi]`` by ``J_v^+ e`` (base x, z rows; bending plane phi = 0 fixed).  The new
curvature is re-planned (pressures or tensions, :func:`.scoop.scoop_plan`) and ramped in with the
fruit free.  ``J_v`` has **no z row** (the CC centre always lies in the base plane z = 0) and no s
column, so the law can correct the horizontal offset only; the vertical sag stays -- reported as
``x.grasp_centre_error_z``.  Actuator limits: a curvature step is limited to ``max_step`` (a fraction
of the current curvature; ``x.control_limited_steps`` counts the limited steps), and a step whose
re-plan the actuator cannot realise (a chamber pressure above its limit, a curvature <= 0) ends the
loop with ``x.control_saturated = 1`` (the reason in the solver message) -- a controller result, not a failed
run.  Checked by ``tests/experiments/test_fruit_harvester_scoop.py``.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ...kinematics import centre_of_arc_jacobian
from .envelope import circle_fit

__all__ = ["centre_controller", "grasp_centre"]


def grasp_centre(run) -> np.ndarray:
    """The physical grasp centre ``(x, z)`` [m, base]: the object's centre, or the backbone's best-fit circle centre."""
    if run.plan.circle is not None:
        return run.sysm.object_centre()
    pos, _ = run.sysm.positions(run.stations)
    c, _ = circle_fit(pos[:, [0, 2]])
    return c


def centre_controller(iterations: int, tolerance: float, replan: Callable[[float], object],
                      max_step: float = 0.25) -> Callable:
    """A ``GraspTask.control`` hook running ``iterations`` resolved-rate steps (module docstring).

    ``replan(kappa) -> GraspPlan`` gives the commands of a new curvature (``ValueError`` where the
    actuator cannot); ``max_step`` limits ``|dk|`` to that fraction of the current curvature.  Extras:
    ``control_steps``, ``grasp_centre_error`` [m] (norm after the last step), its ``_x`` / ``_z``
    components, ``grasp_centre_error_initial``, ``control_limited_steps``, ``control_saturated``;
    series ``control_error`` (k, 2) [m, base (x, z)].
    """

    def control(run) -> None:
        plan = run.plan
        target = np.array([1.0 / plan.kappa[0], 0.0])
        s, kappa = float(plan.ell[0]), float(plan.kappa[0])
        strains = (run.kap, run.eps)
        errors = [target - grasp_centre(run)]
        limited, saturated = 0, False
        for _ in range(iterations):
            if abs(errors[-1][0]) < tolerance:
                break
            J = centre_of_arc_jacobian(s, kappa, 0.0)[[0, 2], :2]  # rows x, z; columns s, k
            ds, dk = np.linalg.pinv(J) @ errors[-1]
            if abs(dk) > max_step * kappa:
                dk, limited = float(np.sign(dk)) * max_step * kappa, limited + 1
            try:
                new = replan(kappa + dk)
            except ValueError as err:  # the actuator cannot realise the step: saturated
                run.log.append(f"grasp-centre control saturated at step {len(errors)}: {err}")
                saturated = True
                break
            k1, e1 = run.strains_of(new)

            def apply(lam, k0=strains[0], e0=strains[1]):
                run.sysm.set_strains(k0 + lam * (k1 - k0), e0 + lam * (e1 - e0))

            run.steps += run.sysm.load_ramp(apply, run.options.max_load_steps)
            strains, s, kappa = (k1, e1), float(new.ell[0]), float(new.kappa[0])
            errors.append(target - grasp_centre(run))
        E = np.array(errors)
        run.extras.update({"control_steps": float(len(E) - 1), "grasp_centre_error": float(np.linalg.norm(E[-1])),
                           "grasp_centre_error_x": float(E[-1, 0]), "grasp_centre_error_z": float(E[-1, 1]),
                           "grasp_centre_error_initial": float(np.linalg.norm(E[0])), "control_kappa": kappa,
                           "control_limited_steps": float(limited), "control_saturated": float(saturated)})
        run.series["control_error"] = E

    return control
