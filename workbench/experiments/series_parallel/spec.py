"""Series-parallel study files: TOML -> validated :class:`SeriesParallelStudy` (Huang et al.'s trunk).

Huang's modules are driven by platform poses, not by ``run(robot, load, options)``, so this study
kind (``[study] kind = "series_parallel"``) has its own small format, validated in the strict style
of the sweep studies and reported with the same one-line messages
(:class:`~workbench.study.messages.StudyError`)::

    studies/bad.toml: motions.module[0].axiz: unknown key; did you mean 'axis'?

Sections (the annotated reference is ``docs/study-format.md``, "Series-parallel studies";
``studies/series_parallel.toml`` is the runnable one)::

    [study]     kind = "series_parallel", name, description, seed, max_cases
    [geometry]  ModuleGeometry overrides (SI units; deg for the angle lists)
    [solver]    n_elements, length_tolerance, max_iterations, fk_tolerance, error_estimate
    [motions]   module = [{axis, amplitude, samples, symmetric, pivot}, ...]   (Fig 6)
                stack = [{shape, amplitude, samples, n_modules, plane, symmetric}, ...]   (Fig 10)
    [report]    presentation hints (the sweep studies' ReportSection; not in the config hash)

Every problem is collected before one :class:`StudyError` is raised; the geometry is checked by
building the :class:`~workbench.physics.series_parallel.ModuleGeometry`.

Checked by ``tests/experiments/series_parallel/test_spec.py``.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator

from ...study.kinds import kind_of
from ...study.messages import StudyError, pydantic_problems, read_toml, suggest
from ...study.overrides import apply_overrides
from ...study.params import canonical_json
from ...study.outcomes import CaseLimits
from ...study.schema import LIMIT_KEYS, CaseLimitFields, ReportSection

__all__ = ["SeriesParallelStudy", "load_series_parallel_study", "is_series_parallel_study", "KIND_NAME",
           "GEOMETRY_KEYS"]

#: ``[study] kind`` of these studies (a key of ``workbench.registry.KINDS``).
KIND_NAME = "series_parallel"
_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)


class _StudySection(BaseModel):
    model_config = _CFG
    kind: Literal["series_parallel"]
    name: str = Field(pattern=r"^[A-Za-z0-9_-]+$", min_length=1, max_length=100)
    description: str = ""
    seed: int = Field(default=0, ge=0)
    max_cases: int = Field(default=500, gt=0)


class _SolverSection(CaseLimitFields):
    model_config = _CFG
    n_elements: int = Field(default=8, ge=2, le=64)
    length_tolerance: float = Field(default=1e-10, gt=0.0)
    max_iterations: int = Field(default=20, ge=1)
    fk_tolerance: float = Field(default=1e-10, gt=0.0)
    error_estimate: Literal["richardson", "none"] = "richardson"


class _ModuleMotion(BaseModel):
    model_config = _CFG
    axis: Literal["x", "y", "z", "rx", "ry", "rz"]
    amplitude: float = Field(gt=0.0)
    samples: int = Field(ge=1, le=101)
    symmetric: bool = True
    # rx / ry only: rotation centre on the module axis at pivot * height (1 = platform centre)
    pivot: float | None = Field(default=None, ge=0.0, le=2.0)
    # ModuleGeometry overrides for these cases only (a sensitivity sweep of the assumed module)
    geometry: dict[str, Any] | None = None

    @field_validator("pivot")
    @classmethod
    def _pivot_only_for_tilts(cls, v: float | None, info: ValidationInfo) -> float | None:
        axis = info.data.get("axis")
        if v is not None and axis is not None and axis not in ("rx", "ry"):
            raise ValueError(f"applies to axis 'rx' or 'ry' only (a rotation centre on the module axis), "
                             f"not to axis {axis!r}")
        return v


class _StackMotion(BaseModel):
    model_config = _CFG
    shape: Literal["translation", "s_shape", "bending"]
    amplitude: float = Field(gt=0.0)
    samples: int = Field(ge=1, le=101)
    n_modules: int = Field(default=3, ge=1, le=10)
    plane: float = 0.0
    symmetric: bool = False
    geometry: dict[str, Any] | None = None


class _MotionsSection(BaseModel):
    model_config = _CFG
    module: list[_ModuleMotion] = Field(default_factory=list)
    stack: list[_StackMotion] = Field(default_factory=list)


#: the sweep studies' [report] section (same keys, same checks)
_ReportSection = ReportSection


class _MotionFile(BaseModel):
    model_config = _CFG
    study: _StudySection
    geometry: dict[str, Any] = Field(default_factory=dict)
    solver: _SolverSection = Field(default_factory=_SolverSection)
    motions: _MotionsSection
    report: _ReportSection = Field(default_factory=_ReportSection)


def _geometry_defaults() -> dict[str, Any]:
    from ...physics.series_parallel import ModuleGeometry  # no Exudyn work at import of this module

    g = ModuleGeometry()
    return {f.name: getattr(g, f.name) for f in fields(g)}


#: keys accepted in ``[geometry]`` (the fields of ModuleGeometry)
GEOMETRY_KEYS = (
    "base_radius", "platform_radius", "base_angles_deg", "platform_angles_deg", "height", "rod_diameter",
    "youngs_modulus", "poisson_ratio", "density", "platform_mass", "mount_offset", "mount_twist_deg",
    "yield_strength",
)


@dataclass(frozen=True)
class SeriesParallelStudy:
    """A validated series-parallel study.

    Attributes
    ----------
    path, name, description : str
    seed, max_cases : int
    geometry : dict
        All ModuleGeometry fields (defaults filled in; angle tuples as lists).
    solver : dict
        The solver keys (without the limits).
    motions : dict
        ``{"module": [ {axis, amplitude, samples, symmetric, pivot}, ...], "stack": [...]}``.
    report : dict
    limits : CaseLimits
        ``[solver] max_case_seconds`` / ``max_case_memory``.
    overrides : tuple of str
        The command-line ``key=value`` overrides applied to the file.
    notes, warnings : tuple of str
        What ``workbench validate`` / ``run`` print (none today; part of the study-kind contract).
    """

    path: str
    name: str
    description: str
    seed: int
    max_cases: int
    geometry: dict[str, Any]
    solver: dict[str, Any]
    motions: dict[str, list[dict[str, Any]]]
    report: dict[str, Any] = field(default_factory=dict)
    limits: CaseLimits = field(default_factory=CaseLimits)
    overrides: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()

    @property
    def models(self) -> tuple[str, ...]:
        return ("target", "series_parallel", "cc_fit")

    def resolved(self) -> dict[str, Any]:
        """Plain-data resolved spec (what the manifest records)."""
        return {
            "study": {"kind": KIND_NAME, "name": self.name, "description": self.description, "seed": self.seed,
                      "models": list(self.models), "max_cases": self.max_cases},
            "geometry": dict(self.geometry),
            "solver": {**self.solver, "max_case_seconds": self.limits.seconds, "max_case_memory": self.limits.memory},
            "motions": self.motions, "report": self.report,
        }

    @property
    def config_hash(self) -> str:
        payload = {"kind": KIND_NAME, "seed": self.seed, "geometry": self.geometry, "solver": self.solver,
                   "motions": self.motions}
        return hashlib.sha256(canonical_json(payload).encode()).hexdigest()[:16]


def _read_toml(p: Path) -> dict[str, Any]:
    return read_toml(p, cannot_read="cannot read", syntax_error="invalid TOML")


def is_series_parallel_study(path: str | Path) -> bool:
    """True when ``path`` is a readable TOML file whose ``[study]`` has ``kind = "series_parallel"``.

    Never raises: unreadable or invalid files are not series-parallel studies (the sweep loader
    then reports their problems); :func:`workbench.study.kinds.kind_of` reads the file.
    """
    return kind_of(path) == KIND_NAME


def _check_geometry(raw: dict[str, Any], defaults: dict[str, Any]) -> tuple[dict[str, Any], list[str]]:
    problems, out = [], dict(defaults)
    for k, v in raw.items():
        if k not in defaults:
            problems.append(f"geometry.{k}: unknown key{suggest(k, list(defaults))}")
            continue
        d = defaults[k]
        if isinstance(d, tuple):
            if not (isinstance(v, list) and len(v) == 6 and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                                                                  and math.isfinite(x) for x in v)):
                problems.append(f"geometry.{k}: must be a list of 6 finite angles [deg], got {v!r}")
                continue
            out[k] = [float(x) for x in v]
        else:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                problems.append(f"geometry.{k}: must be a number, got {type(v).__name__} {v!r}")
                continue
            if not math.isfinite(float(v)):
                problems.append(f"geometry.{k}: must be finite, got {v}")
                continue
            out[k] = float(v)
    for k, v in list(out.items()):
        if isinstance(v, tuple):
            out[k] = list(v)
    if not problems:
        from ...physics.series_parallel import ModuleGeometry

        try:
            ModuleGeometry(**{k: tuple(v) if isinstance(v, list) else v for k, v in out.items()})
        except ValueError as e:
            msg = str(e)
            key = msg.split(" ", 1)[0].replace("ModuleGeometry.", "geometry.")
            problems.append(f"{key}: {msg.split(' ', 1)[1] if ' ' in msg else msg}")
    return out, problems


_LIST_ITEM_MODELS = {("motions", "module"): _ModuleMotion, ("motions", "stack"): _StackMotion}


def _validation_problems(exc: ValidationError) -> list[str]:
    """pydantic errors -> one line each (the generic study's wording); a misspelt required key
    gives one line (the unknown key with its suggestion), not also "missing required key"."""
    lines = pydantic_problems(exc, (), _MotionFile)
    # unknown keys inside list items (motions.module[i]): suggest from the item's fields
    out = []
    suggested: set[str] = set()
    for line in lines:
        loc, _, msg = line.partition(": ")
        if msg == "unknown key":
            parts = loc.replace("]", "").split("[")
            head = tuple(parts[0].split("."))
            if head in _LIST_ITEM_MODELS and len(parts) == 2 and "." in parts[1]:
                key = parts[1].split(".", 1)[1]
                known = list(_LIST_ITEM_MODELS[head].model_fields)
                line = f"{loc}: unknown key{suggest(key, known)}"
        if "did you mean '" in line:
            target = line.split("did you mean '")[1].split("'")[0]
            suggested.add(loc.rsplit(".", 1)[0] + "." + target)
        out.append(line)
    return [ln for ln in out if not (ln.endswith(": missing required key") and ln.partition(": ")[0] in suggested)]


def load_series_parallel_study(path: str | Path, *, max_cases: int | None = None,
                               overrides: tuple[str, ...] = ()) -> SeriesParallelStudy:
    """Read and validate a series-parallel study file; raise :class:`StudyError` listing every problem.

    Each problem is one line ``<file>: <key path>: <reason>``.  ``overrides``: command-line
    ``key=value`` settings (:mod:`workbench.study.overrides`), validated like the file.
    """
    p = Path(path)
    data = apply_overrides(_read_toml(p), overrides)
    problems: list[str] = []
    model = None
    raw_geometry = data.get("geometry", {})
    try:
        model = _MotionFile.model_validate(data)
    except ValidationError as e:
        problems += _validation_problems(e)
    geometry: dict[str, Any] = {}
    if isinstance(raw_geometry, dict):
        geometry, gp = _check_geometry(raw_geometry, _geometry_defaults())
        problems += gp
    if model is not None and not problems:
        for group in ("module", "stack"):
            for i, m in enumerate(getattr(model.motions, group)):
                if m.geometry:
                    _, gp = _check_geometry({**raw_geometry, **m.geometry}, _geometry_defaults())
                    problems += [f"motions.{group}[{i}].{q}" for q in gp]
    if model is not None and not model.motions.module and not model.motions.stack:
        problems.append("motions: no motions given (need at least one entry in motions.module or motions.stack)")
    if model is not None and not problems:
        n = sum(m.samples for m in model.motions.module) + sum(m.samples for m in model.motions.stack)
        cap = max_cases if max_cases is not None else model.study.max_cases
        if n > cap:
            problems.append(f"motions: {n} cases exceed max_cases = {cap}")
    if problems:
        raise StudyError([f"{p}: {msg}" for msg in problems])
    assert model is not None
    return SeriesParallelStudy(
        path=str(p), name=model.study.name, description=model.study.description, seed=model.study.seed,
        max_cases=model.study.max_cases if max_cases is None else max_cases, geometry=geometry,
        solver=model.solver.model_dump(exclude=set(LIMIT_KEYS)),
        limits=CaseLimits(model.solver.max_case_seconds, model.solver.max_case_memory),
        motions={"module": [m.model_dump(exclude_none=True) for m in model.motions.module],
                 "stack": [m.model_dump(exclude_none=True) for m in model.motions.stack]},
        report=model.report.model_dump(exclude_defaults=True),
    )
