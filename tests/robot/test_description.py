"""Robot description: validation at construction, derived quantities, round trips."""

import math

import numpy as np
import pytest

from workbench.robot import (
    CrossSection,
    LoadCase,
    Payload,
    Robot,
    RobotDescriptionError,
    Section,
    TendonActuation,
    TendonGroup,
    base_rotation_for,
)
from workbench.robot.presets import build_preset, get_preset, preset_names


def test_circular_section_matches_closed_form():
    cs = CrossSection.circular(diameter=6e-3, youngs_modulus=210e9, density=7850.0)
    assert cs.EI == pytest.approx(210e9 * math.pi * 6e-3**4 / 64, rel=1e-14)
    assert cs.EA == pytest.approx(210e9 * math.pi * 6e-3**2 / 4, rel=1e-14)
    # G J = E / (2 (1 + nu)) * pi d^4 / 32
    assert cs.GJ == pytest.approx(210e9 / 2.6 * math.pi * 6e-3**4 / 32, rel=1e-14)
    assert cs.mass_per_length == pytest.approx(7850 * math.pi * 9e-6, rel=1e-14)
    # the reference rod of the Exudyn facts note
    assert cs.EI == pytest.approx(13.36, abs=5e-3)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        (dict(EI=-1.0, EA=1.0, GJ=1.0, mass_per_length=0.0), "CrossSection.EI must be > 0"),
        (dict(EI=1.0, EA=0.0, GJ=1.0, mass_per_length=0.0), "CrossSection.EA must be > 0"),
        (dict(EI=1.0, EA=1.0, GJ=float("nan"), mass_per_length=0.0), "CrossSection.GJ must be finite"),
        (dict(EI=1.0, EA=1.0, GJ=1.0, mass_per_length=-2.0), "mass_per_length must be >= 0"),
        (dict(EI="stiff", EA=1.0, GJ=1.0, mass_per_length=0.0), "must be a number"),
    ],
)
def test_cross_section_rejects_bad_values(kwargs, fragment):
    with pytest.raises(RobotDescriptionError, match=fragment):
        CrossSection(**kwargs)


def test_section_and_tendon_validation():
    cs = CrossSection.circular(6e-3)
    with pytest.raises(RobotDescriptionError, match="Section.length must be > 0"):
        Section(length=0.0, cross_section=cs)
    with pytest.raises(RobotDescriptionError, match="n_disks must be a positive integer"):
        Section(length=0.1, cross_section=cs, n_disks=0)
    with pytest.raises(RobotDescriptionError, match="at least one angle"):
        TendonGroup(angles=(), offset=0.01)
    with pytest.raises(RobotDescriptionError, match="offset must be > 0"):
        TendonGroup(angles=(0.0,), offset=-0.01)
    with pytest.raises(RobotDescriptionError, match="at least one Section"):
        Robot(sections=())
    with pytest.raises(RobotDescriptionError, match=r"gravity must have shape \(3,\)"):
        Robot(sections=(Section(0.1, cs),), gravity=(0.0, -9.81))
    with pytest.raises(RobotDescriptionError, match="proper rotation"):
        Robot(sections=(Section(0.1, cs),), base_rotation=((1, 0, 0), (0, 1, 0), (0, 0, -1)))


def test_tendon_table_order_and_disks():
    cs = CrossSection.circular(6e-3)
    s0 = Section(0.3, cs, TendonGroup.evenly_spaced(3, 0.02), n_disks=3)
    s1 = Section(0.2, cs, TendonGroup.evenly_spaced(2, 0.015, first_angle=0.5), n_disks=2)
    r = Robot(sections=(s0, s1))
    table = r.tendon_table()
    assert [j for j, _, _ in table] == [0, 0, 0, 1, 1]
    np.testing.assert_allclose([a for _, a, _ in table], [0, 2 * math.pi / 3, 4 * math.pi / 3, 0.5, 0.5 + math.pi])
    np.testing.assert_allclose(r.disk_stations(), [0.1, 0.2, 0.3, 0.4, 0.5])
    assert r.n_tendons == 5 and r.length == pytest.approx(0.5)


def test_taper_interpolates_linearly():
    a, b = CrossSection.circular(8e-3), CrossSection.circular(4e-3)
    s = Section(1.0, a, cross_section_tip=b)
    mid = s.cross_section_at(0.5)
    assert mid.EI == pytest.approx(0.5 * (a.EI + b.EI))
    g = TendonGroup(angles=(0.0,), offset=0.03, offset_tip=0.01)
    assert g.offset_at(0.25) == pytest.approx(0.025)


def test_dict_round_trip_is_exact():
    r = build_preset("steel_rod", n_sections=2, tendon_count=3, gravity=9.81, base_orientation="horizontal",
                     payload_mass=0.05)
    assert Robot.from_dict(r.to_dict()) == r


@pytest.mark.parametrize("name, g_base", [
    ("vertical", (0, 0, -9.81)), ("horizontal", (-9.81, 0, 0)), ("upside_down", (0, 0, 9.81))])
def test_base_orientations_rotate_gravity(name, g_base):
    R = np.asarray(base_rotation_for(name))
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(R) == pytest.approx(1.0)
    r = build_preset("steel_rod", gravity=9.81, base_orientation=name)
    np.testing.assert_allclose(r.gravity_in_base(), g_base, atol=1e-12)


def test_unknown_orientation_and_preset_parameter_are_named():
    with pytest.raises(ValueError, match="unknown base orientation 'sideways'"):
        base_rotation_for("sideways")
    with pytest.raises(TypeError, match="no parameter\\(s\\) lenght"):
        build_preset("steel_rod", lenght=1.0)
    with pytest.raises(KeyError, match="known presets"):
        get_preset("octopus")
    assert "steel_rod" in preset_names()


def test_actuation_ramps_at_constant_speed_with_delays():
    a = TendonActuation("length", (-0.01, 0.02), start_times=(3.0, 0.0), ramp_durations=(2.0, 4.0))
    c = a.command_at(np.array([0.0, 1.0, 3.0, 4.0, 5.0, 6.0]), default_ramp=1.0)
    np.testing.assert_allclose(c[:, 0], [0, 0, 0, -0.005, -0.01, -0.01])
    np.testing.assert_allclose(c[:, 1], [0, 0.005, 0.015, 0.02, 0.02, 0.02])


def test_actuation_and_load_validation():
    with pytest.raises(RobotDescriptionError, match="cannot push"):
        TendonActuation("tension", (1.0, -2.0))
    with pytest.raises(RobotDescriptionError, match="one per tendon"):
        TendonActuation("length", (0.0, 0.0), start_times=(1.0,))
    with pytest.raises(RobotDescriptionError, match="mode must be"):
        TendonActuation("torque", (1.0,))
    with pytest.raises(RobotDescriptionError, match="duration must be > 0"):
        LoadCase(analysis="dynamic")
    r = build_preset("steel_rod")
    with pytest.raises(RobotDescriptionError, match="robot has 2 tendons"):
        TendonActuation("tension", (1.0, 2.0, 3.0)).check_against(r)
    assert Payload().mass == 0.0
