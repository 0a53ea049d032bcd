"""The constant-curvature (CC) plan of a whole-arm wrap, and of carrying the wrapped object (pure numpy).

The plan is what a CC controller commands (Hannan & Walker, papers/000_, Sec. 5 and Fig 6: "the robot
is given a desired configuration needed to grasp the object ... then uses Eq. (10) to move the
object around"): the distal *wrap sections* bend into arcs that hug the object, their centre of
arc is where CC says the object is held (Shao's grasp centre, papers/002_, Eq 2), the proximal
*approach sections* bring the wrap there.

* Touching curvature of wrap section ``j``: ``1 / rho_j`` with ``rho_j = r + D_j / 2`` (object
  radius plus the section's half diameter: the arm's inner surface lies on the object).  With
  tapered sections the arcs cannot share one centre; the object is placed at the centre of arc of
  the *first* wrap section, so the thinner distal sections spiral slightly inwards (CC's own
  penetration, reported).
* ``squeeze``: the commanded curvature of the wrap sections is ``squeeze / rho_j`` -- tendon tension
  beyond touching, the grip.  CC predicts an arm that penetrates the object (it knows no object);
  the physics shows the grip instead.
* The commands are the CC tendon tensions of those arcs (``workbench.models.cc.actuation_from_arc``,
  tension mode), so the physics runs exactly what CC was told.
* Carrying: the grasp centre follows a straight line; at every sample the approach bend angles
  are solved (Newton on the CC centre of arc, numerical Jacobian, from the previous sample) with the
  wrap unchanged -- the resolved-rate controller of H&W Eq 10 evaluated at the samples.

A wrap whose arm would reach round the object onto itself is refused (self-contact is not
modelled).  Checked by ``tests/experiments/test_whole_arm_grasp.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from ...kinematics import forward_kinematics
from ...physics.contact import RigidCircle

__all__ = ["GraspPlan", "wrap_plan", "carry_plans", "cc_backbone", "section_centre", "signed_arcs"]


@dataclass(frozen=True)
class GraspPlan:
    """A CC plan (plain data): the arcs CC predicts and what drives the physics.

    Attributes
    ----------
    kappa : (n_sections,) ndarray
        Signed CC curvature [1/m] in the base x-z plane (> 0 bends towards base +x).
    ell : (n_sections,) ndarray
        CC arc length of every section [m].
    circle : RigidCircle or None
        The object at its planned centre (base frame).
    wrap_angle : float
        Angle [rad] the wrap sections cover at touching curvature (0 without an object).
    tensions : ndarray or None
        Tendon tensions [N] (global tendon order) of a tendon plan.
    pressures : tuple of ndarray or None
        Chamber pressures [Pa] per section of a fluidic plan.
    layouts : tuple or None
        :class:`~workbench.robot.fluidic.ChamberLayout` per section (fluidic plans).
    approach : (k,) ndarray
        Bend angles [rad] of the approach sections.
    """

    kappa: np.ndarray
    ell: np.ndarray
    circle: RigidCircle | None
    wrap_angle: float = 0.0
    tensions: np.ndarray | None = None
    pressures: tuple | None = None
    layouts: tuple | None = None
    approach: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def fluidic(self) -> bool:
        return self.pressures is not None


def signed_arcs(kappa) -> tuple[np.ndarray, np.ndarray]:
    """Signed planar curvatures -> ``(|kappa|, phi)`` with ``phi = 0`` (towards +x) or ``pi``."""
    k = np.asarray(kappa, dtype=float)
    return np.abs(k), np.where(k >= 0.0, 0.0, math.pi)


def cc_backbone(kappa, ell, s) -> np.ndarray:
    """CC backbone points ``(m, 2)`` (base x, z) at arc lengths ``s`` along the CC arcs [m]."""
    k, phi = signed_arcs(kappa)
    frames = forward_kinematics(k, phi, np.asarray(ell, float), s=np.asarray(s, float))
    return frames[:, [0, 2], 3]


def section_centre(kappa, ell, j: int, rho: float) -> np.ndarray:
    """Centre ``(x, z)`` [m, base] of the circle of radius ``rho`` tangent to the arm at the start of
    section ``j`` on its bending side (> 0 curvature: base +x side of the local frame)."""
    k, phi = signed_arcs(kappa)
    start = float(np.sum(np.asarray(ell)[:j]))
    H = forward_kinematics(k, phi, np.asarray(ell, float), s=np.array([start]))[0]
    side = 1.0 if kappa[j] >= 0 else -1.0
    return H[[0, 2], 3] + side * rho * H[[0, 2], 0]


def _diameters(robot) -> np.ndarray:
    d = [s.cross_section_at(0.5).diameter for s in robot.sections]
    if any(x is None for x in d):
        raise ValueError("a whole-arm wrap needs the section diameters (CrossSection.diameter) of the robot")
    return np.asarray(d, dtype=float)


def _split(robot, wrap_sections: Sequence[int], approach_bend_angles: Sequence[float]):
    n = robot.n_sections
    wrap = sorted({int(j) for j in wrap_sections})
    if not wrap or wrap != list(range(n - len(wrap), n)):
        raise ValueError(f"wrap_sections must be the distal sections (a tail of 0..{n - 1}), got {list(wrap_sections)}")
    approach = list(range(n - len(wrap)))
    a = np.asarray(approach_bend_angles, dtype=float).reshape(-1)
    if a.size != len(approach):
        raise ValueError(f"approach_bend_angles needs {len(approach)} values (sections {approach}), got {a.size}")
    return wrap, approach, a


def wrap_plan(robot, *, object_radius: float, wrap_sections: Sequence[int], approach_bend_angles: Sequence[float],
              squeeze: float = 1.0, object_mass: float = 0.0, friction: float = 0.0) -> GraspPlan:
    """The CC wrap plan of a tendon-driven planar robot (module docstring).

    Raises
    ------
    ValueError
        Bad sections or angles, ``squeeze < 1``, or an arm that would wrap onto itself.
    """
    from ...models.cc import actuation_from_arc

    if not object_radius > 0:
        raise ValueError(f"object_radius must be > 0 [m], got {object_radius}")
    if not squeeze >= 1.0:
        raise ValueError(f"squeeze must be >= 1 (1 = touching; larger grips), got {squeeze}")
    wrap, approach, a = _split(robot, wrap_sections, approach_bend_angles)
    ell = robot.section_lengths
    D = _diameters(robot)
    rho = object_radius + 0.5 * D
    touch = np.zeros(robot.n_sections)
    touch[approach] = a / ell[approach]
    touch[wrap] = 1.0 / rho[wrap]
    angle = float(np.sum(ell[wrap] / rho[wrap]))
    gap = 2.0 * math.pi * rho[wrap[0]] - angle * rho[wrap[0]]
    if gap < 0.5 * (D[wrap[0]] + D[wrap[-1]]):
        raise ValueError(f"the wrap covers {math.degrees(angle):.0f} deg of an object of radius {object_radius:g} m: "
                         f"the arm would reach round onto itself (self-contact is not modelled); use a larger "
                         f"object or fewer wrap sections")
    centre = section_centre(touch, ell, wrap[0], rho[wrap[0]])
    cmd = touch.copy()
    cmd[wrap] *= squeeze
    k, phi = signed_arcs(cmd)
    act = actuation_from_arc(robot, k, phi, "tension")
    return GraspPlan(kappa=cmd, ell=ell.copy(), wrap_angle=angle, tensions=np.asarray(act.values),
                     circle=RigidCircle(radius=object_radius, centre=tuple(centre), mass=object_mass, friction=friction),
                     approach=a)


def carry_plans(robot, plan_kwargs: dict, offset_xz: Sequence[float], samples: int, *, tol: float = 1e-10,
                max_iterations: int = 50) -> list[GraspPlan]:
    """Plans whose grasp centre moves along a straight line by ``offset_xz`` [m, base] in ``samples`` steps.

    Sample 0 is :func:`wrap_plan` (``plan_kwargs``); sample ``i`` solves the approach bend angles
    so that the CC centre is at ``centre_0 + i / (samples - 1) * offset``.

    Raises
    ------
    ValueError
        Fewer than two approach sections, or the line leaves the reach of the approach sections.
    """
    base = wrap_plan(robot, **plan_kwargs)
    if base.approach.size < 2:
        raise ValueError("carrying the grasp centre along a line needs at least two approach sections")
    if samples < 2:
        raise ValueError(f"carry_samples must be >= 2, got {samples}")
    c0 = np.asarray(base.circle.centre)
    off = np.asarray(offset_xz, dtype=float).reshape(2)

    def centre(angles):
        return np.asarray(wrap_plan(robot, **{**plan_kwargs, "approach_bend_angles": list(angles)}).circle.centre)

    plans, a = [base], base.approach.copy()
    for i in range(1, samples):
        target = c0 + off * i / (samples - 1)
        for _ in range(max_iterations):
            e = target - centre(a)
            if np.linalg.norm(e) < tol:
                break
            J = np.column_stack([(centre(a + h) - centre(a - h)) / 2e-6 for h in 1e-6 * np.eye(a.size)])
            a = a + np.linalg.pinv(J) @ e
        else:
            raise ValueError(f"the grasp centre cannot follow the line to sample {i} (offset {off.tolist()} m): "
                             f"the approach sections do not reach it")
        plans.append(wrap_plan(robot, **{**plan_kwargs, "approach_bend_angles": list(a)}))
    return plans
