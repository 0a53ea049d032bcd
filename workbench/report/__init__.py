"""Self-contained HTML comparison reports (matplotlib ``Figure`` objects, Agg; no pyplot).

``build_report(data_dir, out_dir=None) -> Path`` reads ``data/<study>/`` (Parquet part files
and ``_manifest.json``; conventions in :mod:`workbench.report.load`) and writes
``reports/<study>/report.html`` (figures inlined as PNG, no external references),
``figures/*.png|svg`` and the metric tables as CSV.  Command line:
``python -m workbench.report data/<study> [--out DIR]`` (:func:`main`).
"""

from typing import Any

__all__ = ["ResultSet", "build_report", "load_results", "main"]

_LAZY = {"build_report": ".build", "main": ".command", "ResultSet": ".load", "load_results": ".load"}


def __getattr__(name: str) -> Any:
    """Import the builder (matplotlib, pandas) only when a name is used (PEP 562)."""
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name], __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
