"""Shared Exudyn plumbing of the physics models: quiet console, solver settings, state save and
restore for the load ramp, and the clamp, gravity and lumped-mass items the beam models build alike.

Nothing here runs at import except importing Exudyn itself; every system is built inside the caller
from plain parameters.  Item-adding helpers add their items in a fixed order (so a model that uses
them builds exactly the system it built before).  Checked by ``tests/physics/test_exudyn_helpers.py``
and, through the models, by their validation tests.
"""

from __future__ import annotations

from typing import Callable, Sequence

import exudyn as exu
import numpy as np

from ..models import quiet_if_loaded
from ..models.result import SolverOptions

__all__ = [
    "quiet_exudyn",
    "settings",
    "static_settings",
    "dynamic_settings",
    "SolverError",
    "ode2_saver",
    "clamp_coordinates",
    "add_gravity_loads",
    "add_point_masses",
    "lumped_disk_masses",
    "add_cable2d_disks",
    "set_load_factor",
]

SolverError = exu.SolverError


#: Exudyn's console off inside a ``with`` block, saved and restored (one implementation:
#: :func:`workbench.models.quiet_if_loaded`; Exudyn is always loaded here).
quiet_exudyn = quiet_if_loaded


def _no_files(s: "exu.SimulationSettings", sensors_active: bool | None = None) -> None:
    sol = s.solution
    sol.file.write = False
    sol.restart.write = False
    if sensors_active is not None:
        sol.sensors.active = bool(sensors_active)
    sol.sensors.writePeriod = 1e30
    sol.file.information = ""
    s.show.computationTime = False
    s.show.statistics = False
    s.show.globalTimers = False


def settings(
    tolerance: float,
    max_iterations: int = 50,
    n_load_steps: int = 1,
    *,
    absolute_tolerance: float = 1e-12,
    adaptive: bool | None = None,
    minimum_step_size: float | None = None,
    sensors_active: bool | None = None,
) -> "exu.SimulationSettings":
    """Static-solver settings: Newton converged on the step size (``residualMode = 1``), quiet, file-free.

    Parameters
    ----------
    tolerance : float
        ``newton.relativeTolerance`` (on the Newton step size).
    max_iterations : int
        ``newton.maxIterations``.
    n_load_steps : int
        ``numberOfLoadSteps`` of Exudyn's own load stepping.
    absolute_tolerance : float
        ``newton.absoluteTolerance``.
    adaptive, minimum_step_size, sensors_active : optional
        ``staticSolver.adaptiveStep``, ``staticSolver.minimumStepSize`` and
        ``solution.sensors.active``; ``None`` leaves Exudyn's default.

    Returns
    -------
    exudyn.SimulationSettings
        ``settings(tol, it, n, absolute_tolerance=1e-14, adaptive=n > 1, minimum_step_size=1e-3,
        sensors_active=False)`` equals ``series_parallel._systems._settings(tol, it, n)`` field by field
        (``tests/physics/test_exudyn_helpers.py``).
    """
    s = exu.SimulationSettings()
    _no_files(s, sensors_active)
    st = s.staticSolver
    st.verboseMode = 0
    st.numberOfLoadSteps = int(n_load_steps)
    st.newton.relativeTolerance = tolerance
    st.newton.absoluteTolerance = absolute_tolerance
    st.newton.residualMode = 1
    st.newton.maxIterations = int(max_iterations)
    if adaptive is not None:
        st.adaptiveStep = bool(adaptive)
    if minimum_step_size is not None:
        st.minimumStepSize = minimum_step_size
    return s


def static_settings(options: SolverOptions, n_load_steps: int = 1) -> "exu.SimulationSettings":
    """Static-solver settings of the models: :func:`settings` with the options' Newton tolerance."""
    return settings(options.newton_tolerance, 50, n_load_steps)


def dynamic_settings(options: SolverOptions, end_time: float) -> "exu.SimulationSettings":
    """Implicit generalised-alpha settings with the options' time step, quiet, file-free."""
    s = exu.SimulationSettings()
    _no_files(s)
    ti = s.timeIntegration
    ti.verboseMode = 0
    ti.endTime = float(end_time)
    ti.numberOfSteps = max(1, int(round(end_time / options.time_step)))
    ti.generalizedAlpha.spectralRadius = options.spectral_radius
    ti.newton.relativeTolerance = options.newton_tolerance
    ti.newton.absoluteTolerance = 1e-12
    ti.newton.residualMode = 1
    return s


def ode2_saver(mbs, with_ae: bool = False) -> tuple[Callable[[], object], Callable[[object], None]]:
    """``(save, restore)`` of the solver's start state, for :func:`workbench.physics._stepping.load_ramp`.

    ``save()`` copies the *initial* ODE2 coordinates (and, with ``with_ae``, the algebraic ones:
    the constraint multipliers) -- the state a ``SolveStatic(updateInitialValues=True)`` starts
    from; ``restore(saved)`` writes them back as both the initial and the current configuration.
    """
    initial, current = exu.ConfigurationType.Initial, exu.ConfigurationType.Current

    def save():
        q = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=initial))
        a = np.asarray(mbs.systemData.GetAECoordinates(configuration=initial)) if with_ae else None
        return q, a

    def restore(state) -> None:
        q, a = state
        mbs.systemData.SetODE2Coordinates(q, configuration=initial)
        mbs.systemData.SetODE2Coordinates(q, configuration=current)
        if with_ae:
            mbs.systemData.SetAECoordinates(a, configuration=initial)
            mbs.systemData.SetAECoordinates(a, configuration=current)

    return save, restore


def clamp_coordinates(mbs, node: int, coordinates: Sequence[int]) -> None:
    """Fix the given coordinates of ``node``: one ground node, then a ``CoordinateConstraint`` each."""
    from exudyn.itemInterface import CoordinateConstraint, MarkerNodeCoordinate, NodePointGround

    ng = mbs.AddNode(NodePointGround())
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ng, coordinate=0))
    for k in coordinates:
        mk = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=k))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mk]))


def add_gravity_loads(mbs, bodies: Sequence[int]) -> list[int]:
    """One mass-proportional load per body (vector zero until set); returns the load indices."""
    from exudyn.itemInterface import LoadMassProportional, MarkerBodyMass

    loads = []
    for b in bodies:
        mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=b))
        loads.append(mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0, 0, 0])))
    return loads


def add_point_masses(mbs, nodes: Sequence[int], masses: np.ndarray) -> list[int]:
    """An ``ObjectMassPoint`` on every node but the clamped node 0 whose mass is > 0; returns the objects."""
    from exudyn.itemInterface import ObjectMassPoint

    return [
        mbs.AddObject(ObjectMassPoint(nodeNumber=nodes[i], mass=float(m)))
        for i, m in enumerate(masses)
        if m > 0 and i > 0
    ]


def lumped_disk_masses(robot, node_s: np.ndarray, *, midpoint_weights: bool = False) -> np.ndarray:
    """Disk masses lumped onto the two nodes of the element that holds each disk (linear weights).

    Parameters
    ----------
    robot : Robot
        Its sections' ``disk_mass`` and ``disk_positions()``.
    node_s : (n + 1,) ndarray
        Reference arc length of the nodes [m].
    midpoint_weights : bool
        Compute the far-node weight as ``1/2 + (s - s_mid) / L_e`` (``beam3d``'s arithmetic) instead
        of ``(s - s_e) / L_e`` (``ancf3d``'s): the same number up to rounding, kept apart so each
        model's results stay bit-identical.

    Returns
    -------
    ndarray, shape (n + 1,)
        Lumped mass per node [kg] (payload not included).
    """
    lumped = np.zeros(len(node_s))
    elem_len = np.diff(node_s)
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    for j, sec in enumerate(robot.sections):
        if sec.disk_mass > 0:
            for sd in starts[j] + sec.disk_positions():
                e = min(max(int(np.searchsorted(node_s, sd, side="left")) - 1, 0), len(elem_len) - 1)
                if midpoint_weights:
                    w1 = 0.5 + float(sd - 0.5 * (node_s[e] + node_s[e + 1])) / elem_len[e]
                else:
                    w1 = (sd - node_s[e]) / elem_len[e]
                lumped[e] += sec.disk_mass * (1.0 - w1)
                lumped[e + 1] += sec.disk_mass * w1
    return lumped


def add_cable2d_disks(mbs, s_nodes: np.ndarray, nodes: Sequence[int], elements: Sequence[int],
                      disk_s: np.ndarray, disk_m: np.ndarray, with_weight: bool) -> list[int]:
    """Disks on a planar ANCF cable (``ObjectANCFCable2D``): each weight a force at its station, each
    mass lumped linearly onto the two nodes of the element that holds it.

    The weight acts through a position marker on the element at the disk's station (Exudyn's
    consistent Hermite load), so it is a point load where the disk is; the cable has no mass at an
    arbitrary station, so the inertia is exact only when disks sit on nodes (node 0's share sits on
    the clamp and is dropped).  Used by the planar ANCF model and the contact system; checked by
    ``tests/physics/test_ancf_disks.py``.

    Parameters
    ----------
    s_nodes : (n + 1,) ndarray
        Reference arc length of the nodes [m].
    nodes, elements : sequence of int
        The cable's node and element indices.
    disk_s, disk_m : (k,) ndarray
        Disk stations [m] and masses [kg].
    with_weight : bool
        Add the weight loads (gravity is not zero).

    Returns
    -------
    list of int
        One ``LoadForceVector`` per disk (vector zero until set: ``m g`` in Exudyn's plane), or
        ``[]`` without weight.
    """
    from exudyn.itemInterface import LoadForceVector, MarkerBodyPosition, ObjectMassPoint2D

    from ._ancf_geometry import locate

    if disk_m.size == 0:
        return []
    elem, x = locate(s_nodes, disk_s)
    w1 = x / np.diff(s_nodes)[elem]
    lumped = np.zeros(s_nodes.size)
    np.add.at(lumped, elem, disk_m * (1.0 - w1))
    np.add.at(lumped, elem + 1, disk_m * w1)
    for i in np.flatnonzero(lumped[1:] > 0) + 1:
        mbs.AddObject(ObjectMassPoint2D(nodeNumber=nodes[int(i)], mass=float(lumped[i])))
    if not with_weight:
        return []
    return [mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerBodyPosition(
                bodyNumber=elements[int(e)], localPosition=[float(xi), 0.0, 0.0])), loadVector=[0, 0, 0]))
            for e, xi in zip(elem, x)]


def set_load_factor(mbs, loads: Sequence[tuple[int, np.ndarray]], lam: float) -> None:
    """Set every ``(load index, full vector)`` in ``loads`` to ``lam`` times its vector."""
    for ld, v in loads:
        mbs.SetLoadParameter(ld, "loadVector", [float(x) for x in lam * np.asarray(v)])
