"""Richardson extrapolation of the spring-link chain in its link count (statics).

The chain converges to its rod at order 2 in the link length (``error ~ C ds^2``,
``tests/physics/test_spring_link_crossexam.py``), and under strong eyelet loads ``C`` is large
(measured in ``docs/models.md``, "Spring-link").  Two solves at ``N/2`` and ``N``
links combine to ``x_R = x_N + (x_N - x_{N/2}) / 3``, whose error is of higher order, at the cost of
1.5 solves of ``N`` links instead of one of ``4 N``.  Extrapolated: the backbone positions at the
stations, the tip position, the tendon tensions, the length change and the tip twist; the tip and
joint rotations and the joint angles are the ``N``-link chain's (a combination of rotations is not a
rotation).  The error bar ``|x_N - x_R|`` of the tip (an estimate of the ``N``-link chain's own error)
is reported in the extras as ``richardson_tip_bar`` [m].

From a study file: ``[solver] spring_link_richardson = true`` (``docs/study-format.md``).  The study's
discretisation error estimate (:mod:`workbench.models.discretization`) then re-solves with the same
setting, so it compares extrapolated results at ``N``, ``N/2`` and ``N/4`` links with the declared
order 2 (lowered to the observed one where that is lower): an extrapolated result converges at a
higher order, so the bar ``|q_N - q_N/2| / 3`` over-states its error (conservative).
:func:`richardson_problem` is the rule ``validate`` applies before anything runs (the half-resolution
re-solve of the estimate extrapolates ``N/4`` and ``N/2`` links).  Checked by
``tests/physics/test_spring_link_linkrope.py`` (``test_richardson_*``) and
``tests/study/test_spring_link_richardson_key.py``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable

import numpy as np

from ...models.result import ModelFailure, PhysicsResult

__all__ = ["check_richardson", "richardson_problem", "richardson_result"]


def richardson_problem(n_links: int, n_sections: int, analysis: str, estimate: bool = False) -> str | None:
    """Why ``n_links`` cannot be extrapolated, or ``None``.

    Static solves only; ``n_links / 2`` links must be a multiple of the ``n_sections`` sections, and
    with ``estimate`` (the study's discretisation error estimate re-solves at ``n_links / 2``, which
    extrapolates ``n_links / 4`` and ``n_links / 2``) ``n_links / 4`` too.
    """
    if analysis != "static":
        return "richardson=True extrapolates static solves only"
    factor = 4 if estimate else 2
    if n_links % (factor * n_sections):
        why = ("the coarse chain has n_elements / 2 links" if not estimate else
               "the error estimate's half-resolution solve extrapolates n_elements / 4 and n_elements / 2 links")
        return f"richardson=True needs n_elements a multiple of {factor} x {n_sections} sections ({why}), got {n_links}"
    return None


def check_richardson(n_links: int, n_sections: int, analysis: str) -> None:
    """Raise :class:`ModelFailure` when :func:`richardson_problem` finds one (without the estimate's rule)."""
    why = richardson_problem(n_links, n_sections, analysis)
    if why:
        raise ModelFailure(f"spring_link: {why}")


def richardson_result(solve_at: Callable[[int], PhysicsResult], n_links: int) -> PhysicsResult:
    """Solve at ``n_links // 2`` and ``n_links`` links (``solve_at(n)``) and extrapolate at order 2."""
    coarse, fine = solve_at(n_links // 2), solve_at(n_links)

    def ext(a, b):  # noqa: ANN001, ANN202
        return np.asarray(b, dtype=float) + (np.asarray(b, dtype=float) - np.asarray(a, dtype=float)) / 3.0

    tip = ext(coarse.tip_position, fine.tip_position)
    frame = fine.tip_frame.copy()
    frame[:3, 3] = tip
    info = replace(fine.solver, iterations=coarse.solver.iterations + fine.solver.iterations,
                   wall_time=coarse.solver.wall_time + fine.solver.wall_time,
                   message=f"Richardson of {n_links // 2} and {n_links} links ({coarse.solver.message}; "
                           f"{fine.solver.message})")
    return replace(fine, positions=ext(coarse.positions, fine.positions), tip_frame=frame,
                   tendon_tensions=ext(coarse.tendon_tensions, fine.tendon_tensions),
                   length_change=float(ext(coarse.length_change, fine.length_change)),
                   tip_twist=float(ext(coarse.tip_twist, fine.tip_twist)), solver=info,
                   extras={**fine.extras, "richardson_tip_bar": float(np.linalg.norm(fine.tip_position - tip))})
