"""The pairs of models that claim the same physics and the agreement rule.

Two refined sides (:mod:`tests.crossexam.sides`) of one case agree when their tips are closer
than ``bar_a + bar_b + floor``, or when one of them refuses the case (capability check or a
clear run-time error).  The floor is physics, not slack: the strain terms some models ignore
(the inextensible, shear-rigid models -- ANCF cable, spring-link chain, CC -- against the
extensible, shear-deformable Cosserat rod and GE beam), bounded by ``L (N/EA + V/GA)`` with
``N`` the largest axial force (the tendon tension sum of the solves, the tip force, the
weight) and ``V`` the largest shear force (tip force plus weight), plus a numerical floor of
``1e-6 L``.  For the Rao NiTi rod ``EA = 8.3e4 N``: a 1 N tendon load gives 1.2e-5 L, small
against the differences that matter (diagnostics.md: 1e-2 to 8e-2 L).

A pair is judged only when both sides answered: a side that runs longer than
:data:`~tests.crossexam.sides.TIMEOUT` makes the verdict :attr:`Verdict.timed_out` (the test marks it
an explicit xfail naming the timeout, never a pass).  Checked by ``tests/crossexam/test_crossexam.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from tests.crossexam.cases import XCase, build, study_toml
from tests.crossexam.sides import COSSERAT_TOL, Side, Spec, solve_side

__all__ = ["PAIRS", "Pair", "Verdict", "compare", "pairs_for", "relative", "side_study"]

NUMERICAL_FLOOR = 1e-6  # [L]


def _loaded_tendons(case: XCase) -> bool:
    ld = dict(case.load)
    v = ld.get("tensions", ld.get("length_changes", ()))
    return any(x != 0 for x in v) or ld.get("pretension", 0.0) > 0


def _planar(case: XCase) -> bool:
    return dict(case.robot)["tendon_count"] == 2  # the generator keeps planar robots' loads and gravity planar


def _unloaded(case: XCase) -> bool:
    ld = dict(case.load)
    return not any(ld.get("tip_force", ())) and not any(ld.get("tip_torque", ())) and \
        not dict(case.robot).get("gravity")


def _inextensible_length(case: XCase, tendon_model: str) -> bool:
    """Whether the spring-link chain solves the case's length-controlled tendons inextensibly, which
    ``validate`` warns about (:func:`workbench.physics.spring_link.params.inextensible_length_warning`):
    the chain then does not claim the rod's physics (its tensions, and with them the shape, miss the
    backbone's compression by more than the strain floor), so it is not paired with the rods."""
    from workbench.physics.spring_link.params import SpringLinkParams, inextensible_length_warning

    robot, load = build(case)
    return inextensible_length_warning(robot, load, tendon_model, SpringLinkParams()) is not None


def _rod_eyelets(model: str, disks: int) -> Callable[[XCase], Spec]:
    """The continuum-routing side of an eyelet model: routing extrapolation when tendons are loaded."""
    return lambda c: Spec(model, "routing", disks=disks) if _loaded_tendons(c) else Spec(model, "mesh", n=8)


def _routable(case: XCase) -> bool:
    """Whether the disk count may be refined: not with heavy disks (2 d disks of the same mass
    would double their weight, of half the mass would smear it: another robot either way)."""
    return not (_loaded_tendons(case) and case.has("disks"))


@dataclass(frozen=True)
class Pair:
    """Two sides (functions of the case: the spec to solve) and when the pair applies."""

    name: str
    a: Callable[[XCase], Spec]
    b: Callable[[XCase], Spec]
    applies: Callable[[XCase], bool]
    slow_only: bool = False


COSSERAT = lambda c: Spec("cosserat", "tolerance")  # noqa: E731

PAIRS: dict[str, Pair] = {p.name: p for p in (
    Pair("cosserat~beam3d", COSSERAT, _rod_eyelets("beam3d", 10), _routable),
    Pair("cosserat~ancf", COSSERAT, lambda c: Spec("ancf", "mesh", n=4), _planar),
    # the same eyelet physics in two independent models (the beam3d side is shared with beam3d~ancf eyelets in
    # the default tier; spatial cases only in the slow tier); cosserat eyelets are tension-controlled only
    Pair("cosserat eyelets~beam3d eyelets", lambda c: Spec("cosserat", "eyelet_tolerance", disks=10),
         lambda c: Spec("beam3d", "eyelets", disks=10), lambda c: _planar(c) and _loaded_tendons(c) and c.has("tension")),
    Pair("cosserat eyelets~beam3d eyelets 3-D", lambda c: Spec("cosserat", "eyelet_tolerance", disks=10),
         lambda c: Spec("beam3d", "eyelets", disks=10),
         lambda c: not _planar(c) and _loaded_tendons(c) and c.has("tension"), slow_only=True),
    Pair("beam3d~ancf eyelets", lambda c: Spec("beam3d", "eyelets", disks=10), lambda c: Spec("ancf", "eyelets", disks=10),
         lambda c: _planar(c) and _loaded_tendons(c)),
    Pair("spring_link~cosserat", lambda c: Spec("spring_link", "mesh", n=8), COSSERAT,
         lambda c: not _inextensible_length(c, "continuum")),
    Pair("spring_link~beam3d eyelets", lambda c: Spec("spring_link", "eyelets", disks=5),
         lambda c: Spec("beam3d", "eyelets", disks=5), lambda c: _loaded_tendons(c) and
         dict(c.robot)["n_sections"] == 1 and not _inextensible_length(c, "eyelets"), slow_only=True),
    Pair("ancf3d~beam3d", lambda c: Spec("ancf3d", "mesh", n=4), lambda c: Spec("beam3d", "mesh", n=8),
         lambda c: not _loaded_tendons(c)),
    # CC in tension mode neglects only the strain (the floor); in length mode also the tendons' stretch, and
    # a tapered offset varies the tendon moment along a section (no arc: the assumption under test, like loads)
    Pair("cc~cosserat", lambda c: Spec("cc", "exact"), COSSERAT,
         lambda c: _unloaded(c) and c.has("tension") and not c.has("tapered")),
)}


def pairs_for(case: XCase, slow: bool = False) -> list[str]:
    """Names of the pairs that apply to ``case`` (``slow``: include the slow-only pairs)."""
    return [n for n, p in PAIRS.items() if p.applies(case) and (slow or not p.slow_only)]


@dataclass(frozen=True)
class Verdict:
    """The outcome of one pair on one case: both sides, their distance and the tolerance [m]."""

    case: XCase
    pair: str
    a: Side
    b: Side
    length: float
    floor: float

    @property
    def refused(self) -> str:
        return self.a.refused or self.b.refused

    @property
    def failed(self) -> str:
        return self.a.failed or self.b.failed

    @property
    def timed_out(self) -> bool:
        """A side ran longer than :data:`~tests.crossexam.sides.TIMEOUT`: the pair was not judged."""
        return self.failed.startswith("timeout")

    @property
    def distance(self) -> float:
        if self.a.tip is None or self.b.tip is None:
            return float("nan")
        return float(np.linalg.norm(np.subtract(self.a.tip, self.b.tip)))

    @property
    def tolerance(self) -> float:
        return self.a.bar + self.b.bar + self.floor

    @property
    def ok(self) -> bool:
        if self.refused:
            return True
        return not self.failed and self.distance <= self.tolerance

    def message(self) -> str:
        """What the table and a failing assertion print (with the study file that runs the case)."""
        head = (f"{self.case.name} {self.pair}: distance {self.distance / self.length:.2e} L > tolerance "
                f"{self.tolerance / self.length:.2e} L (bars {self.a.bar / self.length:.1e} + "
                f"{self.b.bar / self.length:.1e}, floor {self.floor / self.length:.1e})")
        if self.failed:
            head = f"{self.case.name} {self.pair}: {self.failed}"
        tips = f"\n  {self.a.spec.label}: {self.a.tip}\n  {self.b.spec.label}: {self.b.tip}"
        return head + tips + "".join(f"\n--- study of {s.spec.label} (workbench run) ---\n" + side_study(self.case, s.spec)
                                     for s in (self.a, self.b))


def side_study(case: XCase, spec: Spec) -> str:
    """The study file that runs ``spec`` on ``case`` at its fine resolution (the coarse one is the
    pipeline's Richardson estimate, ``error_estimate = "richardson"``, at half of it; a routing side: the
    eyelet robot of ``2 disks``, whose extrapolation also needs the ``disks`` one)."""
    robot, _ = build(case)
    ns = robot.n_sections
    solver: dict = {"n_stations": 33}
    over: dict = {}
    if spec.kind == "tolerance":
        solver["newton_tolerance"] = COSSERAT_TOL[1]
    elif spec.kind in ("mesh", "eyelets", "routing"):
        solver.update(newton_tolerance=1e-10, max_load_steps=2000, error_estimate="richardson")
        disks = spec.disks * (2 if spec.kind == "routing" else 1)
        solver["n_elements"] = 2 * spec.n * ns if spec.kind == "mesh" else 2 * spec.per * disks * ns
        if spec.kind != "mesh":
            solver["tendon_model"] = "eyelets"
            over["disks_per_section"] = disks
    return study_toml(case, [spec.model], solver, over)


def _floor(case: XCase, tension: float) -> float:
    robot, load = build(case)
    cs = robot.sections[0].cross_section
    g = float(np.linalg.norm(robot.gravity))
    weight = g * (sum(s.length * s.cross_section.mass_per_length + s.n_disks * s.disk_mass for s in robot.sections)
                  + robot.payload.mass)
    F = float(np.linalg.norm(load.tip_force))
    L = robot.length
    return L * ((tension + F + weight) / cs.EA + (F + weight) / cs.GA + NUMERICAL_FLOOR)


def compare(case: XCase, pair: str) -> Verdict:
    """Solve both sides of ``pair`` on ``case`` (cached) and judge them."""
    p = PAIRS[pair]
    a = solve_side(p.a(case), case)
    # a refusal settles the pair: the other side is not solved (its own pairs judge it)
    b = solve_side(p.b(case), case) if not a.refused else Side(p.b(case), None, float("nan"))
    robot, _ = build(case)
    return Verdict(case, pair, a, b, robot.length, _floor(case, max(a.tension, b.tension)))


def relative(v: Verdict) -> float:
    """``distance / tolerance`` (NaN when refused or failed)."""
    return v.distance / v.tolerance if not (v.refused or v.failed) else math.nan
