"""Hannan & Walker: the CC cable plan of a line and its replay on the spring-link chain.

Pipeline (papers/000_, Sec. 3-5):

1. the planar CC resolved-rate controller (Eq. 10-11, :func:`workbench.kinematics.follow_path`)
   tracks a straight end-point line, giving section curvatures ``kappa_i`` per path sample;
2. equal joint angles per section (the paper's assumption, Eq. 2-3): ``theta_i = kappa_i l_i / n``
   for the ``n`` joints of section ``i``;
3. every cable's length change follows from the jointed geometry of Eq. (1), summed over the
   joints it runs through (:func:`cable_changes_from_joint_angles`).

Steps 1-3 are :func:`cc_cable_plan`, shared by the study scenario (:mod:`.scenario`) and the
driver :func:`replay_hannan_walker`, which then solves the spring-link model
(:func:`workbench.physics.spring_link.solve`, eyelet tendons, length control) statically for
each sample's cable commands and compares its tip with the CC tip.

Sign convention: the planar CC model starts along planar ``+y`` and bends towards planar ``-x``
for ``kappa > 0``; the robot's base frame has the backbone along ``+z``, so ``x_base = -x_planar``,
``z_base = y_planar`` and a planar ``kappa > 0`` bends towards base ``+x`` (the sigma = 0 cable
shortens).  In the spring-link chain the eyelets sit ``h = ds/2`` either side of each joint, so
summing Eq. (1) over the joints is the chain's exact cable geometry.

Checked by ``tests/physics/test_hannan_walker.py`` (Eq. 1 against the rope lengths on the Exudyn
eyelets, the inverse, the replay) and ``tests/study/test_scenarios.py``.  Measured tip errors:
``docs/models.md``, "Hannan & Walker replay".
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...kinematics import follow_path, line_path, planar_forward_kinematics
from ...kinematics.hannan_walker import (
    cable_change_from_joint_angle,
    joint_angle_from_cable_change,
    joint_angle_from_curvature,
)
from ...models.result import SolverOptions
from ...physics.spring_link import SpringLinkParams, chain_geometry_from_robot, solve
from ...robot import LoadCase, Robot, TendonActuation

__all__ = [
    "cable_changes_from_joint_angles",
    "joint_angles_from_cable_changes",
    "CCCablePlan",
    "cc_cable_plan",
    "HannanWalkerReplay",
    "replay_hannan_walker",
]


def _routing(robot: Robot, n_links: int):
    geo = chain_geometry_from_robot(robot, n_links)
    per = n_links // robot.n_sections
    h = 0.5 * np.diff(geo.eyelets)  # (N,) half spacing at each joint
    table = robot.tendon_table()
    for _, sigma, grp in table:
        if grp.offset_tip is not None:
            raise ValueError("tapered tendon offsets are not supported by the Eq. (1) cable map")
        if abs(np.sin(sigma)) > 1e-9:
            raise ValueError("the Eq. (1) cable map is planar: tendons must lie at sigma in {0, pi}")
    return geo, per, h, table


def cable_changes_from_joint_angles(joint_angles, robot: Robot, n_links: int | None = None):
    """Cable length changes from joint angles of the jointed planar robot (Eq. 1, summed).

    Parameters
    ----------
    joint_angles : array_like, shape (..., N)
        Joint angles [rad], positive towards base +x (sigma = 0 side).
    robot : Robot
        Planar robot (tendons at sigma in {0, pi}, constant offsets).
    n_links : int, optional
        Number of joints ``N`` (default: the last axis of ``joint_angles``).

    Returns
    -------
    dl : ndarray, shape (..., n_tendons)
        Change of each cable's length from the straight reference [m] (negative = shorter), in
        :meth:`Robot.tendon_table` order.
    """
    q = np.asarray(joint_angles, dtype=float)
    N = q.shape[-1] if n_links is None else int(n_links)
    if q.shape[-1] != N:
        raise ValueError(f"joint_angles must have shape (..., {N}), got {q.shape}")
    geo, per, h, table = _routing(robot, N)
    out = []
    for j, sigma, grp in table:
        m = int(geo.section_end_eyelet[j])
        c = 1.0 if np.cos(sigma) > 0 else -1.0
        # Eq. (1) inverse per joint (kinematics returns the shortening, hence the minus sign)
        pieces = -cable_change_from_joint_angle(c * q[..., :m], grp.offset, h[:m])
        out.append(np.sum(pieces, axis=-1))
    return np.stack(out, axis=-1)


def joint_angles_from_cable_changes(cable_changes, robot: Robot, n_links: int):
    """Per-section joint angles from the sigma = 0 cable of each section (Eq. 1 inverted).

    Assumes equal joint angles within a section (the paper's assumption).  Sections are resolved
    from the base: the part of section ``j``'s cable running through sections ``< j`` is removed
    using the angles already found.

    Parameters
    ----------
    cable_changes : array_like, shape (n_tendons,)
        Length changes [m] in tendon-table order (only the sigma = 0 cables are used).
    robot : Robot
    n_links : int

    Returns
    -------
    theta : ndarray, shape (n_sections,)
        Joint angle of each section [rad], positive towards base +x.
    """
    dl = np.asarray(cable_changes, dtype=float).reshape(-1)
    geo, per, h, table = _routing(robot, n_links)
    if dl.size != len(table):
        raise ValueError(f"cable_changes must have shape ({len(table)},), got {dl.shape}")
    theta = np.full(robot.n_sections, np.nan)
    for i, (j, sigma, grp) in enumerate(table):
        if np.cos(sigma) < 0 or not np.isnan(theta[j]):
            continue
        start = j * per
        before = 0.0
        if start:
            qb = np.repeat(theta[:j], per)
            before = float(np.sum(-cable_change_from_joint_angle(qb, grp.offset, h[:start])))
        per_joint = (dl[i] - before) / per
        theta[j] = float(joint_angle_from_cable_change(-per_joint, grp.offset, h[start]))
    if np.any(np.isnan(theta)):
        raise ValueError("every section needs a cable at sigma = 0")
    return theta


@dataclass(frozen=True, eq=False)
class CCCablePlan:
    """The CC plan of a straight line and its cable commands (:func:`cc_cable_plan`).

    Attributes
    ----------
    path : ndarray, shape (m, 2)
        Line samples in the planar CC frame, ``(-x, z)`` of the base frame [m].
    kappa : ndarray, shape (m, n_sections)
        Section curvatures of the resolved-rate controller (planar sign, towards base +x) [1/m].
    success : bool
        The controller tracked the line to its tolerance.
    tracking_error : ndarray, shape (m,)
        Its tip error per sample [m].
    joint_angles : ndarray, shape (m, N) or (N,), or None
        Equal joint angles per section (Eq. 2-3) of all samples, or of the one requested sample;
        ``None`` when the controller failed.
    cable_changes : ndarray, shape (m, n_tendons) or (n_tendons,), or None
        Cable length commands (Eq. 1) for those joint angles [m].
    """

    path: np.ndarray
    kappa: np.ndarray
    success: bool
    tracking_error: np.ndarray
    joint_angles: np.ndarray | None
    cable_changes: np.ndarray | None


def cc_cable_plan(robot: Robot, start, end, n_samples: int, *, kappa0=None, kappa_d=None, n_links: int = 16,
                  sample: int | None = None) -> CCCablePlan:
    """CC resolved-rate plan of the line ``start -> end`` and its cable commands.

    Parameters
    ----------
    robot : Robot
        Planar robot (see :func:`cable_changes_from_joint_angles`).
    start, end : sequence of 2 numbers
        Line end points in the base x-z plane, ``(x, z)`` [m].
    n_samples : int
        Path samples, both ends included.
    kappa0 : array_like, shape (n_sections,), optional
        Initial curvatures (planar sign) [1/m]; default ``0.1 / L`` in every section.
    kappa_d : array_like, shape (n_sections,), optional
        Null-space target curvatures of Eq. 11 (``None``: no null-space task).
    n_links : int
        Joints of the jointed robot (16 for Hannan & Walker).
    sample : int, optional
        Compute the cable commands of this sample only (0-based); default all samples.

    Returns
    -------
    CCCablePlan
        Without cable commands when the controller did not track the line; the caller decides
        how to report that.
    """
    ell = np.asarray(robot.section_lengths, dtype=float)
    ns = robot.n_sections
    k0 = np.full(ns, 0.1 / robot.length) if kappa0 is None else np.asarray(kappa0, dtype=float)
    # base (x, z) -> planar (-x, z); negated as given (an int 0 stays +0.0)
    path = line_path(np.array([-start[0], start[1]], dtype=float), np.array([-end[0], end[1]], dtype=float),
                     n_samples)
    pr = follow_path(path, k0, ell, kappa_d=kappa_d)
    kappa = np.asarray(pr.q, dtype=float)
    if not pr.success:
        return CCCablePlan(path, kappa, False, np.asarray(pr.error), None, None)
    per = n_links // ns
    k = kappa if sample is None else kappa[sample]
    q = np.repeat(joint_angle_from_curvature(k, ell, per), per, axis=-1)  # Eq. (2-3)
    return CCCablePlan(path, kappa, True, np.asarray(pr.error), q, cable_changes_from_joint_angles(q, robot, n_links))


@dataclass(frozen=True, eq=False)
class HannanWalkerReplay:
    """Result of :func:`replay_hannan_walker` for ``m`` path samples and ``N`` joints.

    Attributes
    ----------
    target : ndarray, shape (m, 3)
        Straight-line samples, base frame [m].
    kappa : ndarray, shape (m, n_sections)
        CC curvatures from the resolved-rate controller (planar sign, towards base +x) [1/m].
    cc_tip : ndarray, shape (m, 3)
        CC tip positions, base frame [m].
    cable_changes : ndarray, shape (m, n_tendons)
        Cable length commands fed to the physics model [m].
    physics_tip : ndarray, shape (m, 3)
        Spring-link tip positions under gravity [m].
    tip_error : ndarray, shape (m,)
        ``|physics_tip - cc_tip|`` [m].
    tensions : ndarray, shape (m, n_tendons)
        Cable tensions in the physics model [N].
    cc_joint_angles, joint_angles : ndarray, shape (m, N)
        Joint angles of the CC (equal per section) and physics solutions [rad].
    """

    target: np.ndarray
    kappa: np.ndarray
    cc_tip: np.ndarray
    cable_changes: np.ndarray
    physics_tip: np.ndarray
    tip_error: np.ndarray
    tensions: np.ndarray
    cc_joint_angles: np.ndarray
    joint_angles: np.ndarray


def _check_replay_inputs(robot: Robot, start, end, kappa0) -> None:
    a = np.asarray(start, dtype=float)
    b = np.asarray(end, dtype=float)
    if a.shape != (2,) or b.shape != (2,):
        raise ValueError(f"start and end must have shape (2,) = (x, z), got {a.shape} and {b.shape}")
    n_sec = robot.n_sections
    k0 = None if kappa0 is None else np.asarray(kappa0, dtype=float)
    if k0 is not None and k0.shape != (n_sec,):
        raise ValueError(f"kappa0 must have shape ({n_sec},), got {k0.shape}")


def replay_hannan_walker(
    robot: Robot,
    start,
    end,
    n_samples: int,
    *,
    kappa0=None,
    n_links: int = 16,
    pretension: float = 0.0,
    options: SolverOptions | None = None,
    params: SpringLinkParams = SpringLinkParams(),
) -> HannanWalkerReplay:
    """Replay a CC straight-line end-point trajectory on the spring-link model.

    Parameters
    ----------
    robot : Robot
        Planar robot, usually ``build_preset("hannan_walker")``.
    start, end : array_like, shape (2,)
        Line end points in the base x-z plane, ``(x, z)`` [m].
    n_samples : int
        Path samples (``>= 2``), both ends included.
    kappa0 : array_like, shape (n_sections,), optional
        Initial CC curvatures (planar sign) [1/m]; default a slight bend ``0.1 / L``.
    n_links : int
        Joints of the spring-link chain (16 for Hannan & Walker).
    pretension : float
        Cable pretension [N] (length control keeps antagonists taut with it).
    options : SolverOptions, optional
        Physics solver options; ``n_elements`` and ``tendon_model`` are overridden with
        ``n_links`` and ``"eyelets"``.
    params : SpringLinkParams

    Returns
    -------
    HannanWalkerReplay
    """
    _check_replay_inputs(robot, start, end, kappa0)
    a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    plan = cc_cable_plan(robot, a, b, n_samples, kappa0=kappa0, n_links=n_links)
    if not plan.success:
        raise ValueError(f"CC resolved-rate controller did not track the line "
                         f"(max error {plan.tracking_error.max():.3g} m)")
    kappa, path, dl = plan.kappa, plan.path, plan.cable_changes
    A = planar_forward_kinematics(kappa, robot.section_lengths)
    cc_tip = np.stack([-A[:, 0, 3], np.zeros(len(A)), A[:, 1, 3]], axis=-1)
    target = np.stack([-path[:, 0], np.zeros(len(path)), path[:, 1]], axis=-1)
    opts = replace(options or SolverOptions(), n_elements=n_links, tendon_model="eyelets")
    tips, tens, qs = [], [], []
    for row in dl:
        act = TendonActuation(mode="length", values=tuple(row), pretension=pretension)
        res = solve(robot, LoadCase(actuation=act), opts, params)
        tips.append(res.tip_position)
        tens.append(res.tendon_tensions)
        qs.append(res.joint_angles[:, 0])
    tips = np.asarray(tips)
    return HannanWalkerReplay(
        target=target, kappa=kappa, cc_tip=cc_tip, cable_changes=dl, physics_tip=tips,
        tip_error=np.linalg.norm(tips - cc_tip, axis=1), tensions=np.asarray(tens),
        cc_joint_angles=plan.joint_angles, joint_angles=np.asarray(qs),
    )
