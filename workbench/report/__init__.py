"""Self-contained HTML comparison reports (matplotlib ``Figure`` objects, Agg; no pyplot).

``build_report(data_dir, out_dir=None) -> Path`` reads ``data/<study>/`` (Parquet part files
and ``_manifest.json``; conventions in :mod:`workbench.report.load`) and writes
``reports/<study>/report.html`` (figures inlined as PNG, no external references),
``figures/*.png|svg`` and the metric tables as CSV.  Command line:
``python -m workbench.report data/<study> [--out DIR]`` (:func:`main`).  ``Study`` and
``load_study`` are the deprecated names of :class:`ResultSet` and :func:`load_results`.
"""

from .build import build_report, main
from .load import ResultSet, Study, load_results, load_study

__all__ = ["ResultSet", "Study", "build_report", "load_results", "load_study", "main"]
