"""Series-parallel study files: strict validation (one line per problem), expansion, stable case ids."""

from __future__ import annotations

import textwrap

import numpy as np
import pytest

from workbench.experiments.series_parallel.expand import amplitude_values, expand_poses
from workbench.experiments.series_parallel.spec import is_series_parallel_study, load_series_parallel_study
from workbench.experiments.series_parallel.worker import module_target, stack_targets
from workbench.study.spec import StudyError

GOOD = """
[study]
kind = "series_parallel"
name = "t"
[geometry]
height = 0.4
[solver]
n_elements = 4
[motions]
module = [ { axis = "x", amplitude = 0.1, samples = 3 } ]
stack = [ { shape = "bending", amplitude = 0.5, samples = 2, n_modules = 2 } ]
"""


def _write(tmp_path, text, name="s.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_good_file_loads_and_is_recognised(tmp_path):
    p = _write(tmp_path, GOOD)
    assert is_series_parallel_study(p)
    s = load_series_parallel_study(p)
    assert s.geometry["height"] == 0.4 and s.geometry["rod_diameter"] == 0.006  # defaults filled in
    assert s.solver["n_elements"] == 4
    assert len(expand_poses(s)) == 5


def test_generic_and_broken_files_are_not_motion_studies(tmp_path):
    assert not is_series_parallel_study("studies/example.toml")
    assert not is_series_parallel_study(_write(tmp_path, "[study\nkind=", "broken.toml"))
    assert not is_series_parallel_study(tmp_path / "missing.toml")


@pytest.mark.parametrize(
    "edit, expected",
    [
        (("axis = \"x\"", "axiz = \"x\""), r"motions\.module\[0\]\.axiz: unknown key; did you mean 'axis'\?"),
        (("axis = \"x\"", "axis = \"w\""), r"motions\.module\[0\]\.axis: must be 'x', 'y', 'z', 'rx', 'ry' or 'rz', got 'w'"),
        (("amplitude = 0.1", "amplitude = -0.1"), r"motions\.module\[0\]\.amplitude: must be > 0.0, got -0.1"),
        (("samples = 3", "samples = 3.0"), r"motions\.module\[0\]\.samples: "),
        (("height = 0.4", "heigth = 0.4"), r"geometry\.heigth: unknown key; did you mean 'height'\?"),
        (("height = 0.4", "height = -0.4"), r"geometry\.height: must be finite and > 0"),
        (("height = 0.4", "height = \"tall\""), r"geometry\.height: must be a number, got str 'tall'"),
        (("n_elements = 4", "n_elemnts = 4"), r"solver\.n_elemnts: unknown key; did you mean 'n_elements'\?"),
        (("shape = \"bending\"", "shape = \"twist\""), r"motions\.stack\[0\]\.shape: must be 'translation', 's_shape' or 'bending'"),
        (("kind = \"series_parallel\"\n", ""), r"study\.kind: missing required key"),
        (("axis = \"x\", amplitude = 0.1", "axis = \"x\", pivot = 0.5, amplitude = 0.1"),
         r"motions\.module\[0\]\.pivot: applies to axis 'rx' or 'ry' only .*, not to axis 'x'$"),
        (("axis = \"x\", amplitude = 0.1", "axis = \"rx\", pivot = -0.5, amplitude = 0.1"),
         r"motions\.module\[0\]\.pivot: must be >= 0"),
    ],
)
def test_bad_files_give_one_line_errors(tmp_path, edit, expected):
    p = _write(tmp_path, GOOD.replace(*edit))
    with pytest.raises(StudyError) as exc:
        load_series_parallel_study(p)
    assert len(exc.value.problems) == 1, exc.value.problems
    line = exc.value.problems[0]
    assert "\n" not in line and line.startswith(f"{p}: ")
    import re

    assert re.search(expected, line), line


def test_several_problems_are_all_reported(tmp_path):
    p = _write(tmp_path, GOOD.replace("height = 0.4", "heigth = 0.4").replace("samples = 3", "samples = 0"))
    with pytest.raises(StudyError) as exc:
        load_series_parallel_study(p)
    assert len(exc.value.problems) == 2


def test_no_motions_is_an_error(tmp_path):
    p = _write(tmp_path, GOOD.split("[motions]")[0] + "[motions]\n")
    with pytest.raises(StudyError, match="no motions given"):
        load_series_parallel_study(p)


def test_expansion_is_deterministic_and_ids_depend_only_on_values(tmp_path):
    a = expand_poses(load_series_parallel_study(_write(tmp_path, GOOD, "a.toml")))
    b = expand_poses(load_series_parallel_study(_write(tmp_path, GOOD, "b.toml")))
    assert [c.case_id for c in a] == [c.case_id for c in b]
    assert len({c.case_id for c in a}) == len(a)
    # renaming the study or reordering the motions does not change the ids
    swapped = GOOD.replace('name = "t"', 'name = "other"')
    mod = 'module = [ { axis = "x", amplitude = 0.1, samples = 3 } ]\n'
    swapped = swapped.replace(mod, "").replace("[motions]\n", "[motions]\n" + mod)
    c = expand_poses(load_series_parallel_study(_write(tmp_path, swapped, "c.toml")))
    assert sorted(x.case_id for x in c) == sorted(x.case_id for x in a)
    # a changed parameter changes every id
    d = expand_poses(load_series_parallel_study(_write(tmp_path, GOOD.replace("height = 0.4", "height = 0.41"), "d.toml")))
    assert not {x.case_id for x in d} & {x.case_id for x in a}
    # the pinned id of one case (guards against accidental changes of the id recipe)
    first = a[0]
    assert first.params["pose"] == {"kind": "module", "shape": "x", "value": -0.1, "n_modules": 1, "plane": 0.0}


def test_amplitude_values():
    assert amplitude_values(0.2, 4, True) == pytest.approx([-0.2, -0.2 / 3, 0.2 / 3, 0.2])
    assert amplitude_values(0.2, 3, True)[1] == 0.0
    assert amplitude_values(1.0, 2, False) == [0.5, 1.0]


def test_stack_targets_geometry():
    """Bending: platforms on one arc (equal chords, tangent = z axis); S-shape: tip parallel to
    the base; translation: parallel platforms at k h height."""
    h, n = 0.5, 3
    B = stack_targets("bending", 1.2, n, h, plane=0.4)
    k = 1.2 / (n * h)
    for j in range(n):
        th = k * h * (j + 1)
        assert np.allclose(B[j, :3, 3], [(1 - np.cos(th)) / k * np.cos(0.4), (1 - np.cos(th)) / k * np.sin(0.4), np.sin(th) / k])
        assert np.allclose(B[j, :3, 2], [np.sin(th) * np.cos(0.4), np.sin(th) * np.sin(0.4), np.cos(th)])
    S = stack_targets("s_shape", 0.5, n, h)
    assert np.allclose(S[-1, :3, :3], np.eye(3), atol=1e-12)
    assert S[-1, 0, 3] > 0 and abs(S[-1, 1, 3]) < 1e-15
    # the S curve is C1: the mid-length platform of a 2-module S sits at the peak angle
    S2 = stack_targets("s_shape", 0.5, 2, h)
    assert np.arccos(S2[0, 2, 2]) == pytest.approx(0.5)
    T = stack_targets("translation", 0.3, n, h)
    assert np.allclose(T[:, :3, 3], [[0.1, 0, 0.5], [0.2, 0, 1.0], [0.3, 0, 1.5]])
    with pytest.raises(ValueError, match="shape must be"):
        stack_targets("twist", 0.1, 2, h)


def test_pivot_is_part_of_tilt_cases_only(tmp_path):
    """rx / ry with a pivot are their own cases (own ids, ``pose.pivot`` column); without one the
    pose dict has no pivot key, so the ids of earlier studies do not change."""
    text = GOOD.replace('module = [ { axis = "x", amplitude = 0.1, samples = 3 } ]',
                        'module = [ { axis = "rx", amplitude = 0.5, samples = 1 }, '
                        '{ axis = "rx", amplitude = 0.5, samples = 1, pivot = 0.5 } ]')
    cases = expand_poses(load_series_parallel_study(_write(tmp_path, text)))
    mods = [c for c in cases if c.params["pose"]["kind"] == "module"]
    assert len(mods) == 2 and mods[0].case_id != mods[1].case_id
    assert "pivot" not in mods[0].params["pose"]
    assert mods[1].params["pose"]["pivot"] == 0.5 and mods[1].swept["pose.pivot"] == 0.5


def test_module_target_rotates_about_the_pivot():
    from scipy.spatial.transform import Rotation

    h, a = 0.5, 0.7
    R = Rotation.from_rotvec([a, 0.0, 0.0]).as_matrix()
    top = module_target(h, "rx", a)  # default: about the platform centre, the platform stays put
    assert np.allclose(top[:3, 3], [0, 0, h]) and np.allclose(top[:3, :3], R)
    mid = module_target(h, "rx", a, pivot=0.5)
    c = np.array([0, 0, h / 2])
    assert np.allclose(mid[:3, 3], c + R @ (np.array([0, 0, h]) - c)) and np.allclose(mid[:3, :3], R)
    assert np.linalg.norm(mid[:3, 3] - c) == pytest.approx(h / 2)
    # a positive rx tilts the platform normal towards -y and swings the platform that way
    assert mid[1, 2] < 0 and mid[1, 3] < 0
    # rz about any centre on the axis is the same pose
    assert np.allclose(module_target(h, "rz", a, pivot=0.3), module_target(h, "rz", a))
