"""Case parameters as data: canonical JSON, stable case ids, flat ``p.*`` columns and back.

Pure functions on plain dicts; imports nothing from the workbench, so every layer (the spec,
expansion, the store, the comparison table, the report) can use them without a cycle.

Checked by ``tests/study/test_expand.py`` (ids) and ``tests/study/test_params.py`` (round trip).
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any, Mapping

__all__ = ["canonical_json", "case_id_for", "case_id_from_sections", "flatten_params", "unflatten_params",
           "section_params"]


def canonical_json(obj: Any) -> str:
    """Deterministic JSON (sorted keys, exact float repr) used for hashes.

    A flat list of finite floats (the common swept value: tensions, lengths) is written without
    the encoder, byte-identical to it (``tests/study/test_params.py``).
    """
    if type(obj) is list and obj and all(type(v) is float for v in obj) and math.isfinite(sum(obj)):
        return "[" + ",".join(map(float.__repr__, obj)) + "]"
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False)


def case_id_for(params: dict[str, Any]) -> str:
    """Stable id of a resolved parameter set (16 hex digits of SHA-256 of canonical JSON)."""
    return hashlib.sha256(canonical_json(params).encode()).hexdigest()[:16]


def _flat_section(section: str, d: Mapping[str, Any]) -> dict[str, Any]:
    return {f"p.{section}.{k}": canonical_json(v) if isinstance(v, (list, tuple, dict)) else v for k, v in d.items()}


def case_id_from_sections(params: Mapping[str, Any], section_json: Mapping[str, str]) -> str:
    """:func:`case_id_for` of ``params`` (a dict of sections), taking ``section_json[sec]`` as the
    canonical JSON of section ``sec`` where given (the caller vouches that it is; e.g. sections
    that every case of a sweep shares, converted once).  Byte-identical to ``case_id_for(params)``."""
    parts = [f"{json.dumps(sec)}:{section_json[sec] if sec in section_json else canonical_json(params[sec])}"
             for sec in sorted(params)]
    return hashlib.sha256(("{" + ",".join(parts) + "}").encode()).hexdigest()[:16]


def flatten_params(params: dict[str, dict[str, Any]], memo: dict[int, tuple] | None = None,
                   shared: tuple[str, ...] = ("robot",)) -> dict[str, Any]:
    """``{"robot": {"length": 0.8}}`` -> ``{"p.robot.length": 0.8}``; lists become JSON strings.

    ``memo`` (optional, the caller's dict): the flat cells of the ``shared`` sections' dicts seen
    before, by identity (the dict is kept in the memo, so its id cannot be reused).  For section
    dicts shared between cases and never changed, e.g. a memoised robot's parameters
    (:func:`~workbench.study.build.resolve_case`), which then are not converted to JSON once per case.
    """
    out: dict[str, Any] = {}
    for section, d in params.items():
        if memo is None or section not in shared:
            out.update(_flat_section(section, d))
            continue
        hit = memo.get(id(d))
        if hit is None or hit[0] is not d or hit[1] != section:
            if len(memo) >= 64:
                memo.clear()
            hit = memo[id(d)] = (d, section, _flat_section(section, d))
        out.update(hit[2])
    return out


def _plain(v: Any) -> Any:
    """A stored cell as plain Python: JSON strings of lists/dicts decoded, numpy scalars unwrapped."""
    if isinstance(v, str) and v[:1] in "[{":
        return json.loads(v)
    item = getattr(v, "item", None)  # numpy scalar (no numpy import needed)
    if item is not None and getattr(v, "ndim", None) == 0:
        return item()
    return v


def _missing(v: Any) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v))


def section_params(row: Mapping[str, Any], section: str) -> dict[str, Any]:
    """The ``p.<section>.*`` cells of a table row as ``{key: value}`` (missing cells left out).

    The inverse of :func:`flatten_params` for one section: JSON strings become lists/dicts again,
    numpy scalars plain numbers; ``None``/NaN cells (parameters another case did not have) are
    dropped.
    """
    pre = f"p.{section}."
    return {k[len(pre):]: _plain(v) for k, v in row.items()
            if str(k).startswith(pre) and not _missing(v)}


def unflatten_params(row: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """All ``p.<section>.<key>`` cells of a row as ``{section: {key: value}}`` (see :func:`section_params`)."""
    sections = sorted({str(k).split(".")[1] for k in row if str(k).startswith("p.") and str(k).count(".") >= 2})
    return {s: section_params(row, s) for s in sections}
