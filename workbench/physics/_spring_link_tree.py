"""Deprecated: import from :mod:`workbench.physics.spring_link.tree`.

Thin re-export kept for old import paths (tests, benchmarks, user code).
"""

from __future__ import annotations

from .spring_link.tree import tree_tip_position

__all__ = ["tree_tip_position"]
