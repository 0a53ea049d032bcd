"""``beam3d`` eyelets on node bodies (issue 31): an eyelet at a disk on an element boundary hangs on a
massless rigid body of the node instead of on the element's end.  Same point and frame, so the same
answer as the element marker (forced here by disabling the node lookup), in tension and length mode,
statics and damped dynamics; and the rope length read from the reeving connector equals the polyline
through its markers."""

import math

import exudyn as exu
import numpy as np
import pytest

from workbench.models.result import SolverOptions
from workbench.physics import _beam3d_system
from workbench.physics.beam3d import run
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

# 4 disks at 0.075 m spacing on a 0.3 m section, 8 elements: every disk on an element boundary
ROBOT = Robot(sections=(Section(length=0.3, cross_section=CrossSection.circular(2e-3),
                                tendons=TendonGroup((0.0, 2 * math.pi / 3, 4 * math.pi / 3), 5e-3, 4e4),
                                n_disks=4),))
OPTS = SolverOptions(n_elements=8, tendon_model="eyelets", n_stations=5)
LOADS = {
    "tension": LoadCase(actuation=TendonActuation("tension", (60.0, 10.0, 0.0))),
    "length": LoadCase(actuation=TendonActuation("length", (-2e-3, 1e-3, 0.0), pretension=5.0)),
}


def _on_elements(monkeypatch):
    monkeypatch.setattr(_beam3d_system.Beam3DSystem, "_node_at", lambda self, s: None)


@pytest.mark.parametrize("mode", ["tension", "length"])
def test_node_body_eyelets_give_the_element_marker_answer_in_statics(mode, monkeypatch):
    built = {}
    real_init = _beam3d_system.Beam3DSystem.__init__

    def spy(self, *a, **k):
        real_init(self, *a, **k)
        built["node_bodies"] = len(self._node_bodies)

    monkeypatch.setattr(_beam3d_system.Beam3DSystem, "__init__", spy)
    on_nodes = run(ROBOT, LOADS[mode], OPTS)
    assert built["node_bodies"] == 4  # the 4 disks
    _on_elements(monkeypatch)
    on_elements = run(ROBOT, LOADS[mode], OPTS)
    assert built["node_bodies"] == 0
    chord = np.linalg.norm(on_nodes.positions[-1] - on_nodes.positions[0])
    assert chord < 0.999 * ROBOT.length  # a bent rod, not a trivial case
    np.testing.assert_allclose(on_nodes.positions, on_elements.positions, rtol=0, atol=1e-10 * ROBOT.length)
    np.testing.assert_allclose(on_nodes.tendon_tensions, on_elements.tendon_tensions, rtol=1e-8, atol=1e-9)


def test_node_body_eyelets_give_the_element_marker_answer_in_damped_dynamics(monkeypatch):
    act = TendonActuation("length", (-2e-3, 1e-3, 0.0), pretension=5.0)
    load = LoadCase(actuation=act, analysis="dynamic", duration=0.1, ramp_time=0.05)
    opts = SolverOptions(n_elements=8, tendon_model="eyelets", n_stations=5, time_step=1e-3, damping=1e-3)
    a = run(ROBOT, load, opts)
    _on_elements(monkeypatch)
    b = run(ROBOT, load, opts)
    moved = np.max(np.abs(a.series["tip_position"] - a.series["tip_position"][0]))
    assert moved > 1e-3
    # both stop Newton at 1e-6 (RMS increment): the two paths differ by far less than the motion
    np.testing.assert_allclose(a.series["tip_position"], b.series["tip_position"], rtol=0, atol=1e-6 * moved)


def test_rope_length_from_the_connector_is_the_polyline_through_its_markers():
    """tendon_state reads the rope length from the connector (Distance): the polyline through the rope's
    markers, in a deformed (random) configuration; tension EA_t stretch / rest with the rest length set."""
    system = _beam3d_system.Beam3DSystem(ROBOT, LOADS["length"], OPTS, "length")
    system.set_tendons(np.array([-2e-3, 1e-3, 0.0]), 1.0)
    mbs = system.mbs
    q = np.random.default_rng(0).normal(scale=2e-3, size=mbs.systemData.ODE2Size())
    mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Current)
    T, stretch = system.tendon_state()
    assert np.any(T > 0)
    for i, markers in enumerate(system.tendon_markers):
        pts = np.array([mbs.GetMarkerOutput(m, exu.OutputVariableType.Position) for m in markers])
        length = np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()
        rest = float(mbs.GetObjectParameter(system.tendon_objects[i][0], "referenceLength"))
        assert stretch[i] == pytest.approx(length - rest, rel=0, abs=1e-14)
        assert T[i] == pytest.approx(max(0.0, 4e4 * (length - rest) / rest), rel=1e-12, abs=1e-12)


def test_undamped_dynamics_keep_the_element_markers():
    """Undamped dynamics keep eyelets on the elements (answers that depend on the last bit stay as they were)."""
    act = TendonActuation("length", (-2e-3, 1e-3, 0.0), pretension=5.0)
    for damping, n_bodies in ((0.0, 0), (1e-3, 4)):
        opts = SolverOptions(n_elements=8, tendon_model="eyelets", time_step=1e-3, damping=damping)
        load = LoadCase(actuation=act, analysis="dynamic", duration=0.1, ramp_time=0.05)
        system = _beam3d_system.Beam3DSystem(ROBOT, load, opts, "length")
        assert len(system._node_bodies) == n_bodies
