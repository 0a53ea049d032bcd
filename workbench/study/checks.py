"""Checks of a sweep study beyond its schema: scenario, load rules, every case.

:func:`workbench.study.spec.parse_study` validates the sections (:mod:`workbench.study.schema`),
then calls these: :func:`check_scenario` (``[scenario]`` typed by the function's defaults),
:func:`load_rules` (cross-field load checks), the sweep axes' checks
(:mod:`workbench.study.sweep_checks`) and, once the study is complete, :func:`check_cases`
(the size limit, duplicate cases, and a dry build of each case's robot and load, so infeasible
commands are input errors before anything runs).  Every problem is one line
``<key path>: <reason>`` (:mod:`workbench.study.messages`).

Validation never imports execution code: it builds cases with :mod:`workbench.study.build` and
expands them with :mod:`workbench.study.expand` (pure), neither of which imports the spec.

Checked by ``tests/study/test_spec.py`` (every file in ``tests/study/bad_configs``) and
``tests/study/test_scenarios.py``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from .build import build_load, build_options, build_robot
from .by_model import BY_MODEL, setters, solver_for_model
from .expand import apply_swept, count_cases, sweep_blocks
from .messages import StudyError, check_robot_value, join_key, num, param_unit, suggest
from .params import canonical_json
from .scenarios import SCENARIOS, load_with_scenario, scenario_parameters
from .schema import LIMIT_KEYS, SAMPLED_BLOCKS

__all__ = ["CHECK_SECONDS", "CaseCheck", "check_scenario", "check_named_params", "load_rules", "case_rules",
           "check_cases"]

# Load list fields whose entries must be >= 0.
_NONNEG_LIST_FIELDS = ("tensions", "start_delays", "ramp_durations")


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
        cv, prob = check_robot_value(k, v, defaults[k], section)
        if prob:
            problems.append(join_key(f"{section}.{k}", prob))
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
                    out.append(f"{where}.{name}[{i}]: must be >= 0 [{param_unit(name)}], got {num(v)}")
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


#: Most time steps a dynamic case may take (``load.duration / solver.time_step``): a sanity bound.
MAX_TIME_STEPS = 10_000_000


def case_rules(params: dict[str, Any], study: Any = None, min_time_step: float | None = None,
               models: Sequence[str] = (), solvers: Sequence[Mapping[str, Any]] | None = None,
               warnings_out: list[str] | None = None) -> list[str]:
    """Checks of one resolved case that need the robot (tendon counts, section counts, a dry build).

    ``study`` is not used (kept for the old signature ``_case_rules(params, study)``);
    ``min_time_step`` (default ``params["solver"]["time_step"]``) bounds the step count of a
    dynamic case by :data:`MAX_TIME_STEPS`.  ``models``: check each model's declared
    capabilities (:mod:`workbench.study.capabilities`) against the built case, under each of
    the ``solvers`` variants (default: the case's own ``[solver]``).  ``warnings_out`` collects
    the plausibility warnings of a case without problems (:mod:`workbench.study.plausibility`).
    """
    import warnings

    with warnings.catch_warnings(), np.errstate(all="ignore"):  # a bad value is reported, not warned about
        warnings.simplefilter("ignore")
        return _case_rules(params, min_time_step, models, solvers, warnings_out)


def _capability_rules(robot, load_case, params, models, solvers) -> list[str]:
    from .. import registry
    from .capabilities import case_features, unsupported

    out: list[str] = []
    for solver in solvers or [params.get("solver", {})]:
        for m in models:  # each model against its own settings ([solver.by_model.<m>] over [solver])
            f = case_features(robot, load_case, params, solver_for_model(solver, m))
            info = registry.table("models").get(m)
            for line in unsupported(m, info.capabilities if info else None, f):
                key, sep, rest = line.partition(": ")
                option = key.partition(".")[2]
                if key.startswith("solver.") and setters(solver, option, [m]):
                    line = f"solver.{BY_MODEL}.{m}.{option}{sep}{rest}"
                if line not in out:
                    out.append(line)
    return out


def _richardson_rules(robot, load_case, params, models, solvers) -> list[str]:
    """``[solver] spring_link_richardson = true`` where the link count cannot be extrapolated
    (:func:`workbench.physics.spring_link.richardson.richardson_problem`; with the study's error
    estimate on, its half-resolution re-solve must extrapolate too)."""
    if "spring_link" not in models:
        return []
    from ..physics.spring_link.richardson import richardson_problem

    out: list[str] = []
    for solver in solvers or [params.get("solver", {})]:
        own = solver_for_model(solver, "spring_link")
        if not own.get("spring_link_richardson"):
            continue
        estimate = (own.get("error_estimate", "richardson") != "none"
                    and "spring_link" not in (own.get("error_estimate_exempt") or []))
        why = richardson_problem(int(own.get("n_elements", 16)), robot.n_sections, load_case.analysis, estimate)
        by_model = setters(solver, "spring_link_richardson", ["spring_link"])
        key = f"solver.{BY_MODEL}.spring_link.spring_link_richardson" if by_model else "solver.spring_link_richardson"
        if why and f"{key}: model 'spring_link' {why}" not in out:
            out.append(f"{key}: model 'spring_link' {why}")
    return out


def _keyed(section: str, e: BaseException, names: Any) -> str:
    """``"<section>.<name>: <message>"`` when the message names exactly one parameter, else ``"<section>: ..."``."""
    import re

    msg = " ".join(str(e).split()) or type(e).__name__
    low = msg.lower()

    def named(n: str) -> bool:
        return any(re.search(rf"(?<![A-Za-z0-9_]){re.escape(w)}(?![A-Za-z0-9_])", low) for w in (n, n.replace("_", " ")))

    hits = [n for n in names if named(n.lower())]
    hits = [h for h in hits if not any(h != o and h in o for o in hits)]
    return f"{section}.{hits[0]}: {msg}" if len(hits) == 1 else f"{section}: {msg}"


def _case_rules(params: dict[str, Any], min_time_step: float | None, models: Sequence[str] = (),
                solvers: Sequence[Mapping[str, Any]] | None = None, warnings_out: list[str] | None = None
                ) -> list[str]:
    try:
        robot = build_robot(params["robot"], params["derived"])
    except Exception as e:  # noqa: BLE001 - every build failure is a user input problem here
        return [_keyed("robot", e, [k for k in params["robot"] if k != "preset"])]
    out = []
    load = params["load"]
    if params.get("scenario"):
        try:
            load = load_with_scenario(robot, load, params["scenario"])
        except Exception as e:  # noqa: BLE001 - an infeasible scenario is an input problem
            return [_keyed("scenario", e, [k for k in params["scenario"] if k != "name"])]
        out.extend(load_rules(load, "load (with scenario)"))
    out.extend(_count_rules(load, robot))
    dt = min_time_step if min_time_step is not None else params.get("solver", {}).get("time_step")
    if load.get("analysis") == "dynamic" and dt and load.get("duration", 0.0) / dt > MAX_TIME_STEPS:
        out.append(f"solver.time_step: load.duration / time_step = {load['duration'] / dt:.3g} steps exceeds "
                   f"{MAX_TIME_STEPS:.0e} (a sanity bound)")
    if not out:
        # dry-build the load case (tendon commands from the CC arc command): infeasible
        # commands are input errors, reported before anything runs
        try:
            load_case = build_load(robot, load)
        except ImportError:
            return out  # workbench.models.cc not installed: checked when the case runs
        except Exception as e:  # noqa: BLE001
            key = "load.bend_plane" if load.get("bend_angle") is not None and "plane" in str(e) else None
            out.append(f"{key}: {e}" if key else _keyed("load", e, [k for k in load if load.get(k) is not None]))
            return out
        out.extend(_capability_rules(robot, load_case, {**params, "load": load}, models, solvers))
        out.extend(_richardson_rules(robot, load_case, params, models, solvers))
        if not out and warnings_out is not None:
            from .plausibility import plausibility_warnings

            warnings_out.extend(plausibility_warnings(robot, load_case, {**params, "load": load}))
            warnings_out.extend(_spring_link_warnings(robot, load_case, params, models))
    return out


def _spring_link_warnings(robot, load_case, params: Mapping[str, Any], models: Sequence[str]) -> list[str]:
    """The spring-link models' own warning (length mode on the inextensible chain)."""
    from ..physics.spring_link.cardan import CARDAN
    from ..physics.spring_link.params import SpringLinkParams, inextensible_length_warning

    out = []
    for m in models:
        if m not in ("spring_link", "spring_link_cardan"):
            continue
        solver = solver_for_model(params.get("solver", {}), m)
        options = build_options({k: v for k, v in solver.items() if k not in LIMIT_KEYS})
        p = CARDAN if m == "spring_link_cardan" else SpringLinkParams(**options.settings("spring_link"))
        line = inextensible_length_warning(robot, load_case, options.tendon_model, p)
        if line:
            out.append(f"solver.spring_link_axial: model '{m}' {line}")
    return out


def _duplicate_entries(blocks: list[list[dict[str, Any]]], names: list[str]) -> list[str]:
    """Identical entries inside one block (blocks set disjoint keys, so only these repeat a case)."""
    out = []
    for block, name in zip(blocks, names):
        seen: dict[str, int] = {}
        for i, entry in enumerate(block):
            key = canonical_json(entry)
            if key in seen:
                out.append(f"{name}[{i}]: identical parameters to {name}[{seen[key]}] ({key}); the sweep would "
                           f"run the same case twice")
            else:
                seen[key] = i
    return out


def _block_names(study) -> list[str]:
    sw = study.sweep
    names = [f'sweep.product["{p}"]' for p in sw.get("product", {})]
    names += ["sweep.zip"] * bool(sw.get("zip")) + ["sweep.cases"] * ("cases" in sw)
    return names + [f"sweep.{b}" for b in SAMPLED_BLOCKS if sw.get(b)]


def _projection(blocks, keep) -> list[list[tuple[int, dict[str, Any]]]]:
    """Per block, the distinct projections of its entries onto the keys ``keep(path)`` (with their first index)."""
    out = []
    for block in blocks:
        seen: dict[str, tuple[int, dict]] = {}
        for i, entry in enumerate(block):
            sub = {k: v for k, v in entry.items() if keep(k)}
            seen.setdefault(canonical_json(sub), (i, sub))
        out.append(list(seen.values()))
    return out


@dataclass
class CaseCheck:
    """What :func:`check_cases` found: problems (one line per distinct problem) and how much it built."""

    problems: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    built: int = 0
    distinct: int = 0

    @property
    def note(self) -> str:
        """A sentence for ``validate`` when the time budget stopped the dry builds early (else ``""``)."""
        if self.built >= self.distinct:
            return ""
        return (f"dry-built {self.built} of {self.distinct} distinct robot/load combinations within the "
                f"{CHECK_SECONDS:g} s validation budget; the others are built when their case runs")


#: Seconds :func:`check_cases` spends dry-building cases before it stops (huge sweeps stay answerable).
CHECK_SECONDS = 10.0


_NUMBER = re.compile(r"-?\d+(\.\d+)?(e[+-]?\d+)?")


def _group(found: dict[str, list[tuple[int, dict]]], total: int, unit: str = "cases") -> list[str]:
    """One line per distinct problem: where it occurs (one case, several, or every case).

    Messages that differ only in their numbers (the case's values) are one problem; the line
    shows the first case's message.
    """
    merged: dict[str, tuple[str, list[tuple[int, dict]]]] = {}
    for msg, where in found.items():
        key = _NUMBER.sub("#", msg)
        first, acc = merged.setdefault(key, (msg, []))
        acc.extend(where)
    lines = []
    for msg, where in merged.values():
        where = sorted(where, key=lambda w: w[0])
        key, _, reason = msg.partition(": ")
        index, swept = where[0]
        example = f"case {index}: {canonical_json(swept)}" if swept else ""
        if len(where) == 1:
            lines.append(f"{key} ({example}): {reason}" if example else msg)
        elif len(where) == total:
            lines.append(f"{key} (every case, e.g. {example}): {reason}")
        else:
            lines.append(f"{key} ({len(where)} of {total} {unit}, e.g. {example}): {reason}")
    return lines


def check_cases(study, source: str, budget: float | None = None, *, run_models: bool = True) -> CaseCheck:
    """The size limit, duplicate cases and :func:`case_rules` of a complete study, bounded in time and memory.

    The cases are counted, not expanded; duplicates are found inside each sweep block; the dry
    builds run over the distinct combinations of robot / derived / scenario / load values
    (solver values are checked on their own), lazily, for at most ``budget`` seconds (default
    :data:`CHECK_SECONDS`).  ``run_models=False``: skip the models' capability checks (a kind
    whose own tasks compute the rows).  A problem that occurs in many cases is one line.

    Raises
    ------
    StudyError
        One line per distinct problem.
    """
    import itertools
    import time

    n = count_cases(study)
    if n > study.max_cases:
        raise StudyError([f"{source}: sweep: {n} cases exceed the limit max_cases = {study.max_cases} "
                          f"(raise study.max_cases or --max-cases)"])
    blocks = sweep_blocks(study)
    dup = _duplicate_entries(blocks, _block_names(study))
    if dup:
        raise StudyError([f"{source}: {p}" for p in dup])
    sizes = [len(b) for b in blocks]
    strides = [1] * len(blocks)
    for i in range(len(blocks) - 2, -1, -1):
        strides[i] = strides[i + 1] * sizes[i + 1]
    rl = _projection(blocks, lambda k: not k.startswith("solver."))
    sv = _projection(blocks, lambda k: k.startswith("solver."))
    check = CaseCheck(distinct=math.prod(len(b) for b in rl) if rl else 1)
    steps = [study.base["solver"].get("time_step")] + [sub["solver.time_step"] for b in sv for _, sub in b
                                                      if "solver.time_step" in sub]
    solvers = list({canonical_json(s_): s_ for s_ in (
        _params({"solver": study.base["solver"]}, [sub for _, sub in combo])["solver"]
        for combo in itertools.islice(itertools.product(*sv), 64))}.values())
    steps += [t.get("time_step") for s_ in solvers for t in (s_.get(BY_MODEL) or {}).values()]  # per-model steps
    min_dt = min((x for x in steps if x), default=None)
    found: dict[str, list[tuple[int, dict]]] = {}
    warned: dict[str, list[tuple[int, dict]]] = {}
    t_end = time.monotonic() + (CHECK_SECONDS if budget is None else budget)
    for combo in itertools.product(*rl):
        if time.monotonic() > t_end:
            break
        params = _params(study.base, [sub for _, sub in combo])
        index = sum(i * st for (i, _), st in zip(combo, strides))
        swept = {k: v for b, (i, _) in zip(blocks, combo) for k, v in b[i].items()}
        warns: list[str] = []
        models = tuple(getattr(study, "models", ())) if run_models else ()
        for m in case_rules(params, study, min_dt, models=models, solvers=solvers, warnings_out=warns):
            found.setdefault(m, []).append((index, swept))
        for w in warns:
            warned.setdefault(w, []).append((index, swept))
        check.built += 1
    for combo in itertools.product(*sv):
        solver = _params(study.base, [sub for _, sub in combo])["solver"]
        for m in (None, *(solver.get(BY_MODEL) or {})):  # [solver], then each model's own settings
            try:
                build_options(solver if m is None else solver_for_model(solver, m))
            except (TypeError, ValueError) as e:
                key = "solver" if m is None else f"solver.{BY_MODEL}.{m}"
                found.setdefault(f"{key}: {e}", []).append((0, {k: v for _, sub in combo for k, v in sub.items()}))
    unit = "cases" if check.distinct == n else "robot/load combinations"
    check.problems = _group(found, check.distinct, unit)
    check.warnings = _group(warned, check.distinct, unit)
    if check.problems:
        raise StudyError([f"{source}: {p}" for p in check.problems])
    return check


def _params(base: dict[str, dict[str, Any]], parts: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    params = {sec: dict(d) for sec, d in base.items()}
    for part in parts:
        apply_swept(params, part)
    return params
