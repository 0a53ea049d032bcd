"""Capability checks: does every model of a study support what each case asks of it?

Each model row of ``workbench.registry.table("models")`` declares its :class:`~workbench.registry.Capabilities`
(dimensions, actuation modes, tendon models, loads, analyses, dynamic restrictions).
:func:`case_features` reads what a built case needs (pure: the robot, the load case and the
solver parameters); :func:`unsupported` compares that with one model's declaration and returns
one line per problem, naming the key to change and the model::

    solver.tendon_model: model 'beam3d' supports loaded tendons only with tendon_model = 'eyelets' (got 'continuum'); change the key or drop the model

:func:`workbench.study.checks.check_cases` calls it for every distinct robot/load combination of
a sweep, so ``validate`` refuses what would fail at run time.  :func:`represents_table` writes the
table "What each model represents" of ``docs/models.md`` from the same declarations
(``workbench list represents`` prints it).  Checked by ``tests/study/test_capabilities.py`` (every
declared limit is one the model itself enforces; the table in the docs is the generated one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

__all__ = ["CaseFeatures", "case_features", "describe", "represents_table", "unsupported"]

_TOL = 1e-12
#: relative base-y gravity component a planar model refuses (as ``workbench.physics._ancf_problem``)
_GRAVITY_TOL = 1e-9


@dataclass(frozen=True)
class CaseFeatures:
    """What one case asks of a model (see :func:`case_features`); ``*_key``: the study key to name."""

    planar: bool
    planar_key: str
    planar_why: str
    tendon_mode: str | None  # "tension" / "length" when the tendons carry a load, else None
    tendon_key: str
    tendon_model: str
    tip_torque: bool
    tip_force: bool
    payload_offset: bool
    payload_key: str
    analysis: str
    damping: float
    gravity_out_of_plane: float = 0.0  # base-y component of gravity [m/s^2] (0 when within the tolerance)
    gravity_key: str = "robot.gravity"
    tapered: bool = False  # some tendon group has a tapered offset (offset_tip)
    tapered_key: str = "robot.preset"


def _first_key(params: Mapping[str, Any], section: str, names: Sequence[str], fallback: str) -> str:
    for n in names:
        if params.get(n) is not None:
            return f"{section}.{n}"
    return fallback


def case_features(robot: Any, load_case: Any, params: Mapping[str, Any], solver: Mapping[str, Any]) -> CaseFeatures:
    """The features of a built case.

    Parameters
    ----------
    robot : Robot
    load_case : LoadCase
        What :func:`~workbench.study.build.build_load` made of the case's ``[load]``.
    params : dict
        The case's resolved parameters (``robot``, ``load``, ...): used to name keys.
    solver : dict
        The ``[solver]`` parameters (``tendon_model``, ``damping``).
    """
    rp, lp = params.get("robot", {}), params.get("load", {})
    planar, key, why = True, "", ""
    for j, sigma, _ in robot.tendon_table():
        if abs(math.sin(sigma)) > 1e-9:
            planar, why = False, f"the tendon of section {j} at sigma = {sigma:.4g} rad is not in the base x-z plane"
            first = rp.get("first_tendon_angle")
            firsts = first if isinstance(first, list) else [first]  # a per-section list, or one value
            if "sections" in rp:  # the description form names the section's tendons
                key = f"robot.sections[{j}].tendons"
            elif first is not None and any(abs(math.sin(f)) > 1e-9 for f in firsts):
                key = "robot.first_tendon_angle"
            else:
                key = _first_key(rp, "robot", ("tendon_count", "tendon_angles"), "robot.preset")
            break
    F, M = np.asarray(load_case.tip_force, float), np.asarray(load_case.tip_torque, float)
    if planar and abs(F[1]) > _TOL * max(1.0, float(np.linalg.norm(F))):
        planar, key, why = False, "load.tip_force", f"the tip force {F.tolist()} N has a y component"
    scale_m = _TOL * max(1.0, float(np.linalg.norm(M)))
    if planar and (abs(M[0]) > scale_m or abs(M[2]) > scale_m):
        planar, key, why = False, "load.tip_torque", f"the tip torque {M.tolist()} N m is not about base y"
    act = load_case.actuation
    mode = None
    if act is not None and robot.n_tendons and (any(v != 0 for v in act.values) or act.pretension > 0):
        mode = act.mode
    tendon_key = _first_key(lp, "load", ("tensions", "length_changes", "bend_angle"), "load")
    if act is not None and not any(v != 0 for v in act.values) and act.pretension > 0:
        tendon_key = "load.pretension"
    offset = robot.payload.mass > 0 and any(robot.payload.offset)
    g = np.asarray(robot.gravity_in_base(), float)
    g_out = float(g[1]) if abs(g[1]) > _GRAVITY_TOL * float(np.linalg.norm(g)) else 0.0
    tapered = any(grp.offset_tip is not None for _, _, grp in robot.tendon_table())
    return CaseFeatures(
        planar=planar, planar_key=key, planar_why=why, tendon_mode=mode, tendon_key=tendon_key,
        tendon_model=str(solver.get("tendon_model", "continuum")), tip_torque=bool(np.any(M != 0)),
        tip_force=bool(np.any(F != 0)), payload_offset=bool(offset),
        payload_key=_first_key(rp, "robot", ("payload_offset", "payload_mass"), "robot.preset"),
        analysis=str(load_case.analysis), damping=float(solver.get("damping", 0.0)),
        gravity_out_of_plane=g_out,
        gravity_key=_first_key(rp, "robot", ("gravity_direction", "base_orientation", "gravity"), "robot.preset"),
        tapered=tapered, tapered_key=_first_key(rp, "robot", ("disk_diameter_step",), "robot.preset"))


def unsupported(model: str, caps: Any, f: CaseFeatures) -> list[str]:
    """Problems of case ``f`` for ``model`` with capabilities ``caps`` (one line each, key first)."""
    if caps is None:
        return []
    m = f"model {model!r}"
    tail = "; change the key or drop the model"
    out = []
    if not f.planar and "spatial" not in caps.dimensions:
        out.append(f"{f.planar_key}: {m} is planar only, but {f.planar_why}{tail}")
    if f.tendon_mode is not None:
        if f.tendon_mode not in caps.actuation:
            what = "cannot carry tendon loads" if not caps.actuation else \
                f"supports only {' / '.join(caps.actuation)} control, not {f.tendon_mode}"
            out.append(f"{f.tendon_key}: {m} {what} (tendon commands must be zero, no pretension){tail}"
                       if not caps.actuation else f"{f.tendon_key}: {m} {what}{tail}")
        elif f.tendon_model not in caps.tendon_models:
            out.append(f"solver.tendon_model: {m} supports loaded tendons only with tendon_model = "
                       f"{' or '.join(repr(t) for t in caps.tendon_models)} (got {f.tendon_model!r}){tail}")
        elif f.tendon_mode == "length" and f.tendon_model not in caps.length_tendon_models:
            out.append(f"solver.tendon_model: {m} supports length-controlled tendons only with tendon_model = "
                       f"{' or '.join(repr(t) for t in caps.length_tendon_models)} (got {f.tendon_model!r}){tail}")
        elif f.tendon_mode == "length" and not f.planar and f.tendon_model not in caps.spatial_length_tendon_models:
            out.append(f"solver.tendon_model: {m} supports length-controlled tendons in a non-planar case only with "
                       f"tendon_model = {' or '.join(repr(t) for t in caps.spatial_length_tendon_models)} (got "
                       f"{f.tendon_model!r}; {f.planar_why}){tail}")
        elif f.tapered and f.tendon_model == "continuum":
            modes = caps.tapered_continuum_tendons if f.planar else caps.spatial_tapered_continuum_tendons
            if f.tendon_mode not in modes:
                where = "a planar" if f.planar else "a non-planar"
                ok = f"only in {' / '.join(modes)} mode" if modes else "in no mode"
                hint = "; or set solver.tendon_model = 'eyelets'" if "eyelets" in caps.tendon_models else ""
                out.append(f"{f.tapered_key}: {m} carries continuum tendons with a tapered offset in {where} case "
                           f"{ok} (got {f.tendon_mode}){hint}{tail}")
    if f.gravity_out_of_plane and caps.gravity == "in_plane":
        out.append(f"{f.gravity_key}: {m} is planar and refuses gravity out of the base x-z plane (base y component "
                   f"{f.gravity_out_of_plane:.4g} m/s^2){tail}")
    if f.tip_torque and "tip_torque" not in caps.loads:
        out.append(f"load.tip_torque: {m} cannot carry a tip torque{tail}")
    if f.tip_force and "tip_force" not in caps.loads:
        out.append(f"load.tip_force: {m} cannot carry a tip force{tail}")
    if f.payload_offset and "payload_offset" not in caps.loads:
        out.append(f"{f.payload_key}: {m} cannot carry a payload with an offset from the tip{tail}")
    if f.analysis not in caps.analyses:
        out.append(f"load.analysis: {m} supports only {' / '.join(caps.analyses)} analysis{tail}")
    elif f.analysis == "dynamic":
        if f.damping > 0 and not caps.dynamic_damping:
            out.append(f"solver.damping: {m} ignores damping in dynamic analysis (got {f.damping:g}); set damping = 0 "
                       f"(dissipation through solver.spectral_radius) or drop the model")
        if f.payload_offset and not caps.dynamic_payload_offset:
            out.append(f"{f.payload_key}: {m} supports a payload offset in static analysis only{tail}")
    return out


def describe(caps: Any) -> str:
    """One line of what ``caps`` supports (``workbench list models``)."""
    if caps is None:
        return "rows of another study kind (not a run(robot, load, options) model)"
    parts = ["/".join(caps.dimensions),
             "tendons: " + ("none" if not caps.actuation else
                            f"{'/'.join(caps.actuation)} via {'/'.join(caps.tendon_models)}"),
             "loads: " + ("/".join(caps.loads) or "none"), "analysis: " + "/".join(caps.analyses),
             "torsion" if caps.torsion else "no torsion"]
    if caps.gravity == "in_plane":
        parts.append("gravity in the base x-z plane only")
    if not caps.dynamic_damping:
        parts.append("no damping in dynamics")
    return "; ".join(parts)


_PATHS = {"continuum": "continuous", "eyelets": "eyelets (straight between disks)"}
_GRAVITY = {"any": "any direction", "in_plane": "base x-z plane only (else refused)", "ignored": "ignored"}


def _tendon_path(caps: Any) -> str:
    if caps.tendon_path:
        return caps.tendon_path
    if not caps.actuation:
        return "no tendons"
    return " or ".join(_PATHS.get(t, t) for t in caps.tendon_models)


def represents_table(models: Mapping[str, Any] | None = None) -> str:
    """The markdown table "What each model represents" from the models' capabilities.

    One row per declared model of ``models`` (default ``workbench.registry.table("models")``): dimensions,
    tendon path, where disk weights act, extensibility, torsion, tendon friction, gravity and
    analyses.  ``docs/models.md`` holds its output (``workbench list represents`` prints it;
    ``tests/study/test_capabilities.py`` checks the docs against it).
    """
    if models is None:
        from ..registry import table

        models = table("models")
    head = ("model", "dimensions", "tendon path", "disk weights", "extensibility", "torsion", "tendon friction",
            "gravity", "analyses")
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for name, info in models.items():
        c = info.capabilities
        if c is None:
            continue
        cells = (f"`{name}`", " / ".join(c.dimensions), _tendon_path(c), c.disk_weights,
                 " + ".join(c.extensibility) or "inextensible", "yes" if c.torsion else "no",
                 "yes" if c.tendon_friction else "none", _GRAVITY.get(c.gravity, c.gravity), " / ".join(c.analyses))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
