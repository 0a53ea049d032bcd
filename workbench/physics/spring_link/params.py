"""Model-specific settings of the spring-link chain and the planarity test (pure numpy).

Checked by ``tests/physics/test_spring_link.py`` (``test_bad_inputs``, the 2-D/3-D and backend tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ...robot import LoadCase, Robot

__all__ = ["SpringLinkParams", "inextensible_length_warning", "is_planar", "resolve_axial"]

_PLANE_TOL = 1e-12


@dataclass(frozen=True)
class SpringLinkParams:
    """Model-specific settings of the spring-link chain.

    Parameters
    ----------
    dimension : {"auto", "2d", "3d"}
        ``"auto"``: planar chain when the robot and load are planar (see :func:`is_planar`),
        spatial chain otherwise.  ``"2d"`` forces the planar chain (raises if the case is not
        planar), ``"3d"`` the spatial chain.
    max_active_set_iterations : int
        Cap on slack/taut switching passes in a static length-controlled solve.
    torsion : {"spring", "locked"}
        3-D chain only.  ``"spring"`` (default): spherical joints with a rotational spring
        ``diag(k, k, GJ/ds)`` on the intrinsic relative rotation vector (the equivalent rod: a
        bend in any fixed plane is twist-free).  ``"locked"``: Cardan (universal) joints, the
        relative rotation about the link axis in the joint's x-y-z Tait-Bryan sequence is
        constrained (Hannan & Walker's 2-DOF joints; an oblique bend then carries the Cardan
        twist, reported as ``tip_twist``).
    axial : bool or None
        ``None`` (default): ``True`` for constant-offset continuum tendons in static length mode on the planar chain (the
        backbone's compression under the tendon forces changes the tendon length, so the
        inextensible chain overestimates the tensions), ``False`` otherwise (:func:`resolve_axial`).
        ``False``: inextensible pin (2-D) / spherical or Cardan (3-D) joints.  ``True``:
        every joint becomes a rigid-body spring (``RigidBodySpringDamper``, intrinsic) with axial
        stiffness ``EA/ds`` and shear stiffness ``GA/ds`` (``CrossSection.GA``, or ``EA`` when it
        is ``None``) besides the bending (and torsion) springs, so the backbone can compress
        (wire-delay compression, continuum-tendon compression ``T``) and ``length_change`` is
        reported.  Not combined with ``torsion="locked"``.  The study key is
        ``[solver] spring_link_axial`` (``SolverOptions.model_settings``).
    backend : {"auto", "bodies", "tree"}
        Exudyn representation of an inextensible chain.  ``"tree"``: one ``ObjectKinematicTree``
        (minimal coordinates, no joint constraints; planar, or in 3-D a chain of Cardan joints
        ``RevoluteX`` + ``RevoluteY`` with springs on both Cardan angles, so it needs
        ``torsion="locked"``); ``"bodies"``: rigid bodies + joints.  Both give the same statics
        (tested to ~1e-10 planar; in 3-D up to the spring law, rotation vector vs Cardan angles,
        second order in the joint angles).  ``"auto"`` (default) uses the tree for eyelet tendons
        (length or tension mode; planar, or 3-D with ``torsion="locked"``) and bodies otherwise;
        ``axial=True`` always uses bodies.  Why (measured Newton convergence and timings):
        ``docs/models.md``, "Spring-link".
    richardson : bool
        Static solves only.  ``False`` (default): one chain of ``n_elements`` links.  ``True``: chains of
        ``n_elements / 2`` and ``n_elements`` links, Richardson-extrapolated at order 2 in the link length
        (:mod:`.richardson`: positions, tip position, tensions; the error bar in the extras as
        ``richardson_tip_bar``); ``n_elements`` must be a multiple of twice the number of sections.  The study
        key is ``[solver] spring_link_richardson``.
    """

    dimension: Literal["auto", "2d", "3d"] = "auto"
    max_active_set_iterations: int = 20
    torsion: Literal["spring", "locked"] = "spring"
    axial: bool | None = None
    backend: Literal["auto", "bodies", "tree"] = "auto"
    richardson: bool = False

    def __post_init__(self) -> None:
        if self.dimension not in ("auto", "2d", "3d"):
            raise ValueError(f"SpringLinkParams.dimension must be 'auto', '2d' or '3d', got {self.dimension!r}")
        if self.backend not in ("auto", "bodies", "tree"):
            raise ValueError(f"SpringLinkParams.backend must be 'auto', 'bodies' or 'tree', got {self.backend!r}")
        if self.axial not in (None, True, False):
            raise ValueError(f"SpringLinkParams.axial must be None, True or False, got {self.axial!r}")
        if self.axial and self.torsion == "locked":
            raise ValueError("SpringLinkParams: axial=True needs torsion='spring'")
        if self.torsion not in ("spring", "locked"):
            raise ValueError(f"SpringLinkParams.torsion must be 'spring' or 'locked', got {self.torsion!r}")
        if self.richardson not in (True, False):
            raise ValueError(f"SpringLinkParams.richardson must be True or False, got {self.richardson!r}")
        if int(self.max_active_set_iterations) < 1:
            raise ValueError("SpringLinkParams.max_active_set_iterations must be >= 1")


def resolve_axial(params: SpringLinkParams, robot: Robot, load: LoadCase, tendon_model: str, use_2d: bool) -> bool:
    """The chain's axial springs: ``params.axial``, or for ``None`` whether the case is planar
    continuum tendons in length mode (where the inextensible chain's tensions are wrong:
    ``tests/physics/test_spring_link_crossexam.py``)."""
    if params.axial is not None:
        return bool(params.axial)
    if params.backend == "tree":  # the tree is inextensible
        return False
    act = load.actuation
    if not (use_2d and tendon_model == "continuum" and act is not None and act.mode == "length"
            and load.analysis == "static"):
        return False
    return not any(grp.offset_tip is not None for _, _, grp in robot.tendon_table())


def inextensible_length_warning(robot: Robot, load: LoadCase, tendon_model: str,
                                params: SpringLinkParams) -> str | None:
    """The ``validate`` warning text for length-controlled tendons on the inextensible chain, or ``None``.

    With joints that cannot shorten, a length command is taken up by bending and tendon stretch
    alone, so the tensions come out too high wherever the real backbone's compression is not
    negligible against the tendons' stretch (a continuous rod: ``EA_t / L_t`` not << ``EA / L``;
    measured in ``tests/physics/test_spring_link_crossexam.py``).  A jointed robot (Hannan & Walker's
    trunk) is inextensible by construction and may ignore it.  Called by
    :func:`workbench.study.checks.case_rules` for the spring-link models.
    """
    act = load.actuation
    if act is None or act.mode != "length":
        return None
    planar, _ = is_planar(robot, load)
    use_2d = params.dimension == "2d" or (params.dimension == "auto" and planar)
    if resolve_axial(params, robot, load, tendon_model, use_2d):
        return None
    return ("solves these length-controlled tendons on an inextensible "
            "chain (the backbone cannot shorten: the command is taken up by bending and tendon stretch alone, "
            "so the tensions are too high for a continuous rod whose compression is not negligible); "
            "spring_link_axial = true adds axial springs EA/ds (2-D, or 3-D on rigid bodies), "
            "a jointed robot is inextensible by construction")


def is_planar(robot: Robot, load: LoadCase) -> tuple[bool, str]:
    """Whether ``robot`` under ``load`` stays in the base x-z plane.

    Returns
    -------
    planar : bool
    reason : str
        Why not (empty when planar).
    """
    for j, sigma, _ in robot.tendon_table():
        if abs(math.sin(sigma)) > 1e-9:
            return False, f"tendon of section {j} at sigma = {sigma:.6g} rad is not in the x-z plane (sigma in {{0, pi}})"
    g = robot.gravity_in_base()
    if abs(g[1]) > _PLANE_TOL * max(1.0, np.linalg.norm(g)):
        return False, f"gravity in the base frame {g.tolist()} has a y component"
    if abs(load.tip_force[1]) > _PLANE_TOL:
        return False, f"tip force {list(load.tip_force)} has a y component"
    if abs(load.tip_torque[0]) > _PLANE_TOL or abs(load.tip_torque[2]) > _PLANE_TOL:
        return False, f"tip torque {list(load.tip_torque)} is not about base y"
    if robot.payload.mass > 0 and abs(robot.payload.offset[1]) > _PLANE_TOL:
        return False, "payload offset has a y component"
    return True, ""
