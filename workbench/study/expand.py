"""Sweep expansion (pure): a validated :class:`~workbench.study.spec.Study` -> list of cases.

Each case carries its fully resolved parameters and a stable ``case_id``: the first 16 hex
digits of the SHA-256 of the canonical JSON of those parameters.  The id depends only on the
parameter values (not on the case's position in the sweep, the study name or the models), so
reruns and resumes match cases exactly.  Imports nothing but :mod:`workbench.study.params`, so the
spec can expand a study while validating it (no cycle).

Checked by ``tests/study/test_expand.py``.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any, Mapping, Protocol

import numpy as np

from .keypath import with_value
from .params import canonical_json, case_id_for, case_id_from_sections, flatten_params
from .schema import SAMPLED_BLOCKS

__all__ = ["Case", "apply_swept", "expand", "count_cases", "case_id_for", "flatten_params", "sweep_blocks",
           "sweep_keys"]


class SweepSpec(Protocol):
    """What expansion reads of a validated :class:`workbench.study.spec.Study` (no import of the spec)."""

    base: dict[str, dict[str, Any]]
    sweep: dict[str, Any]
    seed: int


@dataclass(frozen=True)
class Case:
    """One case of a sweep.

    Attributes
    ----------
    case_id : str
        Stable hash of ``params``.
    index : int
        Position in the expansion order (for messages only).
    params : dict
        Resolved ``{"robot": {...}, "load": {...}, "solver": {...}, "derived": {...}}``
        (plain data, picklable).
    swept : dict
        The swept values of this case, ``{dotted path: value}``.
    """

    case_id: str
    index: int
    params: dict[str, dict[str, Any]]
    swept: dict[str, Any]


def sweep_keys(sweep: Any) -> list[str]:
    """The dotted keys a ``[sweep]`` section names, in block order, each once (the swept axes).

    A mapping block (``product``, ``zip``, ``random`` / ``latin_hypercube`` / ``sobol``) names its
    keys (``n`` is a sample count, not a key); a list block (``cases``) the keys of its entries.
    Tolerates an unvalidated section (anything else names no key): the spec checks cross-key rules
    with it, the result loaders (:mod:`workbench.study.folder`) read the axes of a stored run with it.
    Checked by ``tests/study/test_expand.py``.
    """
    keys: list[str] = []
    if not isinstance(sweep, Mapping):
        return keys
    for body in sweep.values():
        if isinstance(body, Mapping):
            keys += [str(k) for k in body if k != "n"]
        elif isinstance(body, list):
            keys += [str(k) for entry in body if isinstance(entry, Mapping) for k in entry]
    return list(dict.fromkeys(keys))


def sweep_blocks(study: SweepSpec) -> list[list[dict[str, Any]]]:
    """The sweep's blocks in order, each a list of entries ``{dotted path: value}`` (cases = their product)."""
    sw = study.sweep
    blocks: list[list[dict[str, Any]]] = []
    for path, values in sw.get("product", {}).items():
        blocks.append([{path: v} for v in values])
    z = sw.get("zip", {})
    if z:
        n = len(next(iter(z.values())))
        blocks.append([{p: vals[i] for p, vals in z.items()} for i in range(n)])
    if "cases" in sw:
        blocks.append([dict(c) for c in sw["cases"]])
    for tag, block in enumerate(SAMPLED_BLOCKS):
        spec = sw.get(block)
        if spec:
            blocks.append(_samples(spec, study.seed, tag, block))
    return blocks


def _unit_samples(n: int, d: int, rng: np.random.Generator, kind: str) -> np.ndarray:
    """``(n, d)`` points in [0, 1): independent uniform, Latin hypercube or scrambled Sobol (``scipy.stats.qmc``)."""
    if kind == "random":
        return np.column_stack([rng.uniform(0.0, 1.0, n) for _ in range(d)]) if d else np.zeros((n, 0))
    from scipy.stats import qmc

    engine = qmc.LatinHypercube(d, seed=rng) if kind == "latin_hypercube" else qmc.Sobol(d, scramble=True, seed=rng)
    return engine.random(n)


def _samples(spec: dict[str, Any], seed: int, tag: int, kind: str) -> list[dict[str, Any]]:
    """``kind`` samples (:data:`SAMPLED_BLOCKS`), keys in sorted order, seeded by ``[seed, tag]``.

    ``random``: independent uniform draws per key; ``latin_hypercube``: one sample per stratum
    of every key (``scipy.stats.qmc.LatinHypercube``); ``sobol``: a scrambled Sobol sequence
    (``scipy.stats.qmc.Sobol``; ``n`` a power of 2, checked in validation).
    """
    n = int(spec["n"])
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), tag]))
    paths = sorted(k for k in spec if k != "n")
    points = _unit_samples(n, len(paths), rng, kind)
    cols: dict[str, list[Any]] = {}
    for j, path in enumerate(paths):
        lo, hi = spec[path]["low"], spec[path]["high"]
        integer = isinstance(lo, int) and isinstance(hi, int)
        u = points[:, j]
        if integer:
            vals = [int(min(hi, lo + np.floor(x * (hi - lo + 1)))) for x in u]
        else:
            vals = [float(lo + x * (hi - lo)) for x in u]
        cols[path] = vals
    return [{p: cols[p][i] for p in cols} for i in range(n)]


def apply_swept(params: dict[str, dict[str, Any]], swept: Mapping[str, Any]) -> None:
    """Set every ``{key path: value}`` of ``swept`` in ``params`` (a dict of section dicts, changed in place).

    ``section.key`` sets the key; a deeper path (``load.tensions[0]``, ``solver.by_model.ancf.n_elements``)
    replaces the section by a copy with that element set (:func:`workbench.study.keypath.with_value`;
    a missing table key is added: validation has checked the path).
    """
    for path, value in swept.items():
        section, _, key = path.partition(".")
        if "." in key or "[" in key:
            params[section] = with_value(params[section], key, value, create=True)
        else:
            params[section][key] = value


def count_cases(study: SweepSpec) -> int:
    """Number of cases :func:`expand` would produce (without expanding)."""
    n = 1
    sw = study.sweep
    for values in sw.get("product", {}).values():
        n *= len(values)
    if sw.get("zip"):
        n *= len(next(iter(sw["zip"].values())))
    if "cases" in sw:
        n *= len(sw["cases"])
    for block in SAMPLED_BLOCKS:
        if sw.get(block):
            n *= int(sw[block]["n"])
    return n


def expand(study: SweepSpec) -> list[Case]:
    """All cases of ``study``, in a deterministic order (blocks' Cartesian product)."""
    cases = []
    base_json = {sec: canonical_json(d) for sec, d in study.base.items()}  # sections no sweep touches: once
    for i, combo in enumerate(itertools.product(*sweep_blocks(study))):
        swept: dict[str, Any] = {}
        for part in combo:
            swept.update(part)
        params = {sec: {k: (list(v) if isinstance(v, list) else v) for k, v in d.items()}
                  for sec, d in study.base.items()}
        apply_swept(params, swept)
        touched = {path.partition(".")[0] for path in swept}
        fixed = {sec: j for sec, j in base_json.items() if sec not in touched}
        cases.append(Case(case_id=case_id_from_sections(params, fixed), index=i, params=params, swept=swept))
    return cases
