"""Seeded random static cases for the cross-examination of the models (issue 28).

A case is plain data (:class:`XCase`): the parameters of the ``steel_rod`` preset
(:mod:`workbench.robot.presets.steel_rod`, so that a study file can rebuild it), the ``[load]``
parameters of a study and two extras the preset cannot express (a tilted base, a tapered tendon
offset).  :func:`generate` draws cases from ``numpy.random.default_rng((seed, index))``: the
same seed and index always give the same case, and case ``i`` does not depend on how many cases
are drawn.  :func:`build` turns a case into the :class:`~workbench.robot.Robot` and
:class:`~workbench.robot.LoadCase` the models run on; :func:`study_toml` prints a study file
that runs it (``workbench validate`` / ``workbench run``).

Robots: Rao's NiTi rod (d 1.4 mm, E 54 GPa, density 6450 kg/m^3, nu 0.3, 0.2 m sections, 10 mm
tendon offset) and a 2 mm steel rod (0.25 m sections); 1 to 3 sections; planar tendons (0, pi)
or spatial ones (90, 210, 330 deg, the set 90 / -30 / 210 of diagnostics.md in the preset's
evenly spaced order).  Loads are scaled by the rod's own stiffness so that the tip deflection
stays moderate: tendon moments give a bending angle of at most ~0.9 rad, tip forces
``alpha EI / L^2`` with alpha <= 0.6, tip torques ``beta EI / L`` with beta <= 0.4, gravity
``gamma EI / (m' L^3)`` with gamma <= 1.2.  Checked by ``tests/crossexam/test_crossexam.py``
(determinism, the moderate-deflection bound via the Cosserat tips of the default tier).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from workbench.models.cc import actuation_from_arc
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset

__all__ = ["MATERIALS", "XCase", "build", "diagnostic_cases", "generate", "study_toml", "TILT"]

#: Rod materials: preset parameters per material and the section length [m].
MATERIALS = {
    "niti": (dict(diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.3, tendon_offset=0.01), 0.2),
    "steel": (dict(diameter=2e-3, youngs_modulus=210e9, density=7850.0, poisson_ratio=0.3, tendon_offset=0.01), 0.25),
}
#: The "tilted" base: world <- base rotation by 40 deg about the axis (1, 1, 0) / sqrt 2 for spatial
#: cases (gravity gets base x and y components), about base y for planar ones (gravity stays in x-z).
TILT = math.radians(40.0)


@dataclass(frozen=True)
class XCase:
    """One cross-examination case: ``robot`` (steel_rod preset parameters), ``load`` (study
    ``[load]`` parameters) and the extras ``tilted`` (base orientation "tilted", see :data:`TILT`)
    and ``offset_tip`` (tapered tendon offset [m] at each section's end, ``None``: constant).
    ``tags`` name the features drawn (in the case's name and the table)."""

    seed: int
    index: int
    robot: tuple[tuple[str, object], ...]
    load: tuple[tuple[str, object], ...]
    tilted: bool = False
    offset_tip: float | None = None
    tags: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """``s<seed>-<index>-<tags>`` (the pytest id)."""
        return f"s{self.seed}-{self.index}-" + "-".join(self.tags)

    def has(self, *tags: str) -> bool:
        """Whether every tag in ``tags`` was drawn."""
        return all(t in self.tags for t in tags)


def _tilt_rotation(spatial: bool) -> tuple[tuple[float, ...], ...]:
    axis = np.array([1.0, 1.0, 0.0]) / math.sqrt(2.0) if spatial else np.array([0.0, 1.0, 0.0])
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    R = np.eye(3) + math.sin(TILT) * K + (1.0 - math.cos(TILT)) * K @ K
    return tuple(tuple(float(x) for x in row) for row in R)


def build(case: XCase):
    """``(robot, load_case)`` of ``case`` (the steel_rod preset, then the extras)."""
    robot = build_preset("steel_rod", **dict(case.robot))
    if case.tilted:
        robot = replace(robot, base_rotation=_tilt_rotation(dict(case.robot)["tendon_count"] == 3))
    if case.offset_tip is not None:
        robot = replace(robot, sections=tuple(replace(s, tendons=replace(s.tendons, offset_tip=case.offset_tip))
                                              for s in robot.sections))
    ld = dict(case.load)
    act = None
    if "tensions" in ld:
        act = TendonActuation("tension", tuple(ld["tensions"]))
    elif "length_changes" in ld:
        act = TendonActuation("length", tuple(ld["length_changes"]), pretension=ld.get("pretension", 0.0))
    return robot, LoadCase(actuation=act, tip_force=tuple(ld.get("tip_force", (0.0, 0.0, 0.0))),
                           tip_torque=tuple(ld.get("tip_torque", (0.0, 0.0, 0.0))))


def _draw(rng: np.random.Generator, seed: int, index: int) -> XCase:
    material = "niti" if rng.random() < 0.7 else "steel"
    mat, sec_len = MATERIALS[material]
    ns = int(rng.integers(1, 4))
    spatial = rng.random() < 0.5
    length_mode = rng.random() < 0.25
    L = ns * sec_len
    E, d = mat["youngs_modulus"], mat["diameter"]
    EI = E * math.pi * d**4 / 64.0
    mpl = mat["density"] * math.pi * d**2 / 4.0
    off = mat["tendon_offset"]
    tags = [material, f"{ns}sec", "spatial" if spatial else "planar", "length" if length_mode else "tension"]
    robot = dict(mat, length=L, n_sections=ns, tendon_count=3 if spatial else 2,
                 first_tendon_angle=math.pi / 2 if spatial else 0.0, disks_per_section=10,
                 tendon_stiffness=2e4 if length_mode else 1e7)
    load: dict[str, object] = {}
    k = 3 if spatial else 2
    # tendon commands: each section pulls one or two of its tendons; bending angle <= ~0.9 rad in all
    theta = np.zeros(ns * k)
    if rng.random() < 0.85:
        for j in range(ns):
            for t in rng.choice(k, size=int(rng.integers(1, 3)) if spatial else 1, replace=False):
                theta[j * k + t] = rng.uniform(0.1, 0.9) / ns
    if length_mode:  # the CC length changes of one arc per section (antagonists let out), plus pretension
        load["pretension"] = float(round(rng.uniform(0.02, 0.05) * EI / (L * off), 6))
        phi = rng.uniform(0.0, 2.0 * math.pi, ns) if spatial else rng.choice((0.0, math.pi), ns)
        kappa = rng.uniform(0.1, 0.9, ns) / ns / sec_len * (rng.random(ns) < 0.85)
        act = actuation_from_arc(build_preset("steel_rod", **robot), kappa, phi, "length", load["pretension"])
        load["length_changes"] = [float(x) for x in act.values]
    else:
        load["tensions"] = [float(th * EI / (L * off)) for th in theta]
    if rng.random() < 0.35:
        a = rng.uniform(0.1, 0.6) * EI / L**2
        v = rng.normal(size=3)
        if not spatial:
            v[1] = 0.0
        load["tip_force"] = [float(x) for x in a * v / np.linalg.norm(v)]
        tags.append("force")
    if rng.random() < 0.2:
        b = rng.uniform(0.05, 0.4) * EI / L
        v = rng.normal(size=3) if spatial else np.array([0.0, 1.0, 0.0]) * rng.choice((-1.0, 1.0))
        load["tip_torque"] = [float(x) for x in b * v / np.linalg.norm(v)]
        tags.append("torque")
    orient = rng.choice(["none", "none", "vertical", "upside_down", "horizontal", "tilted"])
    tilted = orient == "tilted"
    if orient != "none":
        robot["gravity"] = float(rng.uniform(0.2, 1.2) * EI / (mpl * L**3))
        robot["base_orientation"] = "vertical" if tilted else str(orient)
        tags.append(f"g_{orient}")
        if rng.random() < 0.3:
            robot["payload_mass"] = float(rng.uniform(0.1, 0.5) * mpl * L)
            tags.append("payload")
        if rng.random() < 0.25:
            robot["disk_mass"] = float(rng.uniform(0.5, 2.0) * mpl * sec_len / 10)
            tags.append("disks")
    offset_tip = None
    if rng.random() < 0.15 and any(theta):
        offset_tip = float(off * rng.uniform(0.4, 0.8))
        tags.append("tapered")
    return XCase(seed, index, tuple(sorted(robot.items())), tuple(sorted((k_, _freeze(v)) for k_, v in load.items())),
                 tilted, offset_tip, tuple(tags))


def _freeze(v):
    return tuple(v) if isinstance(v, list) else v


def generate(seed: int, count: int, start: int = 0) -> list[XCase]:
    """Cases ``start .. start + count - 1`` of ``seed`` (pure: see the module docstring)."""
    return [_draw(np.random.default_rng((seed, i)), seed, i) for i in range(start, start + count)]


def diagnostic_cases() -> list[XCase]:
    """The fixed cases of issue 28's diagnostics.md that the random draw does not reach (seed -1).

    0: the branch jump -- Rao NiTi, 3 sections, tensions 0.69 N (section 1's -30 deg tendon) and
    3.11 N (section 3's 90 deg tendon), tip force (0, -0.259, 0) N (tendon order here: 90, 210, 330 deg).
    1: disk weights -- planar Rao NiTi, 2 sections, horizontal base, 10 x 0.5 g disks per section, g.
    2: length mode -- planar Rao NiTi, 1 section, tendon EA 2e4 N, commands (0, -5 mm), pretension 0.32 N.
    """
    mat, sec = MATERIALS["niti"]
    base = dict(mat, disks_per_section=10, tendon_stiffness=1e7)
    jump = dict(base, length=3 * sec, n_sections=3, tendon_count=3, first_tendon_angle=math.pi / 2)
    disks = dict(base, length=2 * sec, n_sections=2, tendon_count=2, gravity=9.81, base_orientation="horizontal",
                 disk_mass=0.5e-3)
    length = dict(base, length=sec, n_sections=1, tendon_count=2, tendon_stiffness=2e4)
    rows = [(jump, dict(tensions=(0.0, 0.0, 0.69, 0.0, 0.0, 0.0, 3.11, 0.0, 0.0), tip_force=(0.0, -0.259, 0.0)),
             ("niti", "3sec", "spatial", "tension", "force", "branch_jump")),
            (disks, dict(tensions=(0.0, 0.0, 0.0, 0.0)), ("niti", "2sec", "planar", "tension", "g_horizontal", "disks")),
            (length, dict(length_changes=(0.0, -5e-3), pretension=0.32), ("niti", "1sec", "planar", "length"))]
    return [XCase(-1, i, tuple(sorted(r.items())), tuple(sorted(ld.items())), tags=t) for i, (r, ld, t) in enumerate(rows)]


def _toml_value(v) -> str:
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (tuple, list)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return repr(float(v)) if isinstance(v, float) else repr(v)


def study_toml(case: XCase, models, solver: dict | None = None, robot: dict | None = None) -> str:
    """A study file that runs ``case`` with ``models`` (``workbench run``), ``solver`` its
    ``[solver]`` keys, ``robot`` preset parameters that replace the case's (``disks_per_section``
    of an eyelet side); the extras the preset cannot express (tilted base, tapered offset) are
    named in a comment, with the line that rebuilds the exact case in Python."""
    lines = [f"# cross-examination case {case.name}: python -m tests.crossexam --seed {case.seed} "
             f"--start {case.index} --count 1"]
    if case.tilted or case.offset_tip is not None:
        lines.append("# NOT expressible by the steel_rod preset (the file runs the case without it): " + ", ".join(
            x for x, on in (("tilted base (tests/crossexam/cases.py TILT)", case.tilted),
                            (f"tendon offset_tip = {case.offset_tip!r}", case.offset_tip is not None)) if on))
        lines.append(f"# exact case: tests.crossexam.cases.build(tests.crossexam.cases.generate({case.seed}, 1, "
                     f"{case.index})[0])")
    lines += ["[study]", f'name = "crossexam_{case.seed}_{case.index}"', f"models = {_toml_value(list(models))}",
              "", "[robot]", 'preset = "steel_rod"']
    lines += [f"{k} = {_toml_value(v)}" for k, v in sorted({**dict(case.robot), **(robot or {})}.items())]
    ld = dict(case.load)
    lines += ["", "[load]", f'mode = "{"length" if "length_changes" in ld else "tension"}"', 'analysis = "static"']
    lines += [f"{k} = {_toml_value(v)}" for k, v in case.load]
    lines += ["", "[solver]"]
    lines += [f"{k} = {_toml_value(v)}" for k, v in sorted((solver or {}).items())]
    return "\n".join(lines) + "\n"
