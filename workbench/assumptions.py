"""Assumptions as data: one frozen :class:`Assumption` for everything a source paper does not give.

Every place that assumes something declares it next to what it describes, as a tuple of
:class:`Assumption` named ``ASSUMED``:

* a robot preset module (``workbench/robot/presets/*.py``; keys are the preset's parameters,
  e.g. ``"joint_stiffness"``, shown as ``robot.joint_stiffness``);
* a scenario module (``registry.table("scenarios")``; keys ``"move_time"`` -> ``scenario.move_time``);
* a study kind module (``registry.table("kinds")``; dotted keys, e.g. ``"geometry.height"``).

The report's Assumptions table reads them all through :func:`declared_assumptions` and fills
in the value the cases ran with (:func:`workbench.report.assumptions.assumption_rows`).  An
experiment's figure caption states its question and assumptions with the same class
(:class:`workbench.experiments.about.StudyAbout`).  This module imports nothing from the
workbench, so every layer can use it.  Checked by ``tests/test_assumptions.py``,
``tests/robot/test_presets_sources.py`` and ``tests/report/test_findings.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

__all__ = ["Assumption", "declared_assumptions"]


@dataclass(frozen=True)
class Assumption:
    """One parameter value or modelling choice the source paper does not give, and where it comes from.

    Attributes
    ----------
    key : str
        The parameter it fixes: a preset parameter (``"joint_stiffness"``), a scenario parameter
        (``"move_time"``) or a dotted study key (``"robot.joint_stiffness"``, ``"geometry.height"``);
        ``""`` for a modelling choice without a parameter.
    source : str
        Where the value comes from or why it was chosen (``"assumed: ..."``, a data sheet, a
        measurement).
    what : str
        What it is, with its unit, for a caption (``"joint spring stiffness per section [N m/rad]"``),
        or a short label of a modelling choice (``"contact law"``); ``""`` when the key says it.
    value : str
        The value as text where no result column holds it (a modelling choice), or the value
        the report read from the rows; ``""`` when the rows give it.
    """

    key: str
    source: str
    what: str = ""
    value: str = ""


def declared_assumptions(module: ModuleType) -> tuple[Assumption, ...]:
    """The ``ASSUMED`` tuple a preset, scenario or study kind module declares (empty when none).

    Raises
    ------
    TypeError
        ``ASSUMED`` holds something other than :class:`Assumption` entries.
    """
    declared = tuple(getattr(module, "ASSUMED", ()) or ())
    bad = [a for a in declared if not isinstance(a, Assumption)]
    if bad:
        raise TypeError(f"{module.__name__}.ASSUMED must hold Assumption entries, got {bad[0]!r}")
    return declared
