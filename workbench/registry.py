"""The one table of plug-ins: models, robot presets, scenarios, study kinds and figure sets.

Data only.  Every entry names its code as a ``"module:attribute"`` string that
:func:`resolve` imports when it is first used, so reading this table imports nothing (neither
Exudyn nor any experiment).  Generic layers find experiment code only through these rows; a
new study is a folder under ``workbench/experiments/`` plus its rows here
(``docs/architecture.md``, "Where to add things").

Checked by ``tests/test_architecture.py`` (every row resolves; nothing here imports workbench).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Mapping

__all__ = ["Capabilities", "FIGURES", "FigureSet", "KINDS", "KindInfo", "LABELS", "MODELS", "ModelInfo", "PRESETS",
           "RowLabel", "SCENARIOS", "resolve", "row_info"]


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
    """

    target: str
    units: str | None = None
    lines: str | None = None
    axes: str | None = None


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
        tendon_models=("continuum",), spatial_length_tendon_models=("continuum",), analyses=("static",),
        note="Cosserat rod with continuously routed tendons (Rucker & Webster 2011), shooting with scipy; "
             "static only; accuracy from newton_tolerance, n_elements unused")),
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
    return MODELS.get(name) or LABELS.get(name)

PRESETS: Mapping[str, str] = {
    "steel_rod": "workbench.robot.presets.steel_rod:steel_rod",
    "hannan_walker": "workbench.robot.presets.hannan_walker:hannan_walker",
    "cojocaru_tronconic": "workbench.robot.presets.cojocaru:cojocaru_tronconic",
    "shao_harvester": "workbench.robot.presets.shao:shao_harvester",
    "hannan_walker_3d": "workbench.robot.presets.hannan_walker_3d:hannan_walker_3d",
    # a data preset: the DataPreset of workbench/robot/presets/rao_2021.toml (docs/robot-format.md)
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
                                axes="workbench.experiments.series_parallel.view:pose_columns"),
    "grasp": KindInfo("workbench.experiments.whole_arm_grasp.kind:KIND"),
    "closed_loop": KindInfo("workbench.experiments.closed_loop.kind:KIND"),
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
