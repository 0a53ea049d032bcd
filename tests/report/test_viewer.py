"""The 3-D view's data: world-frame backbones of every model, disks, tendons, gravity, time frames."""

from __future__ import annotations

import numpy as np
import pytest

from tests.regression.golden import STUDIES_DIR
from workbench.report.load import load_results
from workbench.report.scene import case_scene
from workbench.report.viewer import _model_frames, viewer_scenes


@pytest.fixture(scope="module")
def quickstart(small_study_run):
    return load_results(small_study_run(STUDIES_DIR / "quickstart.toml"))


def test_scenes_are_in_the_world_frame_with_gravity_down(quickstart):
    sc = viewer_scenes(quickstart)
    assert sc["frame"] == "world" and len(sc["cases"]) == quickstart.ok["case_id"].nunique()
    for case in sc["cases"]:
        assert set(case["models"]) == {"cc", "ancf"}
        g = np.asarray(case["gravity"])
        assert g[2] < 0 and np.allclose(g[:2], 0)                   # world -z
        bb = {m: np.asarray(v["frames"][-1][1]) for m, v in case["models"].items()}
        d0 = bb["cc"][1] - bb["cc"][0]
        assert d0[0] > 0.9 * np.linalg.norm(d0)                       # the horizontal rod leaves its base along world +x
        assert bb["cc"][-1][2] > 0                                    # CC bends up (bend plane 0 = world up) ...
        assert bb["ancf"][-1][2] < bb["cc"][-1][2]                    # ... the beam sags below it
        assert case["disks"] and case["tendons"]
        np.testing.assert_allclose(case["e0"], [0, 0, 1], atol=1e-12)  # base x axis = world up (horizontal mount)


def test_base_frame_on_request(quickstart):
    from dataclasses import replace

    sc = viewer_scenes(replace(quickstart, frame="base"))
    case = sc["cases"][0]
    tip = np.asarray(case["models"]["cc"]["frames"][-1][1])[-1]
    assert tip[2] > 0.3 and sc["frame"] == "base"                     # backbone along base +z


def test_dynamic_rows_give_time_frames(quickstart):
    row = quickstart.ok.iloc[0].to_dict()
    P = np.asarray(row["positions"], float).reshape(-1, 3)
    frames = np.stack([P * f for f in (0.0, 0.5, 1.0)])
    row.update({"series.backbone_time": [0.0, 0.5, 1.0], "series.backbone": frames.reshape(-1).tolist(),
                "time": [0.0, 0.25, 0.5, 0.75, 1.0]})
    got, pts = _model_frames(row, case_scene(row), "world")
    assert [f[0] for f in got] == [0.0, 0.5, 1.0]
    np.testing.assert_allclose(np.asarray(got[-1][1]), np.round(case_scene(row).rotation @ P.T, 6).T, atol=1e-6)


def test_a_study_kinds_lines_hook_adds_polylines_in_model_colours(quickstart, monkeypatch):
    """The viewer draws what the kind's registered ``lines`` hook returns, in the report's frame."""
    from workbench.report import viewer

    seg = np.array([[[0.0, 0.0, 0.0], [0.0, 0.0, 0.1]]])  # one line of two points, base frame
    calls = []

    def hook(study):
        calls.append(study)
        return lambda rows: [(m, seg) for m in rows if m == "ancf"]

    monkeypatch.setattr(viewer, "kind_hook", lambda spec, name: hook if name == "lines" else None)
    sc = viewer_scenes(quickstart)
    assert len(calls) == 1
    case = sc["cases"][0]
    assert len(case["lines"]) == 1 and case["lines"][0][0] == viewer.model_color("ancf")
    np.testing.assert_allclose(case["lines"][0][1][0], case["base"], atol=1e-6)  # the base point in world
    monkeypatch.undo()
    assert all(c["lines"] == [] for c in viewer_scenes(quickstart)["cases"])  # a sweep study: no hook


# issue 28 ("The report says what is true"): with a physics reference the viewer put the disks and
# tendons on the first non-reference model's backbone -- CC's -- while the caption said "the first
# physics model's backbone".  Now both name the same model.
def test_disks_sit_on_the_backbone_the_caption_names(quickstart):
    from dataclasses import replace

    import pandas as pd

    from workbench.report.context import PageContext
    from workbench.report.sections import viewer_section

    for study in (quickstart, replace(quickstart, baseline="ancf")):
        sc = viewer_scenes(study)
        assert {c["main"] for c in sc["cases"]} == {"ancf"}, study.baseline
        empty = pd.DataFrame()
        ctx = PageContext(study, empty, empty, empty, (), (), (), viewer_cases=len(sc["cases"]))
        caption = viewer_section(ctx).html
        label = sc["cases"][0]["models"]["ancf"]["label"]
        assert f"tendons (brown) on the {label} backbone (the first physics model" in caption


def test_disk_model_is_the_first_physics_model():
    from workbench.report.viewer import disk_model

    assert disk_model(["cc", "beam3d", "ancf"]) == "beam3d"
    assert disk_model(["target", "cc_fit", "spring_link"]) == "spring_link"
    assert disk_model(["cc"]) == "cc" and disk_model([]) is None


def test_scene_rebuild_errors(monkeypatch):
    """Expected rebuild errors draw in the base frame (known = False); a bug in the rebuild is not hidden
    (issue 28: on main any exception silently gave the identity pose)."""
    from workbench.report import scene

    assert not case_scene({"p.robot.preset": "no_such_preset"}).known
    assert not case_scene({"p.robot.preset": "steel_rod", "p.robot.n_sections": 0}).known

    def broken(params, derived=None):
        raise RuntimeError("bug in build_robot")

    monkeypatch.setattr(scene, "build_robot", broken)
    scene._scene_from_json.cache_clear()
    with pytest.raises(RuntimeError, match="bug in build_robot"):
        case_scene({"p.robot.preset": "steel_rod", "p.robot.length": 0.123456})
    scene._scene_from_json.cache_clear()
