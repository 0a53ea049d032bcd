"""Base <-> world frame conversions (workbench.robot.frames) and the world-frame tip columns."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.robot import base_points_to_world, base_rotation_for, base_vectors_to_world, world_from_base, world_vectors_to_base


def test_world_from_base_round_trip():
    R = np.asarray(base_rotation_for("horizontal"))
    p = np.array([0.1, -0.2, 0.3])
    T = world_from_base(R, p)
    x = np.array([[0.0, 0.0, 0.8], [0.01, 0.02, 0.4]])
    np.testing.assert_allclose(base_points_to_world(x, R, p), (T[:3, :3] @ x.T).T + T[:3, 3])
    g = np.array([0.0, 0.0, -9.81])
    np.testing.assert_allclose(base_vectors_to_world(world_vectors_to_base(g, R), R), g)


@pytest.mark.parametrize("name, tip_world", [("vertical", (0, 0, 1)), ("horizontal", (1, 0, 0)), ("upside_down", (0, 0, -1))])
def test_named_orientations_point_the_straight_backbone(name, tip_world):
    np.testing.assert_allclose(base_points_to_world([0.0, 0.0, 1.0], base_rotation_for(name)), tip_world, atol=1e-15)


def test_horizontal_rod_sags_along_world_minus_z():
    """The quickstart rod (horizontal, gravity only): its tip drops along world -z, not sideways."""
    from workbench.models import SolverOptions, get_model
    from workbench.robot import LoadCase
    from workbench.robot.presets import build_preset

    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    res = get_model("ancf")(robot, LoadCase(), SolverOptions(n_elements=8))
    base_sag = np.asarray(res.positions)[-1] - np.array([0.0, 0.0, robot.length])
    world_sag = base_vectors_to_world(base_sag, robot.base_rotation)
    assert world_sag[2] < -1e-3                                         # downwards, by millimetres
    assert abs(world_sag[1]) < 1e-12 and abs(world_sag[0]) < abs(world_sag[2])
    # the base-frame picture is the misleading one: there the sag is along base -x ("falls left")
    assert base_sag[0] < -1e-3 and abs(base_sag[2]) < abs(base_sag[0])
    # linear theory for the small sag: delta = q L^4 / (8 EI)
    EI = robot.sections[0].cross_section.EI
    q = robot.sections[0].cross_section.mass_per_length * 9.81
    assert -world_sag[2] == pytest.approx(q * robot.length ** 4 / (8 * EI), rel=2e-2)


def test_rows_carry_the_world_tip_next_to_the_base_tip():
    from workbench.models import SolverOptions, get_model
    from workbench.robot import LoadCase
    from workbench.robot.presets import build_preset
    from workbench.study.rows import row_from_result

    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    res = get_model("ancf")(robot, LoadCase(), SolverOptions(n_elements=4))
    row = row_from_result(res, "c", "ancf", {}, robot, 0.0)
    tip_w = base_points_to_world([row["tip_x"], row["tip_y"], row["tip_z"]], robot.base_rotation, robot.base_position)
    np.testing.assert_allclose([row["tip_world_x"], row["tip_world_y"], row["tip_world_z"]], tip_w)
    assert row["tip_world_x"] == pytest.approx(row["tip_z"]) and row["tip_world_z"] == pytest.approx(row["tip_x"])
