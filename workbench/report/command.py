"""The report command line, shared by ``workbench report`` and ``python -m workbench.report``.

Light on purpose (argparse and pathlib only): the CLI builds its parser without importing
matplotlib; :func:`report_command` imports the report builder when it runs.  Checked by
``tests/study/test_cli.py`` and ``tests/report/``.
"""

from __future__ import annotations

import sys
from pathlib import Path

__all__ = ["add_report_arguments", "main", "report_command"]


def add_report_arguments(parser) -> None:
    """The arguments of the report command (``folder``, ``--out``, ``--formats``) on an argparse parser."""
    parser.add_argument("folder", help="e.g. data/quickstart")
    parser.add_argument("--out", help="output folder (default reports/<name of the data folder>)")
    parser.add_argument("--formats", default="png,svg", help="figure file formats, comma separated (png,svg,pdf)")


def report_command(args) -> int:
    """Run the report command for parsed :func:`add_report_arguments` arguments; return the exit code.

    Refuses a folder without ``_manifest.json`` (exit 2, the message on stderr); otherwise builds
    the report and prints the path of ``report.html`` (exit 0).
    """
    from ..study.store import MANIFEST

    folder = Path(args.folder)
    if not (folder / MANIFEST).exists():
        print(f"{folder}: not a study result folder (no {MANIFEST})", file=sys.stderr)
        return 2
    from .build import build_report

    formats = tuple(x for x in args.formats.split(",") if x)
    print(build_report(folder, args.out, formats=formats))
    return 0


def main(argv=None) -> int:
    """Command line: ``python -m workbench.report data/<study> [--out DIR] [--formats png,svg]``."""
    import argparse

    ap = argparse.ArgumentParser(prog="workbench report", description="Write the HTML comparison report of a study.")
    add_report_arguments(ap)
    return report_command(ap.parse_args(list(argv) if argv is not None else None))
