"""The eyelet tendon (spring-damper chain + outer tension solve) against Exudyn's own reeving system.

Justifies the choice of the chain of constant-force segments for ``tendon_model="eyelets"``:
``ObjectConnectorReevingSystemSprings`` is an independent implementation of the same
frictionless, slack-capable rope through rigid markers; both must give the same equilibrium.
(The facts note measured the reeving system at 0.4-1.8 s per static solve at 64 elements vs
26 ms for chains; the timing is printed by ``benchmarks/bench_ancf.py``, not asserted.)
"""

import math

import numpy as np

from workbench.models.result import SolverOptions
from workbench.physics import _ancf_geometry as geo
from workbench.physics._exudyn import quiet_exudyn
from workbench.physics.ancf import build_problem, _StaticDriver, _System, run
from workbench.physics._stepping import ancf_load_ramp
from workbench.physics.tendon_loads import tendon_rest_lengths
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.orientation import base_rotation_for

L = 0.8


def _robot():
    g = TendonGroup(angles=(0.0, math.pi), offset=0.02, axial_stiffness=4e4)
    return Robot(sections=(Section(length=L, cross_section=CrossSection.circular(6e-3), tendons=g, n_disks=8),),
                 gravity=(0.0, 0.0, -9.81), base_rotation=base_rotation_for("horizontal"))


def _reeving_equilibrium(robot, load, options):
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, ObjectConnectorReevingSystemSprings, ObjectGround

    pb = build_problem(robot, load, options)
    act = load.actuation
    with quiet_exudyn():
        sysm = _System(pb, options, "continuum", 0.0)  # plain rod: tendon curvature stays 0
        mbs = sysm.mbs
        ground = mbs.AddObject(ObjectGround())
        ropes = []
        lref = sysm.reference_path_lengths()
        l0 = tendon_rest_lengths(lref, act.values, act.pretension, [t.EAt for t in pb.tendons])
        for i, td in enumerate(pb.tendons):
            marks = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, float(td.y(0.0)), 0.0]))]
            elem, x = geo.locate(pb.s_nodes, np.array(td.eyelets))
            for s_e, e_i, x_i in zip(td.eyelets, elem, x):
                marks.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=sysm.elements[int(e_i)],
                                                           localPosition=[float(x_i), float(td.y(s_e)), 0.0])))
            ropes.append(mbs.AddObject(ObjectConnectorReevingSystemSprings(
                markerNumbers=marks, stiffnessPerLength=td.EAt, dampingPerLength=0.0, referenceLength=float(lref[i]),
                regularizationForce=1e-3, sheavesAxes=exu.Vector3DList([[0.0, 0.0, 1.0]] * len(marks)), sheavesRadii=[0.0] * len(marks))))
        mbs.Assemble()
        drv = _StaticDriver(sysm, options)
        drv.go_to(1.0, np.zeros(len(pb.tendons)))  # gravity with the ropes at their reference length

        def apply(lam):
            for c, a, b in zip(ropes, lref, l0):
                mbs.SetObjectParameter(c, "referenceLength", float(a + lam * (b - a)))

        def save():
            return sysm.coords(exu.ConfigurationType.Initial).copy()

        def restore(q):
            mbs.systemData.SetODE2Coordinates(q.tolist(), configuration=exu.ConfigurationType.Initial)

        ancf_load_ramp(apply, drv._solve, save, restore, max_steps=200, failure=exu.SolverError)
        qn = sysm.node_coords(sysm.coords())
        r, _ = geo.centreline(qn, pb.s_nodes, np.array([L]))
        # rope tension from the rope length through the markers (reeving law EA (l - l0) / l0)
        T = []
        for td, a in zip(pb.tendons, l0):
            st = np.array(td.eyelets)
            pts = np.vstack([[0.0, float(td.y(0.0))], geo.offset_points(qn, pb.s_nodes, st, td.y(st))])
            T.append(td.EAt * (np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)) - a) / a)
    return np.array([r[0, 1], 0.0, r[0, 0]]), np.array(T)


def test_eyelet_chain_matches_reeving_system():
    robot = _robot()
    load = LoadCase(actuation=TendonActuation("length", (-0.01, 0.004), pretension=5.0))
    options = SolverOptions(n_elements=16, tendon_model="eyelets")
    mine = run(robot, load, options)
    tip, T = _reeving_equilibrium(robot, load, options)
    assert np.max(np.abs(mine.tip_position - tip)) <= 1e-6 * L, (mine.tip_position, tip)
    assert np.allclose(mine.tendon_tensions, T, rtol=1e-5, atol=1e-2), (mine.tendon_tensions, T)
    assert mine.tendon_tensions[0] > 100 and mine.tendon_tensions[1] < mine.tendon_tensions[0]
