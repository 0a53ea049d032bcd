"""The measured-data reader: a calibration study's ``[measurements]`` table and its CSV / Parquet file.

:func:`read_measurements` checks the table (its schema :class:`MeasurementsTable`: strict types,
unknown keys refused with "did you mean"; the units through :func:`workbench.units.si_factor`; the
command columns against ``robot.tendon_table()``; backbone stations within ``[0, L]``), reads the
file (``.csv`` with pandas, every cell as text so that a bad cell is found, not coerced;
``.parquet`` with pandas / pyarrow), converts every mapped column to SI (``SI = scale * factor(unit)
* value``; a length command in the ``"pull"`` convention is negated into the
:class:`~workbench.robot.TendonActuation` convention, negative = reeled in) and returns
:class:`~workbench.measure.types.Measurements`.  A tip orientation (unit quaternion ``w, x, y, z``,
``frame <- tip``) must have ``| |q| - 1 | <= QUATERNION_TOLERANCE`` and is normalised before it
becomes a rotation matrix; a tip force given in the world frame is rotated into the base frame.

Every problem is one line.  A key of the table: ``<study>: measurements.<key path>: <reason>``; a
cell of the file: ``<data file>: row <r>, column '<name>' (measurements.<group>): <reason>``, ``r``
the 1-based data row (the header line not counted; a blank line is a row of empty cells).  All
problems of a file are collected (at most :data:`MAX_LINES` lines, then "... and N more") and
raised as one :class:`~workbench.study.messages.StudyError`.  Nothing is simulated and no model is
imported.  The format is ``docs/study-format.md``, "Calibration studies".

Checked by ``tests/measure/test_measure_data.py``, ``tests/measure/test_measure_data_units.py`` and
``tests/measure/test_measure_malformed.py``.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any, Literal, Mapping, get_args

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError

from ..study.messages import StudyError, fmt_loc, pydantic_problems, suggest
from ..units import si_factor
from .types import Measurements

__all__ = ["MAX_LINES", "QUATERNION_TOLERANCE", "MeasurementsTable", "quaternion_matrices", "read_measurements",
           "schema_problems", "table_problems"]

#: Most problem lines one data file reports (then "... and N more problems")
MAX_LINES = 20
#: Largest accepted | |q| - 1 | of a measured tip quaternion (trackers print 4 to 6 digits)
QUATERNION_TOLERANCE = 1e-3
#: the data file suffixes read
SUFFIXES = (".csv", ".parquet")

_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)


class CommandColumns(BaseModel):
    """``[measurements.commands]``: one column per tendon, ``robot.tendon_table()`` order."""

    model_config = _CFG
    columns: list[str] = Field(min_length=1)
    unit: str
    scale: float = 1.0
    convention: Literal["pull", "free_length"] | None = None


class PositionColumns(BaseModel):
    """``[measurements.tip_position]``: x, y, z in ``measurements.frame``."""

    model_config = _CFG
    columns: list[str] = Field(min_length=3, max_length=3)
    unit: str
    scale: float = 1.0


class ForceColumns(BaseModel):
    """``[measurements.tip_force]``: fx, fy, fz in the base or world frame."""

    model_config = _CFG
    columns: list[str] = Field(min_length=3, max_length=3)
    unit: str
    scale: float = 1.0
    frame: Literal["base", "world"]


class OrientationColumns(BaseModel):
    """``[measurements.tip_orientation]``: a unit quaternion ``w, x, y, z`` (``frame <- tip``)."""

    model_config = _CFG
    columns: list[str] = Field(min_length=4, max_length=4)


class BackboneColumns(BaseModel):
    """``[measurements.backbone]``: points at reference arc lengths ``stations`` [m]."""

    model_config = _CFG
    stations: list[float] = Field(min_length=1)
    columns: list[list[str]] = Field(min_length=1)
    unit: str
    scale: float = 1.0


class MeasurementsTable(BaseModel):
    """The ``[measurements]`` table (``docs/study-format.md``, "Calibration studies")."""

    model_config = _CFG
    file: str = Field(min_length=1)
    mode: Literal["tension", "length"]
    frame: Literal["measurement", "base", "world"]
    delimiter: str = Field(default=",", min_length=1, max_length=1)
    commands: CommandColumns
    tip_position: PositionColumns
    tip_force: ForceColumns | None = None
    tip_orientation: OrientationColumns | None = None
    backbone: BackboneColumns | None = None


def schema_problems(model: type[BaseModel], raw: Mapping[str, Any], where: tuple) -> tuple[Any, list[str]]:
    """``(validated model or None, problems)``: :func:`~workbench.study.messages.pydantic_problems` of
    ``raw``, with a misspelt key reported once ("unknown key; did you mean 'k'?", not also "k: missing")."""
    try:
        return model.model_validate(dict(raw)), []
    except ValidationError as e:
        lines = pydantic_problems(e, where, model)
        for err in e.errors():  # an optional sub-table's unknown key: suggest its fields too
            plain = f"{fmt_loc(where + tuple(err['loc']))}: unknown key"
            if err["type"] == "extra_forbidden" and plain in lines:
                lines[lines.index(plain)] = plain + suggest(str(err["loc"][-1]), _fields_at(model, err["loc"][:-1]))
    typos = set()
    for line in lines:
        head, _, rest = line.partition(": unknown key; did you mean '")
        if rest:
            typos.add(f"{head.rpartition('.')[0]}.{rest.partition(chr(39))[0]}: missing required key")
    return None, [line for line in lines if line not in typos]


def _fields_at(model: type[BaseModel], loc: tuple) -> list[str]:
    """Field names of the (nested, possibly optional) pydantic model at ``loc`` (``[]`` when none)."""
    m: Any = model
    for part in loc:
        f = m.model_fields.get(str(part)) if m is not None and not isinstance(part, int) else None
        if f is None:
            return []
        m = next((a for a in (f.annotation, *get_args(f.annotation))
                  if isinstance(a, type) and issubclass(a, BaseModel)), None)
    return list(m.model_fields) if m is not None else []


def _suggest_column(col: str, header: list[str]) -> str:
    """"; did you mean 'X'?" -- a header name equal but for case first, else the closest one."""
    same = [h for h in header if h.lower() == col.lower()]
    if same:
        return f"; did you mean {same[0]!r}?"
    return suggest(col, header).replace("; known keys:", "; columns in the file:")


def _si_unit(t: MeasurementsTable, group: str) -> str:
    return {"commands": "N" if t.mode == "tension" else "m", "tip_force": "N"}.get(group, "m")


def _groups(t: MeasurementsTable) -> dict[str, Any]:
    return {g: getattr(t, g) for g in ("commands", "tip_position", "tip_force", "tip_orientation", "backbone")
            if getattr(t, g) is not None}


def _tendon_order(robot: Any) -> str:
    """``section 1: 90°, -30°, 210°; section 2: ...`` -- the order of ``robot.tendon_table()``."""
    by: dict[int, list[str]] = {}
    for j, sigma, _ in robot.tendon_table():
        by.setdefault(j, []).append(f"{math.degrees(sigma):.4g}°")
    return "; ".join(f"section {j + 1} at {', '.join(a)}" for j, a in by.items())


def table_problems(t: MeasurementsTable, robot: Any, where: str = "measurements") -> list[str]:
    """The problems of a schema-valid table that need no data: units, scales, convention, counts, stations.

    ``robot`` may be ``None`` (an invalid ``[robot]``): the checks against it are then left out.
    """
    out = []
    for g, body in _groups(t).items():
        if hasattr(body, "unit"):
            try:
                si_factor(body.unit, _si_unit(t, g))
            except ValueError as e:
                out.append(f"{where}.{g}.unit: {e}")
        if hasattr(body, "scale") and not body.scale > 0:
            out.append(f"{where}.{g}.scale: must be > 0 (SI value = scale * value * unit), got {body.scale:g}")
    c = t.commands
    if t.mode == "length" and c.convention is None:
        out.append(f"{where}.commands.convention: missing required key in length mode: \"pull\" (a positive value "
                   f"reels the tendon in) or \"free_length\" (negative = reeled in)")
    if t.mode == "tension" and c.convention is not None:
        out.append(f"{where}.commands.convention: applies to length mode only (mode = \"tension\")")
    if robot is not None and len(c.columns) != robot.n_tendons:
        out.append(f"{where}.commands.columns: the robot has {robot.n_tendons} tendons, one column each in the order "
                   f"of robot.tendon_table() ({_tendon_order(robot)}), got {len(c.columns)} columns")
    b = t.backbone
    if b is not None:
        if len(b.columns) != len(b.stations):
            out.append(f"{where}.backbone.columns: one [x, y, z] column triple per station ({len(b.stations)} "
                       f"stations), got {len(b.columns)}")
        out += [f"{where}.backbone.columns[{i}]: must name 3 columns (x, y, z), got {len(cols)}"
                for i, cols in enumerate(b.columns) if len(cols) != 3]
        L = robot.length if robot is not None else math.inf
        out += [f"{where}.backbone.stations[{i}]: {s:g} m is outside [0, L] = [0, {L:g}] m (the robot's length)"
                for i, s in enumerate(b.stations) if not 0.0 <= s <= L]
    seen: dict[str, str] = {}
    for key, col in _mapped(t):
        if col in seen:
            out.append(f"{where}.{key}: column {col!r} is already mapped by {where}.{seen[col]}")
        else:
            seen[col] = key
    if Path(t.file).suffix.lower() not in SUFFIXES:
        out.append(f"{where}.file: must be a .csv or .parquet file, got {t.file!r}")
    return out


def _mapped(t: MeasurementsTable) -> list[tuple[str, str]]:
    """``(key path below measurements, column)`` of every mapped column, in table order."""
    out = []
    for g, body in _groups(t).items():
        if g == "backbone":
            out += [(f"{g}.columns[{i}][{k}]", c) for i, cols in enumerate(body.columns) for k, c in enumerate(cols)]
        else:
            out += [(f"{g}.columns[{k}]", c) for k, c in enumerate(body.columns)]
    return out


def _read_file(path: Path, delimiter: str) -> tuple[list[str], Any]:
    """``(header, frame)`` of the data file; :class:`ValueError` with the reason when it cannot be read."""
    import pandas as pd

    if not path.exists():
        raise ValueError("no such file")
    if path.is_dir():
        raise ValueError("is a folder, not a data file")
    if path.suffix.lower() == ".parquet":
        import pyarrow.parquet as pq

        try:
            header = list(pq.read_schema(path).names)
            frame = pq.read_table(path).to_pandas() if len(set(header)) == len(header) else None
        except Exception as e:  # noqa: BLE001 - any reader failure is an unreadable file
            raise ValueError(f"not a readable Parquet file ({' '.join(str(e).split())[:160]})") from None
        return header, frame
    try:
        with path.open(encoding="utf-8-sig", newline="") as fh:
            header = next(csv.reader(fh, delimiter=delimiter), [])
        if not header:
            raise pd.errors.EmptyDataError
        header = [h.strip() for h in header]
        frame = _csv(path, delimiter) if len(set(header)) == len(header) else None
    except UnicodeDecodeError as e:
        raise ValueError(f"not UTF-8 text (byte 0x{e.object[e.start]:02x} at offset {e.start})") from None
    except pd.errors.EmptyDataError:
        raise ValueError("the file is empty (a header line with the column names and one line per sample)") from None
    except (pd.errors.ParserError, OSError, csv.Error) as e:
        raise ValueError(f"not a readable CSV file ({' '.join(str(e).split())[:160]})") from None
    return header, frame


def _csv(path: Path, delimiter: str, text: bool = False) -> Any:
    """The CSV file as a frame: numbers parsed by pandas' C reader, or (``text``) every cell as its text."""
    import pandas as pd

    kw = {"dtype": str, "keep_default_na": False} if text else {}
    frame = pd.read_csv(path, skip_blank_lines=False, sep=delimiter, encoding="utf-8-sig", **kw)
    frame.columns = [str(c).strip() for c in frame.columns]
    if not text:
        return frame
    empty = (frame == "").all(axis=1)
    keep = len(frame)
    while keep and empty.iloc[keep - 1]:  # blank lines at the end of the file are no samples
        keep -= 1
    return frame.iloc[:keep]


def _cell_problem(text: str) -> str:
    if not text.strip():
        return "empty cell"
    try:
        v = float(text)
    except ValueError:
        return f"text in a number column: {text.strip()[:40]!r}"
    return "NaN (not a number)" if math.isnan(v) else f"must be finite, got {text.strip()}"


def _finite(s: Any) -> np.ndarray | None:
    """The column as floats when it is numeric and every value finite, else ``None``."""
    import pandas as pd

    if s.dtype == bool or not pd.api.types.is_numeric_dtype(s.dtype):
        return None
    v = s.to_numpy(dtype=float)
    return v if np.all(np.isfinite(v)) else None


def _numbers(s: Any) -> tuple[np.ndarray, list[tuple[int, str]]]:
    """A column as floats and ``(row, reason)`` of every cell that is not a finite number."""
    import pandas as pd

    if s.dtype == bool:
        return np.zeros(len(s)), [(1, f"a boolean column, not numbers ({s.dtype})")]
    if pd.api.types.is_numeric_dtype(s.dtype):
        v = s.to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(v))
        return v, [(int(i) + 1, "NaN (not a number) or empty cell" if math.isnan(v[i]) else f"must be finite, "
                    f"got {v[i]}") for i in bad]
    text = s.astype(str) if s.dtype == object else s
    v = pd.to_numeric(text.str.strip(), errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(~np.isfinite(v))
    return v, [(int(i) + 1, _cell_problem(str(s.iloc[i]) if s.iloc[i] is not None else "")) for i in bad]


def quaternion_matrices(q: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(n, 3, 3)`` of unit quaternions ``q`` ``(n, 4)`` ordered ``w, x, y, z`` (normalised here)."""
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1)], axis=1)


def _cap(lines: list[str], data: str) -> list[str]:
    if len(lines) <= MAX_LINES:
        return lines
    return lines[:MAX_LINES] + [f"{data}: ... and {len(lines) - MAX_LINES} more problems in this file"]


def _columns(frame: Any, t: MeasurementsTable, path: Path, where: str) -> tuple[dict[str, np.ndarray], list[str]]:
    """Every mapped column as floats, and one line per bad cell (row order, then column order).

    A CSV column that pandas' C reader did not parse as finite numbers is read again as text, so
    that each bad cell is named by what it holds.
    """
    data = str(path)
    values = {col: _finite(frame[col]) for _, col in _mapped(t)}
    if all(v is not None for v in values.values()):
        return values, []
    if path.suffix.lower() == ".csv":
        frame = _csv(path, t.delimiter, text=True)
    bad: list[tuple[int, int, str]] = []
    empty: dict[int, int] = {}
    for k, (key, col) in enumerate(_mapped(t)):
        v, problems = _numbers(frame[col])
        values[col] = v
        group = key.partition(".")[0]
        bad += [(row, k, f"{data}: row {row}, column {col!r} ({where}.{group}): {why}") for row, why in problems]
        for row, why in problems:
            empty[row] = empty.get(row, 0) + (why == "empty cell")
    blank = {row for row, count in empty.items() if count == len(values) > 1}
    bad = [b for b in bad if b[0] not in blank] + [(row, -1, f"{data}: row {row}: an empty line (every mapped "
                                                               f"column empty)") for row in blank]
    return values, [line for _, _, line in sorted(bad)]


def _group_si(t: MeasurementsTable, g: str, values: Mapping[str, np.ndarray], cols: list[str]) -> np.ndarray:
    body = getattr(t, g)
    factor = body.scale * si_factor(body.unit, _si_unit(t, g))
    return factor * np.stack([values[c] for c in cols], axis=1)


def _row_rules(t: MeasurementsTable, values: Mapping[str, np.ndarray], data: str, where: str) -> list[str]:
    """Rows that are numbers but not valid: negative tensions, quaternions that are not unit length."""
    bad: list[tuple[int, str]] = []
    if t.mode == "tension":
        for col in t.commands.columns:
            for i in np.flatnonzero(values[col] < 0):
                bad.append((int(i) + 1, f"{data}: row {i + 1}, column {col!r} ({where}.commands): a tension must be "
                                        f">= 0 (a tendon cannot push), got {values[col][i]:g} {t.commands.unit}"))
    if t.tip_orientation is not None:
        q = np.stack([values[c] for c in t.tip_orientation.columns], axis=1)
        norm = np.linalg.norm(q, axis=1)
        names = ", ".join(t.tip_orientation.columns)
        for i in np.flatnonzero(np.abs(norm - 1.0) > QUATERNION_TOLERANCE):
            bad.append((int(i) + 1, f"{data}: row {i + 1}, columns {names} ({where}.tip_orientation): not a unit "
                                    f"quaternion: |q| = {norm[i]:.6g} (| |q| - 1 | must be <= "
                                    f"{QUATERNION_TOLERANCE:g})"))
    return [line for _, line in sorted(bad, key=lambda b: b[0])]


def _validated(table: Any, src: str, where: str) -> MeasurementsTable:
    if not isinstance(table, Mapping):
        raise StudyError([f"{src}: {where}: must be a table [{where}], got {type(table).__name__}"])
    t, problems = schema_problems(MeasurementsTable, table, (where,))
    if t is None:
        raise StudyError([f"{src}: {p}" for p in problems])
    return t


def _measurements(t: MeasurementsTable, values: Mapping[str, np.ndarray], robot: Any, n: int) -> Measurements:
    cmd = _group_si(t, "commands", values, t.commands.columns)
    if t.mode == "length" and t.commands.convention == "pull":
        cmd = -cmd  # "pull": positive reels in; TendonActuation: negative free-length change = reeled in
    force = orient = stations = backbone = None
    if t.tip_force is not None:
        force = _group_si(t, "tip_force", values, t.tip_force.columns)
        if t.tip_force.frame == "world" and robot is not None:
            force = force @ np.asarray(robot.base_rotation, float)  # F_base = R^T F_world, R = world <- base
    if t.tip_orientation is not None:
        orient = quaternion_matrices(np.stack([values[c] for c in t.tip_orientation.columns], axis=1))
    if t.backbone is not None:
        stations = np.asarray(t.backbone.stations, float)
        backbone = np.stack([_group_si(t, "backbone", values, cols) for cols in t.backbone.columns], axis=1)
    return Measurements(source=t.file, mode=t.mode, commands=cmd + 0.0,
                        tip_position=_group_si(t, "tip_position", values, t.tip_position.columns), frame=t.frame,
                        file_rows=np.arange(1, n + 1), tip_force=force, tip_orientation=orient,
                        backbone_stations=stations, backbone=backbone)


def read_measurements(table: Mapping[str, Any], study_dir: str | Path, robot: Any, source_label: str = "<study>",
                      where: str = "measurements") -> Measurements:
    """The measured samples of a ``[measurements]`` table, in SI units.

    Parameters
    ----------
    table : mapping
        The ``[measurements]`` table of the study file.
    study_dir : path-like
        The study file's folder (``file`` is relative to it).
    robot : Robot or None
        The nominal robot (tendon count and order, length for the stations, base rotation for a
        world-frame force); ``None`` leaves those checks out.
    source_label : str
        The study file as messages name it.
    where : str
        The table's key path (``"measurements"``).

    Raises
    ------
    StudyError
        Every problem of the table and the file, one line each (module docstring).
    """
    t = _validated(table, source_label, where)
    problems = [f"{source_label}: {p}" for p in table_problems(t, robot, where)]
    path = Path(study_dir) / t.file
    data = str(path)
    if path.suffix.lower() not in SUFFIXES:
        raise StudyError(problems)
    try:
        header, frame = _read_file(path, t.delimiter)
    except ValueError as e:
        raise StudyError(problems + [f"{source_label}: {where}.file: cannot read {data}: {e}"]) from None
    dup = sorted({h for h in header if header.count(h) > 1})
    if dup:
        raise StudyError(problems + [f"{data}: duplicate column names in the header: {', '.join(map(repr, dup))}"])
    missing = [(key, col) for key, col in _mapped(t) if col not in header]
    if missing and len(missing) == len(_mapped(t)):
        shown = ", ".join(map(repr, header[:8])) + (", ..." if len(header) > 8 else "")
        raise StudyError(problems + [f"{data}: none of the columns {where} maps is in the file (header: {shown}); "
                                     f"is the delimiter {t.delimiter!r} right (measurements.delimiter)?"])
    for key, col in missing:
        problems.append(f"{data}: column {col!r} ({where}.{key}): not in the file{_suggest_column(col, header)}")
    if not missing and len(frame) == 0:
        problems.append(f"{data}: no data rows (only the header line)")
    if problems:
        raise StudyError(_cap(problems, data))
    values, cells = _columns(frame, t, path, where)
    if cells:
        raise StudyError(_cap(cells, data))
    n = len(next(iter(values.values())))
    if n == 0:
        raise StudyError([f"{data}: no data rows (only the header line)"])
    rows = _row_rules(t, values, data, where)
    if rows:
        raise StudyError(_cap(rows, data))
    return _measurements(t, values, robot, n)
