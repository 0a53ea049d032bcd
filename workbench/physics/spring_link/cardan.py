"""The registered model ``spring_link_cardan``: the 3-D spring-link chain with two-DOF (Cardan) joints.

Hannan & Walker's trunk has 16 two-DOF joints (papers/000_, Sec. 3): each joint bends about two
axes and cannot twist.  That is :func:`.driver.solve` with ``SpringLinkParams(dimension="3d",
torsion="locked")`` -- Cardan joints ``R_rel = Rx(a) Ry(b)``, springs ``EI / ds`` on both angles,
the kinematic tree for eyelet ropes -- which the default model ``spring_link`` (spherical joints
with a torsion spring) cannot select from a study file.  ``joint_angles`` are ``(N, 2)``, the
Cardan angles ``(a, b)`` of every joint.

A static solve that lands on an equilibrium whose cables are stretched beyond
:data:`MAX_CABLE_STRAIN` is refused (``ModelFailure``): the linear-elastic rope law does not hold
there, and such states are folded branches the full-load Newton start can jump to (measured: one
case of the ``hannan_walker_3d`` study converged with 150-210 kN in 1 mm cables, 100 % strain, tip
0.36 m off).  Checked by ``tests/experiments/test_hannan_walker_3d.py`` (planar motions equal the
planar chain to 1e-9, out-of-plane bending, the strain check).
"""

from __future__ import annotations

import numpy as np

from ...models.result import ModelFailure, PhysicsResult, SolverOptions
from ...robot import LoadCase, Robot
from .driver import solve
from .params import SpringLinkParams

__all__ = ["CARDAN", "MAX_CABLE_STRAIN", "run"]

#: The settings of the two-DOF-joint chain.
CARDAN = SpringLinkParams(dimension="3d", torsion="locked")

#: Largest cable strain ``T / EA_t`` of an accepted static state (10x the yield strain of steel).
MAX_CABLE_STRAIN = 0.02


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Registered model ``"spring_link_cardan"``: :func:`.driver.solve` with :data:`CARDAN`.

    Raises
    ------
    ModelFailure
        As :func:`.driver.solve`, and a static state with a cable strain above
        :data:`MAX_CABLE_STRAIN`.
    """
    res = solve(robot, load, options, CARDAN)
    ea = np.array([grp.axial_stiffness for _, _, grp in robot.tendon_table()])
    T = np.asarray(res.tendon_tensions, dtype=float)
    if load.analysis == "static" and T.size == ea.size and T.size:
        strain = T / ea
        k = int(np.argmax(strain))
        if strain[k] > MAX_CABLE_STRAIN:
            raise ModelFailure(
                f"spring_link_cardan: the static solve converged to a state with cable {k} at {T[k]:.4g} N, strain "
                f"{strain[k]:.3g} > {MAX_CABLE_STRAIN} (beyond the linear-elastic cable; a folded equilibrium branch "
                f"reached from the full-load Newton start), refused")
    return res
