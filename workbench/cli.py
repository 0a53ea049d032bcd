"""The ``workbench`` command.

::

    workbench run STUDY.toml [--out DIR] [--workers N | --scheduler ADDR | --in-process | --cluster KIND]
                             [--resume] [--no-report] [--max-cases N] [--dry-run]
    workbench show DIR
    workbench validate STUDY.toml

Executors of ``run``: by default the cases run one after another in a child process that is
restarted if a case crashes it; ``--workers N`` starts a Dask ``LocalCluster`` with N worker
processes inside the command; ``--scheduler tcp://host:8786`` uses a running Dask cluster
(its workers must have the workbench installed); ``--in-process`` runs in this process (for
debugging: a crashing case takes the command down); ``--cluster slurm|pbs|sge|lsf`` submits the
workers as batch jobs through dask-jobqueue (job options: :mod:`workbench.study.cluster_command`).

Exit codes: 0 every case ok, 1 some cases failed, 2 bad input (invalid study file, folder
mismatch, bad cluster options or a job the batch system refuses), 3 the batch system failed the run (no worker job started, all
workers lost), 130 interrupted.

``run`` and ``validate`` choose the study kind once (:func:`workbench.study.kinds.kind_of` reads
``[study] kind``, :func:`~workbench.study.kinds.get_kind` finds it in ``workbench.registry.KINDS``)
and then use only that kind's ``load`` / ``expand`` / ``models`` and the one runner
:func:`workbench.study.run_cases`.  Checked by ``tests/study/test_cli.py``,
``tests/study/test_spec.py`` and ``tests/study/test_kinds.py``.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path
from typing import Sequence

from .report.command import add_report_arguments, report_command
from .study.cluster_command import add_cluster_arguments

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="workbench", description="Continuum-robot workbench: run and inspect studies.")
    sub = p.add_subparsers(dest="command", required=True)

    r = sub.add_parser("run", help="run a study file (TOML)")
    r.add_argument("study", help="study file, e.g. studies/example.toml")
    r.add_argument("--out", help="output folder (default data/<study.name>)")
    ex = r.add_mutually_exclusive_group()
    ex.add_argument("--workers", type=int, metavar="N", help="Dask LocalCluster with N worker processes")
    ex.add_argument("--scheduler", metavar="ADDR", help="address of a running Dask scheduler (tcp://host:8786)")
    ex.add_argument("--in-process", action="store_true", help="run cases in this process (debugging)")
    add_cluster_arguments(r, ex)
    r.add_argument("--resume", action="store_true", help="continue a run: only cases not yet stored")
    r.add_argument("--no-report", action="store_true", help="do not build the HTML report afterwards")
    r.add_argument("--max-cases", type=int, metavar="N", help="override study.max_cases")
    r.add_argument("--reports-dir", default="reports", help="where reports go (default reports/<name>)")
    r.add_argument("--progress", choices=("auto", "on", "off"), default="auto", help="progress bar (auto: on a TTY)")
    # advanced / tests: 'module:function' returning the model function for a name
    r.add_argument("--model-lookup", help=argparse.SUPPRESS)
    r.add_argument("--arc-actuation", help=argparse.SUPPRESS)
    r.add_argument("--flush-rows", type=int, default=256, help=argparse.SUPPRESS)

    s = sub.add_parser("show", help="summarise a study result folder")
    s.add_argument("folder", help="e.g. data/example")

    rp = sub.add_parser("report", help="write the HTML comparison report of a study result folder")
    add_report_arguments(rp)

    v = sub.add_parser("validate", help="check a study file without running it")
    v.add_argument("study")
    v.add_argument("--max-cases", type=int, metavar="N", help="override study.max_cases")
    return p


def _err(lines: Sequence[str]) -> None:
    for line in lines:
        print(line, file=sys.stderr)


def _resolve(dotted: str):
    mod, _, fn = dotted.partition(":")
    return getattr(importlib.import_module(mod), fn)


def _print_summary(summary, reports_dir: Path | None = None, report_note: str | None = None,
                   show_run: bool = True) -> None:
    from .study.runner import read_manifest, study_name

    man = read_manifest(summary.folder)
    name = study_name(man, "?")
    runs = man.get("runs", [])
    print(f"study {name!r}: {summary.folder}")
    this_run = f" (this run: {summary.n_run} run, {summary.n_skipped} already stored)" if show_run else ""
    print(f"  cases {summary.n_cases}: ok {summary.n_ok}, failed {summary.n_failed}{this_run}")
    missing = summary.n_cases - summary.n_ok - summary.n_failed
    if missing > 0:
        print(f"  not run yet: {missing} (continue with: workbench run STUDY --out {summary.folder} --resume)")
    if runs:
        print(f"  runs {len(runs)}: first start {runs[0].get('start')}, last end {runs[-1].get('end')}, "
              f"last executor {runs[-1].get('executor')}")
    if show_run:
        print(f"  wall time of this run: {summary.wall_time:.2f} s")
    elif runs and runs[-1].get("wall_time") is not None:
        print(f"  wall time of the last run: {runs[-1]['wall_time']:.2f} s")
    w = max([5] + [len(m) for m in summary.per_model])
    print(f"  {'model':<{w}}  {'ok':>6}  {'failed':>6}  {'model time [s]':>14}")
    for m, d in summary.per_model.items():
        print(f"  {m:<{w}}  {d['ok']:>6}  {d['failed']:>6}  {d['wall_time']:>14.3f}")
    if summary.failed_cases:
        import pandas as pd

        df = pd.read_parquet(summary.folder, columns=["case_id", "model", "status", "error"])
        bad = df[df["status"] != "ok"].sort_values(["case_id", "model"]).head(10)
        print(f"  failures ({len(df[df['status'] != 'ok'])} rows; first {len(bad)}):")
        for _, r in bad.iterrows():
            print(f"    {r['case_id']} {r['model']}: {str(r['error'])[:160]}")
    if report_note:
        print(f"  report: {report_note}")
    elif reports_dir is not None:
        found = [reports_dir / n for n in ("report.html", "index.html") if (reports_dir / n).exists()]
        print(f"  report: {found[0] if found else 'none found in ' + str(reports_dir)}")


def _build_report(data_dir: Path, out_dir: Path) -> str:
    """Build the HTML report of ``data_dir`` into ``out_dir``; what to print as its location."""
    from .report import build_report

    out = build_report(data_dir, out_dir)
    return str(out if out is not None else out_dir)


def _load(args):
    """``(kind, validated study)`` of ``args.study``: the one place the study kind is chosen."""
    from .study import get_kind, kind_of

    kind = get_kind(kind_of(args.study))
    return kind, kind.load(args.study, max_cases=args.max_cases)


def _cmd_validate(args) -> int:
    from .study import StudyError

    try:
        kind, study = _load(args)
    except StudyError as e:
        _err(e.problems)
        return 2
    n_cases, models = len(kind.expand(study)), kind.models(study)
    print(f"{args.study}: ok: study {study.name!r}, {n_cases} cases x {len(models)} models "
          f"({', '.join(models)}), config hash {study.config_hash}")
    return 0


def _cmd_run(args) -> int:
    from .study import DaskExecutor, IsolatedExecutor, SerialExecutor, StudyError, run_cases
    from .study.cluster import ClusterError

    try:
        kind, study = _load(args)
    except StudyError as e:
        _err(e.problems)
        return 2
    if args.workers is not None and args.workers < 1:
        _err([f"--workers: must be >= 1, got {args.workers}"])
        return 2
    folder = Path(args.out) if args.out else Path("data") / study.name
    from .study.cluster_command import cluster_from_args, dry_run_text

    try:
        cluster = cluster_from_args(args)
    except StudyError as e:
        _err(e.problems)
        return 2
    if cluster is not None:
        from .study.cluster import JobQueueExecutor

        executor = JobQueueExecutor(cluster)
    elif args.scheduler:
        executor = DaskExecutor(scheduler=args.scheduler)
    elif args.workers is not None:
        executor = DaskExecutor(n_workers=args.workers)
    elif args.in_process:
        executor = SerialExecutor()
    else:
        executor = IsolatedExecutor()
    if args.dry_run:
        print(dry_run_text(study.name, len(kind.expand(study)), kind.models(study), folder,
                           getattr(executor, "name", type(executor).__name__), cluster))
        return 0
    if cluster is not None:
        try:
            executor.preflight()  # a refused job fails here, before the result folder exists
        except ClusterError as e:
            _err([str(e)])
            return 2
    lookup = _resolve(args.model_lookup) if args.model_lookup else None
    arc = _resolve(args.arc_actuation) if args.arc_actuation else None
    progress = {"auto": None, "on": True, "off": False}[args.progress]
    try:
        summary = run_cases(kind, study, folder, executor, resume=args.resume, progress=progress,
                            flush_rows=args.flush_rows, model_lookup=lookup, arc_actuation=arc)
    except StudyError as e:
        _err(e.problems)
        return 2
    except KeyboardInterrupt:
        _err([f"interrupted; finished cases are stored in {folder}; continue with --resume"])
        return 130
    except ClusterError as e:
        _err([f"{e}; finished cases are stored in {folder}; continue with --resume"])
        return 3
    reports_dir = Path(args.reports_dir) / study.name
    note = "skipped (--no-report)" if args.no_report else None
    if not args.no_report:
        try:
            note = _build_report(folder, reports_dir)
        except Exception as e:  # noqa: BLE001 - the results are stored; report failure is not fatal
            note = f"FAILED: {type(e).__name__}: {e}"
    _print_summary(summary, report_note=note)
    return summary.exit_code


def _cmd_show(args) -> int:
    from .study.runner import summarize
    from .study.store import MANIFEST

    folder = Path(args.folder)
    if not (folder / MANIFEST).exists():
        _err([f"{folder}: not a study result folder (no {MANIFEST})"])
        return 2
    summary = summarize(folder)
    from .study.runner import read_manifest, study_name

    name = study_name(read_manifest(folder), folder.name)
    _print_summary(summary, reports_dir=Path("reports") / name, show_run=False)
    return summary.exit_code


def _cmd_report(args) -> int:
    return report_command(args)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit code."""
    args = _parser().parse_args(argv)
    commands = {"run": _cmd_run, "show": _cmd_show, "validate": _cmd_validate, "report": _cmd_report}
    return commands[args.command](args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
