"""Parameter-sweep studies: TOML spec + validation, expansion, executors, Parquet store, runner.

Typical use (the CLI ``workbench run`` does exactly this)::

    from workbench.study import load_study, run_study, DaskExecutor
    study = load_study("studies/example.toml")          # StudyError lists every problem
    summary = run_study(study, "data/example", DaskExecutor(n_workers=2), resume=True)

Nothing here imports Exudyn; workers import models lazily.
"""

from .evaluate import build_load, build_robot, evaluate_case, gravity_from_parameter
from .executors import DaskExecutor, IsolatedExecutor, SerialExecutor, WorkerCrash
from .expand import Case, case_id_for, count_cases, expand
from .runner import RunSummary, read_manifest, run_study, summarize
from .spec import Study, StudyError, load_study, parse_study
from .store import ResultStore, array_shapes, read_table

__all__ = [
    "Case", "DaskExecutor", "IsolatedExecutor", "ResultStore", "RunSummary", "SerialExecutor",
    "Study", "StudyError", "WorkerCrash", "array_shapes", "build_load", "build_robot",
    "case_id_for", "count_cases", "evaluate_case", "expand", "gravity_from_parameter",
    "load_study", "parse_study", "read_manifest", "read_table", "run_study", "summarize",
]
