"""The whole-arm grasp study's question, assumptions and the seed-paper rows it answers, as data.

:data:`ABOUT` (a :class:`~workbench.experiments.about.StudyAbout`; each assumption a modelling
choice: what, the value as text, why) is quoted by the first figure's caption
(:mod:`.figures`); the robot's own assumptions are the preset's, in the report's Assumptions
table.  Checked by ``tests/experiments/test_whole_arm_grasp.py`` (the report names every assumption).
"""

from __future__ import annotations

from ...assumptions import Assumption
from ..about import StudyAbout

__all__ = ["ABOUT"]

ABOUT = StudyAbout(
    question=("When the constant-curvature (CC) plan of a whole-arm wrap is sent to the gravity-loaded trunk, "
              "does the arm hold the object where CC says, how firmly (holding force against a pull-out "
              "load), and does it carry it along the planned path?"),
    assumptions=(
        Assumption("", "Fig 6 shows a round object; no size or mass is given",
                   what="object", value="rigid cylinder normal to the bending plane"),
        Assumption("", "the paper gives none (preset docstring)",
                   what="joint springs, masses", value="the hannan_walker preset's defaults"),
        Assumption("", "continuous reading of the 16-joint trunk",
                   what="backbone", value="planar ANCF rod with the preset's EI, EA per section"),
        Assumption("", "the plan's motors hold tension",
                   what="tendons", value="continuum, frictionless, tension-controlled at the CC plan"),
        Assumption("", "an idealisation: with friction while closing, the 6 cm / squeeze 1.2 / mu 0.3 grasp "
                       "closes with 248 N normal force instead of 185 N",
                   what="closing", value="frictionless; friction acts from the closed grasp on"),
        Assumption("", "the holding force of that grasp is 111 / 117 / 126 N at 1e7 / 1e8 / 1e9 N/m^2 (no "
                       "convergence in the penalty): the x.pen_* error bars carry it",
                   what="contact law", value="penalty 1e8 N/m^2 per length, stick penalty 1e6 N/m^2"),
        Assumption("", "holding against the object's weight direction",
                   what="pull-out", value="straight down, sideways position free, displacement-controlled"),
        Assumption("", "", what="self-contact",
                   value="not modelled: wraps that would reach round onto the arm are refused"),
    ),
    # the seed-paper rows this study answers (issue 17's audit of the papers)
    paper_rows=(
        "Hannan & Walker (papers/000_), Fig 6: wrapping round a circular object and moving it",
        "Shao et al. (papers/002_), Sec. 3.1 / Figs 5-6: scooping an object with the whole trunk",
    ),
)
