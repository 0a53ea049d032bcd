"""The description form of ``[robot]`` (``docs/robot-format.md``): built robots against independent references.

References: the code presets (a description of the same robot must build it bit for bit), the
tube's section properties from two solid rods (``I_tube = I(D) - I(d)``), Cowper's thin-walled
tube shear coefficient ``2 (1 + nu) / (4 + 3 nu)`` (Cowper 1966, J. Appl. Mech. 33:335).
"""

from __future__ import annotations

import math

import pytest

from workbench.robot import CrossSection
from workbench.robot.presets import build_preset
from workbench.robot.spec import robot_from_params, robot_problems, robot_value_sources
from workbench.study.build import resolve_robot
from workbench.study.spec import parse_study


def steel_rod_description() -> dict:
    """steel_rod's defaults written in the description form (spring steel = its E, nu, density, yield)."""
    return {"name": "steel_rod", "gravity": [0.0, 0.0, -0.0],
            "sections": [{"length": 0.8, "material": "spring_steel", "diameter": 6e-3, "disks": {"count": 8},
                          "tendons": [{"count": 2, "offset": 0.02, "axial_stiffness": 4.0e4,
                                       "area": 4.0e4 / 210e9, "strength": 2.41e9}]}]}


def test_description_builds_the_steel_rod_preset_bit_for_bit():
    assert robot_problems(steel_rod_description()) == []
    assert robot_from_params(steel_rod_description()) == build_preset("steel_rod")


def test_stiffness_form_builds_the_shao_preset_bit_for_bit():
    desc = {"name": "shao_harvester", "gravity": [0.0, 0.0, -9.81], "base_orientation": "upside_down",
            "payload": {"mass": 0.0},
            "sections": [{"length": 0.4, "bending_stiffness": 0.3, "axial_stiffness": 2.0e3,
                          "torsional_stiffness": 0.2, "mass_per_length": 0.23 / 0.4, "diameter": 0.06,
                          "disks": {"count": 4}, "tendons": [{"count": 3, "offset": 0.022, "axial_stiffness": 2.0e3}]}]}
    assert robot_from_params(desc) == build_preset("shao_harvester")


def test_tube_is_the_difference_of_two_rods():
    E, rho, nu, D, d = 54e9, 6450.0, 0.3, 2.0e-3, 1.2e-3
    tube = CrossSection.tube(D, d, E, rho, nu)
    outer, inner = CrossSection.circular(D, E, rho, nu), CrossSection.circular(d, E, rho, nu)
    assert tube.EI == pytest.approx(outer.EI - inner.EI, rel=1e-14)
    assert tube.EA == pytest.approx(outer.EA - inner.EA, rel=1e-14)
    assert tube.GJ == pytest.approx(outer.GJ - inner.GJ, rel=1e-14)
    assert tube.mass_per_length == pytest.approx(outer.mass_per_length - inner.mass_per_length, rel=1e-14)
    assert tube.section_modulus == pytest.approx((outer.EI - inner.EI) / E / (D / 2), rel=1e-14)
    assert CrossSection.tube(D, 0.0, E, rho, nu) == outer


def test_thin_tube_shear_coefficient_is_cowpers():
    nu, D = 0.3, 1.0
    t = CrossSection.tube(D, 0.99999 * D, 1.0, 1.0, nu)
    kappa = t.GA / (t.EA / (2 * (1 + nu)))
    assert kappa == pytest.approx(2 * (1 + nu) / (4 + 3 * nu), rel=1e-4)


def test_taper_explicit_disks_and_merged_tendon_groups():
    desc = {"sections": [{"length": 0.3, "material": "steel", "diameter": 4e-3, "tip": {"diameter": 3e-3},
                          "disks": {"positions": [0.1, 0.2, 0.3], "mass": 2e-3},
                          "tendons": [{"angles": [0.0, math.pi], "offset": 0.02, "diameter": 5e-4,
                                       "material": "music_wire_05mm"},
                                      {"angles": [math.pi / 2], "offset": 0.02, "diameter": 5e-4,
                                       "material": "music_wire_05mm"}]}]}
    robot = robot_from_params(desc)
    sec = robot.sections[0]
    assert sec.n_disks == 3 and sec.disk_mass == 2e-3
    assert sec.cross_section_tip == CrossSection.circular(3e-3, 210e9, 7850.0, 0.3)
    assert sec.tendons.angles == (0.0, math.pi, math.pi / 2)
    area = math.pi * 5e-4**2 / 4
    assert sec.tendons.area == area and sec.tendons.axial_stiffness == 203.4e9 * area
    assert sec.tendons.strength == 2.41e9


def test_sources_of_a_description():
    desc = steel_rod_description()
    desc["sections"][0]["youngs_modulus"] = 54e9
    src = robot_value_sources(desc)
    assert src["robot.sections[0].youngs_modulus"] == "set in the study file"
    assert src["robot.sections[0].density"].startswith("material spring_steel: EN 1991-1-1")
    assert src["robot.sections[0].yield_strength"].endswith(
        "(youngs_modulus set in the study file; the strength is still spring_steel's)")
    assert src["robot.sections[0].tendons[0].offset"] == "set in the study file"
    assert src["robot.payload"] == "default: no payload"


def test_a_study_with_a_description_validates_keeps_its_table_and_derives_gravity():
    raw = {"study": {"name": "d", "models": ["cc"]}, "robot": steel_rod_description(),
           "load": {"mode": "tension", "tensions": [1.0, 0.0]}}
    study = parse_study(raw, source="d.toml")
    assert study.base["robot"] == steel_rod_description()
    robot, params = resolve_robot(study.base["robot"], {"gravity_parameter": 2.0})
    cs = robot.sections[0].cross_section
    g = 2.0 * cs.EI / (cs.mass_per_length * 0.8**3)
    assert params["gravity"] == [0.0, 0.0, -g] and robot.gravity == (0.0, 0.0, -g)
