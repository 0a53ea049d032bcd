"""Checks of the ``[sweep]`` axes of a sweep study: key paths, blocks, and every swept value.

:func:`workbench.study.spec.parse_study` calls :func:`check_sweep` once the base parameters are
resolved.  An axis is a key path (:mod:`workbench.study.keypath`: ``robot.length``,
``load.tensions[0]``, ``solver.by_model.ancf.n_elements``) whose head ``section.key`` is a base
parameter (:func:`known_paths`); each value is set into the base parameters and its section
checked by that section's own validator (:func:`check_override`: the ``[robot]`` validator the
spec passes in, :func:`~workbench.study.checks.check_scenario`, the section schema plus
:func:`~workbench.study.checks.load_rules` and the per-model tables' rules).  Two axes may not set
the same value; a ``solver.<option>`` axis that every model's ``by_model`` table sets is refused (it
would change nothing).  Every problem is one line ``sweep.<block>["<axis>"]...: <reason>``.

Checked by ``tests/study/test_spec.py`` (``tests/study/bad_configs``), ``tests/study/test_element_sweeps.py``
and ``tests/study/test_by_model.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

from pydantic import ValidationError

from .by_model import BY_MODEL, by_model_problems, setters
from .checks import check_scenario, load_rules
from .keypath import KeyPathError, get_value, parse_key_path, with_value
from .messages import join_key, num, pydantic_problems, suggest
from .schema import LIMIT_KEYS, SAMPLED_BLOCKS, SECTION_MODELS, SWEEP_SECTIONS, SweepSection

__all__ = ["RobotCheck", "check_override", "check_sweep", "known_paths"]


def known_paths(base: dict[str, dict[str, Any]]) -> list[str]:
    """The dotted keys a sweep axis may name (everything in ``base`` but the preset and scenario names)."""
    return [f"{s}.{k}" for s in SWEEP_SECTIONS for k in base.get(s, {})
            if not (s == "robot" and k == "preset") and not (s == "scenario" and k == "name")]


#: The validator of the resolved ``[robot]`` table: ``robot dict -> (resolved robot, problems)``
#: (:func:`workbench.study.spec.parse_study` passes the one it resolves the file's ``[robot]`` with).
RobotCheck = Callable[[Mapping[str, Any]], "tuple[dict[str, Any] | None, list[str]]"]


def check_override(path: str, value: Any, base: dict[str, dict[str, Any]], robot_check: RobotCheck,
                   models: Sequence[str] = ()) -> tuple[Any, str | None]:
    """Validate one swept value at key ``path``; returns ``(coerced, problem_or_None)``.

    The value is applied to the base parameters (:func:`workbench.study.keypath.with_value`: a
    list element or a nested field, ``load.tensions[0]``), then the whole section is checked by
    its own validator, as the file's section is: ``robot_check`` for ``[robot]``,
    :func:`check_scenario`, the section's schema (plus :func:`load_rules`, and
    :func:`~workbench.study.by_model.by_model_problems` against ``models``) for the others.  The
    problem names no key (the caller prefixes the sweep key).
    """
    section = path.partition(".")[0]
    try:
        data = with_value(base, path, value, create=True)[section]
    except KeyPathError as e:
        return value, str(e).partition(": ")[2]
    if section in ("robot", "scenario"):
        owner = "preset" if section == "robot" else "name"
        top = parse_key_path(path)[1]
        if owner in data:  # a preset's / scenario's parameters: checked as the file's table setting this one
            data = {owner: data[owner], top: data[top]}
        resolved, probs = robot_check(data) if section == "robot" else check_scenario(data)
    else:
        model = SECTION_MODELS[section]
        try:
            resolved = model.model_validate(data).model_dump()
            probs = []
        except ValidationError as e:
            resolved, probs = None, pydantic_problems(e, (section,), model)
        if resolved is not None and section == "load":
            probs = load_rules(resolved, "load")
        if resolved is not None and section == "solver" and resolved.get(BY_MODEL):
            probs = by_model_problems(resolved[BY_MODEL], models)
    if probs or resolved is None:
        return value, "; ".join(p.split(": ", 1)[-1] for p in probs) or "invalid value"
    return get_value({section: resolved}, path), None


def _overlap(a: tuple, b: tuple) -> bool:
    """One key path contains the other (``load.tensions`` and ``load.tensions[0]``)."""
    n = min(len(a), len(b))
    return a[:n] == b[:n]


@dataclass
class _Axes:
    """Bookkeeping of one :func:`check_sweep` call: which block owns each axis, and the problems."""

    base: dict[str, dict[str, Any]]
    robot_check: RobotCheck
    models: Sequence[str] = ()
    known: list[str] = field(default_factory=list)
    owner: dict[str, str] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)

    def path_ok(self, path: str, where: str) -> bool:
        """``path`` names a sweepable value not swept in another block (else a problem is recorded)."""
        if path == "robot.preset":
            self.problems.append(f'{where}["robot.preset"]: the preset cannot be swept (one study per preset)')
            return False
        if path == "scenario.name":
            self.problems.append(f'{where}["scenario.name"]: the scenario cannot be swept (one study per scenario)')
            return False
        if path in {f"solver.{k}" for k in LIMIT_KEYS}:
            self.problems.append(f'{where}["{path}"]: a per-case limit of the run, not a parameter: it cannot be swept')
            return False
        head = ".".join(str(p) for p in path.split("[")[0].split(".")[:2])
        if head not in self.known and head != f"solver.{BY_MODEL}":
            if path.partition(".")[0] not in SWEEP_SECTIONS:
                self.problems.append(f'{where}["{path}"]: unknown axis; axes are key paths into '
                                     f"{', '.join(SWEEP_SECTIONS)}{suggest(path, self.known)}")
            else:
                self.problems.append(f'{where}["{path}"]: unknown axis{suggest(path, self.known)}')
            return False
        try:
            parts = parse_key_path(path)
            with_value(self.base, parts, None, create=True)
        except KeyPathError as e:
            self.problems.append(f'{where}["{path}"]: {str(e).partition(": ")[2]}')
            return False
        return self._owned(path, parts, where) and self._applies(path, where)

    def _owned(self, path: str, parts: tuple, where: str) -> bool:
        """No other axis sets (part of) the same value."""
        for other, block in self.owner.items():
            if other != path and _overlap(parts, parse_key_path(other)):
                self.problems.append(f'{where}["{path}"]: overlaps the axis "{other}" of {block} (a value may be '
                                     f"swept by one axis only)")
                return False
        if path in self.owner and self.owner[path] != where:
            self.problems.append(f'{where}["{path}"]: already swept in {self.owner[path]} '
                                 f"(a key may appear in one block only)")
            return False
        self.owner[path] = where
        return True

    def _applies(self, path: str, where: str) -> bool:
        """A ``solver.<option>`` axis applies to some model (not every model's ``by_model`` table sets it)."""
        section, _, option = path.partition(".")
        if section != "solver" or not self.models:
            return True
        shadow = setters(self.base.get("solver", {}), option, self.models)
        if len(shadow) < len(self.models):
            return True
        self.problems.append(f'{where}["{path}"]: every model sets {option} in [solver.by_model] '
                             f"({', '.join(shadow)}), so this axis changes nothing; sweep "
                             f'"solver.by_model.<model>.{option}" instead')
        return False

    def value(self, path: str, value: Any) -> tuple[Any, str | None]:
        return check_override(path, value, self.base, self.robot_check, self.models)

    def values(self, path: str, values: list[Any], where: str) -> list[Any]:
        """Every value of an axis checked; the coerced values."""
        res = []
        for i, v in enumerate(values):
            cv, prob = self.value(path, v)
            if prob:
                self.problems.append(join_key(f'{where}["{path}"][{i}]', prob))
            res.append(cv)
        return res


def _check_grid(block: dict[str, list[Any]], where: str, axes: _Axes) -> dict[str, list[Any]]:
    """A ``product`` or ``zip`` block: axis -> its checked values."""
    out = {}
    for path, values in block.items():
        if not axes.path_ok(path, where):
            continue
        if not values:
            axes.problems.append(f'{where}["{path}"]: empty axis (give at least one value)')
            continue
        out[path] = axes.values(path, values, where)
    return out


def _check_cases(cases: list[dict[str, Any]], axes: _Axes) -> list[dict[str, Any]]:
    """The ``cases`` block: every case's values checked; all cases must set the same keys."""
    if not cases:
        axes.problems.append("sweep.cases: empty list (give at least one case or remove the key)")
    out = []
    for i, case in enumerate(cases):
        if not case:
            axes.problems.append(f"sweep.cases[{i}]: empty case")
        entry = {}
        for path, v in case.items():
            if not axes.path_ok(path, "sweep.cases"):
                continue
            cv, prob = axes.value(path, v)
            if prob:
                axes.problems.append(join_key(f'sweep.cases[{i}]["{path}"]', prob))
            entry[path] = cv
        out.append(entry)
    if len({frozenset(c) for c in cases}) > 1:
        axes.problems.append("sweep.cases: every case must set the same keys")
    return out


def _check_range(path: str, rng: Any, where: str, axes: _Axes) -> dict[str, Any] | None:
    """One ``{low, high}`` axis of a sample block; ``None`` when it is unusable."""
    if not isinstance(rng, dict):
        axes.problems.append(f'{where}["{path}"]: must be a table {{low = ..., high = ...}}, got {type(rng).__name__}')
        return None
    for k in sorted(set(rng) - {"low", "high"}):
        axes.problems.append(f'{where}["{path}"].{k}: unknown key{suggest(k, ["low", "high"])}')
    if "low" not in rng or "high" not in rng:
        axes.problems.append(f'{where}["{path}"]: needs both low and high')
        return None
    lo, hi = rng["low"], rng["high"]
    ok = True
    for nm, v in (("low", lo), ("high", hi)):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            axes.problems.append(f'{where}["{path}"].{nm}: must be a number, got {type(v).__name__} {v!r}')
            ok = False
            continue
        _, prob = axes.value(path, v)
        if prob:
            axes.problems.append(f'{where}["{path}"].{nm}: {prob}')
            ok = False
    if ok and not lo < hi:
        axes.problems.append(f'{where}["{path}"]: low must be < high, got low = {num(lo)}, high = {num(hi)}')
        ok = False
    if not ok:
        return None
    if not (isinstance(lo, int) and isinstance(hi, int)):
        # an integer parameter cannot take float samples
        _, prob = axes.value(path, (lo + hi) / 2.0)
        if prob:
            axes.problems.append(f'{where}["{path}"]: {prob} (give integer low/high)')
            return None
    return {"low": lo, "high": hi}


def _check_samples(spec: dict[str, Any], where: str, axes: _Axes) -> dict[str, Any]:
    """A ``random``, ``latin_hypercube`` or ``sobol`` block: ``n`` and the checked ranges."""
    n = spec.get("n")
    if n is None:
        axes.problems.append(f"{where}.n: missing required key (number of samples)")
    elif isinstance(n, bool) or not isinstance(n, int) or n < 1:
        axes.problems.append(f"{where}.n: must be an integer >= 1, got {n!r}")
    elif where.endswith("sobol") and n & (n - 1):
        axes.problems.append(f"{where}.n: a Sobol sequence is balanced only for a power of 2, got {n} "
                             f"(use {1 << (n - 1).bit_length() >> 1} or {1 << (n - 1).bit_length()})")
    ranges = {k: v for k, v in spec.items() if k != "n"}
    if not ranges:
        axes.problems.append(f"{where}: no axes (add e.g. \"robot.length\" = {{low = 0.5, high = 1.0}})")
    clean = {}
    for path, rng in ranges.items():
        if not axes.path_ok(path, where):
            continue
        checked = _check_range(path, rng, where, axes)
        if checked is not None:
            clean[path] = checked
    return {"n": n, **clean}


def check_sweep(sw: SweepSection, base: dict[str, dict[str, Any]], robot_check: RobotCheck,
                models: Sequence[str] = ()) -> tuple[dict[str, Any], list[str]]:
    """The ``[sweep]`` blocks with checked values, and the problems (block by block, in file order).

    An axis is a key path (:mod:`workbench.study.keypath`) into the base parameters; each value is
    checked by :func:`check_override` (``robot_check``: the ``[robot]`` validator; ``models``: the
    study's, for ``solver.by_model`` values and axes every model's table shadows).
    """
    axes = _Axes(base, robot_check, models, known=known_paths(base))
    out: dict[str, Any] = {}
    if sw.product:
        out["product"] = _check_grid(sw.product, "sweep.product", axes)
    if sw.zip:
        lengths = {p: len(v) for p, v in sw.zip.items()}
        if len(set(lengths.values())) > 1:
            axes.problems.append("sweep.zip: paired axes must have equal lengths, got "
                                 + ", ".join(f"{p}: {n}" for p, n in lengths.items()))
        out["zip"] = _check_grid(sw.zip, "sweep.zip", axes)
    if "cases" in sw.model_fields_set:
        out["cases"] = _check_cases(sw.cases, axes)
    for block in SAMPLED_BLOCKS:
        spec = getattr(sw, block)
        if spec is not None:
            out[block] = _check_samples(spec, f"sweep.{block}", axes)
    return out, axes.problems
