"""Shared Exudyn helpers (``workbench.physics._exudyn``): settings builders, state save/restore, items."""

from __future__ import annotations

import math

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")

from workbench.models import SolverOptions  # noqa: E402
from workbench.physics import _exudyn as X  # noqa: E402
from workbench.robot import CrossSection, Robot, Section  # noqa: E402


def _flat(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(_flat(v, prefix + k + "."))
        else:
            out[prefix + k] = v
    return out


def _changed(s) -> dict:
    """Fields of settings ``s`` that differ from a fresh ``SimulationSettings``."""
    d0, d = _flat(exu.SimulationSettings().GetDictionary()), _flat(s.GetDictionary())
    assert d.keys() == d0.keys()
    return {k: d[k] for k in d if str(d[k]) != str(d0[k])}


_SP_FIELDS = {  # what the series-parallel solves have always set (the pre-refactor _settings, field by field)
    "show.globalTimers": False, "solution.file.write": False, "solution.sensors.active": False,
    "solution.sensors.writePeriod": 1e30, "staticSolver.newton.absoluteTolerance": 1e-14,
    "staticSolver.newton.residualMode": 1, "staticSolver.minimumStepSize": 1e-3, "staticSolver.verboseMode": 0,
}


@pytest.mark.parametrize("tol, max_iter, n_steps", [(1e-10, 30, 1), (1e-8, 50, 4), (3e-9, 12, 2)])
def test_series_parallel_settings_field_by_field(tol, max_iter, n_steps):
    from workbench.physics.series_parallel import _systems as sp

    want = dict(_SP_FIELDS, **{"staticSolver.newton.maxIterations": max_iter,
                               "staticSolver.newton.relativeTolerance": tol,
                               "staticSolver.numberOfLoadSteps": n_steps,
                               "staticSolver.adaptiveStep": n_steps > 1})
    d0 = _flat(exu.SimulationSettings().GetDictionary())
    want = {k: v for k, v in want.items() if str(v) != str(d0[k])}  # a value equal to Exudyn's default is no change
    assert _changed(sp._settings(tol, max_iter, n_steps)) == want


def test_static_settings_change_only_the_documented_fields():
    assert _changed(X.static_settings(SolverOptions(newton_tolerance=1e-7), 3)) == {
        "show.globalTimers": False,
        "solution.file.write": False,
        "solution.sensors.writePeriod": 1e30,
        "staticSolver.newton.absoluteTolerance": 1e-12,
        "staticSolver.newton.maxIterations": 50,
        "staticSolver.newton.relativeTolerance": 1e-7,
        "staticSolver.newton.residualMode": 1,
        "staticSolver.numberOfLoadSteps": 3,
        "staticSolver.verboseMode": 0,
    }


def test_dynamic_settings_change_only_the_documented_fields():
    got = _changed(X.dynamic_settings(SolverOptions(time_step=1e-3, spectral_radius=0.5), 0.25))
    assert got == {
        "show.globalTimers": False,
        "solution.file.write": False,
        "solution.sensors.writePeriod": 1e30,
        "timeIntegration.generalizedAlpha.spectralRadius": 0.5,
        "timeIntegration.newton.absoluteTolerance": 1e-12,
        "timeIntegration.newton.relativeTolerance": 1e-9,
        "timeIntegration.newton.residualMode": 1,
        "timeIntegration.endTime": 0.25,
        "timeIntegration.numberOfSteps": 250,
    }


def _cantilever(n: int = 4, with_mass: bool = True):
    """A GE-beam cantilever built with the helpers: clamp, gravity on elements and point masses."""
    from exudyn.itemInterface import NodeRigidBodyEP, ObjectBeamGeometricallyExact

    cs = CrossSection.circular(6e-3)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node_s = np.linspace(0.0, 0.8, n + 1)
    nodes = [mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=[float(s), 0, 0, 1, 0, 0, 0])) for s in node_s]
    sec = exu.BeamSection()
    sec.stiffnessMatrix = np.diag([cs.EA, 100 * cs.EA, 100 * cs.EA, cs.GJ, cs.EI, cs.EI])
    sec.massPerLength = cs.mass_per_length
    sec.inertia = cs.mass_per_length * (cs.EI / cs.EA) * np.diag([2.0, 1.0, 1.0])
    elements = [mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[e], nodes[e + 1]],
                                                           length=float(node_s[1] - node_s[0]), sectionData=sec))
                for e in range(n)]
    X.clamp_coordinates(mbs, nodes[0], (0, 1, 2, 4, 5, 6))
    bodies = list(elements)
    if with_mass:
        masses = np.zeros(n + 1)
        masses[-1] = 0.05
        bodies += X.add_point_masses(mbs, nodes, masses)
    loads = [(ld, np.array([0.0, -9.81, 0.0])) for ld in X.add_gravity_loads(mbs, bodies)]
    mbs.Assemble()
    return mbs, nodes, loads, cs


def test_clamp_gravity_and_point_mass_helpers_build_a_sagging_cantilever():
    with X.quiet_exudyn():
        mbs, nodes, loads, cs = _cantilever()
        assert len(loads) == 4 + 1  # every element and the tip mass
        X.set_load_factor(mbs, loads, 0.5)
        np.testing.assert_array_equal(mbs.GetLoadParameter(loads[0][0], "loadVector"), [0.0, -4.905, 0.0])
        X.set_load_factor(mbs, loads, 1.0)
        exu.SolveStatic(mbs, X.static_settings(SolverOptions()), updateInitialValues=True)
        tip = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)
        base = mbs.GetNodeOutput(nodes[0], exu.OutputVariableType.Position)
    L, q, P = 0.8, cs.mass_per_length * 9.81, 0.05 * 9.81
    linear = q * L**4 / (8 * cs.EI) + P * L**3 / (3 * cs.EI)  # small-deflection cantilever
    np.testing.assert_allclose(base, [0.0, 0.0, 0.0], atol=1e-14)
    assert tip[1] == pytest.approx(-linear, rel=0.05)


@pytest.mark.parametrize("with_ae", [False, True])
def test_ode2_saver_restores_the_start_state(with_ae):
    with X.quiet_exudyn():
        mbs, _, loads, _ = _cantilever(with_mass=False)
        save, restore = X.ode2_saver(mbs, with_ae)
        X.set_load_factor(mbs, loads, 1.0)
        exu.SolveStatic(mbs, X.static_settings(SolverOptions()), updateInitialValues=True)
        state = save()
        q1 = np.array(mbs.systemData.GetODE2Coordinates())
        a1 = np.array(mbs.systemData.GetAECoordinates(configuration=exu.ConfigurationType.Initial))
        X.set_load_factor(mbs, loads, 3.0)
        exu.SolveStatic(mbs, X.static_settings(SolverOptions()), updateInitialValues=True)
        assert not np.array_equal(mbs.systemData.GetODE2Coordinates(), q1)
        restore(state)
        for cfg in (exu.ConfigurationType.Initial, exu.ConfigurationType.Current):
            np.testing.assert_array_equal(mbs.systemData.GetODE2Coordinates(configuration=cfg), q1)
        a = np.array(mbs.systemData.GetAECoordinates(configuration=exu.ConfigurationType.Initial))
        assert np.array_equal(a, a1) == with_ae


def test_lumped_disk_masses_conserve_mass_and_both_weightings_agree():
    secs = (Section(length=0.3, cross_section=CrossSection.circular(6e-3), n_disks=5, disk_mass=0.01),
            Section(length=0.5, cross_section=CrossSection.circular(5e-3), n_disks=3, disk_mass=0.02))
    robot = Robot(sections=secs)
    node_s = np.array([0.0, 0.13, 0.3, 0.47, 0.61, 0.8])
    a = X.lumped_disk_masses(robot, node_s)
    b = X.lumped_disk_masses(robot, node_s, midpoint_weights=True)
    assert a.sum() == pytest.approx(5 * 0.01 + 3 * 0.02, rel=1e-14)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-15)
    assert np.all(a >= 0)
    # a disk exactly on a node puts all its mass there
    one = Robot(sections=(Section(length=0.8, cross_section=CrossSection.circular(6e-3), n_disks=1, disk_mass=0.1),))
    m = X.lumped_disk_masses(one, np.linspace(0.0, 0.8, 5))
    assert m[-1] == pytest.approx(0.1) and math.isclose(m[:-1].sum(), 0.0, abs_tol=1e-15)
