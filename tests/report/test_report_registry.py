"""The report reads the registry: model labels/colours, study figure sets; one report command line.

workbench/report/style.py (model_label, model_color), report/build.py (study_figure_sets,
report_command, main), report/load.py (ResultSet / load_results).
"""

from __future__ import annotations

from types import SimpleNamespace

import pandas as pd
import pytest

from synth_study import write_runner_study, write_study
from workbench import registry
from workbench.report.load import ResultSet, load_results
from workbench.report.build import study_figure_sets
from workbench.report.command import main
from workbench.report.figures import GENERIC_FIGURES
from workbench.report.style import model_color, model_label
from workbench.report.style import _FALLBACK


def test_labels_and_colours_are_the_registry_rows():
    for name, info in [*registry.MODELS.items(), *registry.LABELS.items()]:
        assert registry.row_info(name) is info
        assert model_label(name) == info.label
        if info.color is not None:
            assert model_color(name, ["x", name]) == info.color
    assert model_label("not_a_model") == "not_a_model"


def test_models_without_colour_get_fallback_colours_in_order():
    models = ["cc", "series_parallel", "target", "cc_fit"]
    assert [model_color(m, models) for m in models[1:]] == _FALLBACK[:3]
    assert model_color("other") == _FALLBACK[0]  # not among the study's models


def _results(**cols) -> SimpleNamespace:
    df = pd.DataFrame({"model": ["cc"], "status": ["ok"], **{k: [v] for k, v in cols.items()}})
    return SimpleNamespace(ok=df, results=df, models=("cc",))


@pytest.mark.parametrize("cols,sets", [
    ({}, []),
    ({"p.robot.preset": "steel_rod"}, []),
    ({"p.scenario.name": "wire_delay", "p.robot.preset": "cojocaru_tronconic"}, ["wire_delay"]),
    ({"p.scenario.name": "hannan_walker_line", "p.robot.preset": "hannan_walker"}, ["hannan_walker"]),
    ({"p.robot.preset": "shao_harvester"}, ["fruit_harvester"]),
    ({"p.pose.kind": "module"}, ["series_parallel"]),
])
def test_study_figure_sets_each_matches_its_own_study(cols, sets):
    assert study_figure_sets(_results(**cols)) == sets


def test_generic_figures_in_report_order():
    assert [f.__name__ for f in GENERIC_FIGURES] == [
        "error_bar_figures", "shape_overlay_figures", "error_vs_parameter_figures", "validity_map_figures",
        "compression_split_figures", "time_series_figures"]


def test_load_results_gives_a_result_set(tmp_path):
    st = load_results(write_study(tmp_path / "d", "1d"))
    assert isinstance(st, ResultSet)


def test_report_command_refuses_a_folder_without_runner_manifest(tmp_path, capsys):
    data = write_study(tmp_path / "d", "1d")
    (data / "_manifest.json").rename(data / "manifest.json")  # not the runner's name
    assert main([str(data), "--out", str(tmp_path / "out")]) == 2
    assert capsys.readouterr().err.strip() == f"{data}: not a study result folder (no _manifest.json)"


def test_report_command_builds_and_prints_the_path(tmp_path, capsys):
    data = write_runner_study(tmp_path / "data" / "s")
    assert main([str(data), "--out", str(tmp_path / "out"), "--formats", "png"]) == 0
    path = tmp_path / "out" / "report.html"
    assert capsys.readouterr().out.strip() == str(path) and path.exists()
    assert list((tmp_path / "out" / "figures").glob("*.svg")) == []
