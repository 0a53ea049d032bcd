"""The spring-link chain as an Exudyn ``ObjectKinematicTree`` (minimal coordinates), for the
speed comparison of :mod:`benchmarks.bench_spring_link` only.

Same discretisation as :mod:`workbench.physics.spring_link` (half-link layout, joint stiffness
``EI/ds`` as the tree's ``jointPControlVector``).  Planar: one ``RevoluteY`` joint per link
(rotation about base +y, bending towards +x).  3-D: ``RevoluteX`` then ``RevoluteY`` at each joint
(a Cardan joint, torsion locked), the intermediate link massless.  Supported loads: gravity (the
tree's own ``gravity``), a tip moment about base y and continuum tendons at sigma in {0, pi}
(both as constant generalised joint forces, exact for bends in the x-z plane).  The tree has no
eyelet/rope support here, which is why the registered model uses rigid bodies (the tree was also
not faster, see the benchmark).  Static solve with own load ramp (gravity is applied at once by
Exudyn).
"""

from __future__ import annotations

import numpy as np

from ...models.result import ModelFailure, SolverOptions
from ...robot import LoadCase, Robot
from .geometry import chain_geometry_from_robot

__all__ = ["tree_tip_position"]


def tree_tip_position(robot: Robot, load: LoadCase, options: SolverOptions, dimension: str = "2d") -> np.ndarray:
    """Static tip position ``(3,)`` of the kinematic-tree chain (see the module docstring)."""
    import exudyn as exu
    import exudyn.itemInterface as eii

    from .._exudyn import quiet_exudyn, static_settings

    if dimension not in ("2d", "3d"):
        raise ValueError(f"dimension must be '2d' or '3d', got {dimension!r}")
    if any(abs(np.sin(s)) > 1e-9 for _, s, _ in robot.tendon_table()):
        raise ValueError("tree_tip_position supports tendons at sigma in {0, pi} only")
    if np.any(np.abs(load.tip_force) > 0) or abs(load.tip_torque[0]) > 0 or abs(load.tip_torque[2]) > 0:
        raise ValueError("tree_tip_position supports a tip moment about base y only")
    geo = chain_geometry_from_robot(robot, options.n_elements)
    N = geo.n_links
    per = 1 if dimension == "2d" else 2
    n = N * per
    Q = np.full(N, float(load.tip_torque[1]))
    if load.actuation is not None:
        if load.actuation.mode != "tension":
            raise ValueError("tree_tip_position supports tension control only")
        m_end = geo.section_end_eyelet
        for (j, sigma, grp), T in zip(robot.tendon_table(), load.actuation.values):
            Q[: m_end[j]] += T * grp.offset * (1.0 if np.cos(sigma) > 0 else -1.0)
    types, parents, offsets, masses, coms, inertias, P = [], [], [], [], [], [], []
    for k in range(N):
        off = geo.joints[0] if k == 0 else geo.link_lengths[k - 1]
        Ib, Ia = geo.inertia_bending[k], geo.inertia_axial[k]
        body = (float(geo.mass[k]), [0.0, 0.0, float(geo.com[k])], np.diag([Ib, Ib, Ia]).tolist())
        joints = [exu.JointType.RevoluteY] if per == 1 else [exu.JointType.RevoluteX, exu.JointType.RevoluteY]
        for i, jt in enumerate(joints):
            types.append(jt)
            parents.append(len(types) - 2)
            offsets.append([0.0, 0.0, float(off) if i == 0 else 0.0])
            if i == len(joints) - 1:
                masses.append(body[0])
                coms.append(body[1])
                inertias.append(body[2])
            else:  # massless intermediate link of the Cardan joint
                masses.append(0.0)
                coms.append([0.0, 0.0, 0.0])
                inertias.append(np.zeros((3, 3)).tolist())
            P.append(float(geo.stiffness[k]))
    Qfull = np.zeros(n)
    Qfull[per - 1 :: per] = Q
    g = np.asarray(robot.gravity_in_base(), dtype=float)
    with quiet_exudyn():
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        node = mbs.AddNode(eii.NodeGenericODE2(referenceCoordinates=[0.0] * n, initialCoordinates=[0.0] * n,
                                               initialCoordinates_t=[0.0] * n, numberOfODE2Coordinates=n))
        tree = mbs.AddObject(eii.ObjectKinematicTree(
            nodeNumber=node, jointTypes=types, linkParents=parents,
            jointTransformations=exu.Matrix3DList([np.eye(3)] * n),
            jointOffsets=exu.Vector3DList(offsets),
            linkInertiasCOM=exu.Matrix3DList([np.asarray(I) for I in inertias]),
            linkCOMs=exu.Vector3DList(coms), linkMasses=masses, baseOffset=[0.0, 0.0, 0.0],
            gravity=[0.0, 0.0, 0.0], jointForceVector=[0.0] * n, jointPositionOffsetVector=[0.0] * n,
            jointPControlVector=P, jointDControlVector=[0.0] * n, jointVelocityOffsetVector=[0.0] * n))
        mbs.Assemble()
        settings = static_settings(options, 1)
        settings.staticSolver.adaptiveStep = False
        lam, inc, attempts = 0.0, 1.0, 0
        while lam < 1.0:
            target = min(1.0, lam + inc)
            attempts += 1
            if attempts > options.max_load_steps:
                raise ModelFailure("kinematic tree: load ramp exceeded options.max_load_steps")
            q_save = mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Initial)
            mbs.SetObjectParameter(tree, "gravity", (target * g).tolist())
            mbs.SetObjectParameter(tree, "jointForceVector", (target * Qfull).tolist())
            solver = exu.MainSolverStatic()
            try:
                ok = solver.SolveSystem(mbs, settings)
            except exu.SolverError:
                ok = False
            if ok:
                q = mbs.systemData.GetODE2Coordinates()
                mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Initial)
                lam, inc = target, min(1.0, 2 * inc)
            else:
                mbs.systemData.SetODE2Coordinates(q_save, configuration=exu.ConfigurationType.Initial)
                inc *= 0.5
        q = np.asarray(mbs.systemData.GetODE2Coordinates())
    # forward kinematics of the chain
    R = np.eye(3)
    p = np.zeros(3)
    for k in range(N):
        p = p + R @ np.array([0.0, 0.0, geo.joints[0] if k == 0 else geo.link_lengths[k - 1]])
        for i in range(per):
            a = q[k * per + i]
            c, s = np.cos(a), np.sin(a)
            if per == 2 and i == 0:
                R = R @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
            else:
                R = R @ np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return p + R @ np.array([0.0, 0.0, geo.link_lengths[-1]])
