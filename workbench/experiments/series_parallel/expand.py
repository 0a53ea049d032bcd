"""Series-parallel expansion (pure): a validated study -> one case per commanded platform pose.

Each ``[motions]`` entry is sampled at ``samples`` amplitudes; each sample is one commanded
pose.  A case's ``params`` are plain data ``{"pose": {...}, "geometry": {...}, "solver": {...}}``
(recorded as ``p.pose.kind`` = ``module`` | ``stack``, ``shape``, ``value``, ``n_modules``,
``plane``, and ``pivot`` only where a file gives one; ``geometry`` = the study's ``[geometry]``
with the motion's own ``geometry`` overrides, a sensitivity sweep of the assumed module).  Its
``case_id`` is :func:`workbench.study.params.case_id_for` of those params with the pose under
:data:`ID_SECTION`, so it depends only on the values, not on the order of the motions or the
study name, and is the id the study has had since its first runs (old folders resume).

Checked by ``tests/experiments/series_parallel/test_spec.py`` (determinism, ids, values).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...study.expand import Case
from ...study.params import case_id_for
from .spec import SeriesParallelStudy

__all__ = ["ID_SECTION", "amplitude_values", "expand_poses"]

#: the name the case id hashes the pose section under: "motion", the section's name when the
#: study was first run, so case ids (and the cached rows of old folders) do not change with the name
ID_SECTION = "motion"


def amplitude_values(amplitude: float, samples: int, symmetric: bool) -> list[float]:
    """``linspace(-a, a, n)`` (symmetric) or ``linspace(a/n, a, n)``; exact zeros kept exact."""
    if symmetric:
        v = np.linspace(-amplitude, amplitude, samples) if samples > 1 else np.array([amplitude])
    else:
        v = np.linspace(amplitude / samples, amplitude, samples)
    return [0.0 if abs(x) < 1e-15 * amplitude else float(x) for x in v]


def expand_poses(study: SeriesParallelStudy) -> list[Case]:
    """All cases, module motions first (file order), then stack motions; duplicates merged."""
    cases: list[Case] = []
    seen: set[str] = set()

    def add(pose: dict[str, Any], geometry: dict[str, Any] | None = None) -> None:
        params = {"pose": pose, "geometry": {**study.geometry, **(geometry or {})}, "solver": dict(study.solver)}
        cid = case_id_for({ID_SECTION: pose, "geometry": params["geometry"], "solver": params["solver"]})
        if cid in seen:
            return
        seen.add(cid)
        swept = {f"pose.{k}": v for k, v in pose.items()}
        cases.append(Case(case_id=cid, index=len(cases), params=params, swept=swept))

    for m in study.motions.get("module", []):
        for v in amplitude_values(m["amplitude"], m["samples"], m["symmetric"]):
            pose = {"kind": "module", "shape": m["axis"], "value": v, "n_modules": 1, "plane": 0.0}
            if m.get("pivot") is not None:  # rx / ry about a centre on the module axis (absent: platform centre)
                pose["pivot"] = float(m["pivot"])
            add(pose, m.get("geometry"))
    for m in study.motions.get("stack", []):
        for v in amplitude_values(m["amplitude"], m["samples"], m["symmetric"]):
            add({"kind": "stack", "shape": m["shape"], "value": v, "n_modules": m["n_modules"], "plane": m["plane"]},
                m.get("geometry"))
    return cases
