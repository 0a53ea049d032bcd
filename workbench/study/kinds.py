"""Study kinds: how a kind of study file is loaded, expanded into cases and evaluated.

One pipeline runs every kind (:func:`workbench.study.runner.run_cases`); a kind only supplies
the parts that differ, as a subclass of :class:`StudyKind` (an abstract base class: a kind that
leaves out a method cannot be instantiated).  ``[study] kind`` in a file names its kind
(:func:`kind_of`; no key: ``"sweep"``), and :func:`get_kind` finds the object through
``workbench.registry.table("kinds")`` -- so this generic package never imports an experiment.  The kinds
today:

``"sweep"`` (:data:`SWEEP`)
    ``run(robot, load, options)`` models over a robot preset, swept (:mod:`workbench.study.spec`);
    each unit (a case, the models still to compute) yields its rows model by model
    (:func:`workbench.study.evaluate.evaluate_rows`), so a crash keeps the finished models.
``"series_parallel"``, ``"grasp"``, ``"closed_loop"``
    In their experiment folders (``workbench/experiments/*/kind.py``).
``"calibration"``
    Measured data as the reference (``workbench/measure/kind.py``, ``docs/measurements.md``): one case
    per fold, each model calibrated on its training rows and judged on the held-out ones.

A new kind is a :class:`StudyKind` subclass in its experiment folder plus one ``registry.KINDS`` row
(or, outside the workbench, a plug-in's ``trunk_workbench.kinds`` entry point, ``docs/plugins.md``);
the run session, manifest, store, executors, CLI and report come with the pipeline.

Checked by ``tests/study/test_kind_contract.py`` (every registered kind: load with and without
overrides, count, expand, one case at regression size, the rows' columns), ``tests/study/test_kinds.py``
and ``tests/study/test_cli.py``.
"""

from __future__ import annotations

import tomllib
from abc import ABC, abstractmethod
from pathlib import Path
from typing import Any, ClassVar, Iterable, Sequence

from .. import registry
from .build import parameters_as_run
from .evaluate import ROBOTS, evaluate_rows
from .expand import Case, count_cases, expand
from .outcomes import CaseLimits
from .spec import Study, load_study

__all__ = ["StudyKind", "SweepKind", "SWEEP", "get_kind", "kind_of"]


class StudyKind(ABC):
    """What the pipeline needs of a study kind: subclass it and implement every abstract method.

    The validated spec :meth:`load` returns must have ``path``, ``name``, ``config_hash`` and
    ``resolved()`` (recorded in the manifest), and ``overrides`` (the command-line
    ``key=value`` settings applied, recorded in the run record), ``notes`` and ``warnings``
    (tuples of one-line texts ``workbench validate`` / ``run`` print).

    Attributes
    ----------
    name : str
        The ``[study] kind`` value (a key of ``workbench.registry.table("kinds")``).
    flush_rows : int
        Default number of buffered rows per Parquet part.
    separable_models : bool
        The models of a case can be computed one at a time (a unit may name a subset of
        :meth:`models`); ``False``: a case is always computed whole.
    """

    name: ClassVar[str]
    flush_rows: ClassVar[int] = 64
    separable_models: ClassVar[bool] = True

    @staticmethod
    @abstractmethod
    def task(payload: Any) -> Iterable[dict[str, Any]]:
        """The executor's task function: returns or yields the rows of one unit (one case, the
        models of the payload), one per model.  A generator lets the executor keep the finished
        models' rows when a later model crashes the process.  Module-level and picklable (set it
        as ``task = staticmethod(module_function)``); never raises for a case."""

    @abstractmethod
    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Any:
        """Read and validate a study file with command-line ``key=value`` ``overrides`` applied
        (:mod:`workbench.study.overrides`; recorded in the spec's ``overrides``).

        Raises :class:`~workbench.study.messages.StudyError` listing every problem, one line each
        (a key the kind does not know is one of them)."""

    @abstractmethod
    def expand(self, spec: Any) -> list[Case]:
        """Every case of the study, in a deterministic order, with stable ``case_id``."""

    def count(self, spec: Any) -> int:
        """Number of cases (``len(expand(spec))``; a kind may count without expanding)."""
        return len(self.expand(spec))

    @abstractmethod
    def models(self, spec: Any) -> tuple[str, ...]:
        """The ``model`` values every case writes one row for."""

    @abstractmethod
    def recorded_params(self, spec: Any, case: Case) -> dict[str, Any]:
        """The parameters the rows of ``case`` record as ``p.*`` (those it runs with; they fix the column types)."""

    def batch_size(self, n_cases: int, slots: int) -> int:
        """Units per Dask task when the caller does not choose (``slots``: parallel workers); default 1."""
        return 1

    @abstractmethod
    def payload(self, spec: Any, case: Case, models: Sequence[str]) -> Any:
        """The argument of :attr:`task` for one unit: ``case`` and the ``models`` to compute (plain,
        picklable data: it goes to another process)."""

    @abstractmethod
    def limits(self, spec: Any) -> CaseLimits:
        """The per-case limits of the study (``[solver] max_case_seconds`` / ``max_case_memory``)."""


class SweepKind(StudyKind):
    """The sweep study kind: ``run(robot, load, options)`` models over a swept robot and load.

    Units are grouped into Dask tasks (about 8 tasks per worker slot, at most 32 units each):
    that amortises the per-task cost while keeping the load balanced; each unit still runs and
    is timed on its own in the worker's sandbox.
    """

    name = "sweep"
    flush_rows = 256
    separable_models = True
    task = staticmethod(evaluate_rows)

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Study:
        return load_study(path, max_cases=max_cases, overrides=overrides)

    def expand(self, spec: Study) -> list[Case]:
        return expand(spec)

    def count(self, spec: Study) -> int:
        """Number of cases, without expanding them."""
        return count_cases(spec)

    def models(self, spec: Study) -> tuple[str, ...]:
        return tuple(spec.models)

    def recorded_params(self, spec: Study, case: Case) -> dict[str, Any]:
        """:func:`~workbench.study.build.parameters_as_run` (derived gravity, scenario load fields).

        Robots come from this process's memo (:data:`~workbench.study.evaluate.ROBOTS`): a sweep
        over loads builds its robot once, not once per case.
        """
        return parameters_as_run(case.params, ROBOTS)

    def batch_size(self, n_cases: int, slots: int) -> int:
        return min(32, max(1, -(-n_cases // (8 * max(1, slots)))))

    def payload(self, spec: Study, case: Case, models: Sequence[str]) -> tuple:
        """``(case_id, params, models)``: :func:`~workbench.study.evaluate.evaluate_rows`'s argument."""
        return case.case_id, case.params, tuple(models)

    def limits(self, spec: Study) -> CaseLimits:
        return spec.limits


#: The sweep study kind (``registry.table("kinds")["sweep"]``).
SWEEP = SweepKind()


def get_kind(name: str) -> StudyKind:
    """The study kind registered as ``name`` in ``workbench.registry.table("kinds")`` (imported on first use).

    Raises
    ------
    KeyError
        Unknown kind (the message lists the known ones).
    TypeError
        The registered object is not a :class:`StudyKind`.
    """
    rows = registry.table("kinds")
    if name not in rows:
        raise KeyError(f"unknown study kind {name!r}; known kinds: {', '.join(rows)}")
    target = rows[name].target
    kind = registry.resolve(target)
    if not isinstance(kind, StudyKind):
        raise TypeError(f"study kind {name!r} ({registry.package('kinds', name)}): {target!r} is a "
                        f"{type(kind).__name__}, not a StudyKind")
    return kind


def kind_of(path: str | Path) -> str:
    """The study kind of the file ``path``: its ``[study] kind`` when that is a registered kind, else ``"sweep"``.

    Never raises: an unreadable or invalid file, or an unknown ``kind``, is left to the sweep
    loader, which reports the problem in its words (``study.kind: unknown key ...``).
    """
    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError):  # unreadable, not UTF-8, not TOML, nested too deeply
        return "sweep"
    st = data.get("study")
    kind = st.get("kind") if isinstance(st, dict) else None
    return kind if isinstance(kind, str) and kind in registry.table("kinds") else "sweep"
