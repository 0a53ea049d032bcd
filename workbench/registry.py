"""The one table of plug-ins: models, robot presets, scenarios, study kinds and figure sets.

Data only.  Every entry names its code as a ``"module:attribute"`` string that
:func:`resolve` imports when it is first used, so reading this table imports nothing (neither
Exudyn nor any experiment).  Generic layers find experiment code only through these rows; a
new study is a folder under ``workbench/experiments/`` plus its rows here
(``docs/architecture.md``, "Where to add things").

The constants below are the built-in rows.  Installed packages add rows of the same types
through entry points in the groups ``trunk_workbench.<group>`` (:data:`GROUPS`; the walk-through
is ``docs/plugins.md``); :func:`table` returns the merged table of a group and is how every other
module reads rows, so a plug-in row does exactly what a built-in row does, in every process that
sees the same installed packages (the isolated child, process pools, Dask workers).

Checked by ``tests/test_architecture.py`` (every row resolves; nothing here imports workbench;
no other module reads the constants) and ``tests/test_plugins.py`` (discovery, clashes, broken
plug-ins; the example plug-in end to end).
"""

from __future__ import annotations

import functools
import importlib
from dataclasses import dataclass
from importlib import metadata
from types import MappingProxyType
from typing import Any, Mapping

__all__ = ["BUILT_IN", "Capabilities", "Discovery", "ENTRY_POINT_PREFIX", "FIGURES", "FigureSet", "GROUPS", "KINDS",
           "KindInfo", "LABELS", "MODELS", "ModelInfo", "PRESETS", "PluginError", "PluginRow", "ROW_TYPES",
           "RowLabel", "SCENARIOS", "discover", "package", "resolve", "row_info", "table"]


@dataclass(frozen=True)
class Capabilities:
    """What a ``run(robot, load, options)`` model supports; ``validate`` refuses anything else.

    Checked against every case before a run (:mod:`workbench.study.capabilities`); that each
    declared limit is real (the model itself refuses the combination) is checked by
    ``tests/study/test_capabilities.py``.

    Attributes
    ----------
    dimensions : tuple of str
        ``"planar"`` (tendons at sigma in {0, pi}, tip force in the base x-z plane, tip torque
        about base y) and/or ``"spatial"``.
    actuation : tuple of str
        Tendon command modes it can carry when the commands are non-zero (``()``: no tendon loads).
    tendon_models : tuple of str
        ``[solver] tendon_model`` values it supports for loaded tendons.
    length_tendon_models : tuple of str
        Tendon models it supports for length-controlled tendons in any case (planar included).
    spatial_length_tendon_models : tuple of str
        Tendon models it supports for length-controlled tendons in a non-planar case.
    loads : tuple of str
        Optional loads it carries: ``"tip_force"``, ``"tip_torque"``, ``"payload_offset"``.
    analyses : tuple of str
        ``"static"`` and/or ``"dynamic"``.
    dynamic_damping, dynamic_payload_offset : bool
        Whether ``[solver] damping > 0`` / a payload offset are supported in dynamic analysis.
    torsion : bool
        Whether it predicts the tip twist (informational: ``workbench list models``).
    gravity : str
        ``"any"`` (any direction), ``"in_plane"`` (only in the base x-z plane: a component along
        base y is refused) or ``"ignored"`` (no load bends the model, CC).
    tapered_continuum_tendons, spatial_tapered_continuum_tendons : tuple of str
        Command modes in which it carries loaded ``"continuum"`` tendons with a tapered offset
        (``TendonGroup.offset_tip`` set) in a planar / non-planar case.
    disk_weights : str
        What it represents (informational, the "What each model represents" table of
        ``docs/models.md``): where a disk's weight acts -- ``"at the disk"``, ``"on the nodes next to
        the disk"`` (lumped linearly, exact when disks sit on nodes), ``"spread over the section's links"``,
        ``"smeared over the section"`` or ``"ignored"``.
    extensibility : tuple of str
        Backbone deformations beyond bending it represents: ``"axial"``, ``"shear"`` (``()``:
        inextensible).
    tendon_path : str
        How a tendon runs (``""``: from ``tendon_models``, ``"continuum"`` = continuous routing, ``"eyelets"``
        = straight segments between disks).
    tendon_friction : bool
        Whether tendon-disk friction is represented.
    note : str
        What else a user should know (one sentence).
    """

    dimensions: tuple[str, ...] = ("planar", "spatial")
    actuation: tuple[str, ...] = ("tension", "length")
    tendon_models: tuple[str, ...] = ("continuum", "eyelets")
    length_tendon_models: tuple[str, ...] = ("continuum", "eyelets")
    spatial_length_tendon_models: tuple[str, ...] = ("continuum", "eyelets")
    loads: tuple[str, ...] = ("tip_force", "tip_torque", "payload_offset")
    analyses: tuple[str, ...] = ("static", "dynamic")
    dynamic_damping: bool = True
    dynamic_payload_offset: bool = True
    torsion: bool = True
    gravity: str = "any"
    tapered_continuum_tendons: tuple[str, ...] = ("tension", "length")
    spatial_tapered_continuum_tendons: tuple[str, ...] = ("tension", "length")
    disk_weights: str = "at the disk"
    extensibility: tuple[str, ...] = ("axial", "shear")
    tendon_path: str = ""
    tendon_friction: bool = False
    note: str = ""


@dataclass(frozen=True)
class ModelInfo:
    """A row model name -> code and presentation.

    Attributes
    ----------
    target : str
        ``"module:function"`` of ``run(robot, load, options) -> PhysicsResult``.
    label : str
        Name in figures and tables.
    color : str or None
        Line colour in figures (``None``: a fallback colour is picked per report).
    capabilities : Capabilities or None
        What the model supports (``None``: not declared, nothing to check).
    order : float or None
        Convergence order of the model's discretisation error in the element / link count
        (measured by its validation tests, ``docs/models.md``); the discretisation-error estimate
        of the study pipeline uses it (:mod:`workbench.models.discretization`).  ``None``: no
        discretisation (CC) or not declared.
    accuracy : {"mesh", "tolerance"}
        What limits the model's accuracy, i.e. how the study pipeline estimates its error
        (:mod:`workbench.study.estimate`): ``"mesh"`` (coarser re-solves, Richardson with
        ``order``) or ``"tolerance"`` (no mesh: a re-solve at a 100x tighter
        ``newton_tolerance``).
    """

    target: str
    label: str
    color: str | None = None
    capabilities: Capabilities | None = None
    order: float | None = None
    accuracy: str = "mesh"


@dataclass(frozen=True)
class RowLabel:
    """A ``model`` value another study kind writes that is not a ``run`` model (``"plan"``, ...).

    Attributes
    ----------
    label : str
        Name in figures and tables.
    color : str or None
        Line colour in figures (``None``: a fallback colour is picked per report).
    order : float or None
        Convergence order of the row's discretisation error, when the kind estimates one.
    """

    label: str
    color: str | None = None
    order: float | None = None


@dataclass(frozen=True)
class FigureSet:
    """A study-specific set of report figures: ``matches(results) -> bool`` and ``figures(...)``.

    Attributes
    ----------
    matches, figures : str
        ``"module:function"`` of ``matches(results) -> bool`` and of the figures.
    findings : str or None
        ``"module:function"`` of ``findings(results, cmp) -> [str]``, the study-specific
        sentences of the report's Findings section (numbers from the data).
    units : str or None
        ``"module:attribute"`` of a mapping ``key -> (name, unit)`` that extends the unit table
        (:mod:`workbench.units`) by the keys of this study (its scenario parameters, its
        extras); the keys must not be in the generic table.
    """

    matches: str
    figures: str
    findings: str | None = None
    units: str | None = None


@dataclass(frozen=True)
class KindInfo:
    """A study kind: its code and the plug-in points the generic report calls for its results.

    Attributes
    ----------
    target : str
        ``"module:attribute"`` of the :class:`~workbench.study.kinds.StudyKind` object.
    units : str or None
        ``"module:attribute"`` of a mapping ``key -> (name, unit)`` extending the unit table
        (:mod:`workbench.units`) by the kind's parameters and extra columns.
    lines : str or None
        ``"module:function"`` of ``lines(study)``, called once per report with its
        :class:`~workbench.report.load.ResultSet`; it returns a function of one case's rows
        ``{model: row}`` -> ``[(model, points), ...]``: extra polylines of the report's 3-D
        view (``points``: ``(k, n, 3)``, ``k`` lines of ``n`` points in the robot's base frame,
        drawn in the model's colour).
    axes : str or None
        ``"module:function"`` of ``axes(columns) -> [column]``: the parameter columns that vary
        the kind's cases, used where a sweep study's ``[sweep]`` keys would be (the kind's
        study file has no ``[sweep]``).
    robot_show : str or None
        ``"module:function"`` of ``show(spec) -> (lines, figure)`` for a kind whose trunk is not a
        ``[robot]``: called by ``workbench robot show`` with the loaded study ``spec``; ``lines`` are
        the text lines of the resolved trunk (parameters with units, derived quantities),
        ``figure`` a matplotlib ``Figure`` written as the PNG, or ``None``
        (``tests/study/test_robot_show.py``).
    """

    target: str
    units: str | None = None
    lines: str | None = None
    axes: str | None = None
    robot_show: str | None = None


MODELS: Mapping[str, ModelInfo] = {
    # orders: measured on the tip-load elastica and the pure-moment arc (tests/models/test_discretization.py):
    # ancf and ancf3d (cubic Hermite cables) ~4, beam3d 2, spring_link 2
    "cc": ModelInfo("workbench.models.cc:run", "CC", "#222222", Capabilities(
        torsion=False, gravity="ignored", disk_weights="ignored", extensibility=(),
        tendon_path="none (arc from the commands)",
        note="constant curvature from the tendon commands: external loads, gravity and dynamics "
                            "do not bend the arc (the assumption under test)")),
    "ancf": ModelInfo("workbench.physics.ancf:run", "ANCF", "#1f77b4", order=4.0, capabilities=Capabilities(
        dimensions=("planar",), loads=("tip_force", "tip_torque"), torsion=False, gravity="in_plane",
        extensibility=("axial",),
        note="planar ANCF cable (extensible Euler-Bernoulli) in the base x-z plane; gravity out of that plane "
             "is refused")),
    "beam3d": ModelInfo("workbench.physics.beam3d:run", "GE beam", "#d62728", order=2.0, capabilities=Capabilities(
        tendon_models=("eyelets",), spatial_length_tendon_models=("eyelets",),
        dynamic_payload_offset=False, disk_weights="on the nodes next to the disk",
        note="geometrically exact beam; tendons only as eyelet ropes; damping (stiffness-proportional, beta "
             "[s]) added by inter-node connectors")),
    "ancf3d": ModelInfo("workbench.physics.ancf3d:run", "ANCF 3-D", "#9467bd", order=4.0, capabilities=Capabilities(
        actuation=(), loads=("tip_force",), torsion=False,
        extensibility=("axial",), tendon_path="no tendons",
        note="3-D ANCF cable without a cross-section frame: no tendons, tip torque or payload offset")),
    "spring_link": ModelInfo("workbench.physics.spring_link:run", "spring-link", "#2ca02c", order=2.0, capabilities=Capabilities(
        disk_weights="at the disk", extensibility=(),
        note="rigid links and joint springs; continuum tendons as ropes through every link eyelet in 3-D; axial and "
             "shear springs by default only in planar continuum length mode ([solver] spring_link_axial)")),
    # no mesh (shooting to newton_tolerance): no order; its error is estimated by a tighter solve
    "cosserat": ModelInfo("workbench.physics.cosserat:run", "Cosserat rod", "#8c564b", accuracy="tolerance",
                          capabilities=Capabilities(
        tendon_models=("continuum", "eyelets"), length_tendon_models=("continuum",),
        spatial_length_tendon_models=("continuum",), analyses=("static",),
        note="Cosserat rod with continuously routed tendons (Rucker & Webster 2011) or eyelets (straight between "
             "disks, Rao et al. 2021's subsegment rod; tension control only), shooting; static only; accuracy "
             "from newton_tolerance, n_elements unused")),
    "spring_link_cardan": ModelInfo("workbench.physics.spring_link.cardan:run", "spring-link, 2-DOF joints",
                                    "#17becf", order=2.0, capabilities=Capabilities(
        torsion=False, disk_weights="at the disk", extensibility=(),
        note="3-D chain of Cardan (two-DOF, torsion-locked) joints, Hannan & Walker's robot, also for planar cases; "
             "refuses states with cable strain > 2 % (folded branches)")),
    # planar ANCF with a rigid circle (without an object: equal to ancf with continuum tendons, order 4);
    # order 1.5: the held tip of whole-arm wraps at 8-64 elements (observed 1.2-1.7, friction cases ~1,
    # where the per-case observed order is used; benchmarks/measure_contact_convergence.py)
    "contact": ModelInfo("workbench.physics.contact:run", "ANCF + contact", "#ff7f0e", order=1.5, capabilities=Capabilities(
        dimensions=("planar",), actuation=("tension",), tendon_models=("continuum",),
        spatial_length_tendon_models=(), loads=(), analyses=("static",), torsion=False, gravity="in_plane",
        extensibility=("axial",),
        note="planar ANCF cable in contact with a rigid circle; continuum tendons of constant offset in "
             "tension mode, static only, no tip force or torque")),
}

#: Rows of other study kinds (not ``run(robot, load, options)`` models): their labels and colours.
LABELS: Mapping[str, RowLabel] = {
    # rows of the series-parallel study kind; its GE-beam legs converge at order 2
    # (test_series_parallel.py, against the Cosserat shooting solver)
    "series_parallel": RowLabel("series-parallel", order=2.0),
    # rows of the closed-loop study kind: the controller's CC plan, the closed loop on a plant
    "plan": RowLabel("CC plan (open loop)", "#7f7f7f"),
    "spring_link_closed_loop": RowLabel("spring-link, closed loop", "#98df8a"),
    "ancf_closed_loop": RowLabel("ANCF, closed loop", "#aec7e8"),
    "cc_closed_loop": RowLabel("CC tendon map, closed loop", "#c7c7c7"),
}


def row_info(name: str) -> ModelInfo | RowLabel | None:
    """The registry row of the ``model`` value ``name``: a run model (:data:`MODELS`) or another
    kind's row (:data:`LABELS`); ``None`` when neither knows it.  Every reader of labels, colours
    and orders uses this (checked by ``tests/report/test_report_registry.py``)."""
    return table("models").get(name) or LABELS.get(name)

PRESETS: Mapping[str, str] = {
    # parametric data presets: the DataPreset of workbench/robot/presets/<name>.toml, used in the preset form
    "steel_rod": "workbench.robot.presets.data:FILES.steel_rod",
    "hannan_walker": "workbench.robot.presets.data:FILES.hannan_walker",
    "cojocaru_tronconic": "workbench.robot.presets.data:FILES.cojocaru_tronconic",
    "shao_harvester": "workbench.robot.presets.data:FILES.shao_harvester",
    "hannan_walker_3d": "workbench.robot.presets.data:FILES.hannan_walker_3d",
    # a description-form data preset: workbench/robot/presets/rao_2021.toml (docs/robot-format.md)
    "rao_2021": "workbench.robot.presets.data:FILES.rao_2021",
}

#: ``[scenario] name`` -> function ``(robot, **parameters) -> load fields``.
SCENARIOS: Mapping[str, str] = {
    "wire_delay": "workbench.experiments.wire_delay.scenario:wire_delay",
    "hannan_walker_line": "workbench.experiments.hannan_walker.scenario:hannan_walker_line",
    "whole_arm_wrap": "workbench.experiments.whole_arm_grasp.scenario:whole_arm_wrap",
    "harvester_scoop": "workbench.experiments.fruit_harvester.scoop:harvester_scoop",
    "hannan_walker_spatial": "workbench.experiments.hannan_walker.scenario:hannan_walker_spatial",
    "closed_loop": "workbench.experiments.closed_loop.scenario:closed_loop",
    "wire_delay_arm": "workbench.experiments.wire_delay.scenario:wire_delay_arm",
}

#: ``[study] kind`` -> the :class:`~workbench.study.kinds.StudyKind` object that loads, expands and runs it.
KINDS: Mapping[str, KindInfo] = {
    "sweep": KindInfo("workbench.study.kinds:SWEEP"),
    "series_parallel": KindInfo("workbench.experiments.series_parallel.kind:KIND",
                                units="workbench.experiments.series_parallel.units:QUANTITIES",
                                lines="workbench.experiments.series_parallel.view:leg_lines",
                                axes="workbench.experiments.series_parallel.view:pose_columns",
                                robot_show="workbench.experiments.series_parallel.show:show"),
    "grasp": KindInfo("workbench.experiments.whole_arm_grasp.kind:KIND"),
    "closed_loop": KindInfo("workbench.experiments.closed_loop.kind:KIND"),
    "calibration": KindInfo("workbench.measure.kind:KIND"),
}

#: Study-specific figures, in report order (before the generic figures).
FIGURES: Mapping[str, FigureSet] = {
    "wire_delay_arm": FigureSet("workbench.experiments.wire_delay.figures_arm:matches",
                                "workbench.experiments.wire_delay.figures_arm:figures",
                                units="workbench.experiments.wire_delay.units:QUANTITIES"),
    "wire_delay": FigureSet("workbench.experiments.wire_delay.figures:matches",
                            "workbench.experiments.wire_delay.figures:figures",
                            "workbench.experiments.wire_delay.findings:findings",
                            units="workbench.experiments.wire_delay.units:QUANTITIES"),
    "hannan_walker": FigureSet("workbench.experiments.hannan_walker.figures:matches",
                               "workbench.experiments.hannan_walker.figures:figures",
                               units="workbench.experiments.hannan_walker.units:QUANTITIES"),
    "hannan_walker_3d": FigureSet("workbench.experiments.hannan_walker.figures_3d:matches",
                                  "workbench.experiments.hannan_walker.figures_3d:figures",
                                  units="workbench.experiments.hannan_walker.units:QUANTITIES"),
    "closed_loop": FigureSet("workbench.experiments.closed_loop.figures:matches",
                             "workbench.experiments.closed_loop.figures:figures"),
    "fruit_harvester": FigureSet("workbench.experiments.fruit_harvester.figures:matches",
                                 "workbench.experiments.fruit_harvester.figures:figures"),
    "series_parallel_s_shape": FigureSet("workbench.experiments.series_parallel.figures_s_shape:matches",
                                         "workbench.experiments.series_parallel.figures_s_shape:figures"),
    "series_parallel": FigureSet("workbench.experiments.series_parallel.figures:matches",
                                 "workbench.experiments.series_parallel.figures:figures",
                                 "workbench.experiments.series_parallel.findings:findings"),
    "whole_arm_grasp": FigureSet("workbench.experiments.whole_arm_grasp.figures:matches",
                                 "workbench.experiments.whole_arm_grasp.figures:figures"),
    "fruit_harvester_scoop": FigureSet("workbench.experiments.fruit_harvester.scoop_figures:matches",
                                       "workbench.experiments.fruit_harvester.scoop_figures:figures"),
}


def resolve(target: str) -> Any:
    """Import ``"package.module:attribute"`` and return the attribute.

    Raises
    ------
    ValueError
        ``target`` is not of the form ``"module:attribute"``.
    ImportError, AttributeError
        The module or attribute does not exist (a broken registry row).
    """
    module, sep, attr = target.partition(":")
    if not sep or not module or not attr:
        raise ValueError(f"registry target must be 'module:attribute', got {target!r}")
    obj: Any = importlib.import_module(module)
    for part in attr.split("."):
        obj = getattr(obj, part)
    return obj


# -- plug-ins: rows of installed packages, found through entry points --------------------------------------------

#: The groups of rows a plug-in may add; the entry point group of ``g`` is ``ENTRY_POINT_PREFIX + g``.
GROUPS: tuple[str, ...] = ("presets", "models", "scenarios", "kinds", "figures")

#: Prefix of the entry point groups (``trunk_workbench.models`` ...).
ENTRY_POINT_PREFIX = "trunk_workbench."

#: The package :func:`package` names for a built-in row.
BUILT_IN = "built-in"

#: The type of a row of each group: an entry point loads to exactly this type (a preset or
#: scenario row is its ``"module:function"`` target, as in :data:`PRESETS` and :data:`SCENARIOS`).
ROW_TYPES: Mapping[str, type] = MappingProxyType(
    {"presets": str, "models": ModelInfo, "scenarios": str, "kinds": KindInfo, "figures": FigureSet})


class PluginError(ValueError):
    """Two packages register the same row name in one group (the message, one line, names both)."""


@dataclass(frozen=True)
class PluginRow:
    """One row an installed package registers.

    Attributes
    ----------
    group : str
        One of :data:`GROUPS`.
    name : str
        The row's name (the entry point's name).
    row : object
        The row, of type ``ROW_TYPES[group]``.
    package : str
        The registering distribution as ``"name version"``.
    entry_point : str
        ``"group:name"`` of the entry point.
    """

    group: str
    name: str
    row: Any
    package: str
    entry_point: str


@dataclass(frozen=True)
class Discovery:
    """What :func:`discover` found: the valid plug-in rows and one line per broken entry point.

    Attributes
    ----------
    rows : tuple of PluginRow
        Rows in entry point order, all groups.
    problems : tuple of str
        One line per entry point that was ignored (it fails to load, or loads to something other
        than its group's row type), naming the package and the entry point.
    """

    rows: tuple[PluginRow, ...]
    problems: tuple[str, ...]


def _first_line(e: BaseException) -> str:
    text = str(e).strip().splitlines()
    return f"{type(e).__name__}: {text[0]}" if text else type(e).__name__


def _load(group: str, ep: metadata.EntryPoint) -> tuple[PluginRow | None, str | None]:
    """``ep`` loaded as a row of ``group``, or ``None`` and the one line saying why not."""
    dist = getattr(ep, "dist", None)
    pkg = f"{dist.name} {dist.version}" if dist is not None else "an unknown package"
    where = f"plug-in {pkg}: entry point {ep.group}:{ep.name} = {ep.value!r}"
    try:
        row = ep.load()
    except Exception as e:  # noqa: BLE001 - any failure of a third-party import is reported, not raised
        return None, f"{where} cannot be loaded ({_first_line(e)}); ignored"
    want = ROW_TYPES[group]
    if type(row) is not want:
        return None, (f"{where} is a {type(row).__name__}, not a {want.__name__} (the row type of "
                      f"{ENTRY_POINT_PREFIX}{group}); ignored")
    return PluginRow(group, ep.name, row, pkg, f"{ep.group}:{ep.name}"), None


@functools.lru_cache(maxsize=1)
def discover() -> Discovery:
    """The rows installed packages register, from the entry points of this process's environment.

    Loads every entry point of the groups ``trunk_workbench.<group>`` (:data:`GROUPS`) once per
    process (cached; ``discover.cache_clear()`` looks again).  An entry point that fails to load
    or loads to the wrong type is left out with one line in :attr:`Discovery.problems` (the
    built-in rows and the other plug-ins keep working).  Because the entry points are those of
    the installed packages, every process started with the same ``sys.path`` (the isolated
    executor's child, process pools, Dask workers) finds the same rows: checked by
    ``tests/test_plugins.py``.
    """
    rows: list[PluginRow] = []
    problems: list[str] = []
    for group in GROUPS:
        for ep in metadata.entry_points(group=ENTRY_POINT_PREFIX + group):
            row, problem = _load(group, ep)
            if row is not None:
                rows.append(row)
            if problem is not None:
                problems.append(problem)
    return Discovery(tuple(rows), tuple(problems))


def _built_ins(group: str) -> Mapping[str, Any]:
    try:
        return {"presets": PRESETS, "models": MODELS, "scenarios": SCENARIOS, "kinds": KINDS,
                "figures": FIGURES}[group]
    except KeyError:
        raise KeyError(f"unknown registry group {group!r}; groups: {', '.join(GROUPS)}") from None


def _owners(group: str) -> dict[str, tuple[Any, str]]:
    """name -> (row, package) of ``group``: the built-in rows, then the plug-ins' (clash: PluginError)."""
    out = {name: (row, BUILT_IN) for name, row in _built_ins(group).items()}
    for r in discover().rows:
        if r.group != group:
            continue
        if r.name in out:
            first = out[r.name][1]
            first = "the workbench (built-in)" if first == BUILT_IN else f"plug-in {first}"
            raise PluginError(f"{ENTRY_POINT_PREFIX}{group}: {r.name!r} is registered twice, by {first} and by "
                              f"plug-in {r.package} (entry point {r.entry_point}); uninstall or rename one")
        out[r.name] = (r.row, r.package)
    return out


def table(group: str) -> Mapping[str, Any]:
    """The rows of ``group`` (one of :data:`GROUPS`): the built-in rows, then those of installed plug-ins.

    Every module other than this one reads rows through this function (never the constants),
    so a plug-in row is used wherever a built-in row is.  Read-only; built on each call from the
    constants and the cached :func:`discover`.

    Raises
    ------
    PluginError
        Two packages (the workbench or plug-ins) register the same name in ``group``.
    KeyError
        ``group`` is not one of :data:`GROUPS`.
    """
    return MappingProxyType({name: row for name, (row, _) in _owners(group).items()})


def package(group: str, name: str) -> str:
    """Who registers row ``name`` of ``group``: :data:`BUILT_IN` or the plug-in's ``"distribution version"``.

    Raises
    ------
    KeyError
        No such row.
    """
    return _owners(group)[name][1]
