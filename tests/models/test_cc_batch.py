"""Vectorised CC (``workbench.models.cc_batch``) against the CC model (``cc.run``) row by row."""

import zlib

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.models.cc_batch import cc_arcs, cc_backbones, cc_tip_frames, cc_tip_positions
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.presets import build_preset


def _tapered():
    rod = CrossSection.circular(6e-3)
    inner = TendonGroup.evenly_spaced(3, 0.03, offset_tip=0.02)
    outer = TendonGroup.evenly_spaced(4, 0.03, offset_tip=0.01)
    return Robot(sections=(Section(0.5, rod, inner), Section(0.4, rod, outer)))


ROBOTS = {
    "planar_1": lambda: build_preset("steel_rod", tendon_count=2, n_sections=1),
    "planar_2": lambda: build_preset("steel_rod", tendon_count=2, n_sections=2),
    "spatial_1": lambda: build_preset("steel_rod", tendon_count=3, n_sections=1),
    "spatial_3x4": lambda: build_preset("steel_rod", tendon_count=4, n_sections=3),
    "tapered": _tapered,
    "rao_2021": lambda: build_preset("rao_2021"),
}


def _commands(robot, mode, rng, n):
    m = robot.n_tendons
    if mode == "tension":
        c = rng.uniform(0.0, 4.0, (n, m)) * (rng.random((n, m)) < 0.6)
    else:  # small length changes [m]: every section bends well within |kappa| d < 1
        c = rng.uniform(-2e-3, 2e-3, (n, m)) * (rng.random((n, m)) < 0.7)
    c[0] = 0.0  # the straight robot (kappa = 0) among the rows
    return c


def _reference(robot, mode, row, n_stations):
    act = TendonActuation(mode, tuple(float(v) for v in row))
    return get_model("cc")(robot, LoadCase(actuation=act), SolverOptions(n_stations=n_stations))


@pytest.mark.parametrize("name", sorted(ROBOTS))
@pytest.mark.parametrize("mode", ["tension", "length"])
def test_batch_equals_cc_run_row_by_row(name, mode):
    robot = ROBOTS[name]()
    rng = np.random.default_rng(zlib.crc32(f"{name}/{mode}".encode()))
    cmds = _commands(robot, mode, rng, 12)
    tips = cc_tip_positions(robot, mode, cmds)
    frames = cc_tip_frames(robot, mode, cmds)
    backbones = cc_backbones(robot, mode, cmds, 17)
    assert tips.shape == (12, 3) and frames.shape == (12, 4, 4) and backbones.shape == (12, 17, 3)
    assert np.all(np.isfinite(backbones))
    for r, row in enumerate(cmds):
        ref = _reference(robot, mode, row, 17)
        np.testing.assert_allclose(tips[r], ref.tip_position, rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(frames[r], ref.tip_frame, rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(backbones[r], ref.positions, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(tips[0], [0.0, 0.0, robot.length], atol=1e-13)  # straight row (no NaN at kappa = 0)


def test_arcs_equal_arc_from_actuation():
    from workbench.models.cc import arc_from_actuation

    robot = ROBOTS["tapered"]()
    cmds = _commands(robot, "length", np.random.default_rng(3), 6)
    k, p, ell = cc_arcs(robot, "length", cmds)
    for r, row in enumerate(cmds):
        k1, p1, l1 = arc_from_actuation(robot, TendonActuation("length", tuple(row)))
        np.testing.assert_allclose(np.c_[k[r], ell[r]], np.c_[k1, l1], rtol=0.0, atol=1e-12)
        bent = k1 > 1e-9  # the plane of a straight section (row 0: kappa ~ 1e-14, rounding) is arbitrary
        np.testing.assert_allclose(p[r][bent], p1[bent], rtol=0.0, atol=1e-12)


def test_bad_input_is_one_line_naming_the_shape():
    robot = build_preset("rao_2021")
    with pytest.raises(ValueError, match=r"commands must have shape \(n, 6\).*got \(4, 5\)"):
        cc_tip_positions(robot, "tension", np.zeros((4, 5)))
    with pytest.raises(ValueError, match="row 2 is not"):
        cc_tip_positions(robot, "tension", np.r_[np.zeros((2, 6)), np.full((1, 6), np.nan)])
    with pytest.raises(ValueError, match="mode must be"):
        cc_tip_positions(robot, "torque", np.zeros((1, 6)))
    with pytest.raises(ValueError, match="n_stations"):
        cc_backbones(robot, "tension", np.zeros((1, 6)), 1)


def test_empty_batch():
    robot = build_preset("rao_2021")
    assert cc_tip_positions(robot, "tension", np.zeros((0, 6))).shape == (0, 3)
