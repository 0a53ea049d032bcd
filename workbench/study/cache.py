"""A per-case result cache: a row computed once is reused by any later run that asks for the same thing.

Key: ``(model, model code version, case_id)``.  ``case_id`` is the content hash of the case's
parameters as configured (robot, load, solver, derived, scenario: :mod:`workbench.study.params`),
so adding a sweep value or a model to a study -- a new config hash, a new folder -- recomputes only
the new (case, model) pairs.  The *code version* of a model (:func:`code_version`) hashes the
Python source its result depends on -- the package of its registry target (``workbench/physics/``
for the Exudyn models, ``workbench/models/`` for CC; for a plug-in model the whole top-level package
of its target), the robot, kinematics and model-interface packages, the case building and row code
of ``workbench/study/`` -- and the versions of Python, numpy, scipy and Exudyn: editing any of them
invalidates that model's entries.

Only rows that are results are cached: ``ok`` rows and model failures (``failure = "model"``:
raised, not converged, non-finite); crashes, timeouts, memory, killed and lost rows are not; a
run with ``--retry-failed`` does not reuse cached model failures (it recomputes them).
Entries are pickled row dicts, one file per ``<cache>/<model>/<version>/<case_id>.pkl``, written
atomically (two runs may share a cache; the last writer of an identical row wins).  The CLI uses
``<parent of --out>/_cache`` (``--no-cache`` to turn it off); :func:`~workbench.study.runner.run_cases`
only with ``cache=``.  Checked by ``tests/study/test_cache.py``.
"""

from __future__ import annotations

import hashlib
import pickle
from functools import lru_cache
from pathlib import Path
from typing import Any

from .store import atomic_write_bytes

__all__ = ["CACHE_DIR", "ResultCache", "code_version"]

CACHE_DIR = "_cache"
_ROOT = Path(__file__).resolve().parents[1]  # the workbench package
_SHARED = ("robot", "kinematics", "models", "study/build.py", "study/rows.py", "study/evaluate.py",
           "study/params.py", "study/scenarios.py", "experiments")
_VERSIONED = ("numpy", "scipy", "exudyn", "numba")  # numba: the cosserat kernel (last digits differ without)


def _files(p: Path) -> list[Path]:
    return sorted(p.rglob("*.py")) if p.is_dir() else ([p] if p.exists() else [])


def _plugin_sources(top: str) -> list[tuple[str, Path]]:
    """(name, path) of the ``.py`` files of the top-level package ``top`` of a plug-in model (not imported)."""
    from importlib.util import find_spec

    spec = find_spec(top)
    if spec is None:
        return []
    dirs = [Path(d) for d in (spec.submodule_search_locations or [])]
    paths = [f for d in dirs for f in _files(d)] or ([Path(spec.origin)] if spec.origin else [])
    base = dirs[0].parent if dirs else Path(spec.origin or ".").parent
    return sorted((str(p.relative_to(base)), p) for p in set(paths))


def _sources(model: str) -> list[tuple[str, Path]]:
    """(name, path) of the source files ``model``'s results depend on (module docstring)."""
    from .. import registry

    info = registry.table("models").get(model)
    # the package of the model's code; rows of another study kind (registry.LABELS): all of physics
    module = info.target.partition(":")[0] if info is not None else "workbench.physics"
    top, _, rest = module.partition(".")
    out = _plugin_sources(top) if top != "workbench" else []
    parts = [] if top != "workbench" else rest.split(".")[:1]
    out += [(str(p.relative_to(_ROOT)), p) for rel in [*parts, *_SHARED] for p in _files(_ROOT / rel)]
    return sorted(set(out))


@lru_cache(maxsize=None)
def code_version(model: str) -> str:
    """16 hex digits: the hash of ``model``'s source files and numeric library versions (module docstring)."""
    from importlib import metadata
    import platform

    h = hashlib.sha256(f"{model}\npython {platform.python_version()}\n".encode())
    for name in _VERSIONED:
        try:
            h.update(f"{name} {metadata.version(name)}\n".encode())
        except metadata.PackageNotFoundError:
            h.update(f"{name} -\n".encode())
    for name, p in _sources(model):
        h.update(name.encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()[:16]


class ResultCache:
    """The cache in ``folder`` (created on the first write); counts ``hits`` and ``writes``."""

    def __init__(self, folder: str | Path) -> None:
        self.folder = Path(folder)
        self.hits = self.writes = 0

    def _path(self, case_id: str, model: str) -> Path:
        return self.folder / model / code_version(model) / f"{case_id}.pkl"

    def get(self, case_id: str, model: str, ok_only: bool = False) -> dict[str, Any] | None:
        """The cached row of ``(case_id, model)`` at the current code version, or ``None``.

        ``ok_only``: a cached model failure counts as absent (``--retry-failed`` recomputes it).
        """
        p = self._path(case_id, model)
        try:
            row = pickle.loads(p.read_bytes())
        except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ValueError):
            return None  # missing or unreadable (a half-written file cannot exist: writes are atomic)
        if not isinstance(row, dict) or row.get("case_id") != case_id or row.get("model") != model:
            return None
        if ok_only and row.get("status") != "ok":
            return None
        self.hits += 1
        return row

    def put(self, row: dict[str, Any]) -> None:
        """Store ``row`` if it is a result (``ok`` or a model failure); never raises for an unwritable cache."""
        if row.get("status") != "ok" and row.get("failure") != "model":
            return
        p = self._path(str(row["case_id"]), str(row["model"]))
        try:
            p.parent.mkdir(parents=True, exist_ok=True)
            data = pickle.dumps(row, protocol=pickle.HIGHEST_PROTOCOL)
            atomic_write_bytes(p, lambda f: f.write(data))
            self.writes += 1
        except OSError:
            pass  # a read-only or full cache costs time, not results
