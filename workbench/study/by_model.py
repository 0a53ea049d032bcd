"""Per-model solver settings: ``[solver.by_model.<model>]`` tables.

A study compares several models on the same cases, but a model may need its own settings: the
Cosserat rod carries continuum tendons only, the 3-D beam eyelets only, the spring-link chain
converges at order 2 and needs more links than the ANCF beam needs elements.  A table
``[solver.by_model.<model>]`` sets any ``[solver]`` option (:func:`per_model_options`) for that one
model; every other model runs with the ``[solver]`` values::

    [solver]
    tendon_model = "continuum"
    n_elements = 32

    [solver.by_model.beam3d]
    tendon_model = "eyelets"

    [solver.by_model.spring_link]
    n_elements = 128

:func:`solver_for_model` is the one rule for the ``[solver]`` parameters a model runs with (its
table over ``[solver]``): the workers run each model with it and record it in that model's rows
(``p.solver.*``), validation checks each model's capabilities against it.
:func:`by_model_problems` checks the tables (one line per problem, naming the key path).  The
pipeline's own keys (the limits, the error estimate) are not per-model options.

Checked by ``tests/study/test_by_model.py``.
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from pydantic import ValidationError

from .messages import pydantic_problems, suggest
from .schema import LIMIT_KEYS, SolverSection

__all__ = ["BY_MODEL", "NOT_PER_MODEL", "by_model_problems", "per_model_options", "setters", "solver_for_model"]

#: The ``[solver]`` key of the per-model tables.
BY_MODEL = "by_model"
#: ``[solver]`` keys that are not per-model options: the per-case limits, the pipeline's error estimate and warm starts.
NOT_PER_MODEL = (*LIMIT_KEYS, BY_MODEL, "error_estimate", "error_estimate_exempt", "warm_start")


def per_model_options() -> list[str]:
    """The ``[solver]`` options a ``[solver.by_model.<model>]`` table may set."""
    return [k for k in SolverSection.model_fields if k not in NOT_PER_MODEL]


def solver_for_model(solver: Mapping[str, Any], model: str) -> dict[str, Any]:
    """The ``[solver]`` parameters model ``model`` runs with: its ``by_model`` table over ``solver``.

    ``solver`` is a case's ``[solver]`` parameters (plain data); the ``by_model`` key stays (it is
    what the case configured).  Models without a table get ``solver`` unchanged (a copy).
    """
    own = (solver.get(BY_MODEL) or {}).get(model) or {}
    return {**solver, **own}


def setters(solver: Mapping[str, Any], key: str, models: Sequence[str]) -> list[str]:
    """The models of ``models`` whose ``by_model`` table sets ``key`` (for them ``[solver] key`` does not apply)."""
    tables = solver.get(BY_MODEL) or {}
    return [m for m in models if key in (tables.get(m) or {})]


def by_model_problems(by_model: Any, models: Sequence[str], where: str = "solver.by_model") -> list[str]:
    """Problems of a ``by_model`` value, one line each naming the key path.

    Each key must be one of ``models`` (the study's), each value a table of per-model options
    (:func:`per_model_options`) valid as ``[solver]`` values.

    Parameters
    ----------
    by_model : Any
        The ``[solver] by_model`` value (any data: a swept value is checked here too).
    models : sequence of str
        The study's models.
    where : str
        The key path of ``by_model`` in messages.
    """
    if not isinstance(by_model, Mapping):
        return [f"{where}: must be a table of model names ([solver.by_model.<model>]), got {type(by_model).__name__}"]
    out = []
    allowed = per_model_options()
    for name, table in by_model.items():
        here = f"{where}.{name}"
        if name not in models:
            out.append(f"{here}: {name!r} is not one of study.models ({', '.join(models)})")
            continue
        if not isinstance(table, Mapping):
            out.append(f"{here}: must be a table of [solver] options, got {type(table).__name__} {table!r}")
            continue
        for key in table:
            if key in NOT_PER_MODEL:
                out.append(f"{here}.{key}: not a per-model option (set it in [solver] for the whole study)")
            elif key not in allowed:
                out.append(f"{here}.{key}: unknown option{suggest(str(key), allowed)}"
                           .replace("; known keys:", "; per-model options:"))
        try:
            SolverSection.model_validate({k: v for k, v in table.items() if k in allowed})
        except ValidationError as e:
            out.extend(pydantic_problems(e, ("solver", BY_MODEL, name), SolverSection))
    return out
