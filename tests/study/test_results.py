"""The results loader: every column type round-trips, arrays come back in their shapes (static and
dynamic), list parameters as lists, units and frames in attrs and in the Parquet field metadata."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import study_fakes as fakes
from workbench import results
from workbench.study import RunConfig, SerialExecutor, load_study, run_cases, run_study
from workbench.study.store import SCHEMA_FILE


@pytest.fixture(scope="module")
def static_folder(tmp_path_factory):
    """A CC (real, numpy) + fake-ANCF sweep over a list parameter, with one failing case."""
    tmp = tmp_path_factory.mktemp("static")
    p = tmp / "s.toml"
    p.write_text(fakes.GOOD + '\n[sweep]\nproduct = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0], '
                              f'[{fakes.RAISE}, 0.0]], "robot.length" = [0.5, 0.8] }}\n')
    from workbench.models import get_model

    kind = fakes.sweep_kind(lambda name: fakes.arc if name == "ancf" else get_model(name))
    run_cases(kind, load_study(p), tmp / "o", SerialExecutor(), RunConfig(progress=False))
    return tmp / "o"


@pytest.fixture(scope="module")
def dynamic_folder(tmp_path_factory):
    """A dynamic CC case (tendon ramp): time series beside time."""
    tmp = tmp_path_factory.mktemp("dyn")
    p = tmp / "d.toml"
    p.write_text(fakes.GOOD.replace('models = ["cc", "ancf"]', 'models = ["cc"]').replace(
        'tensions = [1.0, 0.0]', 'tensions = [1.0, 0.0]\nanalysis = "dynamic"\nduration = 0.05\nramp_time = 0.02')
        + "time_step = 0.005\n")
    run_study(load_study(p), tmp / "o", SerialExecutor(), RunConfig(progress=False))
    return tmp / "o"


def test_every_column_round_trips(static_folder):
    raw = pd.read_parquet(static_folder).sort_values(["case_id", "model"]).reset_index(drop=True)
    df = results.load(static_folder).sort_values(["case_id", "model"]).reset_index(drop=True)
    assert list(df.columns) == list(raw.columns) and len(df) == len(raw) == 12
    for c in raw.columns:
        for a, b in zip(raw[c], df[c]):
            if isinstance(b, np.ndarray):  # arrays: the same numbers, reshaped
                assert np.array_equal(np.ravel(b), np.asarray(a, float), equal_nan=True), c
            elif c.startswith("p.") and isinstance(a, str) and a.startswith("["):
                assert isinstance(b, list) and b == json.loads(a), c  # JSON string -> list
            elif isinstance(a, float) and np.isnan(a):
                assert isinstance(b, float) and np.isnan(b), c
            else:
                assert type(a) is type(b) and a == b, (c, a, b)  # str, bool, int, float, None unchanged


def test_arrays_have_their_shapes_and_lists_are_lists(static_folder):
    df = results.load(static_folder, ok_only=True)
    assert (df["status"] == "ok").all() and len(df) == 10  # the fake ANCF raises at 13 N (2 rows), CC does not
    row = df.iloc[0]
    assert row["positions"].shape == (9, 3) and row["tip_frame"].shape == (4, 4)
    assert np.allclose(row["positions"][-1], [row["tip_x"], row["tip_y"], row["tip_z"]])
    assert np.allclose(row["tip_frame"][:3, 3], row["positions"][-1])  # base <- tip translation
    assert row["stations"].shape == (9,)
    assert isinstance(row["p.load.tensions"], list) and len(row["p.load.tensions"]) == 2
    assert set(df.attrs["sweep_axes"]) == {"p.load.tensions", "p.robot.length"}


def test_units_and_frames_in_attrs_and_in_the_parquet_field_metadata(static_folder):
    df = results.load(static_folder)
    u, f = df.attrs["units"], df.attrs["frames"]
    assert u["tip_x"] == "m" and f["tip_x"] == "base" and u["positions"] == "m" and f["positions"] == "base"
    assert u["p.load.tensions"] == "N" and u["p.robot.length"] == "m" and u["wall_time"] == "s"
    assert "case_id" not in u and "p.robot.preset" not in u  # text and categories have no unit
    assert df.attrs["manifest"]["study"]["study"]["name"] == "good"
    schema = pq.read_schema(static_folder / SCHEMA_FILE)
    assert schema.field("tip_x").metadata == {b"unit": b"m", b"frame": b"base"}
    assert schema.field("p.load.tensions").metadata == {b"unit": b"N"}


def test_dynamic_series_have_time_first(dynamic_folder):
    df = results.load(dynamic_folder)
    row = df.iloc[0]
    n_t = row["time"].shape[0]
    assert n_t > 2 and row["series.tip_position"].shape == (n_t, 3)
    assert df.attrs["units"]["series.tip_position"] == "m" and df.attrs["frames"]["series.tip_position"] == "base"
    assert df.attrs["units"]["time"] == "s"


def test_not_a_result_folder(tmp_path):
    with pytest.raises(FileNotFoundError, match="not a study result folder"):
        results.load(tmp_path)


# ---------------------------------------------------------------------------------------------
# the optional xarray view over the sweep axes
# ---------------------------------------------------------------------------------------------
def test_xarray_grid_over_the_sweep_axes(static_folder):
    pytest.importorskip("xarray")
    df = results.load(static_folder)
    ds = results.to_xarray(df)
    assert ds.attrs["layout"] == "grid"
    assert dict(ds["tip_x"].sizes) == {"p.load.tensions": 3, "p.robot.length": 2, "model": 2}
    assert ds["positions"].dims[-2:] == ("station", "xyz") and ds.sizes["station"] == 9
    assert ds["tip_x"].attrs == {"units": "m", "frame": "base"} and ds["positions"].attrs["frame"] == "base"
    for _, row in df.iterrows():  # every row at its place, arrays included; failed rows NaN
        at = {"p.load.tensions": json.dumps(row["p.load.tensions"], separators=(",", ":")),
              "p.robot.length": row["p.robot.length"], "model": row["model"]}
        cell = ds.sel(at)
        assert cell["case_id"].item() == row["case_id"] and cell["status"].item() == row["status"]
        if row["status"] == "ok":
            assert cell["tip_x"].item() == row["tip_x"]
            assert np.array_equal(cell["positions"].values, row["positions"])
        else:
            assert np.isnan(cell["tip_x"].item()) and np.all(np.isnan(cell["positions"].values))


def test_xarray_cases_layout_when_not_a_grid(static_folder):
    pytest.importorskip("xarray")
    df = results.load(static_folder)
    part = df[df["case_id"] != df["case_id"].iloc[0]].reset_index(drop=True)  # one case missing: no full grid
    part.attrs = df.attrs
    ds = results.to_xarray(part)
    assert ds.attrs["layout"] == "cases" and dict(ds["tip_x"].sizes) == {"case_id": 5, "model": 2}
    first = part.iloc[0]
    sel = ds.sel(case_id=first["case_id"])
    assert sel["p.robot.length"].item() == first["p.robot.length"]
    assert sel["tip_x"].sel(model=first["model"]).item() == first["tip_x"]


def test_xarray_series_share_the_time_axis(dynamic_folder):
    pytest.importorskip("xarray")
    df = results.load(dynamic_folder)
    ds = results.to_xarray(df)
    n_t = df.iloc[0]["time"].shape[0]
    assert ds["time"].dims[-1] == "t" and ds["series.tip_position"].dims[-2:] == ("t", "xyz")
    assert ds.sizes["t"] == n_t and ds["time"].attrs["units"] == "s"


def test_xarray_missing_names_the_install(static_folder, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "xarray", None)  # as if it were not installed
    with pytest.raises(ImportError, match="pip install xarray"):
        results.to_xarray(results.load(static_folder))


def test_the_report_reads_the_same_table_and_axes(static_folder):
    from workbench.report.load import load_results

    df, st = results.load(static_folder), load_results(static_folder)
    assert sorted(st.results["case_id"] + st.results["model"]) == sorted(df["case_id"] + df["model"])
    assert set(st.results.columns) >= set(df.columns)
    assert {a for a in st.axes if a.startswith("p.")} <= set(df.attrs["sweep_axes"])


def test_parts_of_mixed_schemas_are_refused_not_concatenated(static_folder, tmp_path):
    import shutil

    from workbench.study.store import CorruptPart

    folder = tmp_path / "mixed"
    shutil.copytree(static_folder, folder)
    part = sorted(p for p in folder.glob("part-*.parquet") if p.name != SCHEMA_FILE)[0]
    t = pq.read_table(part)
    i = t.schema.get_field_index("positions")  # list<double> in the schema, text in this part
    t = t.set_column(i, "positions", pa.array(["not an array"] * len(t), pa.string()))
    pq.write_table(t, part)
    with pytest.raises(CorruptPart):
        results.load(folder)
