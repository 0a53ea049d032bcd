"""Study kinds: how a kind of study file is loaded, expanded into cases and evaluated.

One pipeline runs every kind (:func:`workbench.study.runner.run_cases`); a kind only supplies
the parts that differ, as a :class:`StudyKind`.  ``[study] kind`` in a file names its kind
(:func:`kind_of`; no key: ``"sweep"``), and :func:`get_kind` finds the object through
``workbench.registry.KINDS`` -- so this generic package never imports an experiment.  The kinds
today:

``"sweep"`` (:data:`SWEEP`)
    ``run(robot, load, options)`` models over a robot preset, swept (:mod:`workbench.study.spec`);
    each unit (a case, the models still to compute) yields its rows model by model
    (:func:`workbench.study.evaluate.evaluate_rows`), so a crash keeps the finished models.
``"series_parallel"``
    Huang's series-parallel trunk driven by platform poses
    (``workbench/experiments/series_parallel/kind.py``); the three rows of a case are computed
    together (``separable_models = False``).

A new kind is a :class:`StudyKind` object in its experiment folder plus one ``registry.KINDS``
row; the run session, manifest, store, executors, CLI and report come with the pipeline.

Checked by ``tests/study/test_kinds.py``, ``tests/study/test_cli.py`` and ``tests/motion/``.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, Callable, Iterable, Protocol, Sequence

from .. import registry
from .build import parameters_as_run
from .evaluate import _robot_memo, evaluate_rows
from .expand import Case, count_cases, expand
from .outcomes import CaseLimits
from .spec import Study, load_study

__all__ = ["StudyKind", "SweepKind", "SWEEP", "get_kind", "kind_of"]


class StudyKind(Protocol):
    """What the pipeline needs of a study kind.

    The validated spec a kind loads must have ``path``, ``name``, ``config_hash`` and
    ``resolved()`` (recorded in the manifest).

    Attributes
    ----------
    name : str
        The ``[study] kind`` value (a key of ``workbench.registry.KINDS``).
    flush_rows : int
        Default number of buffered rows per Parquet part.
    task : callable
        The executor's task function: ``task(payload)`` returns or yields the rows of one unit
        (one case, the models of the payload), one per model; a generator lets the executor
        keep the finished models' rows when a later model crashes the process (module-level,
        picklable; never raises for a case).
    separable_models : bool
        The models of a case can be computed one at a time (a unit may name a subset of
        :meth:`models`); ``False``: a case is always computed whole.
    """

    name: str
    flush_rows: int
    task: Callable[[Any], Iterable[dict[str, Any]]]
    separable_models: bool

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Any:
        """Read and validate a study file with command-line ``key=value`` ``overrides`` applied
        (:class:`~workbench.study.messages.StudyError` listing every problem)."""

    def expand(self, spec: Any) -> list[Case]:
        """Every case of the study, in a deterministic order, with stable ``case_id``."""

    def models(self, spec: Any) -> tuple[str, ...]:
        """The ``model`` values every case writes one row for."""

    def recorded_params(self, spec: Any, case: Case) -> dict[str, Any]:
        """The parameters the rows of ``case`` record as ``p.*`` (those it runs with; they fix the column types)."""

    def run_options(self, spec: Any, **options: Any) -> Any:
        """Check the run's extra options (``model_lookup``, ``arc_actuation``); what :meth:`payload` gets."""

    def batch_size(self, n_cases: int, slots: int) -> int:
        """Units per Dask task when the caller does not choose (``slots``: parallel workers)."""

    def payload(self, spec: Any, case: Case, models: Sequence[str], options: Any) -> Any:
        """The argument of :attr:`task` for one unit: ``case`` and the ``models`` to compute."""

    def limits(self, spec: Any) -> CaseLimits:
        """The per-case limits of the study (``[solver] max_case_seconds`` / ``max_case_memory``)."""


class SweepKind:
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

        Robots come from this process's memo (:func:`~workbench.study.evaluate._robot_memo`): a sweep
        over loads builds its robot once, not once per case.
        """
        return parameters_as_run(case.params, _robot_memo())

    def run_options(self, spec: Study, *, model_lookup: Callable | None = None,
                    arc_actuation: Callable | None = None) -> tuple[Callable | None, Callable | None]:
        """``(model_lookup, arc_actuation)``: passed to :func:`~workbench.study.evaluate.evaluate_case`."""
        return model_lookup, arc_actuation

    def batch_size(self, n_cases: int, slots: int) -> int:
        return min(32, max(1, -(-n_cases // (8 * max(1, slots)))))

    def payload(self, spec: Study, case: Case, models: Sequence[str], options: tuple) -> tuple:
        model_lookup, arc_actuation = options
        return case.case_id, case.params, tuple(models), model_lookup, arc_actuation

    def limits(self, spec: Study) -> CaseLimits:
        return spec.limits


#: The sweep study kind (``registry.KINDS["sweep"]``).
SWEEP = SweepKind()


def get_kind(name: str) -> StudyKind:
    """The study kind registered as ``name`` in ``workbench.registry.KINDS`` (imported on first use).

    Raises
    ------
    KeyError
        Unknown kind (the message lists the known ones).
    """
    try:
        target = registry.KINDS[name].target
    except KeyError:
        raise KeyError(f"unknown study kind {name!r}; known kinds: {', '.join(registry.KINDS)}") from None
    return registry.resolve(target)


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
    return kind if isinstance(kind, str) and kind in registry.KINDS else "sweep"
