"""Sweep-study files: TOML -> validated :class:`Study`, every problem reported before any simulation.

The format reference (an annotated example of every section, the sweep semantics) is
``docs/study-format.md``; ``studies/example.toml`` is a runnable example.  In short::

    [study]     name, description, seed, models (workbench.models.model_names()), max_cases
    [robot]     preset = "<name>" + overrides of that preset's parameters (typed by its defaults)
    [load]      mode, bend_angle | tensions | length_changes, bend_plane, pretension, tip loads,
                analysis, duration, ramp_time, start_delays, ramp_durations
    [solver]    the fields of workbench.models.SolverOptions; [solver.by_model.<model>] per-model
                settings (:mod:`workbench.study.by_model`)
    [scenario]  optional: name of a registered scenario + its keyword parameters
    [derived]   optional: gravity_parameter (gamma = q L^3 / EI sets the preset's gravity)
    [sweep]     product / zip / cases / random / latin_hypercube / sobol blocks of key-path axes
                (``load.tensions[0]``: :mod:`workbench.study.keypath`)
    [report]    optional presentation hints (not in the config hash)

All quantities are SI.  :func:`load_study` collects *all* problems and raises one
:class:`StudyError` whose ``problems`` are one line each::

    studies/bad.toml: robot.lenght: unknown key; did you mean 'length'?
    studies/bad.toml: sweep.product["robot.length"][1]: must be > 0 [m], got -0.5

:func:`parse_study` runs in steps: the sections against their schema
(:mod:`workbench.study.schema`), the model list, the robot preset and its overrides, the load
and derived rules, the scenario, the sweep axes, and finally every case (size limit, duplicates,
a dry build of robot and load: :mod:`workbench.study.checks`).  All problems come in one pass:
each step runs on what the earlier ones left valid (a key with a problem at its default, a sweep
axis with a problem left out, lines about such keys dropped: :mod:`workbench.study.onepass`);
only a table wrong as a whole (``load: set only one of ...``) stops the case checks.  Validation imports no execution
code (no cycle: ``spec`` -> ``checks`` -> ``build`` / ``expand`` / ``scenarios``).

Checked by ``tests/study/test_spec.py`` (every file of ``tests/study/bad_configs`` and its message).
"""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping, Sequence

from pydantic import BaseModel, ValidationError

from .by_model import by_model_problems
from .keypath import KeyPathError, get_value
from .report_keys import check_report
from .sweep_checks import check_sweep, known_paths
from .checks import check_cases, check_scenario, load_rules
from .messages import StudyError, collapse_indexed, pydantic_problems, read_toml, suggest
from .expand import sweep_keys
from .outcomes import CaseLimits
from .params import canonical_json
from .schema import DEFAULT_MAX_CASES, LIMIT_KEYS, SECTION_MODELS, SWEEP_SECTIONS, StudyFile

__all__ = [
    "Study",
    "StudyError",
    "load_study",
    "parse_study",
    "resolve_robot_table",
    "DEFAULT_MAX_CASES",
    "SWEEP_SECTIONS",
]


# ---------------------------------------------------------------------------------------
# The validated study
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Study:
    """A validated study.

    Attributes
    ----------
    path : str
        The file it came from (for messages).
    name, description : str
    seed : int
    models : tuple of str
    max_cases : int
    base : dict
        Resolved base parameters ``{"robot": {"preset": ..., <all preset parameters>},
        "load": {...}, "solver": {...}, "derived": {...}}`` (plain data).
    sweep : dict
        The ``[sweep]`` section as plain data (keys validated).
    report : dict
        The ``[report]`` hints.
    limits : CaseLimits
        ``[solver] max_case_seconds`` / ``max_case_memory`` (not in ``base``: they limit a run,
        they do not change a result).
    notes : tuple of str
        What validation wants the user to know without refusing the file (one line each).
    warnings : tuple of str
        Plausibility warnings (:mod:`workbench.study.plausibility`), one line each.
    overrides : tuple of str
        The command-line ``key=value`` overrides applied to the file (recorded in the manifest).
    """

    path: str
    name: str
    description: str
    seed: int
    models: tuple[str, ...]
    max_cases: int
    base: dict[str, dict[str, Any]]
    sweep: dict[str, Any] = field(default_factory=dict)
    report: dict[str, Any] = field(default_factory=dict)
    limits: CaseLimits = field(default_factory=CaseLimits)
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    overrides: tuple[str, ...] = ()

    def resolved(self) -> dict[str, Any]:
        """Plain-data resolved spec (what the manifest records; the limits under ``solver``)."""
        out = {
            "study": {
                "name": self.name, "description": self.description, "seed": self.seed,
                "models": list(self.models), "max_cases": self.max_cases,
            },
            **{k: dict(v) for k, v in self.base.items()},
            "sweep": self.sweep,
            "report": self.report,
        }
        out["solver"] = {**out.get("solver", {}), "max_case_seconds": self.limits.seconds,
                         "max_case_memory": self.limits.memory}
        return out

    @property
    def config_hash(self) -> str:
        """Hash of everything that changes results (not name/description/max_cases)."""
        payload = {"models": list(self.models), "seed": self.seed, "base": self.base, "sweep": self.sweep}
        return hashlib.sha256(canonical_json(payload).encode()).hexdigest()[:16]


# ---------------------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------------------
def load_study(path: str | Path, *, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Study:
    """Read and validate a study file; raise :class:`StudyError` listing every problem.

    Parameters
    ----------
    path : path-like
        The TOML file.
    max_cases : int, optional
        Overrides ``study.max_cases`` (the CLI's ``--max-cases``).
    overrides : sequence of str
        ``key=value`` settings from the command line (:mod:`workbench.study.overrides`), applied
        before validation and recorded in :attr:`Study.overrides`; one that would change no case
        (a sweep axis or every model's ``by_model`` table sets the key) is a problem
        (:func:`~workbench.study.overrides.unapplied_overrides`).
    """
    from .overrides import apply_overrides, unapplied_overrides

    raw = apply_overrides(read_toml(path), overrides)
    study = parse_study(raw, source=str(Path(path)), max_cases=max_cases)
    if not overrides:
        return study
    idle = unapplied_overrides(overrides, study.sweep, study.base["solver"], study.models)
    if idle:
        raise StudyError([f"{study.path}: {p}" for p in idle])
    return replace(study, overrides=tuple(overrides))


def _parse_sections(raw: Mapping[str, Any]) -> tuple[dict[str, BaseModel], list[str], dict[str, BaseModel]]:
    """Unknown and missing sections, and every schema section validated (absent ones: defaults).

    Returns ``(sections, problems, repaired)``: ``repaired`` holds the failing sections validated
    without their failing keys (:func:`workbench.study.onepass.repair_section`), for the later checks.
    """
    from .onepass import repair_section

    problems: list[str] = []
    repaired: dict[str, BaseModel] = {}
    top_known = list(StudyFile.model_fields)
    for key in raw:
        if key not in top_known:
            problems.append(f"{key}: unknown section{suggest(key, top_known)}")
    for key in ("study", "robot"):
        if key not in raw:
            problems.append(f"{key}: missing section [{key}]")
    sections: dict[str, BaseModel] = {}
    for name, model in SECTION_MODELS.items():
        if name not in raw:
            if name != "study":
                sections[name] = model()
            continue
        if not isinstance(raw[name], dict):
            problems.append(f"{name}: must be a table [{name}], got {type(raw[name]).__name__}")
            continue
        try:
            sections[name] = model.model_validate(raw[name])
        except ValidationError as e:
            problems.extend(pydantic_problems(e, (name,), model))
            fixed = repair_section(model, raw[name], e)
            if fixed is not None:
                repaired[name] = fixed
    return sections, problems, repaired


def _check_models(sections: Mapping[str, BaseModel]) -> list[str]:
    """``study.models`` known and distinct; ``report.reference`` one of them."""
    from ..models import model_names

    st = sections.get("study")
    if st is None:
        return []
    known_models = model_names()
    problems = []
    for i, m in enumerate(st.models):
        if m not in known_models:
            problems.append(f"study.models[{i}]: unknown model {m!r}{suggest(m, list(known_models))}"
                            .replace("; known keys:", "; known models:"))
    known = [m for m in st.models if m in known_models]
    if len(set(known)) != len(known):
        problems.append("study.models: lists a model twice")
    rep = sections.get("report")
    if rep is not None and rep.reference is not None and rep.reference not in st.models and len(known) == len(st.models):
        problems.append(f"report.reference: {rep.reference!r} is not one of study.models ({', '.join(st.models)})")
    sol = sections.get("solver")
    for i, m in enumerate(getattr(sol, "error_estimate_exempt", None) or []):
        if m not in st.models:
            problems.append(f"solver.error_estimate_exempt[{i}]: {m!r} is not one of study.models ({', '.join(st.models)})")
    if sol is not None and sol.by_model:
        problems += by_model_problems(sol.by_model, st.models)
    return problems


def resolve_robot_table(rraw: Any) -> tuple[dict[str, Any] | None, dict[str, Any], list[str]]:
    """``[robot]`` -> ``(robot parameters of every case, preset defaults, problems)``.

    Preset form: ``{"preset": name, <every preset parameter>}`` and the preset's defaults;
    description form (no preset, or a data preset): the table as written and ``{}``
    (:mod:`workbench.robot.spec`; its problems name their key paths).  Public: the sweep loader and
    the calibration study (:mod:`workbench.measure.spec`) read ``[robot]`` through it.  Checked by
    ``tests/study/test_spec.py`` and ``tests/robot/test_spec_malformed.py``.
    """
    from ..robot.presets import preset_values
    from ..robot.spec import is_description, robot_problems

    if not isinstance(rraw, dict):
        problems = [f"robot: must be a table [robot], got {type(rraw).__name__}"] if rraw is not None else []
        return None, {}, problems
    if "sections" in rraw and "preset" not in rraw or isinstance(rraw.get("preset"), str) and is_description(rraw):
        problems = robot_problems(rraw, "robot")
        return (None if problems else dict(rraw)), {}, problems
    values, defaults, problems = preset_values(rraw, "robot")
    if values is None:
        return None, {}, problems
    return {"preset": rraw["preset"], **values}, defaults, problems


def _robot_check(robot: Mapping[str, Any]) -> tuple[dict[str, Any] | None, list[str]]:
    """The ``[robot]`` validator of a swept value (:func:`~workbench.study.sweep_checks.check_sweep`): the
    resolved table with the value applied, checked by :func:`resolve_robot_table` like the file's."""
    resolved, _, problems = resolve_robot_table(dict(robot))
    return resolved, problems


def _load_and_derived_rules(sections: Mapping[str, BaseModel], rraw: Any,
                            preset_defaults: Mapping[str, Any], raw_sweep: Any = None) -> list[str]:
    """The load's cross-field rules; ``derived.gravity_parameter`` (set or swept) against ``robot.gravity``."""
    problems = []
    load = sections.get("load")
    if load is not None:
        problems.extend(load_rules(load.model_dump(), "load"))
    derived = sections.get("derived")
    swept = set(sweep_keys(raw_sweep))
    gamma = (derived is not None and derived.gravity_parameter is not None) or "derived.gravity_parameter" in swept
    if gamma and isinstance(rraw, dict):
        where = "derived.gravity_parameter" if derived is not None and derived.gravity_parameter is not None \
            else 'sweep["derived.gravity_parameter"]'
        if "gravity" in rraw or "robot.gravity" in swept:
            other = "robot.gravity" if "gravity" in rraw else 'sweep["robot.gravity"]'
            problems.append(f"{where}: conflicts with {other} (gamma sets the gravity; set one of them)")
        if preset_defaults and "gravity" not in preset_defaults:
            problems.append(f"{where}: the preset has no 'gravity' parameter to derive")
    return problems


def _resolve_base(sections: Mapping[str, BaseModel], robot_base: dict[str, Any] | None,
                  scenario_base: dict[str, Any] | None) -> dict[str, dict[str, Any]] | None:
    """The base parameters of every case as plain data (``None`` when a part is invalid)."""
    if robot_base is None or not all(k in sections for k in ("load", "solver", "derived")):
        return None
    base = {
        "robot": robot_base,
        "load": sections["load"].model_dump(),
        # by_model, spring_link_axial, spring_link_richardson and warm_start only when set (keeps the case
        # ids of the studies without them)
        "solver": sections["solver"].model_dump(exclude=set(LIMIT_KEYS) | (
            set() if sections["solver"].by_model else {"by_model"}) | {
            k for k in ("spring_link_axial", "spring_link_richardson") if getattr(sections["solver"], k) is None} | (
            set() if sections["solver"].warm_start else {"warm_start"})),
        "derived": sections["derived"].model_dump(),
    }
    if scenario_base is not None:  # only when given: keeps case ids of scenario-free studies
        base["scenario"] = scenario_base
    return base


def _sensitivity_rules(rep: Any, base: dict[str, Any] | None, sweep: Mapping[str, Any]) -> list[str]:
    """``report.sensitivity`` keys are swept and set in their base section (the baseline value)."""
    if rep is None or base is None or not getattr(rep, "sensitivity", None):
        return []
    swept = set(sweep_keys(sweep))
    problems = []
    for i, key in enumerate(rep.sensitivity):
        section = str(key).partition(".")[0]
        if key not in swept:
            problems.append(f"report.sensitivity[{i}]: {key!r} is not a [sweep] key")
            continue
        try:  # a key path: the element of the base value (load.tensions[0])
            get_value(base, str(key))
        except KeyPathError:
            problems.append(f"report.sensitivity[{i}]: {key!r} needs its baseline value in [{section}]")
    return problems


def _drop_kind(raw: dict[str, Any], source: str) -> None:
    """``[study] kind``: ``"sweep"`` is this kind (dropped); any other value is the one problem of the file."""
    st = raw.get("study")
    if not isinstance(st, dict) or "kind" not in st:
        return
    from .. import registry

    if st["kind"] == "sweep":
        raw["study"] = {k: v for k, v in st.items() if k != "kind"}
        return
    raise StudyError([f"{source}: study.kind: unknown study kind {st['kind']!r}; known kinds: "
                      f"{', '.join(registry.table('kinds'))}"])


def _whole_file_problem(raw: Mapping[str, Any], source: str) -> None:
    """One line instead of many for a file that is empty or belongs to another study kind."""
    if not raw:
        raise StudyError([f"{source}: the file is empty (a study needs at least [study] and [robot])"])
    st = raw.get("study")
    if ("motions" in raw or "geometry" in raw) and not (isinstance(st, dict) and "kind" in st):
        raise StudyError([f"{source}: study.kind: missing; a file with [motions] / [geometry] is a series-parallel "
                          f"study: add kind = \"series_parallel\" to [study]"])


def _with_defaults(base: dict[str, dict[str, Any]], unset: set[str],
                   preset_defaults: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """``base`` with every key that had a problem back at its default (the case checks' view of the file)."""
    out = {sec: dict(d) for sec, d in base.items()}
    for key in unset:
        section, _, path = key.partition(".")
        name = path.split(".")[0].split("[")[0]  # a problem inside a value (robot.diameter[1]): the whole value
        if name not in out.get(section, {}):
            continue
        if section == "robot":
            out[section][name] = preset_defaults.get(name, out[section][name])
        elif section in SECTION_MODELS and name in SECTION_MODELS[section].model_fields:
            out[section][name] = SECTION_MODELS[section].model_fields[name].get_default(call_default_factory=True)
    return out


def parse_study(raw: Mapping[str, Any], *, source: str = "<study>", max_cases: int | None = None,
                run_models: bool = True) -> Study:
    """Validate an already parsed study mapping (see :func:`load_study`).

    Every problem of the file in one pass: each stage runs on what the earlier ones left valid
    (:mod:`workbench.study.onepass`), so a schema error in one table does not hide the sweep or
    case checks of the others.  ``run_models=False``: the study kind computes its rows with its own
    tasks, not through the models' ``run(robot, load, options)``, so their declared capabilities
    are not checked.
    """
    from ..models import model_names
    from .onepass import knock_on, problem_keys, valid_sweep

    raw = dict(raw)
    _whole_file_problem(raw, source)
    _drop_kind(raw, source)
    sections, problems, repaired = _parse_sections(raw)
    usable = {**repaired, **sections}  # the valid sections and the valid part of the others
    problems += _check_models(usable)
    if not run_models and "solver" in usable and usable["solver"].by_model:
        problems.append("solver.by_model: this study kind computes its rows with its own tasks, not with the models' "
                        "run(); per-model settings would not apply (set the options in [solver])")
    robot_base, preset_defaults, robot_problems = resolve_robot_table(raw.get("robot"))
    problems += robot_problems
    unset = problem_keys(problems)
    later = _load_and_derived_rules(usable, raw.get("robot"), preset_defaults, raw.get("sweep"))
    scenario_base, scenario_problems = check_scenario(raw.get("scenario"))
    later += scenario_problems
    base = _resolve_base(usable, robot_base, scenario_base)
    sweep: dict[str, Any] = {}
    sweep_problems: list[str] = []
    if "sweep" in usable and base is not None:
        models = tuple(usable["study"].models) if "study" in usable else ()
        sweep, sweep_problems = check_sweep(usable["sweep"], base, _robot_check, models)
        if raw.get("scenario") is not None and scenario_base is None:  # knock-on errors of a bad [scenario]
            sweep_problems = [p for p in sweep_problems if '["scenario.' not in p.partition(": ")[0]]
        later += sweep_problems
    later += _sensitivity_rules(usable.get("report"), base, sweep)
    st = usable.get("study")
    report = usable["report"].model_dump(exclude_defaults=True) if "report" in usable else None
    scenario_ok = raw.get("scenario") is None or scenario_base is not None  # else its keys are unknown: knock-ons
    if base is not None and report is not None and scenario_ok:
        later += check_report(report, known_paths(base) + sweep_keys(sweep))  # element axes: p.load.tensions[0]
    problems += [p for p in later if not knock_on(p, unset)]
    unset = problem_keys(problems)
    whole = unset & {"robot", "load", "solver", "derived", "scenario"}  # a table as a whole is wrong
    if base is None or "solver" not in usable or not scenario_ok or whole:
        raise StudyError([f"{source}: {p}" for p in collapse_indexed(problems)] or [f"{source}: invalid study"])
    solver = usable["solver"]
    models = tuple(st.models) if st is not None else ()
    study = Study(
        path=source, name=st.name if st else "?", description=st.description if st else "",
        seed=st.seed if st else 0, models=tuple(m for m in models if m in model_names()),
        max_cases=int(max_cases if max_cases is not None else (st.max_cases if st else DEFAULT_MAX_CASES)),
        base=base, sweep=sweep, report=report or {},
        limits=CaseLimits(solver.max_case_seconds, solver.max_case_memory),
    )
    # the cases' view: keys with a problem at their defaults, sweep axes with a problem left out
    checked = replace(study, base=_with_defaults(base, unset, preset_defaults),
                      sweep=valid_sweep(sweep, sweep_problems)) if problems else study
    try:  # size limit, duplicates, a dry build and the models' capabilities of every case (time-bounded)
        check = check_cases(checked, source, run_models=run_models)
    except StudyError as e:  # reported with the file's other problems, in one pass
        if not problems:
            raise
        own = [p[len(source) + 2:] if p.startswith(f"{source}: ") else p for p in e.problems]
        if checked.sweep != sweep:  # case numbers of the reduced sweep are not the file's: show the values only
            own = [re.sub(r"\bcase \d+: ", "", p) for p in own]
        problems += [p for p in own if not knock_on(p, unset)]
        check = None
    if problems or st is None:
        raise StudyError([f"{source}: {p}" for p in collapse_indexed(problems)] or [f"{source}: invalid study"])
    return replace(study, models=models, notes=(check.note,) if check.note else (),
                   warnings=tuple(f"{source}: {w}" for w in check.warnings))
