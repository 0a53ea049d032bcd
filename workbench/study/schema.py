"""The schema of sweep-study files: one strict pydantic model per TOML section.

Strict means no coercion (a string is not a number, a float is not an integer), unknown keys
forbidden and NaN/inf rejected; :func:`workbench.study.messages.pydantic_problems` turns the
errors into one line each.  ``[robot]`` and ``[scenario]`` are free tables here: their keys are
typed by the preset's / scenario's defaults (:mod:`workbench.study.checks`).  The format
itself is described in ``docs/study-format.md``.

Checked by ``tests/study/test_spec.py`` (``SolverSection`` mirrors
:class:`workbench.models.SolverOptions`; every bad config's message).
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

__all__ = [
    "DEFAULT_MAX_CASES", "DEFAULT_MAX_CASE_SECONDS", "SAMPLED_BLOCKS", "LIMIT_KEYS", "MAX_RESOLUTION", "SWEEP_SECTIONS",
    "SECTION_MODELS", "CaseLimitFields", "StudySection", "LoadSection", "SolverSection", "DerivedSection",
    "SweepSection", "ReportSection", "StudyFile",
]

DEFAULT_MAX_CASES = 5000
#: Sweep blocks of sampled values (``n`` samples of ``{low, high}`` ranges), in expansion order.
SAMPLED_BLOCKS = ("random", "latin_hypercube", "sobol")
#: Sections whose keys a ``[sweep]`` axis may name (``"<section>.<key>"``).
SWEEP_SECTIONS = ("robot", "load", "solver", "derived", "scenario")

_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)

#: Default wall-clock limit of one case [s] (``[solver] max_case_seconds``).
DEFAULT_MAX_CASE_SECONDS = 3600.0
#: ``[solver]`` keys that limit a case's run; not solver options, not in the case parameters or the
#: config hash (raising a limit and resuming retries the cases that hit it).
LIMIT_KEYS = ("max_case_seconds", "max_case_memory")
#: Upper bounds of the resolutions (a sanity bound: beyond them a case would hang or exhaust memory).
MAX_RESOLUTION = {"n_elements": 4096, "n_stations": 100_001, "max_load_steps": 100_000}


class CaseLimitFields(BaseModel):
    """The per-case limits of a ``[solver]`` section (every study kind), see :data:`LIMIT_KEYS`.

    ``max_case_seconds`` [s] (default 1 h) stops a case that runs longer (stored failed,
    ``failure = "timeout"``); ``max_case_memory`` [bytes] caps the address space of the process
    running it (default: 3/4 of the physical memory of the machine running it).
    """

    model_config = _CFG
    max_case_seconds: float = Field(default=DEFAULT_MAX_CASE_SECONDS, gt=0.0, le=7 * 86400.0)
    max_case_memory: float | None = Field(default=None, ge=2.0**28)


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


class SolverSection(CaseLimitFields):
    """Mirror of :class:`workbench.models.SolverOptions` plus the limits (a test checks the fields agree)."""

    model_config = _CFG
    n_elements: int = Field(default=16, ge=1, le=MAX_RESOLUTION["n_elements"])
    tendon_model: Literal["continuum", "eyelets"] = "continuum"
    n_stations: int = Field(default=33, ge=2, le=MAX_RESOLUTION["n_stations"])
    newton_tolerance: float = Field(default=1e-9, gt=0.0)
    max_load_steps: int = Field(default=200, ge=1, le=MAX_RESOLUTION["max_load_steps"])
    time_step: float = Field(default=2e-3, gt=0.0)
    damping: float = Field(default=0.0, ge=0.0)
    spectral_radius: float = Field(default=0.8, ge=0.0, le=1.0)
    spring_link_backend: Literal["auto", "tree", "bodies"] = "auto"
    # spring-link axial springs (SpringLinkParams.axial); None: the model's own rule (a case key only when set)
    spring_link_axial: bool | None = None
    # spring-link Richardson extrapolation of N/2 and N links (SpringLinkParams.richardson); None: off
    # (a case key only when set)
    spring_link_richardson: bool | None = None
    error_estimate: Literal["richardson", "none"] = "richardson"
    error_estimate_exempt: list[str] = Field(default_factory=list)
    # warm starts within a worker (workbench.models.warm); a case key only when true (keeps the case ids)
    warm_start: bool = False
    # [solver.by_model.<model>] tables of per-model options (workbench.study.by_model checks them;
    # a case key only when set: keeps the case ids of the studies without it)
    by_model: dict[str, Any] = Field(default_factory=dict)


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
    sobol: dict[str, Any] | None = None


class ReportSection(BaseModel):
    """Presentation hints for ``workbench.report`` (not part of the config hash).

    ``question``, ``assumptions`` (``"section.key"`` -> where the value comes from),
    ``sensitivity`` (the sweep keys that vary an assumption; their value in the base section is the
    baseline) and ``sensitivity_note`` (why an assumption is not swept) feed the report's Question /
    Assumptions / Sensitivity sections
    (:mod:`workbench.report.findings`).
    """

    model_config = _CFG
    axes: list[str] = Field(default_factory=list)
    derived: dict[str, str] = Field(default_factory=dict)
    labels: dict[str, str] = Field(default_factory=dict)
    reference: str | None = None
    question: str = ""
    assumptions: dict[str, str] = Field(default_factory=dict)
    sensitivity: list[str] = Field(default_factory=list)
    sensitivity_note: str = ""
    frame: Literal["world", "base"] = "world"  # frame of the report's shape figures and 3-D view


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


SECTION_MODELS: dict[str, type[BaseModel]] = {
    "study": StudySection,
    "load": LoadSection,
    "solver": SolverSection,
    "derived": DerivedSection,
    "sweep": SweepSection,
    "report": ReportSection,
}
