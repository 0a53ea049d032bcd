"""Calibration study files: TOML -> validated :class:`~workbench.measure.types.CalibrationStudy`.

:func:`load_calibration_study` reads a ``[study] kind = "calibration"`` file (``docs/study-format.md``,
"Calibration studies") with command-line ``key=value`` overrides applied like sweep studies
(:func:`workbench.study.overrides.apply_overrides`) and checks every table before anything runs:

- ``[study]`` (name, kind, description), ``[robot]`` through the sweep's reader
  (:func:`workbench.study.spec.resolve_robot_table`: preset or description form), ``[load]`` and
  ``[solver]`` / ``[report]`` through the sweep schema (:mod:`workbench.study.schema`; ``[load]`` holds
  only what every sample shares: ``pretension``, ``tip_force``, ``tip_torque``);
- ``[measurements]`` and its data file (:func:`workbench.measure.datafile.read_measurements`);
- ``[calibration]``: models known to ``registry.table("models")`` and able to run the measured case
  (a representative case checked by :func:`workbench.study.checks.case_rules`, the models' declared
  capabilities); parameters whose key paths name numbers of the case parameters, with finite bounds
  ``lower < initial < upper`` (the initial value defaults to the robot's, its source from
  :func:`workbench.robot.spec.robot_value_sources`); ``command_zero``; ``registration`` required
  exactly when ``measurements.frame = "measurement"``; the split (``test_fraction`` xor ``folds``,
  ``physics_rows`` in ``[parameters + 1, training rows]``).

Every problem is one line naming the study file and the key path (the data file, column and row for
a cell); all are collected and raised as one :class:`~workbench.study.messages.StudyError`.
Validation imports no model code.  The parameter vector's order is the ``[calibration.parameters]``
file order, then ``command_zero[0..n-1]``, ``registration.translation[0..2]``,
``registration.rotation[0..2]``.  ``CalibrationStudy.robot`` is the *resolved* robot table (a
description form merged onto its data preset; a preset form with every parameter), so
``workbench.study.keypath.with_value(..., create=True)`` can set any calibrated key path in it.

Checked by ``tests/measure/test_measure_spec.py`` and ``tests/measure/test_measure_malformed.py``.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import Any, Literal, Mapping, Sequence

from pydantic import BaseModel, ConfigDict, Field

from ..study.keypath import KeyPathError, format_key_path, get_value, parse_key_path
from ..study.messages import StudyError, fmt_loc, read_toml, suggest
from ..study.params import canonical_json
from ..study.schema import LIMIT_KEYS, LoadSection, ReportSection, SolverSection
from ..units import unit_of
from .datafile import schema_problems
from .types import CalibrationSettings, CalibrationStudy, FitParameter, Measurements, Split

__all__ = ["CALIBRATION_SECTIONS", "KIND_NAME", "LOAD_KEYS", "load_calibration_study"]

KIND_NAME = "calibration"
#: the tables of a calibration study file
CALIBRATION_SECTIONS = ("study", "robot", "load", "solver", "measurements", "calibration", "report")
#: the ``[load]`` keys of a calibration study (every sample shares them)
LOAD_KEYS = ("pretension", "tip_force", "tip_torque")
#: physics_rows when the file does not set it (at most the smallest fold's training rows)
DEFAULT_PHYSICS_ROWS = 60
_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)
_UNIT_BY_WORD = {"offset": "m", "tip_offset": "m", "angles": "rad", "first_angle": "rad", "area": "m²",
                 "mass": "kg", "strength": "Pa", "length": "m", "diameter": "m"}


class StudyTable(BaseModel):
    model_config = _CFG
    name: str = Field(pattern=r"^[A-Za-z0-9_-]+$", min_length=1, max_length=100)
    kind: Literal["calibration"]
    description: str = ""


class Bounds(BaseModel):
    model_config = _CFG
    lower: float
    upper: float
    initial: float | None = None


class TendonBounds(BaseModel):
    model_config = _CFG
    lower: float | list[float]
    upper: float | list[float]
    initial: float | list[float] | None = None


class Vector3Bounds(BaseModel):
    model_config = _CFG
    lower: list[float] = Field(min_length=3, max_length=3)
    upper: list[float] = Field(min_length=3, max_length=3)
    initial: list[float] | None = Field(default=None, min_length=3, max_length=3)


class RegistrationTable(BaseModel):
    model_config = _CFG
    translation: Vector3Bounds
    rotation: Vector3Bounds


class CalibrationTable(BaseModel):
    """The ``[calibration]`` table (``parameters`` entries are checked one by one: :class:`Bounds`)."""

    model_config = _CFG
    models: list[str] = Field(min_length=1)
    seed: int = Field(default=0, ge=0)
    test_fraction: float | None = Field(default=None, gt=0.0, lt=1.0)
    folds: int | None = Field(default=None, ge=2)
    physics_rows: int | None = Field(default=None, ge=1)
    confidence: float = Field(default=0.95, gt=0.0, lt=1.0)
    max_evaluations: int = Field(default=100, ge=1)
    parameters: dict[str, Any] = Field(default_factory=dict)
    command_zero: TendonBounds | None = None
    registration: RegistrationTable | None = None


def _schema(model: type[BaseModel], raw: Any, where: tuple, problems: list[str]) -> Any:
    """``raw`` validated by ``model`` (``None`` and its problems, one line each, when it fails)."""
    if not isinstance(raw, Mapping):
        problems.append(f"{fmt_loc(where)}: must be a table, got {type(raw).__name__} {raw!r}"[:200])
        return None
    out, lines = schema_problems(model, raw, where)
    problems += lines
    return out


def _sections(raw: Mapping[str, Any]) -> list[str]:
    out = [f"{k}: unknown section{suggest(k, list(CALIBRATION_SECTIONS))}" for k in raw if k not in CALIBRATION_SECTIONS]
    for k in ("study", "robot", "measurements", "calibration"):
        if k not in raw:
            out.append(f"{k}: missing section [{k}]")
    st = raw.get("study")
    if isinstance(st, Mapping):
        for k in ("models", "seed"):
            if k in st:
                out.append(f"study.{k}: a calibration study sets {k} in [calibration]")
    return out


def _study(raw: Mapping[str, Any]) -> tuple[StudyTable | None, list[str]]:
    problems: list[str] = []
    st = raw.get("study")
    if not isinstance(st, Mapping):
        return None, []
    body = {k: v for k, v in st.items() if k not in ("models", "seed")}
    return _schema(StudyTable, body, ("study",), problems), problems


def _robot(raw: Mapping[str, Any]) -> tuple[dict[str, Any] | None, Any, list[str]]:
    """The resolved robot table, the nominal robot and the problems of ``[robot]``."""
    from ..robot.spec import is_description, robot_description, robot_from_params
    from ..study.spec import resolve_robot_table

    if "robot" not in raw:
        return None, None, []
    table, _, problems = resolve_robot_table(raw["robot"])
    if table is None or problems:
        return None, None, problems
    if is_description(table):
        table = robot_description(table)
    try:
        return table, robot_from_params(table), []
    except (TypeError, ValueError) as e:
        return None, None, [f"robot: {' '.join(str(e).split())}"]


def _load(raw: Mapping[str, Any], meas_raw: Any) -> tuple[dict[str, Any] | None, list[str]]:
    """``[load]``: the sweep schema, then only :data:`LOAD_KEYS` (the commands come from the data file)."""
    problems: list[str] = []
    lraw = raw.get("load", {})
    sec = _schema(LoadSection, lraw, ("load",), problems)
    if sec is None:
        return None, problems
    why = {"mode": "is measurements.mode", "tensions": "come from the data file ([measurements.commands])",
           "length_changes": "come from the data file ([measurements.commands])",
           "bend_angle": "is not a command of measured data (the commands come from [measurements.commands])",
           "bend_plane": "is not a command of measured data (the commands come from [measurements.commands])"}
    for k in lraw:
        if k not in LOAD_KEYS:
            problems.append(f"load.{k}: {why.get(k, 'has no meaning in a calibration study (static samples)')}; "
                            f"[load] holds only {', '.join(LOAD_KEYS)}")
    if "tip_force" in lraw and isinstance(meas_raw, Mapping) and "tip_force" in meas_raw:
        problems.append("load.tip_force: the data file gives the tip force ([measurements.tip_force]); remove one")
    return {k: v for k, v in sec.model_dump().items() if k in LOAD_KEYS}, problems


def _solver(raw: Mapping[str, Any], models: Sequence[str]) -> tuple[dict[str, Any] | None, list[str], Any]:
    from ..study.by_model import by_model_problems

    problems: list[str] = []
    sec = _schema(SolverSection, raw.get("solver", {}), ("solver",), problems)
    rep = _schema(ReportSection, raw.get("report", {}), ("report",), problems)
    if sec is None:
        return None, problems, rep
    if sec.by_model and models:
        problems += by_model_problems(sec.by_model, list(models))
    return sec.model_dump(exclude=set() if sec.by_model else {"by_model"}), problems, rep


def _models(cal: CalibrationTable) -> list[str]:
    from .. import registry

    rows = registry.table("models")
    out = []
    for i, m in enumerate(cal.models):
        if m not in rows:
            out.append(f"calibration.models[{i}]: unknown model {m!r}{suggest(m, list(rows))}"
                       .replace("; known keys:", "; known models:"))
        elif rows[m].capabilities is None:
            out.append(f"calibration.models[{i}]: {m!r} is not a run(robot, load, options) model")
    if len(set(cal.models)) != len(cal.models):
        out.append("calibration.models: lists a model twice")
    return out


def _unit(path: str) -> str:
    """The unit of a key path's value: the unit table's by section and leaf name, else by the leaf's word."""
    parts = parse_key_path(path)
    leaf = next(str(p) for p in reversed(parts) if isinstance(p, str))
    u = unit_of(f"{parts[0]}.{leaf}")
    if u is None:
        u = next((v for w, v in _UNIT_BY_WORD.items() if leaf == w or leaf.endswith(f"_{w}")), "")
    return u


def _source(path: str, sources: Mapping[str, str]) -> str:
    """Where the value at ``path`` comes from: its own entry, else that of the list it is an element of."""
    parts = parse_key_path(path)
    while parts:
        text = sources.get(format_key_path(parts))
        if text is not None:
            return text
        parts = parts[:-1] if isinstance(parts[-1], int) else ()
    return "default"


def _nominal(path: str, case: Mapping[str, Any], sources: Mapping[str, str]) -> tuple[Any, str]:
    """The value a key path names in the case parameters, or a material's value the robot uses there.

    Raises :class:`KeyPathError` naming the path and why.
    """
    try:
        return get_value(case, path), _source(path, sources)
    except KeyPathError:
        src = _source(path, sources)
        if not src.startswith("material "):
            raise
    from ..robot.materials import material

    parent, _, leaf = path.rpartition(".")
    name = get_value(case, parent).get("material") if isinstance(get_value(case, parent), Mapping) else None
    value = getattr(material(str(name)), "tensile_strength" if leaf == "strength" else leaf, None)
    if value is None:
        raise KeyPathError(f"{path}: material {name!r} gives no {leaf}")
    return value, src


def _hint(key: str, case: Mapping[str, Any]) -> str:
    """For ``robot.<section key>`` of a description-form robot: where a section's value is."""
    from ..robot.section_spec import SECTION_KEYS, TENDON_KEYS

    parts = parse_key_path(key)
    sections = case.get("robot", {}).get("sections")
    if len(parts) != 2 or parts[0] != "robot" or not isinstance(sections, list):
        return ""
    n = len(sections)
    if parts[1] in SECTION_KEYS:
        return f" (a section's value: robot.sections[i].{parts[1]}, i = 0..{n - 1}, one parameter per section)"
    if parts[1] in TENDON_KEYS:
        return f" (a tendon group's value: robot.sections[i].tendons[0].{parts[1]}, i = 0..{n - 1})"
    return ""


def _parameter(key: str, body: Any, case: Mapping[str, Any], sources: Mapping[str, str]
               ) -> tuple[FitParameter | None, list[str]]:
    where = f'calibration.parameters["{key}"]'
    problems: list[str] = []
    b = _schema(Bounds, body, ("calibration", "parameters", key), problems)
    try:
        section = parse_key_path(key)[0]
    except KeyPathError as e:
        return None, problems + [f"{where}: {str(e).partition(': ')[2]}"]
    if section not in ("robot", "load"):
        return None, problems + [f"{where}: only robot.* and load.* values can be calibrated"]
    try:
        value, source = _nominal(key, case, sources)
    except KeyPathError as e:
        return None, problems + [f"{where}: not a value of the case: {str(e).partition(': ')[2]}{_hint(key, case)}"]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None, problems + [f"{where}: must name a number, {key} is {type(value).__name__} {value!r}"]
    if b is None:
        return None, problems
    u = _unit(key)
    us = f" {u}" if u else ""
    initial, source = (b.initial, "set in the study file") if b.initial is not None else (float(value), source)
    if not b.lower < b.upper:
        return None, [f"{where}: lower must be < upper, got lower = {b.lower:g}{us}, upper = {b.upper:g}{us}"]
    if not b.lower < initial < b.upper:
        return None, [f"{where}: the initial value {initial:g}{us} ({source}) must lie inside (lower, upper) = "
                      f"({b.lower:g}, {b.upper:g}){us}; widen the bounds or set initial"]
    return FitParameter(key, float(initial), b.lower, b.upper, u, source), []


def _vector(name: str, lo: Any, hi: Any, init: Any, n: int, unit: str, where: str) -> tuple[list[FitParameter], list[str]]:
    """``n`` parameters ``name[i]`` from scalar or per-entry bounds (initial default 0)."""
    vals = {}
    for label, v in (("lower", lo), ("upper", hi), ("initial", init)):
        if isinstance(v, list) and len(v) != n:
            return [], [f"{where}.{label}: must be one number or {n} (one per {'tendon' if n != 3 else 'axis'}), "
                        f"got {len(v)}"]
        vals[label] = [float(x) for x in v] if isinstance(v, list) else [float(0.0 if v is None else v)] * n
    out, problems = [], []
    scalar = not any(isinstance(v, list) for v in (lo, hi, init))
    for i in range(n):
        l, u, x = vals["lower"][i], vals["upper"][i], vals["initial"][i]
        if not l < x < u and not (scalar and problems):
            entry = "" if scalar else f"entry {i}: "
            problems.append(f"{where}: {entry}need lower < initial < upper, got {l:g} < {x:g} < {u:g} {unit}"
                            + ("" if init is not None else " (initial defaults to 0; set initial)"))
        out.append(FitParameter(f"{name}[{i}]", x, l, u, unit,
                                "set in the study file" if init is not None else "default: 0"))
    return out, problems


def _parameters(cal: CalibrationTable, case: Mapping[str, Any], sources: Mapping[str, str], n_tendons: int | None,
                meas: Measurements | None, frame: Any) -> tuple[list[FitParameter], list[str]]:
    params, problems = [], []
    for key, body in cal.parameters.items():
        p, lines = _parameter(key, body, case, sources)
        problems += lines
        params += [p] if p is not None else []
    cz = cal.command_zero
    if cz is not None and n_tendons is not None:
        unit = "N" if (meas.mode if meas is not None else None) == "tension" else "m"
        got, lines = _vector("command_zero", cz.lower, cz.upper, cz.initial, n_tendons, unit, "calibration.command_zero")
        params, problems = params + got, problems + lines
    reg = cal.registration
    if frame == "measurement" and reg is None:
        problems.append("calibration.registration: missing: positions measured in the tracker's frame "
                        "(measurements.frame = \"measurement\") need the base-to-measurement transform calibrated "
                        "(translation and rotation bounds)")
    elif reg is not None and frame in ("base", "world"):
        problems.append(f"calibration.registration: measurements.frame = {frame!r} is a frame of the robot: there is "
                        f"no registration to calibrate; remove it or set measurements.frame = \"measurement\"")
    elif reg is not None:
        for part, unit in (("translation", "m"), ("rotation", "rad")):
            b = getattr(reg, part)
            got, lines = _vector(f"registration.{part}", b.lower, b.upper, b.initial, 3, unit,
                                 f"calibration.registration.{part}")
            params, problems = params + got, problems + lines
    if not params and not problems:
        problems.append("calibration.parameters: nothing to calibrate (no parameters, command_zero or registration)")
    return params, problems


def _split_problems(cal: CalibrationTable, n: int, p: int) -> tuple[Split | None, list[str]]:
    """``test_fraction`` xor ``folds``; row counts against the parameter count ``p``; the resolved split."""
    from .split import train_sizes

    if (cal.test_fraction is None) == (cal.folds is None):
        got = "both" if cal.folds is not None else "neither"
        return None, [f"calibration: set exactly one of test_fraction and folds (got {got})"]
    if n < p + 1:
        return None, [f"measurements.file: {n} data rows; calibrating {p} parameters needs at least {p + 1} rows"]
    if cal.folds is not None and cal.folds > n:
        return None, [f"calibration.folds: must be <= the {n} data rows, got {cal.folds}"]
    probe = Split(cal.seed, cal.test_fraction, cal.folds, 1)
    train = min(train_sizes(n, probe))
    rows = cal.physics_rows if cal.physics_rows is not None else min(DEFAULT_PHYSICS_ROWS, train)
    out = []
    if rows < p + 1:
        out.append(f"calibration.physics_rows: must be >= the number of parameters + 1 = {p + 1}, got {rows}"
                   + ("" if cal.physics_rows is not None else " (the default: the smallest fold's training rows)"))
    elif rows > train:
        out.append(f"calibration.physics_rows: must be <= the training rows of every fold ({train} of the {n} rows), "
                   f"got {rows}")
    return (None if out else Split(cal.seed, cal.test_fraction, cal.folds, rows)), out


def _capabilities(table: Mapping[str, Any], load: Mapping[str, Any], solver: Mapping[str, Any], meas: Measurements,
                  models: Sequence[str]) -> list[str]:
    """The models' declared capabilities against a representative measured case (one line each).

    The case: the nominal robot, the row with the largest commands and, when the file gives tip
    forces, the force with the largest component out of the base x-z plane (else the largest);
    what a model refuses is refused for the study (the message names the ``[measurements]`` key).
    """
    import numpy as np

    from ..study.checks import case_rules

    row = int(np.argmax(np.abs(meas.commands).sum(axis=1)))
    key = "tensions" if meas.mode == "tension" else "length_changes"
    lp = {**load, "mode": meas.mode, key: [float(v) for v in meas.commands[row]], "analysis": "static"}
    if meas.tip_force is not None:
        F = meas.tip_force
        k = int(np.argmax(np.abs(F[:, 1]))) if np.any(F[:, 1] != 0) else int(np.argmax(np.linalg.norm(F, axis=1)))
        lp["tip_force"] = [float(v) for v in F[k]]
    lines = case_rules({"robot": dict(table), "load": lp, "solver": dict(solver), "derived": {}}, models=list(models))
    out = []
    for line in lines:
        head, sep, rest = line.partition(": ")
        if head == f"load.{key}":
            head = "measurements.commands"
        elif head == "load.tip_force" and meas.tip_force is not None:
            head = "measurements.tip_force"
        out.append(f"{head}{sep}{rest}")
    return out


def _file_digest(study_dir: Path, meas_raw: Any) -> str:
    try:
        return hashlib.sha256((study_dir / str(meas_raw["file"])).read_bytes()).hexdigest()
    except (OSError, KeyError, TypeError, ValueError):
        return ""


def _read(raw: Mapping[str, Any], study_dir: Path, robot: Any, src: str) -> tuple[Measurements | None, list[str]]:
    from .datafile import read_measurements

    if "measurements" not in raw:
        return None, []
    try:
        return read_measurements(raw["measurements"], study_dir, robot, src), []
    except StudyError as e:
        return None, list(e.problems)


def _resolved(st: StudyTable, table: dict, load: dict, solver: dict, report: Any, meas_raw: Mapping[str, Any],
              digest: str, meas: Measurements, cal: CalibrationTable, params: list[FitParameter], split: Split
              ) -> dict[str, Any]:
    """The study as run, plain data (the data file named with its SHA-256, not its arrays)."""
    calib = {**cal.model_dump(exclude={"parameters", "command_zero", "registration"}),
             "physics_rows": split.physics_rows,
             "parameters": [{"name": p.name, "initial": p.initial, "lower": p.lower, "upper": p.upper, "unit": p.unit,
                             "source": p.source} for p in params]}
    return {"study": {"name": st.name, "kind": KIND_NAME, "description": st.description},
            "robot": table, "load": {**load, "mode": meas.mode}, "solver": solver,
            "measurements": {**dict(meas_raw), "sha256": digest, "rows": meas.n},
            "calibration": calib, "report": report.model_dump(exclude_defaults=True) if report is not None else {}}


def load_calibration_study(path: str | Path, max_cases: int | None = None,
                           overrides: Sequence[str] = ()) -> CalibrationStudy:
    """Read and validate a calibration study file; :class:`StudyError` lists every problem, one line each.

    Parameters
    ----------
    path : path-like
        The TOML file (its data file is relative to its folder).
    max_cases : int, optional
        Most cases (models x folds) the run may have (the CLI's ``--max-cases``).
    overrides : sequence of str
        Command-line ``key=value`` settings (:mod:`workbench.study.overrides`), applied before
        validation and recorded in ``CalibrationStudy.overrides``.
    """
    from ..study.overrides import apply_overrides

    src = str(Path(path))
    raw = apply_overrides(read_toml(path), overrides)
    if not raw:
        raise StudyError([f"{src}: the file is empty (a calibration study needs [study], [robot], [measurements] "
                          f"and [calibration])"])
    problems = _sections(raw)
    st, lines = _study(raw)
    problems += lines
    table, robot, lines = _robot(raw)
    problems += lines
    cal = _schema(CalibrationTable, raw["calibration"], ("calibration",), problems) if "calibration" in raw else None
    if cal is not None:
        problems += _models(cal)
    load, lines = _load(raw, raw.get("measurements"))
    problems += lines
    solver, lines, report = _solver(raw, cal.models if cal is not None else ())
    problems += lines
    meas, file_lines = _read(raw, Path(path).parent, robot, src)
    mraw = raw.get("measurements")
    frame = meas.frame if meas is not None else (mraw.get("frame") if isinstance(mraw, Mapping) else None)
    params: list[FitParameter] = []
    split = None
    if cal is not None and table is not None:
        case = {"robot": table, "load": load or {}}
        from ..robot.spec import robot_value_sources

        lraw = raw.get("load") if isinstance(raw.get("load"), Mapping) else {}
        sources = {**robot_value_sources(raw["robot"]), **{f"load.{k}": "set in the study file" for k in lraw}}
        params, lines = _parameters(cal, case, sources, robot.n_tendons, meas, frame)
        problems += lines
        if meas is not None and not lines:
            split, lines = _split_problems(cal, meas.n, len(params))
            problems += lines
    if not problems and meas is not None and cal is not None and not file_lines:
        problems += _capabilities(table, load, solver, meas, cal.models)
        n_cases = len(cal.models) * (cal.folds or 1)
        if max_cases is not None and n_cases > max_cases:
            problems.append(f"calibration: {n_cases} cases (models x folds) exceed max_cases = {max_cases}")
    out = [f"{src}: {p}" for p in problems] + file_lines
    if out or st is None or split is None:
        raise StudyError(out or [f"{src}: invalid calibration study"])
    resolved = _resolved(st, table, load, solver, report, mraw, _file_digest(Path(path).parent, mraw), meas, cal,
                         params, split)
    settings = CalibrationSettings(models=tuple(cal.models), parameters=tuple(params), split=split,
                                   confidence=cal.confidence, max_evaluations=cal.max_evaluations)
    payload = {"kind": KIND_NAME, **{k: v for k, v in resolved.items() if k not in ("study", "report")},
               "solver": {k: v for k, v in solver.items() if k not in LIMIT_KEYS}}
    digest = hashlib.sha256(canonical_json(payload).encode())  # name, description, report, limits: not results
    return CalibrationStudy(path=src, name=st.name, config_hash=digest.hexdigest()[:16], robot=table,
                            load=resolved["load"], solver=solver, report=resolved["report"], measurements=meas,
                            calibration=settings, overrides=tuple(overrides), raw=resolved)
