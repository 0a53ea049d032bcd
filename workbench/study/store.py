"""Result store: one folder per study run, Parquet part files written atomically.

Layout of ``data/<study>/``::

    _manifest.json                        resolved spec, config hash, versions, git, host, runs
    part-0000000000000000000-schema.parquet   zero rows: the table's full schema (sorts first)
    part-<time_ns>-<pid>-<seq>.parquet    result rows, all rows of a case in one part

Every file is written to a unique dot-name (``.<name>.<pid>-<random>.tmp``), fsynced and renamed
(then the folder is fsynced), so ``pandas.read_parquet(folder)`` always reads a consistent table
and a SIGKILL at any moment loses at most the not-yet-flushed rows, which ``--resume``
recomputes.  Only the holder of the folder's lock (:mod:`workbench.study.lock`) writes, so
:meth:`ResultStore.cleanup_temporaries` removes only what dead writers left.  The manifest is
``_manifest.json`` (not ``manifest.json``): Parquet dataset discovery skips names starting with
``_`` or ``.``, but fails on any other non-Parquet file in the folder.

Why a schema file: Parquet dataset discovery takes the schema from the first file (sorted
names) and silently drops columns that other files add.  The schema file holds the union
of all columns seen so far, in a canonical order, and is rewritten (atomically) *before* a part
that adds columns, so columns never go missing (e.g. when the first part holds only failed
rows).  Array columns are ``list<double>`` holding the row-major flattened array; their
per-row shapes (``-1`` = leading length varies) are in the schema metadata
``workbench.shapes`` (JSON) -- see :func:`array_shapes`.

Columns renamed after a folder was written are read under their current names
(:data:`RENAMED_COLUMNS`, applied by :func:`read_table` and :func:`read_columns`), so old
result folders stay readable; nothing is rewritten on disk.
"""

from __future__ import annotations

import contextlib
import json
import os
import pickle
import signal
import struct
import threading
import time
import uuid
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable, Mapping

import pyarrow as pa
import pyarrow.parquet as pq

from .columns import field_metadata
from .outcomes import failure_of_error

__all__ = ["CorruptPart", "RENAMED_COLUMNS", "ResultStore", "SchemaMismatch", "StoredRow", "atomic_write_bytes",
           "check_parts", "current_name", "read_columns", "read_table", "array_shapes", "MANIFEST", "SCHEMA_FILE"]

MANIFEST = "_manifest.json"
SCHEMA_FILE = "part-0000000000000000000-schema.parquet"
#: rows added but not yet in a part, one record per unit (``journal=True``; a dot-name: readers skip it)
JOURNAL = ".rows-journal.bin"
_RECORD = struct.Struct("<II")  # payload length, crc32
_SHAPES_KEY = b"workbench.shapes"

_F64, _LIST = pa.float64(), pa.list_(pa.float64())
CORE_COLUMNS: tuple[tuple[str, pa.DataType], ...] = (
    ("case_id", pa.string()), ("model", pa.string()), ("status", pa.string()), ("error", pa.string()),
    ("failure", pa.string()), ("wall_time", _F64), ("robot_length", _F64), ("robot_gravity", _F64),
    ("tip_x", _F64), ("tip_y", _F64), ("tip_z", _F64), ("tip_frame", _LIST),
    ("length_change", _F64), ("tip_twist", _F64), ("converged", pa.bool_()), ("iterations", pa.int64()),
    ("stations", _LIST), ("positions", _LIST), ("tendon_tensions", _LIST), ("joint_angles", _LIST),
    ("time", _LIST),
)
_CORE_NAMES = {n for n, _ in CORE_COLUMNS}


def _fsync_dir(folder: Path) -> None:
    fd = os.open(folder, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def atomic_write_bytes(path: Path, write) -> None:
    """Write ``path`` via ``write(fileobj)`` to a unique ``.<name>.<pid>-<random>.tmp``, fsync, rename, fsync the folder.

    The temporary is removed if ``write`` fails (an interrupt included).
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:8]}.tmp")
    try:
        with open(tmp, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _fsync_dir(path.parent)


@contextlib.contextmanager
def deferred_interrupts():
    """Hold SIGINT / SIGTERM until the block is done, then act on them as if they came now.

    A part written but not yet taken off the buffer would be written twice by the flush of an
    interrupted run; writes happen inside this block.  Outside the main thread (the timer) it
    does nothing: Python runs signal handlers in the main thread only.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got: list[tuple[int, Any]] = []
    sigs = (signal.SIGINT, signal.SIGTERM)
    old = {s: signal.signal(s, lambda n, f: got.append((n, f))) for s in sigs}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        for n, f in got[:1]:
            h = old[n]
            if callable(h):
                h(n, f)
            elif h == signal.SIG_DFL:
                os.kill(os.getpid(), n)


def _param_type(values: Iterable[Any]) -> pa.DataType:
    kinds = {type(v) for v in values if v is not None}
    if not kinds:
        return pa.float64()
    if kinds <= {bool}:
        return pa.bool_()
    if kinds <= {int}:
        return pa.int64()
    if kinds <= {int, float}:
        return pa.float64()
    return pa.string()


class CorruptPart(ValueError):
    """A Parquet part of the folder cannot be read (``path``, ``reason``)."""

    def __init__(self, path: Path, reason: str):
        self.path, self.reason = Path(path), reason
        super().__init__(f"{path}: unreadable Parquet part ({reason})")


@dataclass(frozen=True)
class StoredRow:
    """What :meth:`ResultStore.stored_rows` reads of one stored row (``part``: its file)."""

    case_id: str
    model: str
    status: str
    failure: str
    part: str


class SchemaMismatch(ValueError):
    """A folder's stored column types differ from the types this run would write (``columns``: name -> (stored, new))."""

    def __init__(self, columns: dict[str, tuple[str, str]]):
        self.columns = columns
        shown = ", ".join(f"{k} is {a} there, {b} now" for k, (a, b) in list(columns.items())[:3])
        more = f" (+{len(columns) - 3} more)" if len(columns) > 3 else ""
        super().__init__(f"stored column types differ from this run's: {shown}{more}")


def _canonical_order(fields: Mapping[str, pa.DataType]) -> list[tuple[str, pa.DataType]]:
    core = [(n, t) for n, t in CORE_COLUMNS]
    rest = sorted(n for n in fields if n not in _CORE_NAMES)
    groups = [n for n in rest if n.startswith("p.")] + [n for n in rest if n.startswith("series.")] \
        + [n for n in rest if not n.startswith(("p.", "series."))]
    return core + [(n, fields[n]) for n in groups]


class ResultStore:
    """Append-only Parquet store of one study run.

    Parameters
    ----------
    folder : path-like
    param_rows : iterable of dict, optional
        Flattened ``p.*`` parameters of every case of the study: fixes the ``p.*`` column
        types up front (mixed int/float -> float, anything else mixed -> string).
    flush_rows, flush_seconds : int, float
        Buffered rows are written as one part when either limit is reached (and on
        :meth:`flush` / :meth:`close`; a timer may call :meth:`flush_if_due` from another thread).
        The rows of one unit (a case's models) are never split across parts.
    journal : bool
        Also append every :meth:`add` to :data:`JOURNAL` (one ``write`` of a length- and
        CRC-framed pickle, no fsync), emptied once its rows are in a part.  The kernel keeps
        what was written when the process dies (SIGKILL, a segfault of the in-process executor),
        so no finished unit is lost, at ~0.03 ms per unit instead of a part (~4 ms) per unit; the
        next run of the folder stores them (:meth:`recover_journal`).  An OS crash can lose
        the unsynced tail, as it loses the buffer.
    """

    def __init__(self, folder: str | Path, param_rows: Iterable[Mapping[str, Any]] = (),
                 flush_rows: int = 256, flush_seconds: float = 2.0, journal: bool = False) -> None:
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self._journaling = bool(journal)
        self._journal: int | None = None  # opened at the first add (after recover_journal)
        self.flush_rows, self.flush_seconds = int(flush_rows), float(flush_seconds)
        self._buffer: list[dict[str, Any]] = []
        self._lock = threading.RLock()
        self._last_flush = time.monotonic()
        self._seq = 0
        self._fields: dict[str, pa.DataType] = {n: t for n, t in CORE_COLUMNS}
        self._shapes: dict[str, list[int]] = {"tip_frame": [4, 4], "positions": [-1, 3]}
        schema_path = self.folder / SCHEMA_FILE
        stored: dict[str, pa.DataType] = {}
        if schema_path.exists():
            old = pq.read_schema(schema_path)
            stored = {f.name: f.type for f in old}
            self._fields.update(stored)
            if old.metadata and _SHAPES_KEY in old.metadata:
                self._shapes.update(json.loads(old.metadata[_SHAPES_KEY]))
        values: dict[str, list[Any]] = {}
        for row in param_rows:
            for k, v in row.items():
                values.setdefault(k, []).append(v)
        clash = {}
        for k, vs in values.items():
            new = _param_type(vs)
            if k in stored and stored[k] != new and any(v is not None for v in vs):
                clash[k] = (str(stored[k]), str(new))
            self._fields.setdefault(k, new)
        if clash:  # appending would fail at the first write, after the cases were computed
            raise SchemaMismatch(clash)
        self._schema: pa.Schema | None = None
        self._write_schema_if_changed()

    # -- reading ----------------------------------------------------------------------
    def part_files(self) -> list[Path]:
        return sorted(p for p in self.folder.glob("part-*.parquet") if p.name != SCHEMA_FILE)

    def stored_rows(self) -> list[StoredRow]:
        """Every stored row's ``(case_id, model, status, failure, part)`` (reads only those columns).

        Rows of older folders without a ``failure`` cell get one from their error text
        (:func:`~workbench.study.outcomes.failure_of_error`).

        Raises
        ------
        CorruptPart
            A part file is not readable Parquet (truncated, overwritten, not Parquet).
        """
        out = []
        for p in self.part_files():
            try:
                names = set(pq.read_schema(p).names)
                cols = [c for c in ("case_id", "model", "status", "failure", "error") if c in names]
                t = pq.read_table(p, columns=cols).to_pydict()
            except (OSError, pa.ArrowException) as e:
                raise CorruptPart(p, str(e).splitlines()[0] if str(e) else type(e).__name__) from None
            n = len(t.get("case_id", []))
            if "case_id" not in t or "model" not in t:
                raise CorruptPart(p, "no case_id/model columns")
            for i in range(n):
                status = (t.get("status") or [None] * n)[i] or "failed"
                failure = (t.get("failure") or [None] * n)[i]
                if status != "ok" and not failure:
                    failure = failure_of_error((t.get("error") or [""] * n)[i] or "")
                out.append(StoredRow(t["case_id"][i], t["model"][i], status, failure or "", p.name))
        return out

    def finished_case_ids(self) -> set[str]:
        """Case ids with rows on disk (reads only the ``case_id`` column)."""
        return {r.case_id for r in self.stored_rows()}

    def cleanup_temporaries(self) -> list[Path]:
        """Remove ``.*.tmp`` files left by killed writers (call only while holding the folder's lock)."""
        removed = []
        for p in self.folder.glob(".*.tmp"):
            p.unlink(missing_ok=True)
            removed.append(p)
        return removed

    # -- writing ----------------------------------------------------------------------
    def _current_schema(self) -> pa.Schema:
        fields = _canonical_order(self._fields)
        meta = {_SHAPES_KEY: json.dumps(self._shapes, sort_keys=True).encode()}
        return pa.schema([pa.field(n, t, metadata=field_metadata(n)) for n, t in fields], metadata=meta)

    def _write_schema_if_changed(self) -> None:
        schema = self._current_schema()
        if self._schema is not None and schema.equals(self._schema, check_metadata=True):
            return
        atomic_write_bytes(self.folder / SCHEMA_FILE, lambda f: pq.write_table(schema.empty_table(), f))
        self._schema = schema

    def recover_journal(self) -> int:
        """Store the rows a dead writer left in :data:`JOURNAL` (those not stored already); how many.

        Reads whole records up to the first torn or corrupt one (a writer killed mid-record),
        writes them as a part and removes the journal.  Call only while holding the folder's
        lock, before this store journals itself.
        """
        path = self.folder / JOURNAL
        if self._journal is not None or not path.exists():
            return 0
        rows = []
        data = path.read_bytes()
        at = 0
        while at + _RECORD.size <= len(data):
            n, crc = _RECORD.unpack_from(data, at)
            body = data[at + _RECORD.size:at + _RECORD.size + n]
            if len(body) < n or zlib.crc32(body) != crc:
                break
            rows.extend(pickle.loads(body))
            at += _RECORD.size + n
        stored = {(r.case_id, r.model) for r in self.stored_rows()} if rows else set()
        rows = [r for r in rows if (r.get("case_id"), r.get("model")) not in stored]
        if rows:
            with self._lock:
                self._buffer.extend(rows)
                self.flush()
        path.unlink()
        _fsync_dir(self.folder)
        return len(rows)

    def _append_journal(self, rows: list[dict[str, Any]]) -> None:
        body = pickle.dumps(rows, protocol=pickle.HIGHEST_PROTOCOL)
        rec = memoryview(_RECORD.pack(len(body), zlib.crc32(body)) + body)
        # one write of a few kB to a regular file; a torn tail (killed mid-write) is skipped by
        # recovery, and an interrupt handled here ends in a flush that empties the journal anyway
        while rec:
            rec = rec[os.write(self._journal, rec):]

    def add(self, rows: list[dict[str, Any]]) -> None:
        """Buffer the rows of one unit (a case's models); flushes when a limit is reached."""
        with self._lock:
            if self._journaling:
                if self._journal is None:
                    self._journal = os.open(self.folder / JOURNAL, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
                self._append_journal(rows)
            self._buffer.extend(rows)
            due = len(self._buffer) >= self.flush_rows or time.monotonic() - self._last_flush >= self.flush_seconds
        if due:
            self.flush()

    def flush_if_due(self) -> Path | None:
        """Flush when rows have waited ``flush_seconds`` (the run session's timer thread calls this)."""
        with self._lock:
            due = self._buffer and time.monotonic() - self._last_flush >= self.flush_seconds
        return self.flush() if due else None

    def flush(self) -> Path | None:
        """Write the buffered rows as one part file (atomic); returns its path.

        The buffer is emptied only once the part is on disk, so an interrupt during the write
        loses nothing that a later :meth:`flush` cannot still write.
        """
        with self._lock:
            self._last_flush = time.monotonic()
            if not self._buffer:
                return None
            rows = [dict(r) for r in self._buffer]
            for r in rows:
                for name, shape in (r.pop("_shapes", None) or {}).items():
                    self._shapes.setdefault(name, shape)
                for k, v in r.items():
                    if k not in self._fields:
                        self._fields[k] = (_LIST if isinstance(v, (list, tuple)) else
                                           pa.string() if isinstance(v, str) else pa.float64())
            self._write_schema_if_changed()
            table = pa.Table.from_pylist(rows, schema=self._schema)
            name = f"part-{time.time_ns():019d}-{os.getpid()}-{self._seq:06d}.parquet"
            self._seq += 1
            path = self.folder / name
            with deferred_interrupts():  # the part on disk and the buffer emptied: both or neither
                # no dictionary pages: the cells are mostly distinct floats, and a 256-row part of 68 columns
                # then writes in 2/3 of the CPU time and 5/6 of the bytes (benchmarks/README.md, runner rows)
                atomic_write_bytes(path, lambda f: pq.write_table(table, f, use_dictionary=False))
                del self._buffer[:len(rows)]
                if self._journal is not None and not self._buffer:
                    # killed before this: the journal's rows are stored already (recovery skips them)
                    os.ftruncate(self._journal, 0)
            return path

    def remove_rows(self, keys: Iterable[tuple[str, str]]) -> int:
        """Delete the stored rows ``(case_id, model)`` in ``keys`` (rows to recompute); returns how many.

        Each part holding such rows is rewritten without them (atomically, same name) or removed
        when nothing is left.  Call only while holding the folder's lock.
        """
        keys = set(keys)
        if not keys:
            return 0
        by_part: dict[str, int] = {}
        for r in self.stored_rows():
            if (r.case_id, r.model) in keys:
                by_part[r.part] = by_part.get(r.part, 0) + 1
        for part in by_part:
            path = self.folder / part
            t = pq.read_table(path)
            ids, models = t.column("case_id").to_pylist(), t.column("model").to_pylist()
            keep = [i for i, (c, m) in enumerate(zip(ids, models)) if (c, m) not in keys]
            if keep:
                kept = t.take(pa.array(keep, pa.int64()))
                atomic_write_bytes(path, lambda f: pq.write_table(kept, f))
            else:
                path.unlink()
                _fsync_dir(self.folder)
        return sum(by_part.values())

    def close(self) -> None:
        self.flush()
        if self._journal is not None:
            os.close(self._journal)
            self._journal = None
            if not self._buffer:
                (self.folder / JOURNAL).unlink(missing_ok=True)


#: Read-side aliases of renamed columns, old name prefix -> current prefix: a folder written
#: before the rename is read under the current names.  ``p.motion.*`` of the series-parallel study
#: (the commanded platform pose) is ``p.pose.*``.  Checked by ``tests/study/test_renamed_columns.py``.
RENAMED_COLUMNS: dict[str, str] = {"p.motion.": "p.pose."}


def current_name(name: str) -> str:
    """The current name of a stored column ``name`` (:data:`RENAMED_COLUMNS`); other names unchanged."""
    for old, new in RENAMED_COLUMNS.items():
        if name.startswith(old):
            return new + name[len(old):]
    return name


def _current_columns(df):
    """``df`` with old column names renamed; an old column merges into its current one where both exist."""
    for c in [c for c in df.columns if current_name(c) != c]:
        new = current_name(c)
        if new in df.columns:  # a folder resumed after the rename: old rows hold the old column
            df[new] = df[new].where(df[new].notna(), df[c])
            df = df.drop(columns=[c])
        else:
            df = df.rename(columns={c: new})
    return df


def read_columns(folder: str | Path, columns: list[str]):
    """The columns of ``columns`` that the folder's table has, as a pandas DataFrame.

    Columns the folder does not have (written by an older version) are filled with ``None``.
    Columns are named by their current names (:func:`current_name`; an old name asked for
    comes back under its current one).

    Raises
    ------
    FileNotFoundError
        The folder holds no Parquet parts.
    CorruptPart
        A part file is not readable Parquet (its name is in the message).
    """
    import pandas as pd

    folder = Path(folder)
    if not any(folder.glob("part-*.parquet")):
        raise FileNotFoundError(f"{folder}: no Parquet parts (no stored rows)")
    try:
        names = set(pq.read_schema(folder / SCHEMA_FILE).names) if (folder / SCHEMA_FILE).exists() else None
    except (OSError, pa.ArrowException) as e:
        raise CorruptPart(folder / SCHEMA_FILE, str(e).splitlines()[0] if str(e) else type(e).__name__) from None
    columns = list(dict.fromkeys(map(current_name, columns)))
    stored = names if names is not None else set(columns)
    want = [c for c in sorted(stored) if current_name(c) in columns] if names is not None else columns
    try:
        df = _current_columns(pd.read_parquet(folder, columns=want))
    except (OSError, pa.ArrowException, ValueError) as e:
        _raise_corrupt_part(folder, e)
    for c in columns:
        if c not in df.columns:
            df[c] = None
    return df[columns]


def check_parts(folder: str | Path) -> None:
    """Raise :class:`CorruptPart` for the first part file of ``folder`` that is not readable Parquet."""
    for p in sorted(Path(folder).glob("part-*.parquet")):
        try:
            pq.read_metadata(p)
        except (OSError, pa.ArrowException) as err:
            raise CorruptPart(p, str(err).splitlines()[0] if str(err) else type(err).__name__) from None


def _raise_corrupt_part(folder: Path, e: Exception):
    for p in sorted(folder.glob("part-*.parquet")):
        try:
            pq.read_metadata(p)
        except (OSError, pa.ArrowException) as err:
            raise CorruptPart(p, str(err).splitlines()[0] if str(err) else type(err).__name__) from None
    raise CorruptPart(folder, str(e).splitlines()[0] if str(e) else type(e).__name__) from None


def read_table(folder: str | Path):
    """The result table of a study folder as a pandas DataFrame (``pd.read_parquet``, columns by current name)."""
    import pandas as pd

    return _current_columns(pd.read_parquet(Path(folder)))


def array_shapes(folder: str | Path) -> dict[str, list[int]]:
    """Per-row shapes of the array columns (``-1``: varies, e.g. the number of stations)."""
    md = pq.read_schema(Path(folder) / SCHEMA_FILE).metadata or {}
    return json.loads(md.get(_SHAPES_KEY, b"{}"))
