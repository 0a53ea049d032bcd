"""Study files: TOML -> validated :class:`Study`, every problem reported before any simulation.

A study file is TOML; all quantities are SI (m, kg, s, N, Pa, rad).  Unknown keys are errors
(with a "did you mean" suggestion), types are strict (a string is not a number, a float is
not an integer), NaN/inf are rejected, and physical sanity is checked (non-positive lengths,
stiffnesses, offsets; negative densities, masses, tensions; empty sweep axes; sweeps larger
than ``study.max_cases``).  :func:`load_study` collects *all* problems and raises one
:class:`StudyError` whose ``problems`` are one line each::

    studies/bad.toml: robot.lenght: unknown key; did you mean 'length'?
    studies/bad.toml: sweep.product["robot.length"][1]: must be > 0 [m], got -0.5

Annotated example (``studies/example.toml`` is a runnable one)::

    [study]
    name = "example"            # output folder data/<name>, report reports/<name>; [A-Za-z0-9_-]
    description = "CC vs ANCF"  # free text
    seed = 1                    # seeds the random / latin_hypercube samples (int >= 0)
    models = ["cc", "ancf"]     # names from workbench.models.MODEL_NAMES
    max_cases = 5000            # refuse sweeps with more cases (the CLI --max-cases overrides)

    [robot]                     # a preset from workbench.robot.presets + parameter overrides
    preset = "steel_rod"        # every other key must be a parameter of the preset, with the
    length = 0.8                # type of its default (float parameters accept integers) [m]
    diameter = 6e-3             # [m]

    [load]                      # how the robot is driven (workbench.robot.LoadCase)
    mode = "tension"            # "tension" (force-controlled tendons) | "length" (motor strokes)
    bend_angle = 1.0            # [rad] CC command: total bending angle kappa*L_j per section
                                #   (scalar for all sections or a list, one per section),
                                #   translated by workbench.models.cc.actuation_from_arc; or
    # tensions = [5.0, 0.0]       # [N] explicit tension per tendon (mode = "tension"), or
    # length_changes = [-1e-3, 0] # [m] explicit free-length change per tendon (mode = "length")
    bend_plane = 0.0            # [rad] bending plane phi of the CC command (scalar or per section)
    pretension = 0.0            # [N] length mode: tension of every tendon when straight
    tip_force = [0.0, 0.0, 0.0] # [N] base frame
    tip_torque = [0.0, 0.0, 0.0]# [N m] base frame
    analysis = "static"         # "static" | "dynamic"
    duration = 0.0              # [s] simulated time (dynamic)
    ramp_time = 1.0             # [s] default constant-speed ramp of every tendon (dynamic)
    # start_delays = [0.0, 0.3] # [s] per tendon: when each motor starts (dynamic)
    # ramp_durations = [1, 1]   # [s] per tendon ramp durations (dynamic)

    [solver]                    # fields of workbench.models.SolverOptions
    n_elements = 16
    n_stations = 33
    tendon_model = "continuum"  # "continuum" | "eyelets"

    [scenario]                  # optional: per-case tendon commands from a registered pure
    name = "wire_delay"         #   function (workbench.study.scenarios.SCENARIOS); the other
    delay = 3.0                 #   keys are its keyword parameters (typed by their defaults),
                                #   sweepable as "scenario.<key>"; its returned [load] fields
                                #   (length_changes, start_delays, ...) replace the [load] ones

    [derived]                   # optional dimensionless parameters resolved per case
    gravity_parameter = 1.0     # gamma = q L^3 / EI with q = backbone weight per length;
                                # sets the preset's gravity to g = gamma EI / (m' L^3)
                                # (uniform robots only; do not also set robot.gravity)

    [sweep]                     # axes: dotted keys into robot / load / solver / derived / scenario
    product = { "load.bend_angle" = [0.5, 1.0, 2.0], "robot.length" = [0.5, 0.8] }  # grid
    zip = { "solver.n_elements" = [8, 16], "solver.n_stations" = [17, 33] }  # paired, equal length
    cases = [ { "load.pretension" = 1.0 }, { "load.pretension" = 2.0 } ]     # explicit list
    random = { n = 4, "robot.tendon_offset" = { low = 0.01, high = 0.03 } }  # uniform samples
    # latin_hypercube = { n = 8, "load.bend_plane" = { low = 0.0, high = 3.14 } }

    [report]                    # optional hints for workbench.report (not in the config hash)
    axes = ["kappaL", "gamma"]  # columns to plot against (default: the sweep axes)
    reference = "cc"            # reference model of the comparison (one of study.models)
    # derived = { d_over_L = "`p.robot.tendon_offset` / robot_length" }  # pandas eval
    # labels = { gamma = "gamma = q L^3 / EI" }

Sweep semantics: every ``product`` axis, the ``zip`` group, the ``cases`` list, the ``random``
samples and the ``latin_hypercube`` samples are *blocks*; the cases are the Cartesian product of
the blocks (in that order), each case merging one entry of every block (above: 3*2*2*2*4 = 96
cases).  A key may appear in one block only.  Random and Latin-hypercube samples are drawn
with ``numpy.random.default_rng(SeedSequence([seed, 0 or 1]))`` over the keys in sorted order;
``low`` and ``high`` both integers draws integers in [low, high].  Without a ``[sweep]`` the
study is one case.
"""

from __future__ import annotations

import difflib
import hashlib
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, Mapping

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from .params import canonical_json

__all__ = [
    "Study",
    "StudyError",
    "load_study",
    "parse_study",
    "DEFAULT_MAX_CASES",
    "SWEEP_SECTIONS",
]

DEFAULT_MAX_CASES = 5000
SWEEP_SECTIONS = ("robot", "load", "solver", "derived", "scenario")


class StudyError(ValueError):
    """A study file is invalid; ``problems`` holds one line per problem."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        super().__init__("\n".join(self.problems))


# ---------------------------------------------------------------------------------------
# pydantic sections (strict: no coercion, unknown keys forbidden, no NaN/inf)
# ---------------------------------------------------------------------------------------
_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)


class StudySection(BaseModel):
    model_config = _CFG
    name: str = Field(pattern=r"^[A-Za-z0-9_-]+$", min_length=1, max_length=100)
    description: str = ""
    seed: int = Field(default=0, ge=0)
    models: list[str] = Field(min_length=1)
    max_cases: int = Field(default=DEFAULT_MAX_CASES, gt=0)


class LoadSection(BaseModel):
    model_config = _CFG
    mode: Literal["tension", "length"] = "tension"
    bend_angle: float | list[float] | None = None
    bend_plane: float | list[float] = 0.0
    tensions: list[float] | None = None
    length_changes: list[float] | None = None
    pretension: float = Field(default=0.0, ge=0.0)
    tip_force: list[float] = Field(default_factory=lambda: [0.0, 0.0, 0.0], min_length=3, max_length=3)
    tip_torque: list[float] = Field(default_factory=lambda: [0.0, 0.0, 0.0], min_length=3, max_length=3)
    analysis: Literal["static", "dynamic"] = "static"
    duration: float = Field(default=0.0, ge=0.0)
    ramp_time: float = Field(default=1.0, ge=0.0)
    start_delays: list[float] | None = None
    ramp_durations: list[float] | None = None


class SolverSection(BaseModel):
    """Mirror of :class:`workbench.models.SolverOptions` (a test checks the fields agree)."""

    model_config = _CFG
    n_elements: int = Field(default=16, ge=1)
    tendon_model: Literal["continuum", "eyelets"] = "continuum"
    n_stations: int = Field(default=33, ge=2)
    newton_tolerance: float = Field(default=1e-9, gt=0.0)
    max_load_steps: int = Field(default=200, ge=1)
    time_step: float = Field(default=2e-3, gt=0.0)
    damping: float = Field(default=0.0, ge=0.0)
    spectral_radius: float = Field(default=0.8, ge=0.0, le=1.0)


class DerivedSection(BaseModel):
    model_config = _CFG
    gravity_parameter: float | None = Field(default=None, ge=0.0)


class SweepSection(BaseModel):
    model_config = _CFG
    product: dict[str, list[Any]] = Field(default_factory=dict)
    zip: dict[str, list[Any]] = Field(default_factory=dict)
    cases: list[dict[str, Any]] = Field(default_factory=list)
    random: dict[str, Any] | None = None
    latin_hypercube: dict[str, Any] | None = None


class ReportSection(BaseModel):
    """Presentation hints for ``workbench.report`` (not part of the config hash)."""

    model_config = _CFG
    axes: list[str] = Field(default_factory=list)
    derived: dict[str, str] = Field(default_factory=dict)
    labels: dict[str, str] = Field(default_factory=dict)
    reference: str | None = None


class StudyFile(BaseModel):
    model_config = _CFG
    study: StudySection
    robot: dict[str, Any]
    load: LoadSection = Field(default_factory=LoadSection)
    solver: SolverSection = Field(default_factory=SolverSection)
    derived: DerivedSection = Field(default_factory=DerivedSection)
    sweep: SweepSection = Field(default_factory=SweepSection)
    report: ReportSection = Field(default_factory=ReportSection)
    scenario: dict[str, Any] | None = None


_SECTION_MODELS: dict[str, type[BaseModel]] = {
    "study": StudySection,
    "load": LoadSection,
    "solver": SolverSection,
    "derived": DerivedSection,
    "sweep": SweepSection,
    "report": ReportSection,
}

# Units per key, for messages.
_UNITS = {
    "bend_angle": "rad", "bend_plane": "rad", "tensions": "N", "length_changes": "m",
    "pretension": "N", "tip_force": "N", "tip_torque": "N m", "duration": "s", "ramp_time": "s",
    "start_delays": "s", "ramp_durations": "s", "time_step": "s",
}

# Load list fields whose entries must be >= 0.
_NONNEG_LIST_FIELDS = ("tensions", "start_delays", "ramp_durations")


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

    def resolved(self) -> dict[str, Any]:
        """Plain-data resolved spec (what the manifest records)."""
        return {
            "study": {
                "name": self.name, "description": self.description, "seed": self.seed,
                "models": list(self.models), "max_cases": self.max_cases,
            },
            **{k: dict(v) for k, v in self.base.items()},
            "sweep": self.sweep,
            "report": self.report,
        }

    @property
    def config_hash(self) -> str:
        """Hash of everything that changes results (not name/description/max_cases)."""
        payload = {"models": list(self.models), "seed": self.seed, "base": self.base, "sweep": self.sweep}
        return hashlib.sha256(canonical_json(payload).encode()).hexdigest()[:16]


# ---------------------------------------------------------------------------------------
# messages
# ---------------------------------------------------------------------------------------
def _suggest(key: str, known: list[str]) -> str:
    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    if close:
        return f"; did you mean {close[0]!r}?"
    return f"; known keys: {', '.join(sorted(known))}" if known else ""


def _fmt_loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        elif "." in str(part):
            out += f'["{part}"]'
        else:
            out += ("." if out else "") + str(part)
    return out


def _num(v: Any) -> str:
    return repr(v) if not isinstance(v, float) else f"{v:g}"


def _translate(err: dict, prefix: tuple, model: type[BaseModel] | None) -> str:
    """One pydantic error -> 'key.path: reason'."""
    loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and p in ("float", "list[float]", "list", "int", "str", "none")))
    # pydantic adds union member tags to loc ("float", "list[float]"); stripped above
    full = prefix + loc
    typ, inp = err["type"], err.get("input")
    key = str(loc[-1]) if loc else ""
    unit = _UNITS.get(key) or next((_UNITS[str(p)] for p in reversed(loc) if str(p) in _UNITS), None)
    u = f" [{unit}]" if unit else ""
    if typ == "extra_forbidden":
        known = _known_keys(model, loc[:-1])
        return f"{_fmt_loc(full)}: unknown key{_suggest(key, known)}"
    if typ == "missing":
        if len(full) == 1:
            return f"{_fmt_loc(full)}: missing section [{full[0]}]"
        return f"{_fmt_loc(full)}: missing required key"
    if typ == "finite_number":
        return f"{_fmt_loc(full)}: must be finite{u}, got {inp}"
    if typ in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        ctx = err.get("ctx", {})
        op, bound = {"greater_than": (">", "gt"), "greater_than_equal": (">=", "ge"),
                     "less_than": ("<", "lt"), "less_than_equal": ("<=", "le")}[typ]
        return f"{_fmt_loc(full)}: must be {op} {ctx.get(bound)}{u}, got {_num(inp)}"
    if typ == "literal_error":
        return f"{_fmt_loc(full)}: must be {err['ctx']['expected']}, got {inp!r}"
    if typ in ("too_short", "too_long"):
        return f"{_fmt_loc(full)}: {err['msg'].lower()}"
    if typ == "string_pattern_mismatch":
        return f"{_fmt_loc(full)}: must match {err['ctx']['pattern']} (letters, digits, '_' and '-'), got {inp!r}"
    if typ == "value_error" and "error" in err.get("ctx", {}):  # a validator's own message
        return f"{_fmt_loc(full)}: {err['ctx']['error']}"
    return f"{_fmt_loc(full)}: {err['msg'][0].lower() + err['msg'][1:]}, got {type(inp).__name__} {inp!r}"


def _known_keys(model: type[BaseModel] | None, loc: tuple) -> list[str]:
    m = model
    for part in loc:
        if m is None or isinstance(part, int):
            return []
        f = m.model_fields.get(str(part))
        if f is None:
            return []
        ann = f.annotation
        m = ann if isinstance(ann, type) and issubclass(ann, BaseModel) else None
    return list(m.model_fields) if m is not None else []


def _pydantic_problems(exc: ValidationError, prefix: tuple, model: type[BaseModel]) -> list[str]:
    seen: dict[tuple, str] = {}
    for e in exc.errors():
        # a value failing every member of a union produces one error per member: keep one,
        # preferring the scalar member's (more specific) message
        loc = tuple(p for p in e["loc"] if not (isinstance(p, str) and p in ("float", "list[float]", "list", "int", "str", "none")))
        if loc in seen and e["type"].endswith("_type"):
            continue
        seen[loc] = _translate(e, prefix, model)
    return list(seen.values())


# ---------------------------------------------------------------------------------------
# robot parameters: typed by the preset's defaults, physical sanity by name
# ---------------------------------------------------------------------------------------
_POSITIVE_PAT = re.compile(r"(length|diameter|modulus|stiffness|offset|radius|thickness|^n_|_count$|per_section$|^k_|_per_disk$)")
_NONNEG_PAT = re.compile(r"(density|mass|gravity|spacing|friction)")
_ROBOT_UNITS = {"length": "m", "diameter": "m", "offset": "m", "modulus": "Pa", "stiffness": "N",
                "density": "kg/m^3", "mass": "kg", "gravity": "m/s^2", "angle": "rad", "radius": "m"}


def _robot_unit(key: str) -> str:
    for k, u in _ROBOT_UNITS.items():
        if k in key:
            return f" [{u}]"
    return ""


def check_robot_value(key: str, value: Any, default: Any) -> tuple[Any, str | None]:
    """Check one robot override against the preset default's type and physical sanity.

    Returns ``(coerced_value, problem_or_None)``.
    """
    u = _robot_unit(key)
    if isinstance(default, bool):
        if not isinstance(value, bool):
            return value, f"must be a boolean (true/false), got {type(value).__name__} {value!r}"
        return value, None
    if isinstance(default, int) and not isinstance(default, bool):
        if isinstance(value, bool) or not isinstance(value, int):
            return value, f"must be an integer, got {type(value).__name__} {value!r}"
        if _POSITIVE_PAT.search(key) and value < 1:
            return value, f"must be >= 1, got {value}"
        if value < 0:
            return value, f"must be >= 0, got {value}"
        return value, None
    if isinstance(default, float) or default is None:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            if default is None and isinstance(value, (str, list)):
                return value, None
            return value, f"must be a number{u}, got {type(value).__name__} {value!r}"
        v = float(value)
        if not math.isfinite(v):
            return v, f"must be finite{u}, got {v}"
        if _POSITIVE_PAT.search(key) and v <= 0:
            return v, f"must be > 0{u}, got {_num(v)}"
        if _NONNEG_PAT.search(key) and v < 0:
            return v, f"must be >= 0{u}, got {_num(v)}"
        return v, None
    if isinstance(default, str):
        if not isinstance(value, str):
            return value, f"must be a string, got {type(value).__name__} {value!r}"
        return value, None
    return value, None


# ---------------------------------------------------------------------------------------
# loading
# ---------------------------------------------------------------------------------------
def load_study(path: str | Path, *, max_cases: int | None = None) -> Study:
    """Read and validate a study file; raise :class:`StudyError` listing every problem.

    Parameters
    ----------
    path : path-like
        The TOML file.
    max_cases : int, optional
        Overrides ``study.max_cases`` (the CLI's ``--max-cases``).
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as e:
        raise StudyError([f"{p}: cannot read file: {e.strerror or e}"]) from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise StudyError([f"{p}: TOML syntax error: {e}"]) from None
    return parse_study(raw, source=str(p), max_cases=max_cases)


def parse_study(raw: Mapping[str, Any], *, source: str = "<study>", max_cases: int | None = None) -> Study:
    """Validate an already parsed study mapping (see :func:`load_study`)."""
    from ..models import MODEL_NAMES
    from ..robot.presets import PRESET_NAMES, preset_parameters

    problems: list[str] = []
    raw = dict(raw)

    top_known = list(StudyFile.model_fields)
    for key in raw:
        if key not in top_known:
            problems.append(f"{key}: unknown section{_suggest(key, top_known)}")
    for key in ("study", "robot"):
        if key not in raw:
            problems.append(f"{key}: missing section [{key}]")

    sections: dict[str, Any] = {}
    for name, model in _SECTION_MODELS.items():
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
            problems.extend(_pydantic_problems(e, (name,), model))

    st: StudySection | None = sections.get("study")
    if st is not None:
        for i, m in enumerate(st.models):
            if m not in MODEL_NAMES:
                problems.append(f"study.models[{i}]: unknown model {m!r}{_suggest(m, list(MODEL_NAMES))}"
                                .replace("; known keys:", "; known models:"))
        if len(set(st.models)) != len(st.models):
            problems.append("study.models: lists a model twice")
        rep = sections.get("report")
        if rep is not None and rep.reference is not None and rep.reference not in st.models:
            problems.append(f"report.reference: {rep.reference!r} is not one of study.models ({', '.join(st.models)})")

    # robot: preset + overrides
    robot_base: dict[str, Any] | None = None
    preset_defaults: dict[str, Any] = {}
    rraw = raw.get("robot")
    if isinstance(rraw, dict):
        preset = rraw.get("preset")
        if preset is None:
            problems.append("robot.preset: missing required key (one of: " + ", ".join(PRESET_NAMES) + ")")
        elif not isinstance(preset, str):
            problems.append(f"robot.preset: must be a string, got {type(preset).__name__} {preset!r}")
        elif preset not in PRESET_NAMES:
            problems.append(f"robot.preset: unknown preset {preset!r}{_suggest(preset, list(PRESET_NAMES))}"
                            .replace("; known keys:", "; known presets:"))
        else:
            try:
                preset_defaults = preset_parameters(preset)
            except ImportError as e:
                problems.append(f"robot.preset: preset {preset!r} is not available in this installation ({e})")
            else:
                robot_base = {"preset": preset}
                for k, v in preset_defaults.items():
                    robot_base[k] = v
                for k, v in rraw.items():
                    if k == "preset":
                        continue
                    if k not in preset_defaults:
                        problems.append(f"robot.{k}: unknown parameter of preset {preset!r}"
                                        f"{_suggest(k, list(preset_defaults))}")
                        continue
                    cv, prob = check_robot_value(k, v, preset_defaults[k])
                    if prob:
                        problems.append(f"robot.{k}: {prob}")
                    else:
                        robot_base[k] = cv
    elif rraw is not None:
        problems.append(f"robot: must be a table [robot], got {type(rraw).__name__}")

    load: LoadSection | None = sections.get("load")
    if load is not None:
        problems.extend(_load_rules(load.model_dump(), "load"))
    derived: DerivedSection | None = sections.get("derived")
    if derived is not None and derived.gravity_parameter is not None and isinstance(rraw, dict):
        if "gravity" in rraw:
            problems.append("derived.gravity_parameter: conflicts with robot.gravity (set one of them)")
        if preset_defaults and "gravity" not in preset_defaults:
            problems.append("derived.gravity_parameter: the preset has no 'gravity' parameter to derive")

    scenario_base, scenario_problems = _check_scenario(raw.get("scenario"))
    problems.extend(scenario_problems)

    base: dict[str, dict[str, Any]] | None = None
    if robot_base is not None and all(k in sections for k in ("load", "solver", "derived")):
        base = {
            "robot": robot_base,
            "load": sections["load"].model_dump(),
            "solver": sections["solver"].model_dump(),
            "derived": sections["derived"].model_dump(),
        }
        if scenario_base is not None:  # only when given: keeps case ids of scenario-free studies
            base["scenario"] = scenario_base

    sweep_plain: dict[str, Any] = {}
    if "sweep" in sections and base is not None:
        sweep_plain, sweep_problems = _check_sweep(sections["sweep"], base, preset_defaults)
        problems.extend(sweep_problems)

    if problems or st is None or base is None:
        raise StudyError([f"{source}: {p}" for p in problems] or [f"{source}: invalid study"])

    study = Study(
        path=source, name=st.name, description=st.description, seed=st.seed,
        models=tuple(st.models), max_cases=int(max_cases if max_cases is not None else st.max_cases),
        base=base, sweep=sweep_plain, report=sections["report"].model_dump(exclude_defaults=True),
    )
    # size and per-case checks need the expansion (pure, cheap)
    from .expand import count_cases, expand

    n = count_cases(study)
    if n > study.max_cases:
        raise StudyError([f"{source}: sweep: {n} cases exceed the limit max_cases = {study.max_cases} "
                          f"(raise study.max_cases or --max-cases)"])
    cases = expand(study)
    case_problems: list[str] = []
    seen: dict[str, int] = {}
    for c in cases:
        if c.case_id in seen:
            case_problems.append(f"sweep: cases {seen[c.case_id]} and {c.index} have identical parameters "
                                 f"({canonical_json(c.swept)})")
            continue
        seen[c.case_id] = c.index
        for m in _case_rules(c.params, study):
            key, _, reason = m.partition(": ")
            where = f" (case {c.index}: {canonical_json(c.swept)})" if c.swept else ""
            case_problems.append(f"{key}{where}: {reason}")
        if len(case_problems) > 20:
            case_problems.append("... (further case problems not listed)")
            break
    if case_problems:
        raise StudyError([f"{source}: {p}" for p in case_problems])
    return study


def _check_scenario(raw: Any) -> tuple[dict[str, Any] | None, list[str]]:
    """Resolve ``[scenario]``: a registered name plus typed parameters (defaults filled in)."""
    from .scenarios import SCENARIOS, scenario_parameters

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
        return None, [f"scenario.name: unknown scenario {name!r}{_suggest(name, sorted(SCENARIOS))}"
                      .replace("; known keys:", "; known scenarios:")]
    defaults = scenario_parameters(name)
    out: dict[str, Any] = {"name": name, **defaults}
    problems = []
    for k, v in raw.items():
        if k == "name":
            continue
        if k not in defaults:
            problems.append(f"scenario.{k}: unknown parameter of scenario {name!r}{_suggest(k, list(defaults))}")
            continue
        cv, prob = check_robot_value(k, v, defaults[k])
        if prob:
            problems.append(f"scenario.{k}: {prob}")
        else:
            out[k] = cv
    return out, problems


def _load_rules(load: dict[str, Any], where: str) -> list[str]:
    """Cross-field and element-wise load checks (structural, robot-independent)."""
    out = []
    for name in _NONNEG_LIST_FIELDS:
        vals = load.get(name)
        if vals is not None:
            for i, v in enumerate(vals):
                if v < 0:
                    out.append(f"{where}.{name}[{i}]: must be >= 0 [{_UNITS[name]}], got {_num(v)}")
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
        out.append(f"{where}.duration: must be > 0 [s] for a dynamic analysis, got {_num(load.get('duration'))}")
    for name in ("bend_angle", "bend_plane"):
        if isinstance(load.get(name), list) and len(load[name]) == 0:
            out.append(f"{where}.{name}: must not be an empty list")
    return out


def _case_rules(params: dict[str, Any], study: Study) -> list[str]:
    """Checks of one resolved case that need the robot (tendon counts, section counts)."""
    from ..models.result import SolverOptions
    from .evaluate import build_robot

    out = []
    try:
        robot = build_robot(params["robot"], params["derived"])
    except Exception as e:  # noqa: BLE001 - every build failure is a user input problem here
        return [f"robot: {e}"]
    load = params["load"]
    if params.get("scenario"):
        from .scenarios import load_with_scenario

        try:
            load = load_with_scenario(robot, load, params["scenario"])
        except Exception as e:  # noqa: BLE001 - an infeasible scenario is an input problem
            return [f"scenario: {e}"]
        out.extend(_load_rules(load, "load (with scenario)"))
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
    try:
        SolverOptions(**params["solver"])
    except (TypeError, ValueError) as e:
        out.append(f"solver: {e}")
    if not out:
        # dry-build the load case (tendon commands from the CC arc command): infeasible
        # commands are input errors, reported before anything runs
        from .evaluate import build_load

        try:
            build_load(robot, load)
        except ImportError:
            pass  # workbench.models.cc not installed: checked when the case runs
        except Exception as e:  # noqa: BLE001
            out.append(f"load: {e}")
    return out


# ---------------------------------------------------------------------------------------
# sweep checks
# ---------------------------------------------------------------------------------------
def _known_paths(base: dict[str, dict[str, Any]]) -> list[str]:
    return [f"{s}.{k}" for s in SWEEP_SECTIONS for k in base.get(s, {})
            if not (s == "robot" and k == "preset") and not (s == "scenario" and k == "name")]


def check_override(path: str, value: Any, base: dict[str, dict[str, Any]],
                   preset_defaults: Mapping[str, Any]) -> tuple[Any, str | None]:
    """Validate one swept value at dotted ``path``; returns ``(coerced, problem_or_None)``."""
    section, _, key = path.partition(".")
    if section == "robot":
        return check_robot_value(key, value, preset_defaults[key])
    if section == "scenario":
        from .scenarios import scenario_parameters

        return check_robot_value(key, value, scenario_parameters(base["scenario"]["name"])[key])
    model = _SECTION_MODELS[section]
    data = dict(base[section])
    data[key] = value
    try:
        validated = model.model_validate(data)
    except ValidationError as e:
        probs = [p.split(": ", 1)[1] for p in _pydantic_problems(e, (section,), model)]
        return value, "; ".join(probs)
    if section == "load":
        probs = _load_rules(validated.model_dump(), "load")
        if probs:
            return value, "; ".join(probs)
    return getattr(validated, key), None


def _check_sweep(sw: SweepSection, base: dict[str, dict[str, Any]],
                 preset_defaults: Mapping[str, Any]) -> tuple[dict[str, Any], list[str]]:
    problems: list[str] = []
    known = _known_paths(base)
    owner: dict[str, str] = {}
    out: dict[str, Any] = {}

    def check_path(path: str, where: str) -> bool:
        if path == "robot.preset":
            problems.append(f'{where}["robot.preset"]: the preset cannot be swept (one study per preset)')
            return False
        if path == "scenario.name":
            problems.append(f'{where}["scenario.name"]: the scenario cannot be swept (one study per scenario)')
            return False
        if path not in known:
            section = path.partition(".")[0]
            if section not in SWEEP_SECTIONS:
                problems.append(f'{where}["{path}"]: unknown axis; axes are dotted keys into '
                                f"{', '.join(SWEEP_SECTIONS)}{_suggest(path, known)}")
            else:
                problems.append(f'{where}["{path}"]: unknown axis{_suggest(path, known)}')
            return False
        if path in owner and owner[path] != where:
            problems.append(f'{where}["{path}"]: already swept in {owner[path]} (a key may appear in one block only)')
            return False
        owner[path] = where
        return True

    def check_values(path: str, values: list[Any], where: str) -> list[Any]:
        res = []
        for i, v in enumerate(values):
            cv, prob = check_override(path, v, base, preset_defaults)
            if prob:
                problems.append(f'{where}["{path}"][{i}]: {prob}')
            res.append(cv)
        return res

    if sw.product:
        out["product"] = {}
        for path, values in sw.product.items():
            if not check_path(path, "sweep.product"):
                continue
            if not values:
                problems.append(f'sweep.product["{path}"]: empty axis (give at least one value)')
                continue
            out["product"][path] = check_values(path, values, "sweep.product")
    if sw.zip:
        out["zip"] = {}
        lengths = {p: len(v) for p, v in sw.zip.items()}
        if len(set(lengths.values())) > 1:
            problems.append("sweep.zip: paired axes must have equal lengths, got "
                            + ", ".join(f"{p}: {n}" for p, n in lengths.items()))
        for path, values in sw.zip.items():
            if not check_path(path, "sweep.zip"):
                continue
            if not values:
                problems.append(f'sweep.zip["{path}"]: empty axis (give at least one value)')
                continue
            out["zip"][path] = check_values(path, values, "sweep.zip")
    if "cases" in sw.model_fields_set:
        if not sw.cases:
            problems.append("sweep.cases: empty list (give at least one case or remove the key)")
        out["cases"] = []
        for i, case in enumerate(sw.cases):
            if not case:
                problems.append(f"sweep.cases[{i}]: empty case")
            entry = {}
            for path, v in case.items():
                if not check_path(path, "sweep.cases"):
                    continue
                cv, prob = check_override(path, v, base, preset_defaults)
                if prob:
                    problems.append(f'sweep.cases[{i}]["{path}"]: {prob}')
                entry[path] = cv
            out["cases"].append(entry)
        if len({frozenset(c) for c in sw.cases}) > 1:
            problems.append("sweep.cases: every case must set the same keys")
    for block in ("random", "latin_hypercube"):
        spec = getattr(sw, block)
        if spec is None:
            continue
        where = f"sweep.{block}"
        n = spec.get("n")
        if n is None:
            problems.append(f"{where}.n: missing required key (number of samples)")
        elif isinstance(n, bool) or not isinstance(n, int) or n < 1:
            problems.append(f"{where}.n: must be an integer >= 1, got {n!r}")
        axes = {k: v for k, v in spec.items() if k != "n"}
        if not axes:
            problems.append(f"{where}: no axes (add e.g. \"robot.length\" = {{low = 0.5, high = 1.0}})")
        clean = {}
        for path, rng in axes.items():
            if not check_path(path, where):
                continue
            if not isinstance(rng, dict):
                problems.append(f'{where}["{path}"]: must be a table {{low = ..., high = ...}}, got {type(rng).__name__}')
                continue
            extra = sorted(set(rng) - {"low", "high"})
            for k in extra:
                problems.append(f'{where}["{path}"].{k}: unknown key{_suggest(k, ["low", "high"])}')
            if "low" not in rng or "high" not in rng:
                problems.append(f'{where}["{path}"]: needs both low and high')
                continue
            lo, hi = rng["low"], rng["high"]
            ok = True
            for nm, v in (("low", lo), ("high", hi)):
                if isinstance(v, bool) or not isinstance(v, (int, float)):
                    problems.append(f'{where}["{path}"].{nm}: must be a number, got {type(v).__name__} {v!r}')
                    ok = False
                    continue
                cv, prob = check_override(path, v, base, preset_defaults)
                if prob:
                    problems.append(f'{where}["{path}"].{nm}: {prob}')
                    ok = False
            if ok and not lo < hi:
                problems.append(f'{where}["{path}"]: low must be < high, got low = {_num(lo)}, high = {_num(hi)}')
                ok = False
            if ok:
                integer = isinstance(lo, int) and isinstance(hi, int)
                if not integer:
                    # an integer parameter cannot take float samples
                    _, prob = check_override(path, (lo + hi) / 2.0, base, preset_defaults)
                    if prob:
                        problems.append(f'{where}["{path}"]: {prob} (give integer low/high)')
                        continue
                clean[path] = {"low": lo, "high": hi}
        out[block] = {"n": n, **clean}
    return out, problems
