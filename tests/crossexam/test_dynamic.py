"""Dynamic cross-examination (issue 28): tip trajectories of a tendon step agree across models.

Cases and the agreement rule in :mod:`tests.crossexam.dynamic`.  Default tier: ANCF vs the
spring-link chain with continuum tendons on the NiTi swing under gravity; the rest (the steel
step, the eyelet pair ANCF vs GE beam, whose GE-beam runs take ~35 s each) is slow.
"""

from __future__ import annotations

import pytest

import tomllib

from workbench.study.spec import parse_study

from tests.crossexam.dynamic import DYNAMIC_CASES, amplitude, dynamic_pair, dynamic_side, dynamic_study

#: (side a, side b): (model, tendon model, elements of the coarse run, time step of the coarse run [s])
PAIRS = {"ancf~spring_link": (("ancf", "continuum", 8, 1e-3), ("spring_link", "continuum", 16, 1e-3)),
         "ancf~beam3d eyelets": (("ancf", "eyelets", 10, 1e-3), ("beam3d", "eyelets", 10, 1e-3))}
DEFAULT = {("niti swing under gravity", "ancf~spring_link")}


def _params():
    for case in DYNAMIC_CASES:
        for pair in PAIRS:
            marks = [] if (case, pair) in DEFAULT else [pytest.mark.slow]
            yield pytest.param(case, pair, id=f"{case}-{pair}", marks=marks)


@pytest.mark.parametrize("case, pair", list(_params()))
def test_tip_trajectories_agree(case, pair):
    a, b = (dynamic_side(case, *s) for s in PAIRS[pair])
    dist, tol = dynamic_pair(case, a, b)
    # the swing is large against the tolerance, so agreement is not trivial
    assert min(amplitude(a), amplitude(b)) > 20.0 * tol, (amplitude(a), amplitude(b), tol)
    assert dist <= tol, (f"{case} {pair}: largest tip distance over time {dist:.3e} m > tolerance {tol:.3e} m "
                         f"(bars {a.bar:.2e} + {b.bar:.2e})\n" + "".join(
                             f"--- study (workbench run) ---\n{dynamic_study(case, *s)}" for s in PAIRS[pair]))


def test_dynamic_study_files_validate():
    """The study files a failure prints parse and pass the capability check."""
    for case in DYNAMIC_CASES:
        for sides in PAIRS.values():
            for s in sides:
                study = parse_study(tomllib.loads(dynamic_study(case, *s)), source=f"{case} {s}")
                assert list(study.models) == [s[0]]
