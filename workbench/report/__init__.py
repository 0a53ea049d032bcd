"""Self-contained HTML comparison reports (matplotlib ``Figure`` objects, Agg; no pyplot).

:func:`workbench.report.build.build_report` ``(data_dir, out_dir=None) -> Path`` reads
``data/<study>/`` (Parquet part files and ``_manifest.json``, read by
:func:`workbench.report.load.load_results`) and writes ``reports/<study>/report.html`` (figures
inlined as PNG, no external references), ``figures/*.png|svg`` and the metric tables as CSV.
Command line: ``python -m workbench.report data/<study> [--out DIR]``
(:func:`workbench.report.command.main`).  The package itself imports nothing, so the command
line imports matplotlib and pandas only when a report is built.
"""
