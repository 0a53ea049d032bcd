"""The ``harvester_scoop`` scenario: Shao's section scoops a fruit, driven by fluidic chambers or tendons.

Registered as ``registry.SCENARIOS["harvester_scoop"]`` and run by the ``grasp`` study kind
(``workbench/experiments/whole_arm_grasp/kind.py``).  Shao et al. (papers/002_) drive Section II with
pressurised FPAs that **lengthen** it; the workbench's first harvester study replaced them by tendons,
which shorten it.  Here both drive the same planar contact physics, beside each other:

* ``actuation = "fluidic"``: chambers where the tendon stand-in has its tendons (the preset's three
  groups at 0/120/240 deg, 22 mm), effective area ``chamber_area``, pressures limited to
  ``max_pressure`` (paper: 0.6 MPa); the least pressures that bend the section by ``bend_angle``
  (:func:`workbench.robot.fluidic.pressures_for_bend`) -- the section extends by ``sum F / EA``;
  CC's arc ``(s, kappa, phi)`` follows from the pressures (:func:`~workbench.robot.fluidic.arc_from_pressures`);
* ``actuation = "tendon"``: the stand-in, CC tensions for ``kappa = bend_angle / L``.

The payload: ``payload = "tip"`` is a point mass at the tip (the preset's ``payload_mass``; the first
study's reading), ``"object"`` a fruit of ``object_diameter`` and ``object_mass`` placed at the CC
centre of arc (Shao Eq 2, the grasp centre) and released into the scoop.  ``control_iterations > 0``
runs the grasp-centre controller (:mod:`.centre_control`).  **Assumed** (the paper gives none):
``chamber_area = 3e-4 m^2``, chosen so that the 270 deg scoop (the envelope's wrap angle) needs
0.54 MPa, within the paper's 0.6 MPa; the preset's EI, EA; a rigid round fruit.  Pure numpy.
Checked by ``tests/experiments/test_fruit_harvester_scoop.py``.
"""

from __future__ import annotations

import inspect
import math
from typing import Any, Mapping

import numpy as np

from ...physics.contact import ContactLaw, RigidCircle
from ...robot.fluidic import ChamberLayout, arc_from_pressures, pressures_for_bend
from ..whole_arm_grasp.plan import GraspPlan
from ..whole_arm_grasp.tasks import GraspTask

__all__ = ["harvester_scoop", "grasp_case", "layout_of", "scoop_plan"]


def harvester_scoop(
    robot,
    *,
    actuation: str = "fluidic",
    bend_angle: float = 1.5 * math.pi,
    payload: str = "object",
    object_diameter: float = 0.1,
    object_mass: float = 0.1,
    friction: float = 0.3,
    chamber_area: float = 3.0e-4,
    max_pressure: float = 0.6e6,
    release: bool = True,
    control_iterations: int = 0,
    control_tolerance: float = 2e-4,
    contact_stiffness: float = 1.0e8,
    friction_stiffness: float = 1.0e6,
    contact_segments: int = 8,
    error_estimate: bool = True,
    penalty_estimate: bool = True,
) -> dict[str, Any]:
    """Load fields of one scoop case (module docstring): tendon tensions, or none for chambers.

    Parameters
    ----------
    actuation : {"fluidic", "tendon"}
    bend_angle : float
        CC bend angle ``kappa s`` [rad] of the section (towards base +x).
    payload : {"object", "tip"}
        A fruit in the scoop (``object_diameter`` [m], ``object_mass`` [kg], ``friction``) or the
        robot's tip mass (``robot.payload_mass``; then ``object_mass`` must be 0).
    chamber_area, max_pressure : float
        Effective chamber area [m^2] and pressure limit [Pa] (fluidic).
    release, control_iterations, control_tolerance :
        Release the fruit into the scoop; grasp-centre controller steps and tolerance [m].
    contact_stiffness, friction_stiffness, contact_segments, error_estimate, penalty_estimate :
        As in ``whole_arm_wrap`` (:mod:`workbench.experiments.whole_arm_grasp.scenario`).
    """
    params = {k: v for k, v in locals().items() if k != "robot"}
    plan, _ = grasp_case(robot, params)
    if plan.fluidic:
        return {}
    return {"mode": "tension", "tensions": [float(t) for t in plan.tensions]}


def layout_of(robot, area: float, max_pressure: float) -> ChamberLayout:
    """Chamber lines where the single section's tendon group is (angles and offset), with the given area."""
    if robot.n_sections != 1 or robot.sections[0].tendons is None:
        raise ValueError("harvester_scoop needs a one-section robot whose tendon group marks the chamber positions")
    g = robot.sections[0].tendons
    return ChamberLayout(angles=g.angles, offset=g.offset, area=area, max_pressure=max_pressure)


def scoop_plan(robot, p: Mapping[str, Any], kappa: float | None = None) -> GraspPlan:
    """The CC plan (module docstring); ``kappa`` replaces the bend by a curvature (the controller's replan)."""
    from ...models.cc import actuation_from_arc

    sec = robot.sections[0]
    cs = sec.cross_section_at(0.5)
    L = sec.length
    if p["actuation"] == "fluidic":
        lay = layout_of(robot, float(p["chamber_area"]), float(p["max_pressure"]))
        theta = float(p["bend_angle"]) if kappa is None else None
        if theta is None:
            from ...robot.fluidic import pressures_from_arc

            pr = pressures_from_arc(lay, float(kappa), 0.0, cs.EI, cs.EA, L)
        else:
            pr = pressures_for_bend(lay, theta, 0.0, cs.EI, L)
        s, k, _ = arc_from_pressures(lay, pr, cs.EI, cs.EA, L)
        extra = {"pressures": (pr,), "layouts": (lay,)}
    elif p["actuation"] == "tendon":
        s = L
        k = float(p["bend_angle"]) / L if kappa is None else float(kappa)
        extra = {"tensions": np.asarray(actuation_from_arc(robot, [k], [0.0], "tension").values)}
    else:
        raise ValueError(f"actuation must be 'fluidic' or 'tendon', got {p['actuation']!r}")
    if not k > 0:
        raise ValueError(f"the scoop needs a bend > 0, got curvature {k}")
    circle = None
    if p["payload"] == "object":
        if robot.payload.mass > 0:
            raise ValueError("payload = 'object' with robot.payload_mass > 0: give the fruit's mass as object_mass")
        circle = RigidCircle(radius=0.5 * float(p["object_diameter"]), centre=(1.0 / k, 0.0),
                             mass=float(p["object_mass"]), friction=float(p["friction"]))
    elif p["payload"] == "tip":
        if float(p["object_mass"]) != 0.0:
            raise ValueError("payload = 'tip' takes the mass from robot.payload_mass; set object_mass = 0")
    else:
        raise ValueError(f"payload must be 'object' or 'tip', got {p['payload']!r}")
    return GraspPlan(kappa=np.array([k]), ell=np.array([s]), circle=circle, wrap_angle=k * s, **extra)


def grasp_case(robot, params: Mapping[str, Any]):
    """``(GraspPlan, GraspTask)`` of one scoop case from its resolved scenario parameters."""
    from .centre_control import centre_controller

    defaults = {k: v.default for k, v in inspect.signature(harvester_scoop).parameters.items() if k != "robot"}
    p = {**defaults, **{k: v for k, v in params.items() if k != "name"}}
    plan = scoop_plan(robot, p)
    D = robot.sections[0].cross_section_at(0.5).diameter or 0.0
    if plan.circle is not None and plan.wrap_angle * (1.0 / plan.kappa[0]) > 2 * math.pi / plan.kappa[0] - D:
        raise ValueError(f"a bend of {math.degrees(plan.wrap_angle):.0f} deg makes the section reach round onto "
                         f"itself (self-contact is not modelled)")
    control = None
    if int(p["control_iterations"]) > 0:
        control = centre_controller(int(p["control_iterations"]), float(p["control_tolerance"]),
                                    lambda kappa: scoop_plan(robot, p, kappa))
    law = ContactLaw(stiffness=float(p["contact_stiffness"]), friction_stiffness=float(p["friction_stiffness"]),
                     segments=int(p["contact_segments"]))
    gap = 0.0 if plan.circle is None else abs(1.0 / plan.kappa[0] - plan.circle.radius - 0.5 * D)
    escape = None if plan.circle is None else plan.circle.radius + gap
    return plan, GraspTask(release=bool(p["release"]), law=law, control=control, escape_distance=escape)
