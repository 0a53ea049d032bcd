"""The fluidic harvester study's question, assumptions and seed-paper rows, as data (see :mod:`.scoop_figures`).

:data:`ABOUT` (a :class:`~workbench.experiments.about.StudyAbout`; each assumption a modelling
choice: what, the value as text, why).  Checked by ``tests/experiments/test_fruit_harvester_scoop.py``.
"""

from __future__ import annotations

from ...assumptions import Assumption
from ..about import StudyAbout

__all__ = ["ABOUT"]

ABOUT = StudyAbout(
    question=("Does Shao's centre-of-arc grasp hold with the real actuation (pressurised chambers that lengthen "
              "the section, instead of the tendon stand-in that shortens it) and with the fruit as an object in "
              "the scoop instead of a tip mass -- and can the centre-of-arc Jacobian close the loop on it?"),
    assumptions=(
        Assumption("", "the paper gives 12 FPAs in 3 groups, no force law",
                   what="chambers",
                   value="three chamber lines at the tendon stand-in's 0/120/240 deg and 22 mm, F = A p"),
        Assumption("", "the 270 deg scoop then needs 0.54 MPa, within the paper's 0.6 MPa",
                   what="chamber area", value="A = 3e-4 m^2"),
        Assumption("", "the paper gives L and mass only",
                   what="section", value="the shao_harvester preset's rod (EI 0.3 N m^2, EA 2 kN; 400 mm, 230 g)"),
        Assumption("", "paper: up to 100 mm, 200 g",
                   what="fruit", value="rigid 100 mm sphere (a cylinder in the plane) released into the scoop"),
        Assumption("", "at 1e6 the 100 g fluidic fruit slipped out during the release and at 1e8 two fluidic cases "
                       "did not converge; 1e7 vs 1e8 moves the settled fruit by <= 0.2 mm (x.pen_* bars: 1e7 vs 1e6)",
                   what="contact law", value="penalty 1e7 N/m^2, stick 1e5 N/m^2, friction 0.3"),
        Assumption("", "the paper gives the Jacobian, not the law",
                   what="controller", value="Shao Eq 4-5 (corrected J_v), bending plane fixed, 4 steps"),
    ),
    paper_rows=(
        "Shao et al. (papers/002_), Sec. 2.2: FPAs elongate when pressurised (fluidic chambers instead of tendons)",
        "Shao et al., Sec. 4 / Fig 8: objects up to 200 g scooped in the wrap (payload as an object, not a tip mass)",
        "Shao et al., Eq 4-5: the centre-of-arc Jacobian, here closing the loop on the physics",
    ),
)
