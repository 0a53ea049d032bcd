"""Richardson extrapolation of the spring-link chain in its link count (statics).

The chain converges to its rod at order 2 in the link length (``error ~ C ds^2``,
``tests/physics/test_spring_link_crossexam.py``), and under strong eyelet loads ``C`` is large
(measured in ``docs/models.md``, "Spring-link").  Two solves at ``N/2`` and ``N``
links combine to ``x_R = x_N + (x_N - x_{N/2}) / 3``, whose error is of higher order, at the cost of
1.5 solves of ``N`` links instead of one of ``4 N``.  Extrapolated: the backbone positions at the
stations, the tip position, the tendon tensions, the length change and the tip twist; the tip and
joint rotations and the joint angles are the ``N``-link chain's (a combination of rotations is not a
rotation).  The error bar ``|x_N - x_R|`` of the tip (an estimate of the ``N``-link chain's own error)
is reported in the extras as ``richardson_tip_bar`` [m].  Checked by
``tests/physics/test_spring_link_linkrope.py`` (``test_richardson_*``).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Callable

import numpy as np

from ...models.result import ModelFailure, PhysicsResult

__all__ = ["check_richardson", "richardson_result"]


def check_richardson(n_links: int, n_sections: int, analysis: str) -> None:
    """Raise :class:`ModelFailure` unless a static solve with ``n_links`` can be extrapolated
    (``n_links / 2`` links must be a multiple of the ``n_sections`` sections)."""
    if analysis != "static":
        raise ModelFailure("spring_link: richardson=True extrapolates static solves only")
    if n_links % (2 * n_sections):
        raise ModelFailure(f"spring_link: richardson=True needs n_elements a multiple of 2 x {n_sections} sections "
                           f"(the coarse chain has n_elements / 2 links), got {n_links}")


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
