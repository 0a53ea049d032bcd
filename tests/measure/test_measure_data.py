"""The measured-data reader: columns -> SI arrays, conventions, frames, CSV and Parquet alike.

References are independent of the reader: the fixture's generator (``fixtures/make_measured.py``)
wrote CC's tip in a tracker frame in mm; re-running CC on the commands read back and applying the
generator's transform must give the positions read back (to the generator's 0.05 mm noise).
"""

from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from workbench.measure.datafile import quaternion_matrices, read_measurements
from workbench.robot.spec import robot_from_params

FIX = Path(__file__).with_name("fixtures")
ROBOT = robot_from_params({"preset": "rao_2021"})


def _table() -> dict:
    return tomllib.loads((FIX / "calibration.toml").read_text(encoding="utf-8"))["measurements"]


def test_columns_are_read_in_si_and_agree_with_cc_through_the_known_transform():
    import importlib.util

    spec = importlib.util.spec_from_file_location("make_measured", FIX / "make_measured.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    from workbench.models import cc
    from workbench.models.result import SolverOptions
    from workbench.robot import LoadCase, TendonActuation

    m = read_measurements(_table(), FIX, ROBOT, "cal.toml")
    raw = pd.read_csv(FIX / "measured.csv")
    assert m.n == 40 and m.mode == "tension" and m.frame == "measurement"
    np.testing.assert_array_equal(m.file_rows, np.arange(1, 41))
    np.testing.assert_allclose(m.commands, 1e-3 * raw[[f"T{i}" for i in range(1, 7)]].to_numpy(), rtol=1e-15)
    R = gen.rotation_matrix(gen.ROTATION)
    for i in (0, 17, 39):
        res = cc.run(ROBOT, LoadCase(actuation=TendonActuation("tension", tuple(m.commands[i]))), SolverOptions())
        expect = R @ res.tip_position + gen.TRANSLATION
        assert np.linalg.norm(m.tip_position[i] - expect) < 5 * gen.NOISE
        np.testing.assert_allclose(m.tip_orientation[i], R @ res.tip_frame[:3, :3], atol=5e-6)
    assert m.backbone.shape == (40, 3, 3) and m.backbone_stations.tolist() == [0.1, 0.2, 0.3]
    np.testing.assert_allclose(m.backbone[5, 1], 1e-3 * raw.loc[5, ["b2x", "b2y", "b2z"]].to_numpy(float))


def test_parquet_gives_the_same_samples_as_csv(tmp_path):
    pd.read_csv(FIX / "measured.csv").to_parquet(tmp_path / "measured.parquet")
    a = read_measurements(_table(), FIX, ROBOT, "cal.toml")
    b = read_measurements({**_table(), "file": "measured.parquet"}, tmp_path, ROBOT, "cal.toml")
    for name in ("commands", "tip_position", "tip_orientation", "backbone"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))


def test_scale_unit_and_the_pull_convention(tmp_path):
    """"1 unit = 0.1 mm of shortening": value 20 -> reeled in 2 mm -> free-length change -0.002 m."""
    pd.DataFrame({"L1": [20.0, 0.0], "L2": [0.0, -5.0], "x": [1.0, 2.0], "y": [0.0, 0.0], "z": [400.0, 399.0]}
                 ).to_csv(tmp_path / "len.csv", index=False)
    robot = None  # two tendon columns: the check against the robot's tendon count is left out
    t = {"file": "len.csv", "mode": "length", "frame": "base",
         "commands": {"columns": ["L1", "L2"], "unit": "mm", "scale": 0.1, "convention": "pull"},
         "tip_position": {"columns": ["x", "y", "z"], "unit": "mm"}}
    m = read_measurements(t, tmp_path, robot, "s.toml")
    np.testing.assert_allclose(m.commands, [[-0.002, 0.0], [0.0, 0.0005]], rtol=1e-12)
    np.testing.assert_allclose(m.tip_position[1], [0.002, 0.0, 0.399])
    t["commands"]["convention"] = "free_length"
    np.testing.assert_allclose(read_measurements(t, tmp_path, None, "s.toml").commands, [[0.002, 0.0], [0.0, -0.0005]])


def test_a_world_frame_force_is_rotated_into_the_base_frame(tmp_path):
    """A horizontal robot (base x = world z, base y = -world y, base z = world x): a world force (0, 1, 2) mN is (2, -1, 0) mN in base."""
    robot = robot_from_params({"preset": "rao_2021", "base_orientation": "horizontal"})
    df = pd.read_csv(FIX / "measured.csv")
    df["fx"], df["fy"], df["fz"] = 0.0, 1.0, 2.0
    df.to_csv(tmp_path / "measured.csv", index=False)
    t = {**_table(), "tip_force": {"columns": ["fx", "fy", "fz"], "unit": "mN", "frame": "world"}}
    m = read_measurements(t, tmp_path, robot, "s.toml")
    np.testing.assert_allclose(m.tip_force[0], [2e-3, -1e-3, 0.0], atol=1e-18)
    t["tip_force"]["frame"] = "base"
    np.testing.assert_allclose(read_measurements(t, tmp_path, robot, "s.toml").tip_force[0], [0.0, 1e-3, 2e-3])


def test_quaternions_become_rotation_matrices():
    """Against Rodrigues' formula: q = (cos a/2, sin a/2 k) is the rotation by a about k."""
    rng = np.random.default_rng(3)
    for _ in range(5):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        a = rng.uniform(-3, 3)
        K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        R = np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K
        q = np.r_[np.cos(a / 2), np.sin(a / 2) * k] * 1.0004  # within the tolerance: normalised
        np.testing.assert_allclose(quaternion_matrices(q[None])[0], R, atol=1e-12)


def test_a_semicolon_file_needs_its_delimiter(tmp_path):
    shutil.copy(FIX / "measured.csv", tmp_path / "measured.csv")
    text = (tmp_path / "measured.csv").read_text(encoding="utf-8").replace(",", ";")
    (tmp_path / "measured.csv").write_text(text, encoding="utf-8")
    from workbench.study.messages import StudyError

    with pytest.raises(StudyError) as info:
        read_measurements(_table(), tmp_path, ROBOT, "s.toml")
    assert info.value.problems == [f"{tmp_path / 'measured.csv'}: none of the columns measurements maps is in the "
                                   f"file (header: 'T1;T2;T3;T4;T5;T6;x;y;z;qw;qx;qy;qz;b1x;b1y;b1z;b2x;b2y;b2z;b3x;"
                                   f"b3y;b3z'); is the delimiter ',' right (measurements.delimiter)?"]
    m = read_measurements({**_table(), "delimiter": ";"}, tmp_path, ROBOT, "s.toml")
    np.testing.assert_array_equal(m.commands, read_measurements(_table(), FIX, ROBOT, "s.toml").commands)


def test_spaces_around_names_and_blank_lines(tmp_path):
    """Spaces after the delimiter are not part of a name; blank lines at the end are no samples, inside one line each."""
    from workbench.study.messages import StudyError

    lines = (FIX / "measured.csv").read_text(encoding="utf-8").splitlines()
    (tmp_path / "measured.csv").write_text(", ".join(lines[0].split(",")) + "\n" + "\n".join(lines[1:]) + "\n\n\n",
                                           encoding="utf-8")
    m = read_measurements(_table(), tmp_path, ROBOT, "s.toml")
    assert m.n == 40
    np.testing.assert_array_equal(m.tip_position, read_measurements(_table(), FIX, ROBOT, "s.toml").tip_position)
    (tmp_path / "measured.csv").write_text("\n".join(lines[:6] + [""] + lines[6:]) + "\n", encoding="utf-8")
    with pytest.raises(StudyError) as info:
        read_measurements(_table(), tmp_path, ROBOT, "s.toml")
    assert info.value.problems == [f"{tmp_path / 'measured.csv'}: row 6: an empty line (every mapped column empty)"]


def test_a_spreadsheet_export_with_a_byte_order_mark_and_crlf(tmp_path):
    text = (FIX / "measured.csv").read_text(encoding="utf-8")
    (tmp_path / "measured.csv").write_bytes(b"\xef\xbb\xbf" + text.replace("\n", "\r\n").encode("utf-8"))
    m = read_measurements(_table(), tmp_path, ROBOT, "s.toml")
    np.testing.assert_array_equal(m.commands, read_measurements(_table(), FIX, ROBOT, "s.toml").commands)
