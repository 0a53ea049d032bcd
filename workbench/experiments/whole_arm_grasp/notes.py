"""The whole-arm grasp study's question, assumptions and the seed-paper rows it answers, as data.

Kept apart from the figures so the report's "Question / Findings / Assumptions" sections can take
them (the figures' summaries quote them until then).  Each assumption: ``(what, value, why)``.
Checked by ``tests/experiments/test_whole_arm_grasp.py`` (the report names every assumption).
"""

from __future__ import annotations

__all__ = ["QUESTION", "ASSUMPTIONS", "SEED_ROWS"]

QUESTION = ("When the constant-curvature (CC) plan of a whole-arm wrap is sent to the gravity-loaded trunk, "
            "does the arm hold the object where CC says, how firmly (holding force against a pull-out "
            "load), and does it carry it along the planned path?")

ASSUMPTIONS = (
    ("object", "rigid cylinder normal to the bending plane", "Fig 6 shows a round object; no size or mass is given"),
    ("joint springs, masses", "the hannan_walker preset's defaults", "the paper gives none (preset docstring)"),
    ("backbone", "planar ANCF rod with the preset's EI, EA per section", "continuous reading of the 16-joint trunk"),
    ("tendons", "continuum, frictionless, tension-controlled at the CC plan", "the plan's motors hold tension"),
    ("closing", "frictionless; friction acts from the closed grasp on",
     "an idealisation: with friction while closing, the 6 cm / squeeze 1.2 / mu 0.3 grasp closes with 248 N "
     "normal force instead of 185 N"),
    ("contact law", "penalty 1e8 N/m^2 per length, stick penalty 1e6 N/m^2",
     "the holding force of that grasp is 111 / 117 / 126 N at 1e7 / 1e8 / 1e9 N/m^2 (no convergence in the "
     "penalty): the x.pen_* error bars carry it"),
    ("pull-out", "straight down, sideways position free, displacement-controlled",
     "holding against the object's weight direction"),
    ("self-contact", "not modelled: wraps that would reach round onto the arm are refused", ""),
)

#: Seed-paper rows this study answers (the papers' figures and sections it reproduces).
SEED_ROWS = (
    "Hannan & Walker (papers/000_), Fig 6: wrapping round a circular object and moving it",
    "Shao et al. (papers/002_), Sec. 3.1 / Figs 5-6: scooping an object with the whole trunk",
)
