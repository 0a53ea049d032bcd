"""The ``workbench`` command.

::

    workbench run STUDY.toml [--out DIR] [--workers N | --scheduler ADDR | --in-process | --cluster KIND]
                             [--resume [--retry-failed]] [--no-report] [--max-cases N] [--dry-run]
    workbench show DIR
    workbench validate STUDY.toml
    workbench report DIR [--out DIR] [--formats png,svg]
    workbench list models|presets|scenarios|kinds
    workbench robot show STUDY.toml|PRESET [KEY=VALUE ...] [--out robot.png] [--tension T]
    workbench --version

Executors of ``run``: by default the cases run one after another in a child process that is
restarted if a case crashes it or runs past ``[solver] max_case_seconds``; ``--workers N``
starts a Dask ``LocalCluster`` with N worker processes inside the command; ``--scheduler
tcp://host:8786`` uses a running Dask cluster (its workers must have the same workbench
installed; the address is checked before anything is written); ``--in-process`` runs in this
process: the debugging executor, without isolation; ``--cluster slurm|pbs|sge|lsf`` submits the
workers as batch jobs through dask-jobqueue (job options: :mod:`workbench.study.cluster_command`;
a job the batch system refuses is bad input, exit 2; a queue that starts no job, exit 3).

The report of a run goes to ``reports/<name of the data folder>/`` (``--out data/x2`` ->
``reports/x2/``), so two runs never overwrite each other's report.

Exit codes (:data:`EXIT_CODES`, also in ``--help``): 0 every case ok, 1 some cases failed,
2 bad input (nothing was run), 3 infrastructure failed (cluster lost, workers killed: finished
cases are stored and ``--resume`` retries the rest), 130 interrupted (Ctrl-C), 143 terminated
(SIGTERM); after 130/143 finished cases are stored and ``--resume`` continues.

``run`` and ``validate`` choose the study kind once (:func:`workbench.study.kinds.kind_of` reads
``[study] kind``, :func:`~workbench.study.kinds.get_kind` finds it in ``workbench.registry.table("kinds")``)
and then use only that kind's ``load`` / ``expand`` / ``models`` and the one runner
:func:`workbench.study.run_cases`.  Checked by ``tests/study/test_cli.py``,
``tests/study/test_cli_errors.py``, ``tests/study/test_spec.py`` and ``tests/study/test_kinds.py``.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from pathlib import Path
from typing import Sequence

from . import registry
from .cli_list import TOPICS, list_command
from .cli_robot import add_robot_arguments, robot_command
from .report.command import add_report_arguments, report_command
from .study.cluster_command import add_cluster_arguments

__all__ = ["EXIT_CODES", "main"]

EXIT_CODES = {
    0: "every case ok",
    1: "some cases failed (model failures, crashes, timeouts: see `workbench show`)",
    2: "bad input: study file, options, or a result folder in use / of another study (nothing was run)",
    3: "infrastructure failed: the cluster was lost or workers were killed; finished cases are stored, "
       "--resume retries the rest",
    130: "interrupted (Ctrl-C): finished cases are stored; continue with --resume",
    143: "terminated (SIGTERM, e.g. a batch scheduler): finished cases are stored; continue with --resume",
}


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so the run stores what finished (exit 143)."""


def _epilog() -> str:
    return "exit codes:\n" + "\n".join(f"  {k:>3}  {v}" for k, v in EXIT_CODES.items())


class _Parser(argparse.ArgumentParser):
    """argparse without prefix matching (``--worker 2`` is an error) and with one-line errors."""

    def __init__(self, *a, **kw) -> None:
        kw.setdefault("allow_abbrev", False)
        super().__init__(*a, **kw)

    def error(self, message: str):  # noqa: D401 - argparse's hook
        self.exit(2, f"{self.prog}: {message}{self._hint(message)} (see {self.prog} --help)\n")

    def parse_args(self, args=None, namespace=None):  # noqa: D102 - remembers the words for the hint
        self._words = list(sys.argv[1:] if args is None else args)
        return super().parse_args(args, namespace)

    def _options(self, words: list[str]) -> list[str]:
        """The option strings of this parser and of the subcommand named in ``words``."""
        out = []
        for a in self._actions:
            out += [o for o in a.option_strings if o.startswith("--")]
            if isinstance(a, argparse._SubParsersAction):
                sub = next((a.choices[w] for w in words if w in a.choices), None)
                out += sub._options(words) if isinstance(sub, _Parser) else []
        return sorted(set(out))

    def _hint(self, message: str) -> str:
        """``; did you mean --workers?`` for an unrecognized option close to a known one."""
        import difflib

        if "unrecognized arguments:" not in message:
            return ""
        words = [w for w in message.partition("unrecognized arguments:")[2].split() if w.startswith("--")]
        for w in words:
            close = difflib.get_close_matches(w.partition("=")[0], self._options(getattr(self, "_words", [])), n=1,
                                              cutoff=0.75)
            if close:
                return f"; did you mean {close[0]}?"
        return ""


def _version() -> str:
    from . import __version__

    return f"workbench {__version__} (trunk-workbench, Python {sys.version.split()[0]})"


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="workbench", description="Continuum-robot workbench: run and inspect studies.")
    p.add_argument("--version", action="version", version=_version())
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    r = sub.add_parser("run", help="run a study file (TOML)", epilog=_epilog(),
                       formatter_class=argparse.RawDescriptionHelpFormatter,
                       description="Run a study.  Default executor: one case after another in an isolated child "
                                   "process (a crash or a timeout fails only that case).")
    r.add_argument("study", help="study file, e.g. studies/example.toml (a bare name finds studies/<name>.toml)")
    r.add_argument("overrides", nargs="*", metavar="KEY=VALUE",
                   help="settings that override the file, validated like it (solver.n_elements=32, "
                        "study.models='[\"cc\"]'); recorded in the manifest")
    r.add_argument("--out", help="output folder (default data/<study.name>); its report goes to reports/<folder name>")
    ex = r.add_mutually_exclusive_group()
    ex.add_argument("--workers", type=int, metavar="N", help="Dask LocalCluster with N worker processes")
    ex.add_argument("--scheduler", metavar="ADDR", help="address of a running Dask scheduler (tcp://host:8786)")
    ex.add_argument("--in-process", action="store_true",
                    help="run cases in this process: the debugging executor, without isolation (a crashing "
                         "case ends the command)")
    add_cluster_arguments(r, ex)
    r.add_argument("--resume", action="store_true",
                   help="continue a run: compute what is not stored; retries cases that failed for "
                        "infrastructure reasons (timeout, memory, killed, lost)")
    r.add_argument("--retry-failed", action="store_true", help="with --resume: also retry model failures and crashes")
    r.add_argument("--force", action="store_true",
                   help="discard the results stored in --out and run again (not with --resume)")
    r.add_argument("--no-report", action="store_true", help="do not build the HTML report afterwards")
    r.add_argument("--no-cache", action="store_true",
                   help="compute every case (default: reuse rows of the same case, model and model code version "
                        "from <parent of --out>/_cache, and store new ones there)")
    r.add_argument("--max-cases", type=int, metavar="N", help="override study.max_cases")
    r.add_argument("--reports-dir", default="reports", help="where reports go (default reports/<data folder name>)")
    r.add_argument("--progress", choices=("auto", "on", "off"), default="auto",
                   help="progress bar (auto: a bar on a terminal, a log line every 10%% or 30 s otherwise)")
    r.add_argument("--flush-rows", type=int, default=None, help=argparse.SUPPRESS)

    s = sub.add_parser("show", help="summarise a study result folder")
    s.add_argument("folder", help="e.g. data/example")
    s.add_argument("--reports-dir", default="reports",
                   help="where to look for its report (default reports/<data folder name>, as for run)")

    rp = sub.add_parser("report", help="write the HTML comparison report of a study result folder")
    add_report_arguments(rp)

    ls = sub.add_parser("list", help="what the registry offers, built-in and plug-ins (with each row's package): "
                                     "models (with capabilities), presets, scenarios, kinds, figures")
    ls.add_argument("topic", choices=TOPICS)

    add_robot_arguments(sub)

    v = sub.add_parser("validate", help="check a study file without running it")
    v.add_argument("study", help="study file or bare name (studies/<name>.toml)")
    v.add_argument("overrides", nargs="*", metavar="KEY=VALUE | STUDY",
                   help="settings that override the file(s); further study files (validate studies/*.toml)")
    v.add_argument("--max-cases", type=int, metavar="N", help="override study.max_cases")
    return p


def _err(lines: Sequence[str]) -> None:
    for line in lines:
        print(line, file=sys.stderr)


def _clip(text: str, n: int = 200) -> str:
    """``text`` cut at a word boundary near ``n`` characters (with an ellipsis)."""
    text = " ".join(str(text).split())
    if len(text) <= n:
        return text
    cut = text.rfind(" ", 0, n)
    return text[:cut if cut > n // 2 else n] + " ..."


def _print_summary(summary, report_note: str | None = None, show_run: bool = True) -> None:
    from .study.lock import describe_holder, lock_holder
    from .study.session import read_manifest, study_name

    man = read_manifest(summary.folder)
    name = study_name(man, "?")
    runs = man.get("runs", [])
    study_file = (runs[-1].get("study_file") if runs else None) or man.get("study_file") or "STUDY.toml"
    source = (runs[-1].get("study_file") if runs else None) or man.get("study_file")
    print(f"study {name!r}" + (f" ({source})" if source else "") + f": {summary.folder}")
    n_cached, n_computed = summary.n_cached, summary.n_computed
    if n_cached and n_computed is not None:
        done = f"{n_computed} computed, {summary.n_run - n_computed} from the cache ({n_cached} model rows)"
    else:
        done = f"{summary.n_run} run" + (f", {n_cached} model rows from the cache" if n_cached else "")
    this_run = f" (this run: {done}, {summary.n_skipped} already stored)" if show_run else ""
    print(f"  cases {summary.n_cases}: ok {summary.n_ok}, failed {summary.n_failed}{this_run}")
    missing = summary.n_cases - summary.n_ok - summary.n_failed
    if missing > 0:
        print(f"  not run yet: {missing} (continue with: workbench run {study_file} --out {summary.folder} --resume)")
    if summary.failures:
        kinds = ", ".join(f"{k} {v}" for k, v in summary.failures.items())
        retried = sum(v for k, v in summary.failures.items() if k in ("timeout", "memory", "killed", "lost"))
        hint = f"; --resume retries {retried} of them" if retried else ""
        print(f"  failed rows by reason: {kinds}{hint}")
    if summary.n_duplicates:
        print(f"  WARNING: {summary.n_duplicates} duplicate (case_id, model) rows (two runs wrote into this folder); "
              f"--resume recomputes them")
    if runs:
        last = runs[-1]
        state, holder = lock_holder(summary.folder)
        if last.get("end"):
            end = f"last end {last['end']} ({last.get('outcome') or 'completed'})"
        elif state == "running":
            end = f"running now ({describe_holder(holder)})"
        else:
            end = "the last run did not record its end (killed?)"
        print(f"  runs {len(runs)}: first start {runs[0].get('start')}, {end}, last executor {last.get('executor')}")
    if show_run:
        print(f"  wall time of this run: {summary.wall_time:.2f} s")
    elif runs and runs[-1].get("wall_time") is not None:
        print(f"  wall time of the last run: {runs[-1]['wall_time']:.2f} s")
    w = max([5] + [len(m) for m in summary.per_model])
    print(f"  {'model':<{w}}  {'ok':>6}  {'failed':>6}  {'model time [s]':>14}")
    for m, d in summary.per_model.items():
        print(f"  {m:<{w}}  {d['ok']:>6}  {d['failed']:>6}  {d['wall_time']:>14.3f}")
    if summary.failed_cases:
        from .study.store import read_columns

        df = read_columns(summary.folder, ["case_id", "model", "status", "error", "failure"])
        bad = df[df["status"] != "ok"].sort_values(["case_id", "model"]).head(10)
        print(f"  failures ({len(df[df['status'] != 'ok'])} rows; first {len(bad)}):")
        for _, r in bad.iterrows():
            print(f"    {r['case_id']} {r['model']} [{r['failure'] or '?'}]: {_clip(r['error'])}")
    if report_note:
        print(f"  report: {report_note}")


def _report_dir(folder: Path, reports_dir: str | Path = "reports") -> Path:
    """Where the report of the data folder ``folder`` goes: ``<reports_dir>/<folder name>``."""
    return Path(reports_dir) / folder.resolve().name


def _build_report(data_dir: Path, out_dir: Path) -> str:
    """Build the HTML report of ``data_dir`` into ``out_dir``; what to print as its location."""
    from .report.build import build_report

    print(f"building report {out_dir} ...", file=sys.stderr, flush=True)
    out = build_report(data_dir, out_dir)
    return str(out if out is not None else out_dir)


def find_study(text: str) -> Path:
    """The study file ``text`` names: the path itself, else ``studies/<text>`` or ``studies/<text>.toml``.

    Raises
    ------
    StudyError
        Nothing of that name exists (one line listing the studies of ``studies/``).
    """
    from .study import StudyError

    if not str(text).strip():
        raise StudyError(["study: empty path (give a study file, e.g. studies/example.toml, or a bare name)"])
    p = Path(text)
    if p.exists() or p.name != text:  # a path with a folder: the loader says what is wrong with it
        return p
    here = Path("studies")
    for cand in (here / text, here / f"{text}.toml"):
        if cand.is_file():
            return cand
    known = sorted(q.stem for q in here.glob("*.toml")) if here.is_dir() else []
    tail = f"; studies in {here}/: {', '.join(known)}" if known else ""
    raise StudyError([f"{text}: no such study file (nor {here / p.stem}.toml){tail}"])


def _load(args):
    """``(kind, validated study)`` of ``args.study``: the one place the study kind is chosen."""
    from .study import get_kind, kind_of

    from .study import StudyError

    if getattr(args, "max_cases", None) is not None and args.max_cases < 1:
        raise StudyError([f"--max-cases: must be >= 1, got {args.max_cases}"])
    path = find_study(args.study)
    args.study = str(path)
    kind = get_kind(kind_of(path))
    return kind, kind.load(path, max_cases=args.max_cases, overrides=tuple(getattr(args, "overrides", None) or ()))


def _cmd_validate(args) -> int:
    """``validate STUDY [STUDY ...] [KEY=VALUE ...]``: each study checked with the overrides; rc 2 if any fails."""
    more = [a for a in args.overrides if "=" not in a and (a.endswith(".toml") or Path(a).is_file())]
    if not more:
        return _validate_one(args)
    overrides = [a for a in args.overrides if a not in more]
    codes = [_validate_one(argparse.Namespace(**{**vars(args), "study": s, "overrides": overrides}))
             for s in [args.study, *more]]
    return max(codes)


def _validate_one(args) -> int:
    from .study import StudyError

    try:
        kind, study = _load(args)
    except StudyError as e:
        _err(e.problems)
        return 2
    n_cases = kind.count(study)
    models = kind.models(study)
    given = study.overrides
    print(f"{args.study}: ok: study {study.name!r}, {n_cases} cases x {len(models)} models "
          f"({', '.join(models)}), config hash {study.config_hash}"
          + (f" (with {len(given)} override(s): {' '.join(given)})" if given else ""))
    for note in study.notes:
        print(f"  note: {note}")
    for w in study.warnings:
        print(f"  warning: {w}")
    return 0


def _check_out(folder: Path) -> str | None:
    """Why ``folder`` cannot be a result folder (``None``: it can), checked before anything runs."""
    text = str(folder)
    if not text.strip():
        return "--out: empty path"
    try:
        if folder.exists() and not folder.is_dir():
            return f"--out {folder}: exists and is not a folder"
        p = folder
        while not p.exists() and p != p.parent:
            p = p.parent
    except (ValueError, OSError) as e:
        return f"--out {text!r}: invalid path ({e})"
    if not p.is_dir():
        return f"--out {folder}: {p} is a file, not a folder"
    if not os.access(p, os.W_OK | os.X_OK):
        return f"--out {folder}: no permission to write in {p}"
    from .study.store import MANIFEST

    if p == folder and not (folder / MANIFEST).exists():
        # the table is every file of the folder (pandas.read_parquet): other files would make it unreadable
        others = sorted(q.name for q in folder.iterdir() if not q.name.startswith((".", "_")))
        if others:
            return (f"--out {folder}: not empty and not a study result folder (holds {others[0]}"
                    f"{f' and {len(others) - 1} more' if len(others) > 1 else ''}); choose a new or empty folder")
    return None


def _executor(args, cluster=None):
    """The executor the options ask for, or the one-line problem with them."""
    from .study import DaskExecutor, IsolatedExecutor, SerialExecutor
    from .study.executors import check_scheduler_address

    if cluster is not None:
        from .study.cluster import JobQueueExecutor

        return JobQueueExecutor(cluster), None
    if args.workers is not None and args.workers < 1:
        return None, f"--workers: must be >= 1, got {args.workers}"
    if args.scheduler:
        problem = check_scheduler_address(args.scheduler)
        if problem:
            return None, f"--scheduler {args.scheduler}: {problem}"
        return DaskExecutor(scheduler=args.scheduler), None
    if args.workers is not None:
        return DaskExecutor(n_workers=args.workers), None
    if args.in_process:
        return SerialExecutor(), None
    return IsolatedExecutor(), None


def _on_sigterm(signum, frame):
    raise Terminated()


def _cmd_run(args) -> int:
    old = signal.signal(signal.SIGTERM, _on_sigterm)
    folder = None
    try:
        rc, folder = _run(args)
        return rc
    except Terminated:
        _err([f"terminated (SIGTERM); finished cases are stored in {folder or 'the output folder'}; "
              f"continue with --resume"])
        return 143
    except KeyboardInterrupt:
        _err([f"interrupted; finished cases are stored in {folder or 'the output folder'}; continue with --resume"])
        return 130
    finally:
        signal.signal(signal.SIGTERM, old)


def _run(args) -> tuple[int, Path | None]:
    from .study import RunConfig, StudyError, run_cases
    from .study.outcomes import ExecutorStartError, InfrastructureError
    from .study.store import CorruptPart

    if args.retry_failed and not args.resume:
        _err(["--retry-failed: needs --resume (it retries the failed cases of a stored run)"])
        return 2, None
    if args.force and args.resume:
        _err(["--force: not with --resume (--force discards the stored results, --resume continues them)"])
        return 2, None
    try:
        kind, study = _load(args)
    except StudyError as e:
        _err(e.problems)
        return 2, None
    for w in study.warnings:
        _err([f"warning: {w}"])
    if args.out is not None and not args.out.strip():
        _err(["--out: empty path (give a folder, e.g. --out data/my_run)"])
        return 2, None
    folder = Path(args.out) if args.out is not None else Path("data") / study.name
    problem = _check_out(folder)
    from .study.cluster_command import cluster_from_args, dry_run_text

    try:
        cluster = cluster_from_args(args)
    except StudyError as e:
        _err(e.problems)
        return 2, None
    executor, exec_problem = _executor(args, cluster)
    if problem or exec_problem:
        _err([problem or exec_problem])
        return 2, None
    if args.dry_run:
        n = len(kind.expand(study))
        name = executor.name
        print(dry_run_text(study.name, n, kind.models(study), folder, name, cluster,
                           kind.limits(study),
                           kind.batch_size(n, executor.slots)))
        return 0, None
    if cluster is not None:
        try:
            executor.preflight()  # a refused job fails here, before the result folder exists
        except ExecutorStartError as e:
            _err([str(e)])
            return 2, None
    if args.in_process and sys.stderr.isatty():  # (the manifest and `show` name the executor too)
        _err(["--in-process: cases run in this process without isolation (the debugging executor): a case that "
              "crashes ends the command (the cases before it are stored), the time limit interrupts Python code only"])
    config = RunConfig(resume=args.resume, retry_failed=args.retry_failed, force=args.force,
                       progress={"auto": None, "on": True, "off": False}[args.progress], flush_rows=args.flush_rows,
                       cache=None if args.no_cache else folder.resolve().parent / "_cache")
    try:
        summary = run_cases(kind, study, folder, executor, config)
    except StudyError as e:
        _err(e.problems)
        return 2, folder
    except CorruptPart as e:
        _err([f"{e.path}: unreadable Parquet part ({e.reason})"])
        return 2, folder
    except ExecutorStartError as e:
        _err([f"{e}; nothing was run"])
        return 2, folder
    except InfrastructureError as e:
        stored = "finished cases are stored; continue with --resume" if folder.exists() else "nothing was stored"
        _err([f"{folder}: infrastructure failed: {e}; {stored}"])
        return 3, folder
    note = "skipped (--no-report)" if args.no_report else None
    if not args.no_report:
        try:
            note = _build_report(folder, _report_dir(folder, args.reports_dir))
        except Exception as e:  # noqa: BLE001 - the results are stored; report failure is not fatal
            note = f"FAILED: {type(e).__name__}: {_clip(e)} (retry with: workbench report {folder})"
    _print_summary(summary, report_note=note)
    return summary.exit_code, folder


def _not_a_result_folder(folder: Path) -> str:
    """The one-line refusal of a folder without a manifest, with a hint where the results are."""
    from .study.store import MANIFEST

    line = f"{folder}: not a study result folder (no {MANIFEST})"
    data = Path("data") / folder.name
    if (data / MANIFEST).exists() and data.resolve() != folder.resolve():
        return f"{line}; the results of {folder.name!r} are in {data}"
    if (folder / "report.html").exists() or "reports" in folder.parts:
        return f"{line}; this looks like a report folder: results are in data/<name>"
    if not folder.exists():
        return f"{line}: {folder} does not exist"
    return line


def _cmd_show(args) -> int:
    from .study import StudyError
    from .study.runner import summarize
    from .study.session import read_manifest
    from .study.store import MANIFEST, CorruptPart

    folder = Path(args.folder)
    if not (folder / MANIFEST).exists():
        _err([_not_a_result_folder(folder)])
        return 2
    try:
        read_manifest(folder)
        summary = summarize(folder)
        rdir = _report_dir(folder, args.reports_dir)
        found = [rdir / n for n in ("report.html", "index.html") if (rdir / n).exists()]
        _print_summary(summary, report_note=str(found[0]) if found else f"none yet in {rdir}",
                       show_run=False)
    except StudyError as e:
        _err(e.problems)
        return 2
    except CorruptPart as e:
        _err([f"{e.path}: unreadable Parquet part ({e.reason})"])
        return 2
    except FileNotFoundError:
        _err([f"{folder}: holds a manifest but no stored rows yet (the run stored nothing, or is starting)"])
        return 2
    return summary.exit_code


_FORMATS = ("png", "svg", "pdf")


def _cmd_report(args) -> int:
    from .study import StudyError
    from .study.store import CorruptPart

    from .study.session import read_manifest
    from .study.store import MANIFEST, check_parts

    folder = Path(args.folder)
    if args.out is None:
        args.out = str(_report_dir(folder))
    bad = [f for f in args.formats.split(",") if f and f not in _FORMATS]
    if bad or not [f for f in args.formats.split(",") if f]:
        _err([f"--formats: unknown figure format {bad[0]!r}; choose from {', '.join(_FORMATS)} (comma separated)"
              if bad else f"--formats: empty; choose from {', '.join(_FORMATS)}"])
        return 2
    if not (folder / MANIFEST).exists():
        _err([_not_a_result_folder(folder)])
        return 2
    try:
        if (folder / MANIFEST).exists():
            read_manifest(folder)
            if not any(folder.glob("part-*.parquet")):
                _err([f"{folder}: holds a manifest but no stored rows yet (the run stored nothing, or is starting)"])
                return 2
            check_parts(folder)
        return report_command(args)
    except StudyError as e:
        _err(e.problems)
    except CorruptPart as e:
        _err([f"{e.path}: unreadable Parquet part ({e.reason})"])
    except (ValueError, OSError) as e:
        _err([f"{folder}: cannot build the report: {_clip(e)}"])
    return 2


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit code."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as e:  # --help, --version (0) or a usage error (2, one line on stderr)
        return e.code if isinstance(e.code, int) else 2
    commands = {"run": _cmd_run, "show": _cmd_show, "validate": _cmd_validate, "report": _cmd_report,
                "list": list_command, "robot": lambda a: robot_command(a, find_study)}
    _err([f"warning: {line}" for line in registry.discover().problems])  # broken plug-ins, one line each
    try:
        code = commands[args.command](args)
        sys.stdout.flush()
    except registry.PluginError as e:  # two packages register one name: nothing can be trusted to run
        _err([str(e)])
        code = 2
    except BrokenPipeError:  # `workbench show data/x | head`: the reader left; no traceback
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        code = 0
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
