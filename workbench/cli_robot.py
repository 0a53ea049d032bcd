"""``workbench robot show <study.toml | preset> [KEY=VALUE ...] [--case N|ID] [--out robot.png] [--tension T]``.

Prints the robot's parameters as resolved (units from :mod:`workbench.units`), the robot as built
(every section's fields with units), its derived quantities
(:mod:`workbench.study.robot_summary`: EI, EA, GJ and mass per length per section, total mass, the
gravity parameter gamma, the first bending frequency, tendon stiffness and strength, the stresses at
a stated command) and writes its picture (:mod:`workbench.report.robot_picture`) as a PNG.

A bare name that is a registered preset is that preset with its defaults; anything else is a study
file (a path, or a bare name found as ``studies/<name>.toml``), loaded by its kind's loader, so every
problem is the validator's one line (a kind may wrap the sweep :class:`~workbench.study.spec.Study` as
its ``study`` attribute, as closed_loop does), and its base robot resolved by
:func:`workbench.study.build.resolve_robot` (``[derived] gravity_parameter`` applied; the sweep is not,
unless ``--case`` picks one case of the kind's expansion).
A study whose kind registers a ``robot_show`` hook (:class:`workbench.registry.KindInfo`; series_parallel:
six-rod modules, no ``[robot]``) prints that hook's lines and writes its figure instead (:func:`kind_show`);
a kind with neither is refused in one line.
Runs no simulation (a ``robot_show`` hook may solve its trunk's home pose).  Checked by ``tests/study/test_robot_show.py`` (every preset and every committed
study; bad input gives one line and exit code 2).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

if TYPE_CHECKING:  # the summary code (numpy, scipy) is imported when the command runs
    from .study.robot_summary import RobotSummary

__all__ = ["add_robot_arguments", "robot_command", "resolve_target", "summary_lines", "parse_tension", "kind_show"]


def add_robot_arguments(sub) -> None:
    """The ``robot`` command and its ``show`` sub-command on the CLI's sub-parsers ``sub``."""
    rb = sub.add_parser("robot", help="describe a robot: resolved fields, derived quantities, picture")
    rsub = rb.add_subparsers(dest="robot_command", required=True, parser_class=type(rb))
    s = rsub.add_parser("show", help="print a preset's or a study's robot with its derived quantities; "
                                     "write its picture (PNG)")
    s.add_argument("target", help="a robot preset (workbench list presets) or a study file / bare study name")
    s.add_argument("overrides", nargs="*", metavar="KEY=VALUE",
                   help="settings that override the study file, validated like it (robot.diameter=1e-3)")
    s.add_argument("--out", default="robot.png", help="where the picture goes (default robot.png)")
    s.add_argument("--case", metavar="N|ID",
                   help="a study's case (its index in the expansion or its case id) instead of the base robot")
    s.add_argument("--tension", metavar="T",
                   help="command for the stresses [N]: one tension on the first tendon of every section, or one "
                        "per tendon, comma separated (default: the tensions that bend every section by 90 deg in CC)")


def parse_tension(text: str | None) -> float | tuple[float, ...] | None:
    """``--tension`` as a number, a tuple (comma separated) or ``None``; ValueError with one line."""
    if text is None:
        return None
    try:
        vals = tuple(float(x) for x in str(text).split(","))
    except ValueError:
        raise ValueError(f"--tension: not a number or comma-separated numbers: {text!r}") from None
    if not all(math.isfinite(v) and v >= 0 for v in vals):
        raise ValueError(f"--tension: tensions must be finite and >= 0 N, got {text}")
    return vals[0] if len(vals) == 1 else vals


def _pick_case(kind, spec, case: str, path: Path):
    """The case ``case`` (index or case id) of the study ``spec``; StudyError with one line if there is none."""
    from .study import StudyError

    cases = kind.expand(spec)
    for c in cases:
        if case == c.case_id or (case.isdigit() and int(case) == c.index):
            return c
    raise StudyError([f"--case {case}: no such case in {path} ({len(cases)} cases: give an index "
                      f"0..{len(cases) - 1} or a case id)"])


def resolve_target(target: str, overrides: tuple[str, ...], find_study: Callable[[str], Path],
                   case: str | None = None) -> tuple[Any, dict[str, Any], str]:
    """``(robot, its parameters as resolved, where it comes from)`` for a preset name or a study file.

    ``case`` (index or case id) picks one case of the study instead of its base robot.

    Raises
    ------
    StudyError
        Unknown preset / file, an invalid study, a study that describes no ``[robot]``; one line per problem.
    """
    from . import registry
    from .study import StudyError, get_kind, kind_of
    from .study.build import resolve_robot
    from .study.expand import sweep_keys
    from .study.spec import Study

    if target in registry.table("presets") and not Path(target).exists():
        if overrides or case is not None:
            what = overrides[0] if overrides else f"--case {case}"
            raise StudyError([f"{what}: applies to a study file, not to the preset {target!r}"])
        from .robot.presets import preset_parameters

        robot, _ = resolve_robot({"preset": target})
        return robot, {"preset": target, **preset_parameters(target)}, f"preset {target} with its defaults"
    try:
        path = find_study(target)
    except StudyError as e:
        if Path(target).name == target:  # a bare name: say both places that were searched
            rest = e.problems[0].removeprefix(f"{target}: ")
            raise StudyError([f"{target}: not a robot preset (known: {', '.join(registry.table('presets'))}) and {rest}"]
                             ) from None
        raise
    kind = get_kind(kind_of(path))
    spec = kind.load(path, overrides=tuple(overrides))
    study = spec if isinstance(spec, Study) else getattr(spec, "study", None)  # a kind may wrap the sweep Study
    base = study.base if isinstance(study, Study) else None
    if base is None and isinstance(getattr(spec, "robot", None), dict):  # a kind with one nominal robot (calibration)
        if case is not None:
            raise StudyError([f"--case {case}: a {kind.name!r} study has one nominal robot; drop --case"])
        try:
            robot, params = resolve_robot(spec.robot)
        except (ValueError, TypeError, KeyError) as e:
            raise StudyError([f"{path}: robot: {e}"]) from None
        how = f"preset {params['preset']}" if "preset" in params else "described in the file"
        return robot, params, f"study {path}: its nominal robot ({how}; before calibration)"
    if not isinstance(base, dict) or "robot" not in base:
        raise StudyError([f"{path}: a {kind.name!r} study has no [robot] section: robot show describes the tendon-"
                          f"driven robots of [robot] (this study's trunk is given by its own sections and its kind registers no "
                          f"robot_show)"])
    chosen = None if case is None else _pick_case(kind, spec, str(case), path)
    given = base if chosen is None else chosen.params
    try:
        robot, params = resolve_robot(given["robot"], given.get("derived"))
    except (ValueError, TypeError, KeyError) as e:
        raise StudyError([f"{path}: robot: {e}"]) from None
    how = f"preset {params['preset']}" if "preset" in params else "described in the file"
    if chosen is not None:
        values = ", ".join(f"{k} = {v}" for k, v in chosen.swept.items() if k.startswith(("robot.", "derived.")))
        return robot, params, (f"study {path}: case {chosen.index} ({chosen.case_id}; {how})"
                               + (f"; {values}" if values else ""))
    swept = [k for k in sweep_keys(study.sweep) if k.startswith(("robot.", "derived."))]
    where = f"study {path}: its base robot ({how})"
    return robot, params, where + (f"; swept in the study, not shown (see --case): {', '.join(swept)}"
                                   if swept else "")


def _g(x: float | None, scale: float = 1.0, fmt: str = ".4g") -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x * scale, fmt)


def _vec(v) -> str:
    return "(" + ", ".join(format(float(x) + 0.0, ".4g") for x in v) + ")"


def _table(header: list[str], rows: list[list[str]], indent: str = "  ") -> list[str]:
    w = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(header)]
    line = indent + "  ".join(h.rjust(n) for h, n in zip(header, w))
    return [line] + [indent + "  ".join(c.rjust(n) for c, n in zip(r, w)) for r in rows]


def _section_rows(robot) -> list[list[str]]:
    rows = []
    for j, s in enumerate(robot.sections):
        for tag, cs in (("", s.cross_section), (" tip", s.cross_section_tip)):
            if cs is None:
                continue
            rows.append([f"{j + 1}{tag}", _g(s.length) if not tag else "", _g(cs.diameter, 1e3), _g(cs.area, 1e6),
                         _g(cs.section_modulus, 1e9), _g(cs.EI), _g(cs.EA), _g(cs.GJ), _g(cs.GA),
                         _g(cs.mass_per_length), _g(cs.yield_strength, 1e-6),
                         str(s.n_disks) if not tag else "", _g(s.disk_mass * 1e3) if not tag else ""])
    return rows


def _robot_lines(robot) -> list[str]:
    R = robot.base_rotation
    out = ["the robot as built", f"  length L {robot.length:.4g} m, {robot.n_sections} section(s), {robot.n_tendons} tendon(s)",
           f"  base position {_vec(robot.base_position)} m; base z axis in the world {_vec(R[i][2] for i in range(3))};"
           f" gravity {_vec(robot.gravity)} m/s² (world)",
           f"  payload {robot.payload.mass:.4g} kg at {_vec(robot.payload.offset)} m (tip frame)", "", "sections"]
    out += _table(["#", "L [m]", "d [mm]", "A [mm²]", "W [mm³]", "EI [N m²]", "EA [N]", "GJ [N m²]", "GA [N]",
                   "m' [kg/m]", "yield [MPa]", "disks", "disk [g]"], _section_rows(robot))
    return out


def _tendon_lines(summary: RobotSummary) -> list[str]:
    rows = [[str(t.section + 1), str(t.count), " ".join(f"{math.degrees(a):.4g}" for a in t.angles),
             _g(t.offset, 1e3), _g(t.offset_tip, 1e3), _g(t.routed_length), _g(t.axial_stiffness),
             _g(t.spring_stiffness), _g(t.area, 1e6), _g(t.strength, 1e-6), _g(t.force_at_strength)]
            for t in summary.tendons]
    if not rows:
        return ["tendons: none"]
    return ["tendons (a group ends at its section's last disk)"] + _table(
        ["section", "n", "angles [deg]", "d base [mm]", "d tip [mm]", "L_t [m]", "EA_t [N]", "EA_t/L_t [N/m]",
         "A_t [mm²]", "strength [MPa]", "F at strength [N]"], rows)


def _derived_lines(summary: RobotSummary) -> list[str]:
    p = summary.sections
    out = ["derived quantities"] + _table(
        ["section", "EI [N m²]", "EA [N]", "GJ [N m²]", "m' [kg/m]", "m' + disks [kg/m]", "mass [kg]"],
        [[str(s.index + 1), _g(s.EI) + ("" if s.EI_tip is None else f"..{_g(s.EI_tip)}"), _g(s.EA), _g(s.GJ),
          _g(s.mass_per_length) + ("" if s.mass_per_length_tip is None else f"..{_g(s.mass_per_length_tip)}"),
          _g(s.mass_per_length_smeared), _g(s.mass)] for s in p])
    backbone, disks = sum(s.backbone_mass for s in p), sum(s.disk_mass for s in p)
    out.append(f"  total mass {summary.total_mass:.4g} kg (backbone {backbone:.4g}, disks {disks:.4g}, "
               f"payload {summary.robot.payload.mass:.4g})")
    g = math.hypot(*summary.robot.gravity)
    if summary.gamma is None:
        out.append("  gravity parameter gamma = q L³/EI: not defined (sections differ, tapered, or massless; "
                   "the rule of [derived] gravity_parameter)")
    else:
        out.append(f"  gravity parameter gamma = q L³/EI: {summary.gamma:.4g} at |g| = {g:.4g} m/s² "
                   f"({summary.gamma_standard:.4g} at 9.80665 m/s²; backbone weight only)")
    f = summary.frequency
    out.append("  first bending frequency: none (massless robot)" if f is None else
               f"  first bending frequency (clamped base) {f.hertz:.4g} Hz: {f.method}, {f.note}")
    return out


def _stress_lines(summary: RobotSummary) -> list[str]:
    st = summary.stresses
    if st is None:
        return [f"stresses at 90 deg per section: not available ({summary.stress_problem})"]
    rows = [[str(j + 1), _g(math.degrees(a)), _g(None if st.backbone is None else st.backbone[j], 1e-6),
             _g(None if st.backbone_strength is None else st.backbone_strength[j], 1e-6),
             _g(None if st.backbone is None else st.backbone[j] / st.backbone_strength[j])]
            for j, a in enumerate(st.bend_angles)]
    out = [f"stresses at the command: {st.command} (CC arc; gravity and tip loads not included)"]
    out += _table(["section", "bend angle [deg]", "backbone [MPa]", "yield [MPa]", "ratio"], rows)
    trows = [[str(sec + 1), _g(math.degrees(sig)), _g(T), _g(None if st.tendon is None else st.tendon[i], 1e-6),
              _g(None if st.tendon_strength is None else st.tendon_strength[i], 1e-6),
              _g(None if st.tendon is None else st.tendon[i] / st.tendon_strength[i])]
             for i, ((sec, sig, _), T) in enumerate(zip(summary.robot.tendon_table(), st.tensions))]
    out += _table(["tendon of section", "angle [deg]", "tension [N]", "stress [MPa]", "strength [MPa]", "ratio"],
                  trows)
    out.append(f"  largest ratio: backbone {_g(st.backbone_ratio)}, tendons {_g(st.tendon_ratio)} "
               f"(> 1: beyond the strength; '-': strength or area unknown)")
    return out


def _leaves(value: Any, path: str) -> list[tuple[str, Any]]:
    """``(key path, value)`` of every leaf of nested robot parameters (``a.b``, ``a[i].b``; scalar lists whole)."""
    if isinstance(value, dict):
        return [leaf for k, v in value.items() for leaf in _leaves(v, f"{path}.{k}")]
    if isinstance(value, (list, tuple)) and any(isinstance(v, (dict, list, tuple)) for v in value):
        return [leaf for i, v in enumerate(value) for leaf in _leaves(v, f"{path}[{i}]")]
    return [(path, value)]


def _parameter_lines(params: dict[str, Any]) -> list[str]:
    """The robot's parameters as resolved, one per line with the unit of ``workbench.units`` (none if unknown)."""
    from .units import unit_of

    out = ["parameters (as resolved; the unit where workbench/units.py knows the key)"]
    for key, value in _leaves(params, "robot"):
        unit = unit_of(key)
        text = format(value, ".6g") if isinstance(value, float) else str(value)
        out.append(f"  {key} = {text}" + (f" [{unit}]" if unit else ""))
    return out


def summary_lines(summary: RobotSummary, where: str, params: dict[str, Any] | None = None) -> list[str]:
    """The lines ``workbench robot show`` prints for ``summary`` (parameters, robot, tendons, derived, stresses)."""
    head = [f"robot {summary.robot.name!r}: {where}"] + (_parameter_lines(params) + [""] if params else [])
    return (head + _robot_lines(summary.robot) + [""] + _tendon_lines(summary) + [""] + _derived_lines(summary)
            + [""] + _stress_lines(summary))


def kind_show(target: str, overrides: tuple[str, ...], find_study: Callable[[str], Path], case: str | None,
              tension: str | None) -> tuple[list[str], Any] | None:
    """``(lines, figure)`` of the ``robot_show`` hook of the study kind of ``target``, or ``None``.

    ``None`` when ``target`` is a preset, no study file, or a study whose kind has no ``robot_show``
    (:class:`~workbench.registry.KindInfo`): :func:`resolve_target` then describes its ``[robot]`` or
    says in one line why it cannot.  Raises StudyError (one line) for an invalid study or for
    ``--case`` / ``--tension``, which apply to ``[robot]`` studies only.
    """
    from . import registry
    from .study import StudyError, get_kind, kind_of

    if target in registry.table("presets") and not Path(target).exists():
        return None
    try:
        path = find_study(target)
    except StudyError:
        return None
    name = kind_of(path)
    row = registry.table("kinds").get(name)
    hook = getattr(row, "robot_show", None)
    if not hook:
        return None
    spec = get_kind(name).load(path, overrides=tuple(overrides))
    for flag, value in (("--case", case), ("--tension", tension)):
        if value is not None:
            raise StudyError([f"{flag} {value}: applies to studies with a [robot], not to the {name!r} study {path}"])
    return registry.resolve(hook)(spec)


def _print_shown(lines: list[str], figure, out: Path) -> int:
    """Print a kind's ``robot_show`` lines and write its figure to ``out`` (exit 0; 2 if it cannot be written)."""
    for line in lines:
        print(line)
    if figure is None:
        print("\npicture: none (this study kind draws none)")
        return 0
    try:
        figure.savefig(out, dpi=110, format="png")
    except OSError as e:
        print(f"--out {out}: cannot write the picture ({e.strerror or e})", file=sys.stderr)
        return 2
    print(f"\npicture: {out}")
    return 0


def robot_command(args, find_study: Callable[[str], Path]) -> int:
    """``workbench robot show``: print the robot and write its picture (exit 0); bad input: one line, exit 2."""
    from .report.robot_picture import save_robot_picture
    from .study import StudyError
    from .study.robot_summary import summarize_robot

    if not str(args.out).strip() or Path(args.out).is_dir():
        print(f"--out {args.out!r}: give a file name for the picture, e.g. robot.png", file=sys.stderr)
        return 2
    try:
        shown = kind_show(args.target, tuple(args.overrides), find_study, args.case, args.tension)
        if shown is not None:
            return _print_shown(*shown, Path(args.out))
        tension = parse_tension(args.tension)
        robot, params, where = resolve_target(args.target, tuple(args.overrides), find_study, args.case)
        summary = summarize_robot(robot, tension)
    except StudyError as e:
        for line in e.problems:
            print(line, file=sys.stderr)
        return 2
    except ValueError as e:
        msg = str(e)
        print(msg if msg.startswith("--tension") else f"--tension: {msg}", file=sys.stderr)
        return 2
    for line in summary_lines(summary, where, params):
        print(line)
    out = Path(args.out)
    try:
        save_robot_picture(robot, out, title=f"{robot.name}: L = {robot.length:.4g} m, "
                                             f"{summary.total_mass:.4g} kg, {robot.n_sections} section(s)")
    except OSError as e:
        print(f"--out {out}: cannot write the picture ({e.strerror or e})", file=sys.stderr)
        return 2
    print(f"\npicture: {out}")
    return 0
