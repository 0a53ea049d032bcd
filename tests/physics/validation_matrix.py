"""The validation matrix (issue 14): every model x every reference case, errors at two resolutions.

Rows are load cases with an independent reference (closed form or a non-Exudyn solver); columns
are the registered models.  Each cell is solved at a coarse and a fine resolution; the error is
the tip distance from the reference over the robot length, the observed order ``log2(e_c / e_f)``
(resolutions differ by a factor 2).  A model that cannot do a row has a reason instead (and must
reject the case with a clear error, never return a wrong answer).  ``EA`` and ``GA`` are 100 x
the rod's in every row, so that extensible and shear-deformable models meet the inextensible
references (elastica) within ~1e-6 L (the floor: ``P/EA + P/GA``, and for the planar tendon +
tip force row the tendon compression ``T/EA`` = 2e-6); the exact arcs of the tendon rows include
the compression.  (x 1e4, as the ANCF tests use, makes beam3d's static Newton fail: 803 load
steps at 8 elements, more than 2000 at 16.)

Run ``python -m tests.physics.validation_matrix [row ...]`` from the repository root to print the
markdown table of ``docs/models.md``; ``tests/physics/test_validation_matrix.py`` asserts it.
"""

from __future__ import annotations

import functools
import math
import sys
import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from workbench.kinematics import forward_kinematics
from workbench.models import SolverOptions, get_model
from workbench.reference.elastica import clamped_elastica
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.orientation import base_rotation_for

L = 0.8
TIGHT = dict(newton_tolerance=1e-10, max_load_steps=2000)


def stiff(cs: CrossSection) -> CrossSection:
    """The cross-section with EA and GA x 100 (bending and torsion unchanged)."""
    return replace(cs, EA=100.0 * cs.EA, GA=100.0 * (cs.GA if cs.GA is not None else cs.EA))


def steel(gravity: float = 0.0, disks: int = 8, tendons=(0.0, math.pi)) -> Robot:
    """0.8 m, 6 mm steel rod (EI 13.36 N m^2), one section, horizontal base (base x up)."""
    cs = stiff(CrossSection.circular(6e-3))
    return Robot(sections=(Section(L, cs, TendonGroup(angles=tendons, offset=0.02), n_disks=disks),),
                 gravity=(0.0, 0.0, -gravity), base_rotation=base_rotation_for("horizontal"))


def nitinol(disks: int = 10) -> Robot:
    """Issue 14's spatial robot: 2 x 0.2 m NiTi (E 54 GPa, d 1.4 mm; density 6450 kg/m^3, Poisson
    0.33 assumed), tendons at 90 / -30 / 210 deg per section, 10 mm offset, EA_t 1e7 N."""
    cs = stiff(CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.33))
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, cs, tg, n_disks=disks), Section(0.2, cs, tg, n_disks=disks)))


def arcs_tip(robot: Robot, tensions) -> np.ndarray:
    """Tip of the exact continuum-tendon solution without external loads: one arc per section,
    curvature ``|sum T r| / EI`` towards ``sum T r``, shortened by ``sum T / EA``."""
    kap, phi, ell = [], [], []
    for j, sec in enumerate(robot.sections):
        m, comp = np.zeros(2), 0.0
        for (k, sig, grp), T in zip(robot.tendon_table(), tensions):
            if k >= j:
                m += T * grp.offset * np.array([math.cos(sig), math.sin(sig)])
                comp += T
        eps = comp / sec.cross_section.EA
        kap.append(np.linalg.norm(m) / sec.cross_section.EI / (1.0 - eps))
        phi.append(math.atan2(m[1], m[0]))
        ell.append(sec.length * (1.0 - eps))
    return forward_kinematics(np.asarray(kap), np.asarray(phi), np.asarray(ell))[:3, 3]


def _elastica_tip(robot: Robot, *, force=(0.0, 0.0), moment=0.0, q=(0.0, 0.0)) -> np.ndarray:
    EI = robot.sections[0].cross_section.EI
    ref = clamped_elastica(L, EI, tip_force=force, tip_moment=moment, distributed_load=q, stations=2,
                           n_continuation=12)
    return np.array([ref.tip[1], 0.0, ref.tip[0]])  # elastica plane: a = base z, b = base x


@dataclass(frozen=True)
class Case:
    robot: Robot
    load: LoadCase
    reference: np.ndarray
    length: float
    spatial: bool = False
    tendons: bool = False
    #: Error floor [1/L] of an inextensible reference against the (stiff, extensible) models:
    #: ``F/EA + F/GA`` of the largest force; an order is quoted only above 5 x the floor.
    floor: float = 0.0


def _floor(robot: Robot, force: float) -> float:
    cs = robot.sections[0].cross_section
    return force / cs.EA + force / cs.GA


def _alpha(disks: int = 8) -> Case:
    r = steel(disks=disks)
    P = 5.0 * r.sections[0].cross_section.EI / L**2
    return Case(r, LoadCase(tip_force=(-P, 0.0, 0.0)), _elastica_tip(r, force=(0.0, -P)), L, floor=_floor(r, P))


def _gamma(disks: int = 8) -> Case:
    cs = steel().sections[0].cross_section
    g = 8.0 * cs.EI / (cs.mass_per_length * L**3)
    r = steel(gravity=g, disks=disks)
    q = cs.mass_per_length * g
    return Case(r, LoadCase(), _elastica_tip(r, q=(0.0, -q)), L, floor=_floor(r, q * L))


def _moment(disks: int = 8) -> Case:
    r = steel(disks=disks)
    M = 2.0 * math.pi * r.sections[0].cross_section.EI / L
    return Case(r, LoadCase(tip_torque=(0.0, M, 0.0)), np.zeros(3), L)  # a full circle back to the base


def _planar_tendon(disks: int = 8) -> Case:
    r = steel(disks=disks)
    T = math.pi * r.sections[0].cross_section.EI / (L * 0.02)  # kappa L = pi
    return Case(r, LoadCase(actuation=TendonActuation("tension", (T, 0.0))), arcs_tip(r, (T, 0.0)), L, tendons=True)


_SPATIAL_T = (4.0, 0.0, 0.0, 0.0, 2.0, 0.0)


def _spatial_tendon(disks: int = 10) -> Case:
    r = nitinol(disks)
    return Case(r, LoadCase(actuation=TendonActuation("tension", _SPATIAL_T)), arcs_tip(r, _SPATIAL_T), 0.4,
                spatial=True, tendons=True)


def _planar_tendon_force(disks: int = 8) -> Case:
    """Tendon (kappa L = 1.5 alone) against a tip force alpha = 2 along -x: in the plane a
    continuum tendon equals a tip moment ``T d`` for the inextensible rod (its total internal
    moment obeys the tendon-free equations), so the elastica with that moment is exact."""
    r = steel(disks=disks)
    EI = r.sections[0].cross_section.EI
    T = 1.5 * EI / (L * 0.02)
    P = 2.0 * EI / L**2
    load = LoadCase(actuation=TendonActuation("tension", (T, 0.0)), tip_force=(-P, 0.0, 0.0))
    return Case(r, load, _elastica_tip(r, force=(0.0, -P), moment=T * 0.02), L, tendons=True, floor=_floor(r, T + P))


def _spatial_tendon_force(disks: int = 10) -> Case:
    """The spatial robot with a 0.1 N tip force along base y; reference: the Cosserat model at a
    residual tolerance of 1e-12 (no Exudyn; its own cell is therefore not a check of it)."""
    load = LoadCase(actuation=TendonActuation("tension", _SPATIAL_T), tip_force=(0.0, 0.1, 0.0))
    return Case(nitinol(disks), load, _cosserat_reference(load), 0.4, spatial=True, tendons=True)


@functools.lru_cache(maxsize=4)
def _cosserat_reference(load: LoadCase) -> np.ndarray:
    tip = get_model("cosserat")(nitinol(), load, SolverOptions(newton_tolerance=1e-12)).tip_position
    tip.setflags(write=False)
    return tip


ROWS: dict[str, tuple[str, Callable[..., Case]]] = {
    "alpha": ("tip load alpha = PL^2/EI = 5 (elastica)", _alpha),
    "gamma": ("self-weight gamma = qL^3/EI = 8 (elastica)", _gamma),
    "moment": ("pure tip moment, 2 pi (circle)", _moment),
    "planar_tendon": ("planar tendon, kappa L = pi (exact arc)", _planar_tendon),
    "spatial_tendon": ("spatial 2-section tendons (exact arcs)", _spatial_tendon),
    "planar_tendon_force": ("planar tendon + tip force (elastica)", _planar_tendon_force),
    "spatial_tendon_force": ("spatial tendons + tip force (Cosserat, tol 1e-12)", _spatial_tendon_force),
}

#: Resolutions (coarse, fine): elements / links; the Cosserat model's residual tolerance.
RESOLUTION = {"ancf": (8, 16), "beam3d": (8, 16), "ancf3d": (8, 16), "spring_link": (16, 32), "cosserat": (1e-6, 1e-9)}
#: Eyelet cells, (model, row) -> disks per section at (coarse, fine) and elements (links) per disk
#: interval.  beam3d: before issue 18, 2 elements per interval stalled its static Newton in the planar
#: tendon row (8 disks, 16 elements: load factor 0.33, 59 s; now 4 s), and so did 16 disks at 1 per
#: interval (load factor 0.27; now 0.24 s): that row runs at 4 / 8 disks, pre-asymptotic
#: (at kappa L = pi the 4-disk chords pass the backbone axis).  spring_link: its 3-D continuum
#: tendons are body-fixed end torques, exact only where the rod does not twist, so the twisting
#: tendon + tip force row needs eyelets.
EYELETS = {("beam3d", "planar_tendon"): ((4, 8), 1), ("beam3d", "planar_tendon_force"): ((8, 16), 1),
           ("beam3d", "spatial_tendon"): ((4, 8), 1), ("beam3d", "spatial_tendon_force"): ((4, 8), 1),
           ("spring_link", "spatial_tendon_force"): ((5, 10), 1)}


def setup(row: str, model: str, i: int) -> tuple[Case, SolverOptions, str]:
    """The case, options and a resolution note of ``row`` for ``model`` at resolution ``i`` (0, 1)."""
    build = ROWS[row][1]
    c = build()
    if model == "cosserat":
        return c, SolverOptions(newton_tolerance=RESOLUTION[model][i], max_load_steps=2000), ""
    if (model, row) not in EYELETS:
        return c, SolverOptions(n_elements=RESOLUTION[model][i], **TIGHT), ""
    disks, per = EYELETS[(model, row)]
    c = build(disks[i])
    opts = SolverOptions(n_elements=per * disks[i] * c.robot.n_sections, tendon_model="eyelets", **TIGHT)
    return c, opts, f"eyelets, {disks[0]} / {disks[1]} disks per section, {per} el. per disk"


CC_ONLY_ARCS = "not modelled: CC ignores tip loads and gravity"
#: (model, row) -> why the model cannot do the row.
UNSUPPORTED: dict[tuple[str, str], str] = {
    **{("cc", r): CC_ONLY_ARCS for r in ("alpha", "gamma", "moment", "planar_tendon_force", "spatial_tendon_force")},
    ("ancf", "spatial_tendon"): "planar only (rejected: tendon not in the x-z plane)",
    ("ancf", "spatial_tendon_force"): "planar only (rejected)",
    ("ancf3d", "moment"): "no rotational coordinates (tip torque rejected)",
    **{("ancf3d", r): "no tendons (rejected)" for r in ("planar_tendon", "spatial_tendon", "planar_tendon_force",
                                                           "spatial_tendon_force")},
}


@dataclass(frozen=True)
class Cell:
    row: str
    model: str
    errors: tuple[float, float] | None
    resolutions: tuple
    note: str = ""
    seconds: float = 0.0
    floor: float = 0.0

    @property
    def order(self) -> float:
        """``log2(e_coarse / e_fine)``; NaN where it means nothing (exact, at the floor, a tolerance)."""
        if self.errors is None or self.model in ("cc", "cosserat"):
            return float("nan")
        if self.errors[1] < 1e-12 or self.errors[1] < 5.0 * self.floor:
            return float("nan")
        return math.log2(self.errors[0] / self.errors[1])


def evaluate(row: str, model: str) -> Cell:
    """Solve ``row`` with ``model`` at its two resolutions (see the module docstring)."""
    if (model, row) in UNSUPPORTED:
        return Cell(row, model, None, (), UNSUPPORTED[(model, row)])
    run = get_model(model)
    t0 = time.perf_counter()
    if model == "cc":
        c = ROWS[row][1]()
        e = np.linalg.norm(run(c.robot, c.load, SolverOptions()).tip_position - c.reference) / c.length
        return Cell(row, model, (e, e), ("exact",), "neglects the tendon compression", time.perf_counter() - t0)
    errs, res, note, floor = [], [], "", 0.0
    for i in (0, 1):
        c, opts, note = setup(row, model, i)
        res.append(opts.newton_tolerance if model == "cosserat" else opts.n_elements)
        errs.append(float(np.linalg.norm(run(c.robot, c.load, opts).tip_position - c.reference) / c.length))
        floor = c.floor
    if model == "cosserat" and row == "spatial_tendon_force":
        note = "the reference itself (tol 1e-12)"
    return Cell(row, model, (errs[0], errs[1]), tuple(res), note, time.perf_counter() - t0, floor)


MODEL_ORDER = ("cc", "ancf", "beam3d", "ancf3d", "spring_link", "cosserat")


def _fmt(cell: Cell) -> str:
    if cell.errors is None:
        return cell.note
    if cell.model == "cc":
        return f"{cell.errors[0]:.1e} (exact)"
    o = cell.order
    if not math.isnan(o):
        tail = f", order {o:.1f}"
    elif cell.model == "cosserat":
        tail = ""
    elif cell.errors[1] < 1e-12:
        tail = ", exact (round-off)"
    else:
        tail = f", at the floor {cell.floor:.0e}"
    return f"{cell.errors[0]:.1e} / {cell.errors[1]:.1e}{tail}" + (f" ({cell.note})" if cell.note else "")


def main(argv: list[str]) -> int:
    rows = argv or list(ROWS)
    print("| case | " + " | ".join(MODEL_ORDER) + " |")
    print("|---" * (len(MODEL_ORDER) + 1) + "|")
    for r in rows:
        cells = [evaluate(r, m) for m in MODEL_ORDER]
        print(f"| {ROWS[r][0]} | " + " | ".join(_fmt(c) for c in cells) + " |", flush=True)
        print("<!-- seconds: " + ", ".join(f"{c.model} {c.seconds:.1f}" for c in cells) + " -->", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
