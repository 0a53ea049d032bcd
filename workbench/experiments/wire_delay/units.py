"""Names and units of the wire-delay scenarios' parameters (``scenario.*``).

Registered as the ``units`` of the ``wire_delay`` and ``wire_delay_arm`` rows of
``workbench.registry.FIGURES`` (the generic unit table, :mod:`workbench.units`, holds no study
keys).  Data only (the study messages read it).  Checked by ``tests/report/test_units.py``.
"""

from __future__ import annotations

__all__ = ["QUANTITIES"]

#: key (without ``p.``) -> (readable name, unit), as in :data:`workbench.units.UNITS`
QUANTITIES = {
    "scenario.delay": ("wire delay", "s"), "scenario.move_time": ("wire move time", "s"),
    "scenario.settle_time": ("settling time", "s"), "scenario.theta": ("bending angle θ", "rad"),
    "scenario.alpha": ("bending direction α", "rad"), "scenario.delayed_wire": ("delayed wire", ""),
}
