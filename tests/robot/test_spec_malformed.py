"""Malformed robot descriptions: each rejected before anything runs, in one line naming its key path.

Every entry of :data:`CASES` is a ``[robot]`` table with one mistake and the key path (and a
fragment of the reason) its one problem line must name.  :func:`workbench.robot.spec.robot_problems`
is what ``workbench validate`` calls for ``[robot]`` (``workbench/study/spec.py::resolve_robot_table``);
the last test runs three of them through ``workbench validate`` itself.  The count is asserted
(issue 29: at least 40).
"""

from __future__ import annotations

import copy
import subprocess
import sys
from pathlib import Path

import pytest

from workbench.robot.spec import robot_problems

ROOT = Path(__file__).resolve().parents[2]


def good() -> dict:
    """A valid two-section description (the Rao robot written out)."""
    sec = {"length": 0.2, "material": "niti", "diameter": 1.4e-3, "density": 6450.0, "disks": {"count": 10},
           "tendons": [{"angles": [1.5708, -0.5236, 3.6652], "offset": 0.01, "axial_stiffness": 1e7}]}
    return {"sections": [copy.deepcopy(sec), copy.deepcopy(sec)], "gravity": [0.0, 0.0, -9.81]}


def edit(path: str, value, *, delete: bool = False) -> dict:
    """:func:`good` with the value at ``path`` (dotted, ``[i]`` indices) replaced or deleted."""
    import re

    d = good()
    parts = re.findall(r"([A-Za-z_]+)|\[(\d+)\]", path)
    node = d
    for name, idx in parts[:-1]:
        node = node[name] if name else node[int(idx)]
    name, idx = parts[-1]
    key = name if name else int(idx)
    if delete:
        del node[key]
    else:
        node[key] = value
    return d


S1 = "robot.sections[1]"
CASES = [
    # (description, key path the line must start with, fragment of its reason)
    (edit("sections", []), "robot.sections", "non-empty list"),
    (edit("sections", {"length": 0.2}), "robot.sections", "non-empty list"),
    ({"gravity": [0, 0, -9.81]}, "robot.sections", "missing required key"),
    (edit("secions", [1]), "robot.secions", "did you mean 'sections'"),
    (edit("gravity", [0.0, -9.81]), "robot.gravity", "expected 3 numbers [m/s^2], got 2"),
    (edit("gravity", "down"), "robot.gravity", "list of numbers"),
    (edit("gravity", [0, 0, "g"]), "robot.gravity[2]", "must be a number"),
    (edit("base_position", [0, 0, float("nan")]), "robot.base_position[2]", "finite"),
    (edit("base_orientation", "sideways"), "robot.base_orientation", "expected one of"),
    (edit("base_rotation", [[1, 0, 0], [0, 1, 0]]), "robot.base_rotation", "3 rows"),
    (edit("base_rotation", [[2, 0, 0], [0, 1, 0], [0, 0, 1]]), "robot.base_rotation", "rotation"),
    (edit("payload", {"mass": -0.1}), "robot.payload.mass", ">= 0"),
    (edit("payload", {"mas": 0.1}), "robot.payload.mas", "did you mean 'mass'"),
    (edit("payload", 0.1), "robot.payload", "must be a table"),
    (edit("payload", {"mass": 0.1, "offset": [0, 0]}), "robot.payload.offset", "expected 3 numbers"),
    (edit("name", 3), "robot.name", "must be a string"),
    (edit("sections[1]", 0.2), S1, "must be a table"),
    (edit("sections[1].length", -0.2), f"{S1}.length", "> 0"),
    (edit("sections[1].length", "0.2"), f"{S1}.length", "must be a number"),
    (edit("sections[1].length", None, delete=True), f"{S1}.length", "missing required key"),
    (edit("sections[1].lenght", 0.2), f"{S1}.lenght", "did you mean 'length'"),
    (edit("sections[1].diameter", 0.0), f"{S1}.diameter", "> 0"),
    (edit("sections[1].diameter", None, delete=True), f"{S1}.diameter", "missing"),
    (edit("sections[1].outer_diameter", 2e-3), f"{S1}.diameter", "not both"),
    ({"sections": [good()["sections"][0], {**{k: v for k, v in good()["sections"][1].items() if k != "diameter"},
                                            "outer_diameter": 2e-3, "inner_diameter": 2e-3}]},
     f"{S1}.inner_diameter", "must be < outer_diameter"),
    ({"sections": [good()["sections"][0], {**{k: v for k, v in good()["sections"][1].items() if k != "diameter"},
                                            "inner_diameter": 1e-3}]}, f"{S1}.outer_diameter", "missing"),
    (edit("sections[1].material", "nitinol"), f"{S1}.material", "unknown material 'nitinol'; known materials"),
    (edit("sections[1].material", 54e9), f"{S1}.material", "must be a string"),
    (edit("sections[1].material", None, delete=True), f"{S1}.youngs_modulus", "missing (no material given)"),
    (edit("sections[1].density", None, delete=True), f"{S1}.density", "material niti gives none"),
    (edit("sections[1].youngs_modulus", -54e9), f"{S1}.youngs_modulus", "> 0"),
    (edit("sections[1].poisson_ratio", 0.5), f"{S1}.poisson_ratio", "< 0.5"),
    (edit("sections[1].poisson_ratio", -1.5), f"{S1}.poisson_ratio", "> -1"),
    ({"sections": [good()["sections"][0], {**good()["sections"][1], "poisson_ratio": 0.3, "shear_modulus": 20e9}]},
     f"{S1}.shear_modulus", "not both"),
    (edit("sections[1].density", -6450.0), f"{S1}.density", ">= 0"),
    (edit("sections[1].yield_strength", 0.0), f"{S1}.yield_strength", "> 0"),
    (edit("sections[1].tip", {"diameter": -1e-3}), f"{S1}.tip.diameter", "> 0"),
    (edit("sections[1].tip", {"diametre": 1e-3}), f"{S1}.tip.diametre", "did you mean 'diameter'"),
    (edit("sections[1].bending_stiffness", 0.01), f"{S1}.material", "takes no material data"),
    (edit("sections[1].disks", None, delete=True), f"{S1}.disks", "missing required key"),
    (edit("sections[1].disks", 10), f"{S1}.disks", "must be a table"),
    (edit("sections[1].disks", {"count": 2.5}), f"{S1}.disks.count", "must be an integer"),
    (edit("sections[1].disks", {"count": 0}), f"{S1}.disks.count", "[1, 100000]"),
    (edit("sections[1].disks", {"count": 10, "mass": -1e-3}), f"{S1}.disks.mass", ">= 0"),
    (edit("sections[1].disks", {"mass": 1e-3}), f"{S1}.disks.count", "set count or positions"),
    (edit("sections[1].disks", {"positions": [0.05, 0.1, 0.2]}), f"{S1}.disks.positions", "equally spaced"),
    (edit("sections[1].tendons", {"angles": [0.0]}), f"{S1}.tendons", "must be a list of tables"),
    (edit("sections[1].tendons[0].angles", [0.0, "x"]), f"{S1}.tendons[0].angles[1]", "must be a number"),
    (edit("sections[1].tendons[0].angles", []), f"{S1}.tendons[0].angles", "at least one"),
    (edit("sections[1].tendons[0].angles", 1.57), f"{S1}.tendons[0].angles", "list of numbers"),
    (edit("sections[1].tendons[0].count", 3), f"{S1}.tendons[0].angles", "one of them"),
    (edit("sections[1].tendons[0].offset", None, delete=True), f"{S1}.tendons[0].offset", "missing required key"),
    (edit("sections[1].tendons[0].offset", -0.01), f"{S1}.tendons[0].offset", "> 0"),
    (edit("sections[1].tendons[0].tip_offset", 0.0), f"{S1}.tendons[0].tip_offset", "> 0"),
    (edit("sections[1].tendons[0].axial_stiffness", None, delete=True), f"{S1}.tendons[0].axial_stiffness",
     "missing"),
    (edit("sections[1].tendons[0].youngs_modulus", 200e9), f"{S1}.tendons[0].youngs_modulus", "not both"),
    (edit("sections[1].tendons[0].material", "unobtainium"), f"{S1}.tendons[0].material", "unknown material"),
    (edit("sections[1].tendons[0].strenght", 2e9), f"{S1}.tendons[0].strenght", "did you mean 'strength'"),
    (edit("sections[1].tendons", [good()["sections"][1]["tendons"][0],
                                  {"angles": [0.0], "offset": 0.02, "axial_stiffness": 1e7}]),
     f"{S1}.tendons[1]", "differs from"),
    ({"preset": "rao_2021", "sections": [{}]}, "robot.sections", "give 2 tables"),
    ({"preset": "rao_2021", "sections": [{}, {"diameter": "thin"}]}, f"{S1}.diameter", "must be a number"),
    ({"preset": "rao_2021", "sections": [{}, {"tendons": [{"angles": [0.0, True]}]}]},
     f"{S1}.tendons[0].angles[1]", "must be a number"),
    ({"preset": "steel_rod", "n_sections": 2, "diameter": [6e-3]}, "robot.diameter", "expected 2 values"),
    ({"preset": "steel_rod", "n_sections": 2, "diameter": [6e-3, -1e-3]}, "robot.diameter[1]", "> 0"),
    ({"preset": "steel_rod", "n_sections": 2, "first_tendon_angle": [0.0, "a"]}, "robot.first_tendon_angle[1]",
     "must be a number"),
    ({"preset": "steel_rod", "length": [0.4, 0.4]}, "robot.length", "must be a number"),
    ({"preset": "steel_rod", "diamter": 6e-3}, "robot.diamter", "did you mean 'diameter'"),
    ({"preset": "steel_rods"}, "robot.preset", "unknown preset"),
]


def test_at_least_forty_malformed_descriptions():
    assert len(CASES) >= 40, len(CASES)


@pytest.mark.parametrize("params,path,reason", CASES, ids=[f"{i}:{c[1]}" for i, c in enumerate(CASES)])
def test_malformed_description_is_one_line_naming_its_key_path(params, path, reason):
    problems = robot_problems(params)
    assert len(problems) == 1, problems
    line = problems[0]
    assert "\n" not in line
    key, _, why = line.partition(": ")
    assert key == path, line
    assert reason in why, line


def test_the_good_description_has_no_problem():
    assert robot_problems(good()) == []


def test_workbench_validate_rejects_a_malformed_description_before_running(tmp_path):
    """Through the CLI: one line per problem, each naming the file and the key path; exit status 1."""
    text = (ROOT / "studies" / "rao_rotated.toml").read_text(encoding="utf-8")
    bad = text.replace("diameter = 1.0e-3", "diameter = -1.0e-3\nlenght = 0.2")
    assert bad != text
    path = tmp_path / "bad.toml"
    path.write_text(bad, encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "workbench", "validate", str(path)], capture_output=True,
                          text=True, cwd=ROOT, timeout=300)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0 and "Traceback" not in out, out
    lines = [ln for ln in out.splitlines() if "robot." in ln]
    assert len(lines) == 2, out
    assert any(ln.endswith("robot.sections[1].diameter: must be > 0 [m], got -0.001") for ln in lines), lines
    assert any("robot.sections[1].lenght: unknown key; did you mean 'length'?" in ln for ln in lines), lines
    assert all(ln.startswith(f"{path}: ") for ln in lines), lines
