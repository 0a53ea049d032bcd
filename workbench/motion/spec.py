"""Motion-study files: TOML -> validated :class:`MotionStudy` (Huang et al.'s series-parallel trunk).

The generic study runner (:mod:`workbench.study`) sweeps ``run(robot, load, options)`` models over
:class:`~workbench.robot.Robot` descriptions; a parallel module is driven by platform poses
instead, so motion studies have their own (small) file format, validated in the same strict style
and reported with the same one-line messages (:class:`workbench.study.spec.StudyError`)::

    studies/bad.toml: motions.module[0].axiz: unknown key; did you mean 'axis'?

Annotated example (``studies/series_parallel.toml`` is the runnable one)::

    [study]
    kind = "series_parallel"       # required: marks a motion study (see is_motion_study)
    name = "series_parallel"       # output folder data/<name>; [A-Za-z0-9_-]
    description = "Huang Fig 6 / Fig 10 motions"
    seed = 0                       # recorded (the motions are deterministic)
    max_cases = 500

    [geometry]                     # ModuleGeometry overrides (SI units: m, Pa, kg, deg for angles)
    height = 0.5
    rod_diameter = 0.006

    [solver]
    n_elements = 8                 # GE beam elements per leg
    length_tolerance = 1e-10       # IK Newton: max insertion-length update [m]
    max_iterations = 20            # IK Newton iterations
    fk_tolerance = 1e-10           # FK static solve: Newton relative tolerance

    [motions]
    # single module (Fig 6): platform pose = home pose moved along / rotated about one base axis
    # (rotations about the platform origin at its home position; for rx / ry, pivot = p puts
    # the rotation centre at p * height on the module axis instead, e.g. 0.5 = mid-height); values
    # linspace(-amplitude, amplitude, samples), or linspace(amplitude/samples, amplitude, samples)
    # with symmetric = false.  Units: m for x/y/z, rad for rx/ry/rz.
    module = [ { axis = "x", amplitude = 0.2, samples = 5 },
               { axis = "rx", amplitude = 0.785, samples = 5, pivot = 0.5 } ]
    # n modules in series (Fig 10): platform k on a prescribed backbone (see stack_targets):
    # "translation" (amplitude = lateral tip offset [m], platforms stay parallel to the base),
    # "s_shape" (amplitude = tangent angle at mid-length [rad], tip parallel to the base),
    # "bending" (amplitude = total bend angle of one constant-curvature arc [rad]);
    # plane = direction of the motion from base x [rad].
    stack = [ { shape = "bending", amplitude = 1.0, samples = 3, n_modules = 3, symmetric = false } ]

    [report]                       # passed to workbench.report (not in the config hash)
    reference = "target"
    axes = ["p.motion.value"]
"""

from __future__ import annotations

import hashlib
import math
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, ValidationInfo, field_validator

from ..study.spec import StudyError, _pydantic_problems, _suggest, canonical_json

__all__ = ["MotionStudy", "load_motion_study", "is_motion_study", "KIND", "GEOMETRY_KEYS"]

KIND = "series_parallel"
_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)


class _StudySection(BaseModel):
    model_config = _CFG
    kind: Literal["series_parallel"]
    name: str = Field(pattern=r"^[A-Za-z0-9_-]+$", min_length=1, max_length=100)
    description: str = ""
    seed: int = Field(default=0, ge=0)
    max_cases: int = Field(default=500, gt=0)


class _SolverSection(BaseModel):
    model_config = _CFG
    n_elements: int = Field(default=8, ge=2, le=64)
    length_tolerance: float = Field(default=1e-10, gt=0.0)
    max_iterations: int = Field(default=20, ge=1)
    fk_tolerance: float = Field(default=1e-10, gt=0.0)


class _ModuleMotion(BaseModel):
    model_config = _CFG
    axis: Literal["x", "y", "z", "rx", "ry", "rz"]
    amplitude: float = Field(gt=0.0)
    samples: int = Field(ge=1, le=101)
    symmetric: bool = True
    # rx / ry only: rotation centre on the module axis at pivot * height (1 = platform centre)
    pivot: float | None = Field(default=None, ge=0.0, le=2.0)

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


class _MotionsSection(BaseModel):
    model_config = _CFG
    module: list[_ModuleMotion] = Field(default_factory=list)
    stack: list[_StackMotion] = Field(default_factory=list)


class _ReportSection(BaseModel):
    model_config = _CFG
    axes: list[str] = Field(default_factory=list)
    derived: dict[str, str] = Field(default_factory=dict)
    labels: dict[str, str] = Field(default_factory=dict)
    reference: str | None = None


class _MotionFile(BaseModel):
    model_config = _CFG
    study: _StudySection
    geometry: dict[str, Any] = Field(default_factory=dict)
    solver: _SolverSection = Field(default_factory=_SolverSection)
    motions: _MotionsSection
    report: _ReportSection = Field(default_factory=_ReportSection)


def _geometry_defaults() -> dict[str, Any]:
    from ..physics.series_parallel import ModuleGeometry  # no Exudyn work at import of this module

    g = ModuleGeometry()
    return {f.name: getattr(g, f.name) for f in fields(g)}


#: keys accepted in ``[geometry]`` (the fields of ModuleGeometry)
GEOMETRY_KEYS = (
    "base_radius", "platform_radius", "base_angles_deg", "platform_angles_deg", "height", "rod_diameter",
    "youngs_modulus", "poisson_ratio", "density", "platform_mass", "mount_offset", "mount_twist_deg",
)


@dataclass(frozen=True)
class MotionStudy:
    """A validated motion study.

    Attributes
    ----------
    path, name, description : str
    seed, max_cases : int
    geometry : dict
        All ModuleGeometry fields (defaults filled in; angle tuples as lists).
    solver : dict
    motions : dict
        ``{"module": [ {axis, amplitude, samples, symmetric, pivot}, ...], "stack": [...]}``.
    report : dict
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

    @property
    def models(self) -> tuple[str, ...]:
        return ("target", "series_parallel", "cc_fit")

    def resolved(self) -> dict[str, Any]:
        """Plain-data resolved spec (what the manifest records)."""
        return {
            "study": {"kind": KIND, "name": self.name, "description": self.description, "seed": self.seed,
                      "models": list(self.models), "max_cases": self.max_cases},
            "geometry": dict(self.geometry), "solver": dict(self.solver), "motions": self.motions,
            "report": self.report,
        }

    @property
    def config_hash(self) -> str:
        payload = {"kind": KIND, "seed": self.seed, "geometry": self.geometry, "solver": self.solver,
                   "motions": self.motions}
        return hashlib.sha256(canonical_json(payload).encode()).hexdigest()[:16]


def _read_toml(p: Path) -> dict[str, Any]:
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as e:
        raise StudyError([f"{p}: cannot read: {e.strerror or e}"]) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise StudyError([f"{p}: invalid TOML: {e}"]) from None


def is_motion_study(path: str | Path) -> bool:
    """True when ``path`` is a readable TOML file whose ``[study]`` has ``kind = "series_parallel"``.

    Never raises: unreadable or invalid files are not motion studies (the generic loader then
    reports their problems).
    """
    try:
        data = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return False
    st = data.get("study")
    return isinstance(st, dict) and st.get("kind") == KIND


def _check_geometry(raw: dict[str, Any], defaults: dict[str, Any]) -> tuple[dict[str, Any], list[str]]:
    problems, out = [], dict(defaults)
    for k, v in raw.items():
        if k not in defaults:
            problems.append(f"geometry.{k}: unknown key{_suggest(k, list(defaults))}")
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
        from ..physics.series_parallel import ModuleGeometry

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
    lines = _pydantic_problems(exc, (), _MotionFile)
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
                line = f"{loc}: unknown key{_suggest(key, known)}"
        if "did you mean '" in line:
            target = line.split("did you mean '")[1].split("'")[0]
            suggested.add(loc.rsplit(".", 1)[0] + "." + target)
        out.append(line)
    return [ln for ln in out if not (ln.endswith(": missing required key") and ln.partition(": ")[0] in suggested)]


def load_motion_study(path: str | Path, *, max_cases: int | None = None) -> MotionStudy:
    """Read and validate a motion-study file; raise :class:`StudyError` listing every problem.

    Each problem is one line ``<file>: <key path>: <reason>``.
    """
    p = Path(path)
    data = _read_toml(p)
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
    return MotionStudy(
        path=str(p), name=model.study.name, description=model.study.description, seed=model.study.seed,
        max_cases=model.study.max_cases if max_cases is None else max_cases, geometry=geometry,
        solver=model.solver.model_dump(),
        motions={"module": [m.model_dump(exclude_none=True) for m in model.motions.module],
                 "stack": [m.model_dump() for m in model.motions.stack]},
        report=model.report.model_dump(exclude_defaults=True),
    )
