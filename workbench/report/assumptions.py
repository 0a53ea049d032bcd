"""The report's Assumptions table: every parameter a source paper does not give, its value and source.

Gathered from data, never from docstrings: the ``ASSUMED`` tuples of
:class:`workbench.assumptions.Assumption` (read by :func:`workbench.assumptions.declared_assumptions`) of

* the robot preset's module (``workbench.registry.table("presets")``), values from the rows' ``p.robot.*``
  when the study sets them, else the preset's default; the source reads "set in the study file"
  where the study sets a value of its own;
* a robot in the description form (``docs/robot-format.md``): every value with its source
  (:func:`workbench.robot.spec.robot_value_sources`: the study file, a named material, a data preset);
* the scenario module (``workbench.registry.table("scenarios")``), values from ``p.scenario.*``;
* the study kind module (``workbench.registry.table("kinds")``; keys ``"section.key"``, e.g. the
  series-parallel module geometry), values from the rows;

then the study's own ``[report] assumptions`` (``"section.key"`` -> text), values from the rows,
how the error bars are made (the discretisation estimate and the models' orders) and, when the
study sets ``[solver] warm_start = true``, that solves started from other cases (:mod:`workbench.models.warm`).

A swept value is shown as its range with the baseline of the study's base section.  Checked by
``tests/report/test_findings.py``.
"""

from __future__ import annotations

import sys
from typing import Any, Mapping

import numpy as np

from .. import registry
from ..assumptions import Assumption, declared_assumptions
from .load import ResultSet
from .style import fmt

__all__ = ["assumption_rows"]


def _text(v: Any) -> str:
    if isinstance(v, float):
        return fmt(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_text(x) for x in v) + "]"
    if isinstance(v, Mapping):
        return ", ".join(f"{k} = {_text(x)}" for k, x in v.items())
    return str(v)


def _value(study: ResultSet, key: str, default: Any = None) -> str:
    """The value(s) the cases ran with (``p.<key>``), else ``default``, else the base section's."""
    col = f"p.{key}"
    ok = study.ok
    section, _, name = key.partition(".")
    base = study.spec.get(section) if isinstance(study.spec.get(section), Mapping) else {}
    if col in ok and ok[col].notna().any():
        vals = list(dict.fromkeys(ok[col].dropna()))
        if len(vals) == 1:
            return _text(_plain(vals[0]))
        nums = [float(v) for v in vals if isinstance(v, (int, float, np.floating)) and not isinstance(v, bool)]
        if len(nums) == len(vals):
            b = base.get(name)
            return f"swept {fmt(min(nums))} … {fmt(max(nums))}" + (f" (baseline {_text(b)})" if b is not None else "")
        return "swept: " + ", ".join(_text(_plain(v)) for v in vals)
    if default is not None:
        return _text(default)
    if name in base:
        return _text(base[name])
    return "n/a"


def _plain(v: Any) -> Any:
    import json

    if isinstance(v, str) and v[:1] == "[":
        try:
            return json.loads(v)
        except ValueError:
            return v
    return v.item() if hasattr(v, "item") and getattr(v, "ndim", 1) == 0 else v


def _module_of(target: str):
    module = target.partition(":")[0]
    __import__(module)
    return sys.modules[module]


def _declared_rows(study: ResultSet, section: str, target: str | None,
                   defaults: Mapping[str, Any] | None = None) -> list[Assumption]:
    """The ``ASSUMED`` of the module of ``target`` as table rows (key ``section.key`` unless dotted)."""
    if not target:
        return []
    out = []
    for a in declared_assumptions(_module_of(target)):
        key = a.key if "." in a.key else f"{section}.{a.key}"
        default = None if defaults is None else defaults.get(a.key)
        out.append(Assumption(key, a.source, value=_value(study, key, default)))
    return out


def _preset_rows(study: ResultSet) -> list[Assumption]:
    """The preset's assumed parameters as rows (:func:`~workbench.robot.presets.preset_sources`), each
    with its true source: a value the study sets (different from the preset's) reads "set in the study file"; a backbone strength left at the
    preset's while the study changes the material's stiffness says so."""
    robot = study.spec.get("robot") if isinstance(study.spec.get("robot"), Mapping) else {}
    name = robot.get("preset")
    presets = registry.table("presets")
    if not name or name not in presets:
        return []
    from ..robot.presets import data_preset, preset_parameters, preset_sources

    if data_preset(name) is not None:  # the description form: _description_rows
        return []
    defaults = preset_parameters(name)
    rows = [Assumption(f"robot.{k}", text, value=_value(study, f"robot.{k}", robot.get(k, defaults.get(k))))
            for k, text in preset_sources(name)["assumed"].items()]
    changed = {k for k in defaults if k in robot and robot[k] != defaults[k] or f"p.robot.{k}" in study.ok
               and study.ok[f"p.robot.{k}"].nunique() > 1}
    out = []
    for r in rows:
        key = r.key.partition(".")[2]
        source = "set in the study file" if key in changed else r.source
        if key == "yield_strength" and key not in changed and changed & {"youngs_modulus", "density"}:
            source = (f"still the preset's ({r.source}) although the study sets "
                      f"{' and '.join(sorted(changed & {'youngs_modulus', 'density'}))}: set robot.yield_strength "
                      "for another material")
        out.append(Assumption(r.key, source, value=r.value))
    return out


def _description_rows(study: ResultSet) -> list[Assumption]:
    """Every value of a description-form robot with its source (:func:`workbench.robot.spec.robot_value_sources`)."""
    from ..robot.materials import material
    from ..robot.spec import is_description, robot_description, robot_value_sources

    robot = study.spec.get("robot")
    if not isinstance(robot, Mapping) or not is_description(robot):
        return []
    try:
        sources = robot_value_sources(robot)
        desc = robot_description(robot)
    except (ValueError, TypeError, KeyError):  # a table the study's validation refused: nothing to show
        return []
    rows = []
    for key, source in sources.items():
        value = _leaf(desc, key.partition(".")[2])
        if value is None and source.startswith("material "):
            field = key.rpartition(".")[2]
            value = getattr(material(source[len("material "):].partition(":")[0]),
                            "tensile_strength" if field == "strength" else field, None)
        rows.append(Assumption(key, source, value=_text(value) if value is not None else ""))
    return rows


def _leaf(data: Any, path: str) -> Any:
    """The value at relative key path ``path`` (``sections[1].diameter``) of ``data``; ``None`` when absent."""
    import re

    node = data
    for name, index in re.findall(r"([A-Za-z_][A-Za-z0-9_]*)|\[(\d+)\]", path):
        ok = isinstance(node, Mapping) and name in node if name else isinstance(node, list) and int(index) < len(node)
        if not ok:
            return None
        node = node[name] if name else node[int(index)]
    return node


def _estimate_row(study: ResultSet) -> list[Assumption]:
    models = [m for m in study.models if registry.row_info(m) is not None and registry.row_info(m).order]
    if not models or "x.disc_tip_error" not in study.results:
        return []
    orders = ", ".join(f"{registry.row_info(m).label} {fmt(registry.row_info(m).order)}" for m in models)
    return [Assumption("error bars", value="Richardson, 1/2 and 1/4 resolution",
                       source=f"each physics case re-solved with half and a quarter of the elements / links (dynamics: "
                       f"2x and 4x the time step); error = |q_N - q_N/2| / (2^p - 1) with the declared order p "
                       f"({orders}; dynamics at most 2), lowered to the observed order when smaller. A CC "
                       f"comparison is 'not converged' when its error bar exceeds 10 % of its error, unless error "
                       f"plus error bar stay below 1e-5 L (agreement whatever the mesh).")]


def assumption_rows(study: ResultSet) -> list[Assumption]:
    """Every assumption of the study (see the module docstring), preset first."""
    spec = study.spec
    scen = spec.get("scenario") if isinstance(spec.get("scenario"), Mapping) else {}
    kind = (spec.get("study") or {}).get("kind") if isinstance(spec.get("study"), Mapping) else None
    rows = _preset_rows(study) + _description_rows(study)
    kinds = registry.table("kinds")
    rows += _declared_rows(study, "scenario", registry.table("scenarios").get(scen.get("name", "")))
    rows += _declared_rows(study, "", kinds[kind].target if kind in kinds else None)
    rep = spec.get("report") if isinstance(spec.get("report"), Mapping) else {}
    seen = {r.key for r in rows}
    for key, text in (rep.get("assumptions") or {}).items():
        if key in seen:  # the study's own words replace the preset's
            rows = [r for r in rows if r.key != key]
        rows.append(Assumption(str(key), str(text), value=_value(study, str(key))))
    return rows + _estimate_row(study) + _warm_row(study)


def _warm_row(study: ResultSet) -> list[Assumption]:
    solver = study.spec.get("solver") if isinstance(study.spec.get("solver"), Mapping) else {}
    if solver.get("warm_start") is not True:
        return []
    res = study.results
    warm = int((res["warm_from"].fillna("").astype(str) != "").sum()) if "warm_from" in res else 0
    return [Assumption("solver.warm_start", value="true",
                       source=f"{warm} of {len(res)} rows started from the state of an earlier case at a fraction of "
                       "their load (column warm_from: its case id), the others cold; answers agree with cold solves "
                       "within the solver tolerance where the cold ramp follows the load path (docs/study-format.md "
                       "\"Warm starts\")")]
