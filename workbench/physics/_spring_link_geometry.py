"""Deprecated: import from :mod:`workbench.physics.spring_link.geometry`.

Thin re-export kept for old import paths (tests, benchmarks, user code).
"""

from __future__ import annotations

from .spring_link.geometry import ChainGeometry, _section_of, chain_geometry_from_robot

__all__ = ["ChainGeometry", "chain_geometry_from_robot", "_section_of"]
