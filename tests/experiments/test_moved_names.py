"""The old import paths of the moved experiment code still give the same objects (deprecated shims).

Guards the moves of issue 12: study/scenarios.py, physics/wire_delay.py,
physics/hannan_walker_trajectory.py, report/_studies_b.py and report/_motion.py now forward to
workbench/experiments/ through registry strings.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping

import pytest

from workbench import registry

MOVED = [
    ("workbench.physics.wire_delay", "wire_lengths_tronconic", "workbench.experiments.wire_delay.analysis", "wire_lengths_tronconic_workbench"),
    ("workbench.physics.wire_delay", "arc_from_wire_lengths_tronconic", "workbench.experiments.wire_delay.analysis", "arc_from_wire_lengths_tronconic_workbench"),
    ("workbench.physics.wire_delay", "simulate_wire_delay", "workbench.experiments.wire_delay.analysis", "simulate_wire_delay"),
    ("workbench.physics.wire_delay", "default_options", "workbench.experiments.wire_delay.analysis", "default_options"),
    ("workbench.physics.wire_delay", "WireDelayResult", "workbench.experiments.wire_delay.analysis", "WireDelayResult"),
    ("workbench.physics.wire_delay", "_cc_tip", "workbench.experiments.wire_delay.analysis", "cc_tip_positions"),
    ("workbench.physics.wire_delay", "_eq12", "workbench.experiments.wire_delay.analysis", "eq12_compression"),
    ("workbench.physics.hannan_walker_trajectory", "cable_changes_from_joint_angles", "workbench.experiments.hannan_walker.replay", "cable_changes_from_joint_angles"),
    ("workbench.physics.hannan_walker_trajectory", "joint_angles_from_cable_changes", "workbench.experiments.hannan_walker.replay", "joint_angles_from_cable_changes"),
    ("workbench.physics.hannan_walker_trajectory", "replay_hannan_walker", "workbench.experiments.hannan_walker.replay", "replay_hannan_walker"),
    ("workbench.physics.hannan_walker_trajectory", "HannanWalkerReplay", "workbench.experiments.hannan_walker.replay", "HannanWalkerReplay"),
    ("workbench.study.scenarios", "wire_delay", "workbench.experiments.wire_delay.scenario", "wire_delay"),
    ("workbench.study.scenarios", "hannan_walker_line", "workbench.experiments.hannan_walker.scenario", "hannan_walker_line"),
    ("workbench.report._studies_b", "circle_fit", "workbench.experiments.fruit_harvester.envelope", "circle_fit"),
    ("workbench.report._studies_b", "HARVESTER_LIMITS", "workbench.experiments.fruit_harvester.envelope", "HARVESTER_LIMITS"),
    ("workbench.report._motion", "motion_figures", "workbench.experiments.series_parallel.figures", "motion_figures"),
    ("workbench.report._motion", "motion_overview_figure", "workbench.experiments.series_parallel.figures", "motion_overview_figure"),
    ("workbench.report._motion", "motion_legs_figure", "workbench.experiments.series_parallel.figures", "motion_legs_figure"),
]


@pytest.mark.parametrize("old_mod,old,new_mod,new", MOVED)
def test_old_path_gives_the_moved_object(old_mod, old, new_mod, new):
    assert getattr(importlib.import_module(old_mod), old) is getattr(importlib.import_module(new_mod), new)


@pytest.mark.parametrize("mod", ["workbench.physics.wire_delay", "workbench.physics.hannan_walker_trajectory",
                                 "workbench.study.scenarios", "workbench.report._studies_b", "workbench.report._motion"])
def test_shims_say_deprecated_and_reject_unknown_names(mod):
    m = importlib.import_module(mod)
    assert "Deprecated" in m.__doc__ or "deprecated" in m.__doc__
    with pytest.raises(AttributeError, match="no_such_name"):
        getattr(m, "no_such_name")


def test_scenarios_is_a_read_only_view_of_the_registry():
    from workbench.study.scenarios import SCENARIOS

    assert isinstance(SCENARIOS, Mapping)
    assert list(SCENARIOS) == list(registry.SCENARIOS) and list(SCENARIOS)[:2] == ["wire_delay", "hannan_walker_line"]
    assert {"whole_arm_wrap", "harvester_scoop", "hannan_walker_spatial", "closed_loop", "wire_delay_arm"} <= set(SCENARIOS)
    assert len(SCENARIOS) == len(registry.SCENARIOS) == 7 and "wire_delay" in SCENARIOS and "nope" not in SCENARIOS
    for name, fn in SCENARIOS.items():
        assert callable(fn) and fn is registry.resolve(registry.SCENARIOS[name])
    with pytest.raises(TypeError):
        SCENARIOS["x"] = None  # type: ignore[index]
    with pytest.raises(KeyError):
        SCENARIOS["nope"]


def test_legacy_study_figures_dispatch_is_the_registered_sets():
    from types import SimpleNamespace

    import pandas as pd

    from workbench.report._studies_b import study_figures

    assert study_figures(SimpleNamespace(ok=pd.DataFrame({"model": []})), None) == []
