"""The plug-in points a study kind offers the generic report (``workbench.registry.KindInfo``).

The report never names a study's columns: a kind whose results need more than the generic
figures and view registers hooks on its ``KINDS`` row (``lines``: extra polylines of the 3-D
view; ``axes``: the parameter columns that vary its cases), and the report calls them through
:func:`kind_hook`.  Checked by ``tests/report/test_viewer.py`` and ``tests/report/test_errorbars.py``.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

from .. import registry

__all__ = ["kind_hook"]


def kind_hook(spec: Mapping[str, Any], name: str) -> Callable | None:
    """The hook ``name`` (``"lines"`` / ``"axes"``) of the study kind of resolved spec ``spec``, else ``None``."""
    inner = spec.get("study") if isinstance(spec.get("study"), Mapping) else {}
    row = registry.table("kinds").get(str(inner.get("kind", "sweep")))
    target = getattr(row, name, None) if row is not None else None
    return registry.resolve(target) if target else None
