"""The robot picture (``workbench.report.robot_picture``): what it draws is the robot's geometry.

The tendon paths end where the description says (terminating disk, tip offset of a tapered group),
the side views' lateral stretch is the stated whole number, and the PNG is written.
"""

from __future__ import annotations

import math

import numpy as np

from workbench.report.robot_picture import lateral_scale, robot_figure, save_robot_picture, tendon_paths
from workbench.robot.presets import build_preset


def test_tendon_paths_end_at_their_disk_with_the_tip_offset():
    r = build_preset("cojocaru_tronconic")
    paths = tendon_paths(r)
    assert len(paths) == r.n_tendons
    for (sec, sigma, p), (sec2, sigma2, g) in zip(paths, r.tendon_table()):
        assert (sec, sigma) == (sec2, sigma2)
        d_tip = g.offset_tip
        np.testing.assert_allclose(p[-1], [d_tip * math.cos(sigma), d_tip * math.sin(sigma), r.section_ends[sec]],
                                   atol=1e-12)
        np.testing.assert_allclose(p[0], [g.offset * math.cos(sigma), g.offset * math.sin(sigma), 0.0], atol=1e-12)


def test_lateral_scale_by_hand():
    # steel_rod: L = 0.8 m, widest = tendon offset 0.02 m -> 0.8 / (8 x 0.02) = 5
    assert lateral_scale(build_preset("steel_rod")) == 5.0
    # a robot wider than L / 8 is not squeezed
    assert lateral_scale(build_preset("steel_rod", length=0.1, tendon_offset=0.05)) == 1.0


def test_figure_has_three_panels_and_states_the_scale():
    fig = robot_figure(build_preset("steel_rod", gravity=9.81, payload_mass=0.1), title="t")
    axes = fig.get_axes()
    assert len(axes) == 3
    assert "lateral scale x5" in axes[0].get_xlabel()
    assert "true scale" in axes[2].get_title()


def test_png_is_written(tmp_path):
    out = save_robot_picture(build_preset("hannan_walker"), tmp_path / "sub" / "r.png")
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
