"""Names and units of the Hannan-Walker trajectory scenarios' parameters (``scenario.*``).

Registered as the ``units`` of the ``hannan_walker`` and ``hannan_walker_3d`` rows of
``workbench.registry.FIGURES`` (the generic unit table, :mod:`workbench.units`, holds no study
keys).  Data only (the study messages read it).  Checked by ``tests/report/test_units.py``.
"""

from __future__ import annotations

__all__ = ["QUANTITIES"]

#: key (without ``p.``) -> (readable name, unit), as in :data:`workbench.units.UNITS`
QUANTITIES = {
    "scenario.shape": ("trajectory", None), "scenario.sample": ("snapshot", ""),
    "scenario.n_samples": ("snapshots", ""),
}
