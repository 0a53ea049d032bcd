"""compare.table.section_ends_from_row rebuilds the preset from a row's flattened p.robot.* cells
(un-flattened with study.params.section_params)."""

from __future__ import annotations

import math

import numpy as np

from workbench.compare.table import section_ends_from_row
from workbench.study.params import flatten_params


def test_section_ends_from_stored_cells():
    row = {
        "p.robot.preset": "steel_rod",
        "p.robot.length": np.float64(0.6),   # numpy scalars as read back from Parquet
        "p.robot.n_sections": np.int64(2),
        "p.robot.disk_mass": math.nan,        # a parameter another case did not have
        "p.robot.payload_mass": None,
        "p.robot.not_a_parameter": 3.0,       # ignored
        "p.load.bend_angle": 1.0,
    }
    np.testing.assert_allclose(section_ends_from_row(row), [0.3, 0.6], rtol=1e-15)


def test_section_ends_round_trip_of_flatten_params():
    row = flatten_params({"robot": {"preset": "steel_rod", "length": 0.9, "n_sections": 3}})
    np.testing.assert_allclose(section_ends_from_row(row), [0.3, 0.6, 0.9], rtol=1e-15)


def test_section_ends_column_wins_and_unknown_preset_gives_none():
    assert section_ends_from_row({"section_ends": [0.1, 0.2], "p.robot.preset": "steel_rod"}).tolist() == [0.1, 0.2]
    assert section_ends_from_row({"p.robot.preset": "no_such_preset"}) is None
    assert section_ends_from_row({}) is None
