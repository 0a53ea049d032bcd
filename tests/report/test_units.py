"""The unit table: labels with units for robot.*, load.*, scenario.* keys; never two units on one axis."""

from __future__ import annotations

import pandas as pd

from workbench.report.style import case_title, axis_label, short_label, value_text
from workbench.report.units import label_of, shown_unit, unit_groups
from workbench.units import UNITS


def test_known_keys_get_name_and_unit():
    assert label_of("p.robot.payload_mass") == "payload mass [kg]"
    assert label_of("p.load.bend_angle") == "bending angle θ [rad]"
    assert label_of("p.scenario.delay") == "wire delay [s]"
    assert label_of("tip_twist") == "tip twist [rad]"
    assert label_of("tendon_stretch") == "tendon stretch [m]"
    assert label_of("p.scenario.shape") == "trajectory"          # a category: no unit
    assert shown_unit("p.robot.n_sections") == ""                   # dimensionless
    # every robot.*, load.*, scenario.* entry names a unit or is explicitly unitless/categorical
    assert all(u is None or isinstance(u, str) for k, (_, u) in UNITS.items())


def test_study_labels_win_and_unknown_keys_keep_their_name():
    assert label_of("p.robot.payload_mass", {"p.robot.payload_mass": "payload [kg]"}) == "payload [kg]"
    assert label_of("p.robot.something_new") == "robot.something_new"   # no guessed unit
    assert axis_label("p.scenario.shape") == "trajectory"


def test_case_titles_carry_units():
    assert value_text("p.robot.payload_mass", 0.1) == "0.1 kg"
    assert short_label("p.robot.payload_mass") == "payload mass"
    title = case_title({"p.robot.payload_mass": 0.1, "p.scenario.shape": "line"},
                        ["p.robot.payload_mass", "p.scenario.shape"], {})
    assert title == "payload mass = 0.1 kg, trajectory = line"


def test_pose_amplitude_unit_depends_on_the_pose():
    df = pd.DataFrame({"p.pose.value": [0.2, 0.5, -0.2, 1.0],
                       "p.pose.shape": ["x", "rx", "z", "bending"]})
    groups = unit_groups(df, "p.pose.value")
    assert set(groups) == {"m", "rad"}
    assert list(groups["m"]) == [0, 2] and list(groups["rad"]) == [1, 3]
    title = case_title({"p.pose.value": 0.5, "p.pose.shape": "rx"}, ["p.pose.value", "p.pose.shape"], {})
    assert title == "motion amplitude = 0.5 rad, motion = rx"
