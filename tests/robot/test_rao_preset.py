"""The data preset ``rao_2021`` (Rao et al. 2021, the tdcr-modeling robot) and the worked example study.

References: the robot as the peer benchmark states it (``/work/shared/notes/peer-benchmark.md``:
2 x 0.2 m NiTi, E = 54 GPa, nu = 0.3, d = 1.4 mm, 10 disks, tendons at 90 / -30 / 210 deg, 10 mm
pitch radius) built directly from the dataclasses; the tip of peer case 1 from the closed-form
constant-curvature arcs (no external load and tendons along the backbone: CC is exact up to the
backbone's axial and shear compliance; Webster & Jones 2010, IJRR 29(13), Eq. 9), computed here
from the section moments.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.presets import build_preset, data_preset
from workbench.robot.spec import robot_from_params, robot_problems, robot_value_sources
from workbench.study.spec import load_study

ROOT = Path(__file__).resolve().parents[2]
ANGLES = (math.pi / 2, -math.pi / 6, 7 * math.pi / 6)
CASE1 = (2.0, 0.0, 0.0, 0.0, 1.0, 0.0)  # peer case 1 [N]


def paper_robot(d2: float = 1.4e-3, rotate2: float = 0.0) -> Robot:
    """The robot as the paper states it, written with the dataclasses."""
    def section(d, rot):
        cs = CrossSection.circular(d, 54e9, 6450.0, 0.3)
        tg = TendonGroup(angles=tuple(a + rot for a in ANGLES), offset=0.01, axial_stiffness=1e7)
        return Section(0.2, cs, tg, n_disks=10)
    return Robot(sections=(section(1.4e-3, 0.0), section(d2, rotate2)), name="rao_2021")


def arcs_tip(robot: Robot, tensions) -> np.ndarray:
    """Tip of one constant-curvature arc per section: curvature vector sum(T d e_sigma) / EI."""
    R, p = np.eye(3), np.zeros(3)
    table = robot.tendon_table()
    for j, sec in enumerate(robot.sections):
        m = sum(T * g.offset * np.array([math.cos(s), math.sin(s)]) for (k, s, g), T in zip(table, tensions) if k >= j)
        kappa = np.linalg.norm(m) / sec.cross_section.EI
        phi, ell = math.atan2(m[1], m[0]), sec.length
        c, s = math.cos(phi), math.sin(phi)
        Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        th = kappa * ell
        Ry = np.array([[math.cos(th), 0, math.sin(th)], [0, 1, 0], [-math.sin(th), 0, math.cos(th)]])
        local = np.array([(1 - math.cos(th)) / kappa * c, (1 - math.cos(th)) / kappa * s, math.sin(th) / kappa])
        p = p + R @ local
        R = R @ Rz @ Ry @ Rz.T
    return p


def test_rao_preset_is_the_paper_robot_bit_for_bit():
    assert data_preset("rao_2021") is not None
    assert build_preset("rao_2021") == paper_robot()


def test_every_value_of_the_rao_preset_has_a_stated_source():
    sources = robot_value_sources({"preset": "rao_2021"})
    assert sources["robot.sections[1].youngs_modulus"].startswith("material niti: Rao")
    assert sources["robot.sections[0].density"].startswith("preset rao_2021: assumed 6450")
    assert sources["robot.sections[0].diameter"].startswith("preset rao_2021: backbone radius 0.7 mm")
    assert not [k for k, v in sources.items() if "no source stated" in v or v == "set in the study file"]


def test_rotated_thinner_section_two_is_what_the_overrides_say():
    params = load_study(ROOT / "studies" / "rao_rotated.toml").base["robot"]
    assert robot_problems(params) == []
    assert robot_from_params(params) == paper_robot(d2=1.0e-3, rotate2=math.pi / 3)
    src = robot_value_sources(params)
    assert src["robot.sections[1].diameter"] == "set in the study file"
    assert src["robot.sections[1].tendons[0].angles"] == "set in the study file"
    assert src["robot.sections[0].diameter"].startswith("preset rao_2021:")


@pytest.mark.parametrize("rotated", [False, True])
def test_cc_on_peer_case_1_is_the_closed_form_arcs(rotated):
    robot = paper_robot(1.0e-3, math.pi / 3) if rotated else build_preset("rao_2021")
    load = LoadCase(actuation=TendonActuation("tension", CASE1))
    tip = get_model("cc")(robot, load, SolverOptions()).tip_position
    np.testing.assert_allclose(tip, arcs_tip(robot, CASE1), rtol=0, atol=1e-12)


def test_cosserat_on_peer_case_1_agrees_with_the_arcs():
    """Continuous tendons, no external load: the Cosserat rod differs from the arcs only by the
    backbone's axial/shear strain (T / EA ~ 4e-5 here), below 5e-5 L."""
    robot = build_preset("rao_2021")
    load = LoadCase(actuation=TendonActuation("tension", CASE1))
    tip = get_model("cosserat")(robot, load, SolverOptions(newton_tolerance=1e-10)).tip_position
    err = np.linalg.norm(tip - arcs_tip(robot, CASE1))
    assert err < 5e-5 * robot.length, err
