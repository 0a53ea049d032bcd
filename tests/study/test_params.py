"""Flat ``p.*`` columns round-trip to the parameters they came from (workbench.study.params)."""

import numpy as np

from workbench.study.params import canonical_json, case_id_for, flatten_params, section_params, unflatten_params


def test_flatten_unflatten_round_trip():
    params = {"robot": {"preset": "steel_rod", "length": 0.8, "n_disks": 8, "offsets": [0.01, 0.02]},
              "load": {"bend_angle": [1.0, 0.5], "tip_force": None, "mode": "tension"},
              "derived": {"gravity_parameter": 1.0}}
    flat = flatten_params(params)
    assert flat["p.load.bend_angle"] == "[1.0,0.5]"
    back = unflatten_params(flat)
    params["load"].pop("tip_force")  # None cells are "not set" in a table
    assert back == params


def test_section_params_unwraps_numpy_and_skips_nan():
    row = {"p.robot.length": np.float64(0.8), "p.robot.n_disks": np.int64(8), "p.robot.taper": float("nan"),
           "p.load.bend_angle": "[1.0]", "tip_x": 0.1}
    out = section_params(row, "robot")
    assert out == {"length": 0.8, "n_disks": 8}
    assert type(out["length"]) is float and type(out["n_disks"]) is int
    assert section_params(row, "load") == {"bend_angle": [1.0]}


def test_case_id_depends_only_on_values():
    a = {"robot": {"x": 1.0, "y": 2}, "load": {}}
    b = {"load": {}, "robot": {"y": 2, "x": 1.0}}
    assert canonical_json(a) == canonical_json(b)
    assert case_id_for(a) == case_id_for(b)
    assert case_id_for(a) != case_id_for({"robot": {"x": 1.0, "y": 3}, "load": {}})


def test_flatten_params_memo_keys_shared_sections_by_identity():
    from workbench.study.params import flatten_params

    robot = {"preset": "steel_rod", "disks": [0.1, 0.2]}
    memo: dict = {}
    a = flatten_params({"robot": robot, "load": {"tensions": [1.0, 0.0]}}, memo)
    b = flatten_params({"robot": robot, "load": {"tensions": [2.0, 0.0]}}, memo)
    assert a == flatten_params({"robot": robot, "load": {"tensions": [1.0, 0.0]}})
    assert b["p.load.tensions"] == "[2.0,0.0]" and b["p.robot.disks"] == "[0.1,0.2]"
    assert len(memo) == 1  # only the shared robot section is memoised
    other = {"preset": "steel_rod", "disks": [0.3]}  # another dict: converted, not taken from the memo
    assert flatten_params({"robot": other}, memo)["p.robot.disks"] == "[0.3]"


def test_case_id_from_sections_is_case_id_for():
    from workbench.study.params import case_id_from_sections

    params = {"robot": {"preset": "steel_rod", "offsets": [0.01, 0.02], "name": "é"},
              "load": {"tensions": [1.5, 0.0], "mode": "tension"}, "derived": {}}
    given = {sec: canonical_json(d) for sec, d in params.items() if sec != "load"}
    assert case_id_from_sections(params, given) == case_id_for(params)
    assert case_id_from_sections(params, {}) == case_id_for(params)
    wrong = {"robot": canonical_json({"preset": "other"})}  # the caller's JSON is what is hashed
    assert case_id_from_sections(params, wrong) != case_id_for(params)


def test_canonical_json_of_a_float_list_is_the_encoders_bytes():
    import json

    import numpy as np
    import pytest

    rng = np.random.default_rng(0)
    samples = [[float(x) for x in rng.normal(size=n) * 10.0 ** rng.integers(-30, 30, size=n)] for n in (1, 3, 17)]
    samples += [[-0.0, 0.0, 5e-324, 1e16, 0.1 + 0.2], [1e308, 1e308], [1.0, 2], [True, 1.0], []]
    for v in samples:
        assert canonical_json(v) == json.dumps(v, sort_keys=True, separators=(",", ":"), allow_nan=False)
    for bad in ([1.0, float("nan")], [float("inf")]):
        with pytest.raises(ValueError):
            canonical_json(bad)
