"""Sweeping one element (``load.tensions[0]``, ``robot.joint_stiffness[1]``): the cases, the one-line messages
of bad key paths and values, and the swept element as a number in the table, the report and xarray."""

from __future__ import annotations

import json
import textwrap

import numpy as np
import pytest

import study_fakes as fakes
from workbench.study import RunConfig, SerialExecutor, StudyError, expand, load_study
from workbench.study.runner import run_cases


def _sweep(block: str) -> str:
    return f"\n[sweep]\n{block}\n"


def test_an_element_sweep_is_the_whole_vector_sweep_it_spells(write_study):
    """Same cases, same case ids as sweeping the whole vectors (the ids hash the parameters, not the axis)."""
    element = expand(load_study(write_study(_sweep('product = { "load.tensions[0]" = [1.0, 2.5] }'))))
    whole = expand(load_study(write_study(_sweep('product = { "load.tensions" = [[1.0, 0.0], [2.5, 0.0]] }'))))
    assert [c.params for c in element] == [c.params for c in whole]
    assert [c.case_id for c in element] == [c.case_id for c in whole]
    assert element[1].swept == {"load.tensions[0]": 2.5} and element[1].params["load"]["tensions"] == [2.5, 0.0]


def test_a_preset_list_element(tmp_path):
    p = tmp_path / "hw.toml"
    p.write_text(textwrap.dedent("""\
        [study]
        name = "hw"
        models = ["cc"]
        [robot]
        preset = "hannan_walker"
        [sweep]
        product = { "robot.joint_stiffness[1]" = [60.0, 100.0] }
        """))
    cases = expand(load_study(p))
    assert [list(c.params["robot"]["joint_stiffness"]) for c in cases] == [[120.0, 60.0, 50.0, 25.0],
                                                                           [120.0, 100.0, 50.0, 25.0]]
    p.write_text(p.read_text().replace("[60.0, 100.0]", "[60.0, -1.0]"))
    with pytest.raises(StudyError) as e:
        load_study(p)
    assert e.value.problems == [f'{p}: sweep.product["robot.joint_stiffness[1]"][1]: must be > 0 [N m/rad], got -1']


@pytest.mark.parametrize("block, line", [
    ('product = { "load.tensions[2]" = [1.0] }',
     'sweep.product["load.tensions[2]"]: index 2 is out of range (load.tensions has 2 entries)'),
    ('product = { "robot.length[0]" = [1.0] }',
     'sweep.product["robot.length[0]"]: robot.length is a number, not a list; [0] needs a list'),
    ('product = { "load.tip_force.x" = [1.0] }',
     'sweep.product["load.tip_force.x"]: load.tip_force is a list, not a table; .x needs a table'),
    ('product = { "load.tensions[0]" = [-1.0] }', 'sweep.product["load.tensions[0]"][0]: must be >= 0 [N], got -1'),
    ('product = { "load.tensions[a]" = [1.0] }',
     'sweep.product["load.tensions[a]"]: malformed key path; expected dotted keys with [i] list indices, e.g. '
     'load.tensions[0] or robot.sections[1].diameter'),
    ('product = { "load.tensions" = [[1.0, 0.0]] }\nzip = { "load.tensions[1]" = [2.0] }',
     'sweep.zip["load.tensions[1]"]: overlaps the axis "load.tensions" of sweep.product (a value may be swept by '
     'one axis only)'),
    ('cases = [{ "load.tensions[3]" = 1.0 }]',
     'sweep.cases["load.tensions[3]"]: index 3 is out of range (load.tensions has 2 entries)'),
    ('random = { n = 4, "load.tensions[0]" = { low = -2.0, high = 1.0 } }',
     'sweep.random["load.tensions[0]"].low: must be >= 0 [N], got -2'),
])
def test_bad_element_axes_are_one_line_naming_the_key(write_study, block, line):
    path = write_study(_sweep(block))
    with pytest.raises(StudyError) as e:
        load_study(path)
    assert e.value.problems == [f"{path}: {line}"]


def test_the_swept_element_is_a_number_in_table_report_and_xarray(tmp_path, write_study):
    from workbench.report.load import load_results
    from workbench.results import load, to_xarray

    study = load_study(write_study(_sweep('product = { "load.tensions[0]" = [1.0, 2.0, 4.0] }')
                                   + '\n[report]\naxes = ["load.tensions[0]"]\nsensitivity = ["load.tensions[0]"]\n'))
    run_cases(fakes.sweep_kind(), study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    df = load(tmp_path / "out")
    col = "p.load.tensions[0]"
    assert df[col].dtype == np.float64 and sorted(set(df[col])) == [1.0, 2.0, 4.0]
    # the column is the element of the stored whole vector, row by row
    assert all(r[col] == r["p.load.tensions"][0] for _, r in df.iterrows())
    assert df.attrs["sweep_axes"] == [col]
    ds = to_xarray(df)
    assert ds[col].dtype == np.float64 and ds[col].values.tolist() == [1.0, 2.0, 4.0] and ds.attrs["layout"] == "grid"
    rs = load_results(tmp_path / "out")
    assert rs.axes == (col,) and col not in rs.categories
    from workbench.report.headline import baseline_value, sensitivity_keys

    assert sensitivity_keys(rs) == [col] and baseline_value(rs, col) == 1.0  # the file's tensions = [1.0, 0.0]


def test_a_whole_vector_axis_is_labelled_by_its_numbers(tmp_path, write_study):
    from workbench.report.load import category_label, load_results

    assert category_label("[10.0,0.0]") == "(10, 0)" and category_label("line") == "line"
    assert category_label('[{"a":1}]') == '[{"a":1}]'
    study = load_study(write_study(_sweep('product = { "load.tensions" = [[10.0, 0.0], [2.0, 0.5], [0.25, 0.0]] }')))
    run_cases(fakes.sweep_kind(), study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    rs = load_results(tmp_path / "out")
    assert rs.categories["p.load.tensions"] == ("(0.25, 0)", "(2, 0.5)", "(10, 0)")  # in numeric order
    assert json.loads(rs.results["p.load.tensions"].iloc[0])  # the stored cell itself is unchanged
