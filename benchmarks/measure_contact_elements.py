"""Which Exudyn contact element is right for a backbone on a rigid circle: a measurement, not a test.

Run from the repository root: ``python benchmarks/measure_contact_elements.py``.  The hand case of
``tests/physics/test_contact.py``: a cantilever (L = 1 m, EI = 1 N m^2, EA = 1e4 N, 16 ANCF
elements) pressed upwards by a rigid circle (R = 5 cm, centre 0.6 m from the clamp) that is lifted
by ``delta`` past first touch, in 10 static steps.  Reference: linear Euler-Bernoulli with the
contact point on the circle (``F = 3 EI w_c / x_c^3``).  For every element it prints the force on
the circle (the circle's fixture reaction), the force the beam feels (its clamp's reaction), both
against the reference, the Newton steps and the wall time of the ten solves:

* ``ObjectContactCircleCable2D`` (frictionless, 8 segments per element),
* ``ObjectContactFrictionCircleCable2D`` with ``frictionCoefficient = 0`` (what the workbench uses),
* ``GeneralContact`` (``AddANCFCable`` + ``AddSphereWithMarker``) for a range of contact stiffnesses;

then, with friction 0.3, the ratio of tangential to normal force on the circle when it slides 2 mm
along the beam (static solves: Coulomb friction should give 0.3).

The line-contact penalty of the two circle elements is per segment: ``k_line * element length /
segments`` with ``k_line = 1e8 N/m^2`` (``ContactLaw``'s default); GeneralContact's stiffness is
per contact point [N/m].  Results: ``docs/models.md``, "Planar contact".
"""

from __future__ import annotations

import math
import time

import numpy as np

L, EI, EA, MU, N, R, A = 1.0, 1.0, 1e4, 0.1, 16, 0.05, 0.6


def beam_theory(delta: float) -> float:
    """Contact force [N] of linear beam theory on the circle lifted ``delta`` into the beam."""
    th, F = 0.0, 0.0
    for _ in range(60):
        xc, wc = A - R * math.sin(th), delta - R + R * math.cos(th)
        F = 3.0 * EI * wc / xc**3
        th = F * xc**2 / (2.0 * EI)
    return F


def build(kind: str, stiffness: float, segments: int = 8, mu: float = 0.0):
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint, MarkerBodyCable2DShape, MarkerBodyRigid, MarkerNodeCoordinate, MarkerNodeRigid,
        NodeGenericData, NodePoint2DSlope1, NodePointGround, NodeRigidBody2D, ObjectANCFCable2D,
        ObjectContactCircleCable2D, ObjectContactFrictionCircleCable2D, ObjectRigidBody2D,
    )

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    le = L / N
    nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[i * le, 0, 1, 0])) for i in range(N + 1)]
    els = [mbs.AddObject(ObjectANCFCable2D(nodeNumbers=[nodes[i], nodes[i + 1]], length=le, bendingStiffness=EI,
                                           axialStiffness=EA, massPerLength=MU, useReducedOrderIntegration=2))
           for i in range(N)]
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    clamp = [mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(
        MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=c))])) for c in (0, 1, 3)]
    nR = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[A, -R - 1e-3, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=nR, mass=1.0, inertia=1.0))
    cons = [mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(
        MarkerNodeCoordinate(nodeNumber=nR, coordinate=c))])) for c in range(3)]
    if kind == "general":
        gc = mbs.AddGeneralContact()
        gc.verboseMode = 0
        gc.AddSphereWithMarker(mbs.AddMarker(MarkerNodeRigid(nodeNumber=nR)), radius=R, contactStiffness=stiffness,
                               contactDamping=0.0, frictionMaterialIndex=0)
        for e in els:
            gc.AddANCFCable(objectIndex=e, halfHeight=0.0, contactStiffness=stiffness, contactDamping=0.0,
                            frictionMaterialIndex=0)
        gc.SetFrictionPairings(np.full((1, 1), mu))
        gc.SetSearchTreeBox(pMin=[-0.2, -0.5, -0.1], pMax=[1.2, 0.5, 0.1])
        gc.SetSearchTreeCellSize(numberOfCells=[32, 8, 1])
    else:
        mR = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
        k = stiffness * le / segments
        for e in els:
            mc = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=e, numberOfSegments=segments))
            if kind == "plain":
                nd = mbs.AddNode(NodeGenericData(initialCoordinates=[0.1] * segments, numberOfDataCoordinates=segments))
                mbs.AddObject(ObjectContactCircleCable2D(markerNumbers=[mR, mc], nodeNumber=nd,
                                                         numberOfContactSegments=segments, contactStiffness=k,
                                                         circleRadius=R))
            else:
                nd = mbs.AddNode(NodeGenericData(initialCoordinates=[0.1] * segments + [-2.0] * segments
                                                 + [0.0] * segments, numberOfDataCoordinates=3 * segments))
                mbs.AddObject(ObjectContactFrictionCircleCable2D(
                    markerNumbers=[mR, mc], nodeNumber=nd, numberOfContactSegments=segments, contactStiffness=k,
                    frictionStiffness=k if mu > 0 else 0.0, frictionCoefficient=mu, circleRadius=R))
    mbs.Assemble()
    return exu, mbs, clamp, cons


def measure(kind: str, stiffness: float, delta: float = 0.005, steps: int = 10, mu: float = 0.0,
            slide: float = 0.0) -> dict:
    """Press (``steps`` solves), then, if ``slide`` > 0, move the circle along the beam by ``slide`` [m]
    (its rotation locked) in ``steps`` solves: ``friction`` = |tangential / normal force on the circle|."""
    exu, mbs, clamp, cons = build(kind, stiffness, mu=mu)
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.staticSolver.verboseMode = 0
    s.staticSolver.newton.relativeTolerance = 1e-10
    s.staticSolver.newton.absoluteTolerance = 1e-12
    s.staticSolver.newton.residualMode = 1
    s.staticSolver.newton.maxIterations = 50
    s.staticSolver.adaptiveStep = False
    s.staticSolver.discontinuous.iterationTolerance = 1e-7
    s.staticSolver.discontinuous.maxIterations = 50
    newton, ok, t0 = 0, True, time.perf_counter()
    path = [(0.0, (delta + 1e-3) * i / steps) for i in range(1, steps + 1)]
    path += [(slide * i / steps, delta + 1e-3) for i in range(1, steps + 1)] if slide > 0 else []
    for dx, dy in path:
        mbs.SetObjectParameter(cons[0], "offset", dx)
        mbs.SetObjectParameter(cons[1], "offset", dy)
        solver = exu.MainSolverStatic()
        try:
            ok = bool(solver.SolveSystem(mbs, s))
        except Exception:  # noqa: BLE001 - a measurement: record and stop
            ok = False
        newton += int(solver.it.newtonStepsCount)
        if not ok:
            break
        sd = mbs.systemData
        sd.SetSystemState(systemStateList=sd.GetSystemState(), configuration=exu.ConfigurationType.Initial)
    wall = time.perf_counter() - t0
    F = beam_theory(delta)
    on_circle = float(mbs.GetObjectOutput(cons[1], exu.OutputVariableType.Force)) if ok else math.nan
    on_beam = float(-mbs.GetObjectOutput(clamp[1], exu.OutputVariableType.Force)) if ok else math.nan
    tang = float(mbs.GetObjectOutput(cons[0], exu.OutputVariableType.Force)) if ok else math.nan
    return {"ok": ok, "circle": on_circle / F - 1.0, "beam": on_beam / F - 1.0, "newton": newton, "wall": wall,
            "friction": abs(tang / on_circle)}


def main() -> None:
    from workbench.physics._exudyn import quiet_exudyn

    rows = [(f"ObjectContactCircleCable2D k={k:.0e} N/m^2", "plain", k) for k in (1e5, 1e6, 1e7, 1e8)]
    rows += [(f"ObjectContactFrictionCircleCable2D mu=0 k={k:.0e}", "friction", k) for k in (1e5, 1e6, 1e7, 1e8)]
    rows += [(f"GeneralContact k={k:.0e} N/m", "general", k) for k in (1e4, 1e5, 1e6, 1e7, 1e8, 1e9)]
    print(f"reference (linear beam theory, delta 5 mm): F = {beam_theory(0.005):.6f} N")
    print(f"{'element':46s} {'ok':>3s} {'circle/F-1':>11s} {'beam/F-1':>11s} {'newton':>7s} {'wall [s]':>9s}")
    for name, kind, k in rows:
        with quiet_exudyn():
            m = measure(kind, k)
        print(f"{name:46s} {'yes' if m['ok'] else 'NO':>3s} {m['circle']:11.2e} {m['beam']:11.2e} "
              f"{m['newton']:7d} {m['wall']:9.3f}")
    print("\nfriction in a static solve: press, then slide the circle 2 mm along the beam (rotation locked), mu = 0.3")
    print(f"{'element':46s} {'ok':>3s} {'|F_t / F_n|':>11s}")
    for name, kind, k in (("ObjectContactFrictionCircleCable2D k=1e+08", "friction", 1e8),
                          ("GeneralContact k=1e+08 N/m", "general", 1e8)):
        with quiet_exudyn():
            m = measure(kind, k, mu=0.3, slide=0.002)
        print(f"{name:46s} {'yes' if m['ok'] else 'NO':>3s} {m['friction']:11.3e}")


if __name__ == "__main__":
    main()
