"""Studies: TOML spec + validation, expansion, executors, Parquet store, one runner for every kind.

Typical use (the CLI ``workbench run`` does exactly this)::

    from workbench.study import DaskExecutor, RunConfig, get_kind, kind_of, run_cases
    kind = get_kind(kind_of("studies/example.toml"))     # "sweep" unless [study] kind says otherwise
    study = kind.load("studies/example.toml")            # StudyError lists every problem
    summary = run_cases(kind, study, "data/example", DaskExecutor(n_workers=2), RunConfig(resume=True))

For sweep studies ``load_study`` and ``run_study`` are the same two steps.  Nothing here imports
Exudyn; workers import models lazily.
"""

from .build import build_load, build_options, build_robot, gravity_from_parameter
from .evaluate import evaluate_case
from .executors import DaskExecutor, IsolatedExecutor, SerialExecutor
from .expand import Case, case_id_for, count_cases, expand
from .kinds import SWEEP, StudyKind, get_kind, kind_of
from .run_config import RunConfig
from .runner import RunSummary, run_cases, run_study, summarize
from .session import RunSession, read_manifest, study_name
from .spec import Study, StudyError, load_study, parse_study
from .store import ResultStore, array_shapes, read_table

__all__ = [
    "Case", "DaskExecutor", "IsolatedExecutor", "ResultStore", "RunConfig", "RunSession", "RunSummary", "SWEEP",
    "SerialExecutor", "Study", "StudyError", "StudyKind", "array_shapes", "build_load",
    "build_options", "build_robot", "case_id_for", "count_cases", "evaluate_case", "expand", "get_kind",
    "gravity_from_parameter", "kind_of", "load_study", "parse_study", "read_manifest", "read_table",
    "run_cases", "run_study", "study_name", "summarize",
]
