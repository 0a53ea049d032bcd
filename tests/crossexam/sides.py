"""One side of a cross-examination pair: a model solved at two resolutions, a tip and its error bar.

Every side is a refined estimate (:class:`Side`).  A ``"mesh"`` side runs the model at
``n / 2``, ``n`` and ``2n`` elements per section and compares the tip of the finest solve, with the
Richardson error bar ``|x_2n - x_n| / (2^p - 1)`` (:func:`workbench.models.discretization.richardson_error`),
``p`` the model's declared order in :data:`workbench.registry.MODELS` lowered to the order observed
over the three resolutions where that is lower (:func:`~workbench.models.discretization.effective_order`)
-- the error estimate the study pipeline uses.  (With two resolutions and the declared order alone,
ANCF's continuum tendon with a tapered offset, whose per-element reference curvature is piecewise
constant and converges at order ~2, got a bar ~5 x too small.)  ``"eyelets"`` sides run ``per`` and
``2 per`` elements per disk interval at the declared order.  Special sides:

* ``cosserat`` (no mesh): residual tolerances 1e-8 and 1e-10; the bar is the tip difference; with eyelets
  (``"eyelet_tolerance"``) the same at ``disks`` per section.
* eyelets extrapolated to continuous routing (issue 28 diagnostics: disk count ``d -> 2d`` with
  one element per disk interval, observed order ~2): the tip ``x_2d + (x_2d - x_d) / 3``, bar
  ``|x_2d - x_d| / 3``.
* ``cc``: exact for its own assumption, bar 0.

A side is *refused* when the capability check (:func:`workbench.study.capabilities.unsupported`)
refuses the case or the model raises :class:`~workbench.models.ModelFailure` / ``ValueError``
(the planar models' error) -- the reason is kept.  A solve longer than :data:`TIMEOUT` seconds
is a failure of its own (``timeout``), never a refusal.  Solves are cached per process
(:func:`functools.lru_cache`), so pairs sharing a side solve it once.
Checked by ``tests/crossexam/test_crossexam.py``.
"""

from __future__ import annotations

import functools
import signal
import time
from dataclasses import dataclass, replace

import numpy as np

from workbench import registry
from workbench.models import ModelFailure, SolverOptions, get_model
from workbench.models.discretization import effective_order, observed_order, richardson_error
from workbench.study.capabilities import case_features, unsupported

from tests.crossexam.cases import XCase, build

__all__ = ["COSSERAT_TOL", "Side", "Spec", "TIMEOUT", "refusal", "solve_side"]

#: Longest accepted single solve [s] (diagnostics.md: a Cosserat spatial length-mode case ran > 600 s).
TIMEOUT = 20.0
#: Cosserat residual tolerances (coarse, fine).
COSSERAT_TOL = (1e-8, 1e-10)


@dataclass(frozen=True)
class Spec:
    """How a side is solved: ``model``; ``kind`` one of ``"mesh"`` (``n`` elements per section,
    continuum tendons), ``"eyelets"`` (``disks`` per section, ``per`` elements per disk interval),
    ``"routing"`` (eyelets at ``disks`` and ``2 disks``, extrapolated), ``"tolerance"``, ``"eyelet_tolerance"``
    (``"tolerance"`` with eyelets at ``disks`` per section), ``"exact"``."""

    model: str
    kind: str
    n: int = 0
    disks: int = 0
    per: int = 1

    @property
    def label(self) -> str:
        if self.kind == "mesh":
            return f"{self.model} ({self.n // 2}/{self.n}/{2 * self.n} el. per section)"
        if self.kind == "eyelets":
            return f"{self.model} eyelets ({self.disks} disks, {self.per}/{2 * self.per} el. per interval)"
        if self.kind == "routing":
            return f"{self.model} eyelets {self.disks}->{2 * self.disks} disks, extrapolated"
        if self.kind == "tolerance":
            return f"{self.model} (tol {COSSERAT_TOL[0]:g}/{COSSERAT_TOL[1]:g})"
        if self.kind == "eyelet_tolerance":
            return f"{self.model} eyelets ({self.disks} disks, tol {COSSERAT_TOL[0]:g}/{COSSERAT_TOL[1]:g})"
        return self.model


@dataclass(frozen=True)
class Side:
    """A refined tip: ``tip`` [m] (base frame), ``bar`` [m], the largest tendon tension sum
    ``tension`` [N] of the solves (for the floor), the solves' wall time, and ``refused`` (reason,
    empty when solved) or ``failed`` (a solve that neither converged nor refused)."""

    spec: Spec
    tip: tuple[float, float, float] | None
    bar: float
    tension: float = 0.0
    seconds: float = 0.0
    refused: str = ""
    failed: str = ""


class _Timeout(BaseException):  # not Exception: the solvers' retry loops must not catch it
    pass


#: set by the alarm: raised inside an Exudyn user function, the timeout comes back as Exudyn's own
#: error (``ModelError: Error in Python USER FUNCTION``), which must not read as a refusal
_FIRED: list[bool] = [False]


def _alarm(signum, frame):  # pragma: no cover - only on a hung solve
    _FIRED[0] = True
    raise _Timeout()


@functools.cache
def _compiled(model: str) -> None:
    """Run one small solve of ``model`` outside the timeout, once per process: a fresh install compiles the
    cosserat numba kernel on its first solve (26-28 s CPU, once), and the eyelet kernel on its first eyelet
    solve, which is not the case's solving time."""
    if model != "cosserat":
        return
    from workbench.robot import LoadCase
    from workbench.robot.actuation import TendonActuation
    from workbench.robot.presets import build_preset

    robot = build_preset("rao_2021")
    for tendon_model in ("continuum", "eyelets"):
        get_model(model)(robot, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0, 0.0, 0.0, 0.0))),
                         SolverOptions(tendon_model=tendon_model))


def _run(model: str, robot, load, opts: SolverOptions):
    _compiled(model)
    old = signal.signal(signal.SIGALRM, _alarm)
    _FIRED[0] = False
    signal.setitimer(signal.ITIMER_REAL, TIMEOUT)
    try:
        return get_model(model)(robot, load, opts)
    except (ModelFailure, ValueError, RuntimeError):
        if _FIRED[0]:
            raise _Timeout() from None
        raise
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)


def _with_disks(robot, disks: int):
    return replace(robot, sections=tuple(replace(s, n_disks=disks) for s in robot.sections))


def _capability(model: str, robot, load, tendon_model: str) -> str:
    f = case_features(robot, load, {}, {"tendon_model": tendon_model})
    lines = unsupported(model, registry.MODELS[model].capabilities, f)
    return "capability: " + lines[0] if lines else ""


def _solves(spec: Spec, case: XCase):
    """``[(robot, options), ...]`` (coarse first) of ``spec`` on ``case``."""
    robot, _ = build(case)
    ns = robot.n_sections
    tight = dict(newton_tolerance=1e-10, max_load_steps=2000)
    if spec.kind == "tolerance":
        return [(robot, SolverOptions(newton_tolerance=t, max_load_steps=2000)) for t in COSSERAT_TOL]
    if spec.kind == "eyelet_tolerance":
        r = _with_disks(robot, spec.disks)
        return [(r, SolverOptions(newton_tolerance=t, max_load_steps=2000, tendon_model="eyelets"))
                for t in COSSERAT_TOL]
    if spec.kind == "exact":
        return [(robot, SolverOptions())]
    if spec.kind == "mesh":
        return [(robot, SolverOptions(n_elements=k * spec.n * ns // 2, **tight)) for k in (1, 2, 4)]
    if spec.kind == "eyelets":
        r = _with_disks(robot, spec.disks)
        return [(r, SolverOptions(n_elements=k * spec.per * spec.disks * ns, tendon_model="eyelets", **tight))
                for k in (1, 2)]
    return [(_with_disks(robot, k * spec.disks), SolverOptions(n_elements=k * spec.per * spec.disks * ns,
                                                               tendon_model="eyelets", **tight)) for k in (1, 2)]


def refusal(spec: Spec, case: XCase) -> str:
    """The capability check's first objection to ``spec`` on ``case`` (``""``: none)."""
    _, load = build(case)
    robot, opts = _solves(spec, case)[-1]
    return _capability(spec.model, robot, load, opts.tendon_model)


@functools.lru_cache(maxsize=None)
def solve_side(spec: Spec, case: XCase) -> Side:
    """The refined tip of ``spec`` on ``case`` (see the module docstring)."""
    _, load = build(case)
    solves = _solves(spec, case)
    why = _capability(spec.model, solves[-1][0], load, solves[-1][1].tendon_model)
    if why:
        return Side(spec, None, float("nan"), refused=why)
    tips, tension, t0 = [], 0.0, time.perf_counter()
    for robot, opts in solves:
        try:
            res = _run(spec.model, robot, load, opts)
        except (ModelFailure, ValueError) as e:
            return Side(spec, None, float("nan"), seconds=time.perf_counter() - t0,
                        refused=f"run time: {type(e).__name__}: {str(e).splitlines()[0][:200]}")
        except _Timeout:
            return Side(spec, None, float("nan"), seconds=time.perf_counter() - t0,
                        failed=f"timeout: no result after {TIMEOUT:g} s")
        tips.append(np.array(res.tip_position, float))
        tension = max(tension, float(np.sum(res.tendon_tensions)))
    dt = time.perf_counter() - t0
    if spec.kind == "exact":
        return Side(spec, tuple(tips[0]), 0.0, tension, dt)
    diff = float(np.linalg.norm(tips[-1] - tips[-2]))
    order = registry.MODELS[spec.model].order
    if spec.kind == "mesh":
        order = effective_order(order, observed_order(diff, float(np.linalg.norm(tips[1] - tips[0]))))
    if spec.kind in ("tolerance", "eyelet_tolerance"):
        return Side(spec, tuple(tips[1]), diff, tension, dt)
    if spec.kind == "routing":
        return Side(spec, tuple(tips[1] + (tips[1] - tips[0]) / 3.0), diff / 3.0, tension, dt)
    return Side(spec, tuple(tips[-1]), richardson_error(diff, 2.0, order), tension, dt)
