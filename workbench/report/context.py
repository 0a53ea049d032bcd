"""What the report page is made of: :class:`Section` (one part of the page) and :class:`PageContext`.

Section builders (:mod:`.sections`, or any module named in :data:`.page.SECTIONS`) take a
:class:`PageContext` and return a :class:`Section` or ``None``.  Checked by ``tests/report/``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import pandas as pd

from .load import ResultSet

__all__ = ["PageContext", "Section"]


@dataclass(frozen=True)
class Section:
    """One part of the page: ``id`` is its HTML anchor, ``html`` trusted (already escaped) markup."""

    id: str
    title: str
    html: str
    heading: bool = True


@dataclass(frozen=True)
class PageContext:
    """What a section builder may use."""

    study: ResultSet
    cmp: pd.DataFrame
    summary: pd.DataFrame
    failed: pd.DataFrame
    failed_columns: tuple[str, ...]
    figures_html: tuple[str, ...]
    figure_names: tuple[str, ...]
    downloads: tuple[tuple[str, str, str], ...] = ()
    """``(file name, data URI or relative path, description)`` per download link."""
    viewer_cases: int = 0
    viewer_left_out: int = 0
    extra: Mapping[str, Any] = field(default_factory=dict)
