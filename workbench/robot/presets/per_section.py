"""Per-section values of a preset's parameter: a scalar for every section, or one value per section.

Used by the presets whose module declares ``PER_SECTION`` (:mod:`workbench.robot.presets`);
checked by ``tests/robot/test_per_section.py``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["per_section"]


def per_section(name: str, value: Any, n: int) -> tuple[Any, ...]:
    """``value`` as ``n`` per-section values: a scalar repeated, or a list of exactly ``n`` entries.

    Raises
    ------
    ValueError
        A list whose length is not ``n``.
    """
    if isinstance(value, (list, tuple)):
        if len(value) != n:
            raise ValueError(f"{name} must hold {n} values (one per section), got {len(value)}")
        return tuple(value)
    return (value,) * n
