"""One computation of the wire-delay commands for the scenario, the driver and the report.

workbench/experiments/wire_delay/analysis.py: wire_delay_commands, commanded_wire_lengths,
cc_reading; the scenario (experiments/wire_delay/scenario.py) and figures.matches.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd

from workbench.experiments.wire_delay.analysis import (
    arc_from_wire_lengths_tronconic_workbench,
    cc_reading,
    cc_tip_positions,
    commanded_wire_lengths,
    wire_delay_commands,
    wire_geometry,
    wire_lengths_tronconic_workbench,
)
from workbench.experiments.wire_delay.figures import matches
from workbench.experiments.wire_delay.scenario import wire_delay
from workbench.robot import TendonActuation
from workbench.robot.presets import build_preset


def _robot():
    return build_preset("cojocaru_tronconic", n_sections=1)


def test_scenario_commands_are_wire_delay_commands():
    robot = _robot()
    out = wire_delay(robot, theta=0.6, alpha=0.3, move_time=2.0, delay=1.5, delayed_wire=2, settle_time=0.5)
    cmd = wire_delay_commands(robot, theta=0.6, alpha=0.3, move_time=2.0, delay=1.5, delayed_wire=2)
    assert out["length_changes"] == [float(v) for v in cmd.length_changes]
    assert out["start_delays"] == [0.0, 0.0, 1.5] == list(cmd.start_delays)
    assert out["ramp_durations"] == [2.0, 2.0, 2.0]
    assert out["duration"] == 4.0 and out["ramp_time"] == 2.0


def test_commands_are_the_paper_wire_lengths():
    robot = _robot()
    g = wire_geometry(robot)
    cmd = wire_delay_commands(robot, theta=math.pi / 4, alpha=math.pi / 4, move_time=4.0, delay=3.0, delayed_wire=0)
    L0 = wire_lengths_tronconic_workbench(0.0, 0.0, g.length, g.offset_base, g.offset_tip, g.sigma)
    Lf = wire_lengths_tronconic_workbench(math.pi / 4, math.pi / 4 + math.pi, g.length, g.offset_base, g.offset_tip, g.sigma)
    assert cmd.rest_lengths.tobytes() == L0.tobytes() and cmd.final_lengths.tobytes() == Lf.tobytes()
    # the commanded lengths over time follow the constant-speed ramps; at the end they are a CC arc (e = 0)
    act = TendonActuation("length", tuple(cmd.length_changes), start_times=cmd.start_delays,
                          ramp_durations=cmd.ramp_durations)
    t = np.array([0.0, 2.0, 3.0, 7.0, 8.0])
    L = commanded_wire_lengths(robot, act, t, 4.0)
    np.testing.assert_array_equal(L[0], L0)
    np.testing.assert_allclose(L[-1], Lf, atol=1e-15)
    np.testing.assert_allclose(L[1, 1:], L0[1:] + 0.5 * (Lf - L0)[1:], atol=1e-15)
    assert L[2, 0] == L0[0]  # wire 1 still waits at t = delay
    cc = cc_reading(L, g)
    np.testing.assert_allclose(cc.virtual_compression[[0, -1]], 0.0, atol=1e-12)
    assert cc.virtual_compression[2] < -5e-3  # at t = delay the late wire lags most (docs: -6.23 mm)
    th, ph, e = arc_from_wire_lengths_tronconic_workbench(L, g.length, g.offset_base, g.offset_tip, g.sigma)
    assert cc.tip.tobytes() == cc_tip_positions(th, ph, g.length).tobytes()


def test_cc_tip_positions_is_the_arc_tip():
    L, th, ph = 0.35, 0.8, 1.1
    r = L * (1 - math.cos(th)) / th
    np.testing.assert_allclose(cc_tip_positions(th, ph, L), [r * math.cos(ph), r * math.sin(ph), L * math.sin(th) / th],
                               rtol=1e-14)
    np.testing.assert_array_equal(cc_tip_positions(0.0, 0.3, L), [0.0, 0.0, L])


def test_matches_only_wire_delay_scenario_studies():
    def results(**cols):
        return SimpleNamespace(ok=pd.DataFrame({"model": ["cc"], **{k: [v] for k, v in cols.items()}}))

    assert matches(results(**{"p.scenario.name": "wire_delay"}))
    assert not matches(results(**{"p.scenario.name": "hannan_walker_line"}))
    assert not matches(results())
    assert not matches(SimpleNamespace(ok=pd.DataFrame({"model": []})))
