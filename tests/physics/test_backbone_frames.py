"""Decimated backbone frames of dynamic runs (``series.backbone``): the helper and every dynamic model."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.models.backbone_frames import MAX_FRAMES, backbone_series, frame_stride


def test_frame_stride_keeps_at_most_max_frames():
    for n in (1, 2, 59, 60, 61, 100, 1000, 1001):
        stride = frame_stride(n)
        kept = len(range(0, n, stride)) + 1  # + the final state
        assert kept <= MAX_FRAMES, (n, stride, kept)
    assert frame_stride(10) == 1
    with pytest.raises(ValueError):
        frame_stride(10, max_frames=1)


def test_backbone_series_checks_shapes():
    out = backbone_series([0.0, 1.0], np.zeros((2, 5, 3)))
    assert out["backbone"].shape == (2, 5, 3) and out["backbone_time"].tolist() == [0.0, 1.0]
    with pytest.raises(ValueError, match="shape"):
        backbone_series([0.0], np.zeros((2, 5, 3)))


def _dynamic_case(model: str):
    from workbench.models import SolverOptions, get_model
    from workbench.models.cc import actuation_from_arc
    from workbench.robot import LoadCase
    from workbench.robot.presets import build_preset

    robot = build_preset("steel_rod", gravity=9.81, base_orientation="horizontal")
    act = None if model == "ancf3d" else actuation_from_arc(robot, kappa=[1.0], phi=[0.0], mode="length" if model == "cc" else "tension")
    load = LoadCase(actuation=act, analysis="dynamic", duration=0.2, ramp_time=0.1)
    opts = SolverOptions(n_elements=4, time_step=2e-3, n_stations=7,
                         tendon_model="eyelets" if model == "beam3d" else "continuum")
    return get_model(model)(robot, load, opts)


@pytest.mark.parametrize("model", ["cc", "ancf", "beam3d", "ancf3d", "spring_link"])
def test_dynamic_models_store_backbone_frames_ending_in_the_final_shape(model):
    res = _dynamic_case(model)
    bb, bt = np.asarray(res.series["backbone"]), np.asarray(res.series["backbone_time"])
    assert bb.ndim == 3 and bb.shape[1:] == np.asarray(res.positions).shape, bb.shape
    assert 2 <= bb.shape[0] <= MAX_FRAMES and bb.shape[0] == bt.size
    assert np.all(np.diff(bt) > 0) and bt[0] == pytest.approx(res.time[0]) and bt[-1] == pytest.approx(res.time[-1])
    np.testing.assert_allclose(bb[-1], res.positions, atol=1e-9)      # last frame = the stored final shape
    assert np.ptp(bb[:, -1, :], axis=0).max() > 0                      # the tip moves: frames differ
