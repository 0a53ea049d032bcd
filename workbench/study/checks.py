"""Checks of a sweep study beyond its schema: scenario, load rules, sweep axes, every case.

:func:`workbench.study.spec.parse_study` validates the sections (:mod:`workbench.study.schema`),
then calls these: :func:`check_scenario` (``[scenario]`` typed by the function's defaults),
:func:`load_rules` (cross-field load checks), :func:`check_sweep` (every axis of every block,
value by value, :func:`check_override`) and, once the study is complete, :func:`check_cases`
(the size limit, duplicate cases, and a dry build of each case's robot and load, so infeasible
commands are input errors before anything runs).  Every problem is one line
``<key path>: <reason>`` (:mod:`workbench.study.messages`).

Validation never imports execution code: it builds cases with :mod:`workbench.study.build` and
expands them with :mod:`workbench.study.expand` (pure), neither of which imports the spec.

Checked by ``tests/study/test_spec.py`` (every file in ``tests/study/bad_configs``) and
``tests/study/test_scenarios.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from pydantic import ValidationError

from .build import build_load, build_options, build_robot
from .expand import count_cases, expand
from .messages import UNITS, StudyError, check_robot_value, num, pydantic_problems, suggest
from .params import canonical_json
from .scenarios import SCENARIOS, load_with_scenario, scenario_parameters
from .schema import SECTION_MODELS, SWEEP_SECTIONS, SweepSection

__all__ = ["check_scenario", "load_rules", "case_rules", "check_cases", "check_override", "check_sweep",
           "known_paths"]

# Load list fields whose entries must be >= 0.
_NONNEG_LIST_FIELDS = ("tensions", "start_delays", "ramp_durations")
# At most this many per-case problems are listed.
_MAX_CASE_PROBLEMS = 20


# ---------------------------------------------------------------------------------------
# scenario and load
# ---------------------------------------------------------------------------------------
def check_scenario(raw: Any) -> tuple[dict[str, Any] | None, list[str]]:
    """Resolve ``[scenario]``: a registered name plus typed parameters (defaults filled in)."""
    if raw is None:
        return None, []
    if not isinstance(raw, dict):
        return None, [f"scenario: must be a table [scenario], got {type(raw).__name__}"]
    name = raw.get("name")
    if name is None:
        return None, ["scenario.name: missing required key (one of: " + ", ".join(sorted(SCENARIOS)) + ")"]
    if not isinstance(name, str):
        return None, [f"scenario.name: must be a string, got {type(name).__name__} {name!r}"]
    if name not in SCENARIOS:
        return None, [f"scenario.name: unknown scenario {name!r}{suggest(name, sorted(SCENARIOS))}"
                      .replace("; known keys:", "; known scenarios:")]
    defaults = scenario_parameters(name)
    values, problems = check_named_params("scenario", raw, defaults, f"scenario {name!r}", skip="name")
    return {"name": name, **values}, problems


def check_named_params(section: str, raw: Mapping[str, Any], defaults: Mapping[str, Any], owner: str,
                       skip: str) -> tuple[dict[str, Any], list[str]]:
    """The parameters of a preset or scenario: the defaults with ``raw``'s checked values applied.

    Returns ``(values, problems)``: one problem per unknown key (with a suggestion) or bad value,
    as ``"<section>.<key>: ..."``; ``skip`` is the key that names the owner (``preset``/``name``).
    """
    out: dict[str, Any] = dict(defaults)
    problems = []
    for k, v in raw.items():
        if k == skip:
            continue
        if k not in defaults:
            problems.append(f"{section}.{k}: unknown parameter of {owner}{suggest(k, list(defaults))}")
            continue
        cv, prob = check_robot_value(k, v, defaults[k])
        if prob:
            problems.append(f"{section}.{k}: {prob}")
        else:
            out[k] = cv
    return out, problems


def load_rules(load: dict[str, Any], where: str) -> list[str]:
    """Cross-field and element-wise load checks (structural, robot-independent)."""
    out = []
    for name in _NONNEG_LIST_FIELDS:
        vals = load.get(name)
        if vals is not None:
            for i, v in enumerate(vals):
                if v < 0:
                    out.append(f"{where}.{name}[{i}]: must be >= 0 [{UNITS[name]}], got {num(v)}")
            if len(vals) == 0:
                out.append(f"{where}.{name}: must not be empty")
    given = [k for k in ("bend_angle", "tensions", "length_changes") if load.get(k) is not None]
    if len(given) > 1:
        out.append(f"{where}: set only one of bend_angle, tensions, length_changes (got {', '.join(given)})")
    if load.get("tensions") is not None and load.get("mode") != "tension":
        out.append(f"{where}.tensions: needs mode = \"tension\" (got mode = {load.get('mode')!r})")
    if load.get("length_changes") is not None and load.get("mode") != "length":
        out.append(f"{where}.length_changes: needs mode = \"length\" (got mode = {load.get('mode')!r})")
    if load.get("analysis") == "dynamic" and not load.get("duration", 0) > 0:
        out.append(f"{where}.duration: must be > 0 [s] for a dynamic analysis, got {num(load.get('duration'))}")
    for name in ("bend_angle", "bend_plane"):
        if isinstance(load.get(name), list) and len(load[name]) == 0:
            out.append(f"{where}.{name}: must not be an empty list")
    return out


# ---------------------------------------------------------------------------------------
# every case
# ---------------------------------------------------------------------------------------
def _count_rules(load: Mapping[str, Any], robot) -> list[str]:
    """Entry counts of the load lists against the robot's tendons and sections."""
    out = []
    nt, ns = robot.n_tendons, robot.n_sections
    for name in ("tensions", "length_changes", "start_delays", "ramp_durations"):
        v = load.get(name)
        if v is not None and len(v) != nt:
            out.append(f"load.{name}: must have {nt} entries (one per tendon of the robot), got {len(v)}")
    for name in ("bend_angle", "bend_plane"):
        v = load.get(name)
        if isinstance(v, list) and len(v) != ns:
            out.append(f"load.{name}: must be a scalar or have {ns} entries (one per section), got {len(v)}")
    if (load.get("bend_angle") is not None or load.get("tensions") is not None
            or load.get("length_changes") is not None) and nt == 0:
        out.append("load: the robot has no tendons to actuate")
    return out


def case_rules(params: dict[str, Any], study: Any = None) -> list[str]:
    """Checks of one resolved case that need the robot (tendon counts, section counts, a dry build).

    ``study`` is not used (kept for the old signature ``_case_rules(params, study)``).
    """
    try:
        robot = build_robot(params["robot"], params["derived"])
    except Exception as e:  # noqa: BLE001 - every build failure is a user input problem here
        return [f"robot: {e}"]
    out = []
    load = params["load"]
    if params.get("scenario"):
        try:
            load = load_with_scenario(robot, load, params["scenario"])
        except Exception as e:  # noqa: BLE001 - an infeasible scenario is an input problem
            return [f"scenario: {e}"]
        out.extend(load_rules(load, "load (with scenario)"))
    out.extend(_count_rules(load, robot))
    try:
        build_options(params["solver"])
    except (TypeError, ValueError) as e:
        out.append(f"solver: {e}")
    if not out:
        # dry-build the load case (tendon commands from the CC arc command): infeasible
        # commands are input errors, reported before anything runs
        try:
            build_load(robot, load)
        except ImportError:
            pass  # workbench.models.cc not installed: checked when the case runs
        except Exception as e:  # noqa: BLE001
            out.append(f"load: {e}")
    return out


def check_cases(study, source: str) -> None:
    """The size limit, duplicate cases and :func:`case_rules` of every case of a complete study.

    Raises
    ------
    StudyError
        One line per problem (at most about 20 case problems are listed).
    """
    n = count_cases(study)
    if n > study.max_cases:
        raise StudyError([f"{source}: sweep: {n} cases exceed the limit max_cases = {study.max_cases} "
                          f"(raise study.max_cases or --max-cases)"])
    case_problems: list[str] = []
    seen: dict[str, int] = {}
    for c in expand(study):
        if c.case_id in seen:
            case_problems.append(f"sweep: cases {seen[c.case_id]} and {c.index} have identical parameters "
                                 f"({canonical_json(c.swept)})")
            continue
        seen[c.case_id] = c.index
        for m in case_rules(c.params, study):
            key, _, reason = m.partition(": ")
            where = f" (case {c.index}: {canonical_json(c.swept)})" if c.swept else ""
            case_problems.append(f"{key}{where}: {reason}")
        if len(case_problems) > _MAX_CASE_PROBLEMS:
            case_problems.append("... (further case problems not listed)")
            break
    if case_problems:
        raise StudyError([f"{source}: {p}" for p in case_problems])


# ---------------------------------------------------------------------------------------
# sweep axes
# ---------------------------------------------------------------------------------------
def known_paths(base: dict[str, dict[str, Any]]) -> list[str]:
    """The dotted keys a sweep axis may name (everything in ``base`` but the preset and scenario names)."""
    return [f"{s}.{k}" for s in SWEEP_SECTIONS for k in base.get(s, {})
            if not (s == "robot" and k == "preset") and not (s == "scenario" and k == "name")]


def check_override(path: str, value: Any, base: dict[str, dict[str, Any]],
                   preset_defaults: Mapping[str, Any]) -> tuple[Any, str | None]:
    """Validate one swept value at dotted ``path``; returns ``(coerced, problem_or_None)``."""
    section, _, key = path.partition(".")
    if section == "robot":
        return check_robot_value(key, value, preset_defaults[key])
    if section == "scenario":
        return check_robot_value(key, value, scenario_parameters(base["scenario"]["name"])[key])
    model = SECTION_MODELS[section]
    data = dict(base[section])
    data[key] = value
    try:
        validated = model.model_validate(data)
    except ValidationError as e:
        probs = [p.split(": ", 1)[1] for p in pydantic_problems(e, (section,), model)]
        return value, "; ".join(probs)
    if section == "load":
        probs = load_rules(validated.model_dump(), "load")
        if probs:
            return value, "; ".join(probs)
    return getattr(validated, key), None


@dataclass
class _Axes:
    """Bookkeeping of one :func:`check_sweep` call: which block owns each axis, and the problems."""

    base: dict[str, dict[str, Any]]
    preset_defaults: Mapping[str, Any]
    known: list[str] = field(default_factory=list)
    owner: dict[str, str] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)

    def path_ok(self, path: str, where: str) -> bool:
        """``path`` names a sweepable key not swept in another block (else a problem is recorded)."""
        if path == "robot.preset":
            self.problems.append(f'{where}["robot.preset"]: the preset cannot be swept (one study per preset)')
            return False
        if path == "scenario.name":
            self.problems.append(f'{where}["scenario.name"]: the scenario cannot be swept (one study per scenario)')
            return False
        if path not in self.known:
            if path.partition(".")[0] not in SWEEP_SECTIONS:
                self.problems.append(f'{where}["{path}"]: unknown axis; axes are dotted keys into '
                                     f"{', '.join(SWEEP_SECTIONS)}{suggest(path, self.known)}")
            else:
                self.problems.append(f'{where}["{path}"]: unknown axis{suggest(path, self.known)}')
            return False
        if path in self.owner and self.owner[path] != where:
            self.problems.append(f'{where}["{path}"]: already swept in {self.owner[path]} '
                                 f"(a key may appear in one block only)")
            return False
        self.owner[path] = where
        return True

    def value(self, path: str, value: Any) -> tuple[Any, str | None]:
        return check_override(path, value, self.base, self.preset_defaults)

    def values(self, path: str, values: list[Any], where: str) -> list[Any]:
        """Every value of an axis checked; the coerced values."""
        res = []
        for i, v in enumerate(values):
            cv, prob = self.value(path, v)
            if prob:
                self.problems.append(f'{where}["{path}"][{i}]: {prob}')
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
                axes.problems.append(f'sweep.cases[{i}]["{path}"]: {prob}')
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
    """A ``random`` or ``latin_hypercube`` block: ``n`` and the checked ranges."""
    n = spec.get("n")
    if n is None:
        axes.problems.append(f"{where}.n: missing required key (number of samples)")
    elif isinstance(n, bool) or not isinstance(n, int) or n < 1:
        axes.problems.append(f"{where}.n: must be an integer >= 1, got {n!r}")
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


def check_sweep(sw: SweepSection, base: dict[str, dict[str, Any]],
                preset_defaults: Mapping[str, Any]) -> tuple[dict[str, Any], list[str]]:
    """The ``[sweep]`` blocks with checked values, and the problems (block by block, in file order)."""
    axes = _Axes(base, preset_defaults, known=known_paths(base))
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
    for block in ("random", "latin_hypercube"):
        spec = getattr(sw, block)
        if spec is not None:
            out[block] = _check_samples(spec, f"sweep.{block}", axes)
    return out, axes.problems
