"""Warm starts of the spring-link chain (``workbench.physics.spring_link.driver``): the static ramp
continued from a solve at a fraction of the same load (Exudyn initial coordinates and the tendons'
active set).  Reference: the cold solve of the same load (the ramp from the unloaded chain); the
tolerance is the static Newton's (positions agree to ~1e-11 L, measured).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

OPTS = SolverOptions(n_elements=20, tendon_model="eyelets")


@pytest.fixture(scope="module")
def rao():
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.3)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, rod, tg, n_disks=10), Section(0.2, rod, tg, n_disks=10)))


def _load(s: float, force=(0.0, 0.1, 0.0)) -> LoadCase:
    return LoadCase(actuation=TendonActuation("tension", (2 * s, 2 * s, 0.0, 0.0, 3 * s, 0.0)),
                    tip_force=tuple(s * f for f in force))


@pytest.mark.parametrize("options", [OPTS, replace(OPTS, model_settings={"spring_link": {"richardson": True}})],
                         ids=["20 links", "Richardson 10 + 20"])
def test_a_fraction_of_the_load_continues_the_cold_path(rao, options):
    run = get_model("spring_link")
    half = run(rao, _load(0.5), options)
    assert half.warm_state is not None
    cold = run(rao, _load(1.0), options)
    warm = run(rao, _load(1.0), replace(options, warm_state=half.warm_state))
    assert warm.extras["warm_started"] == 1.0 and warm.solver.path_event == ""
    assert np.abs(warm.positions - cold.positions).max() < 1e-9 * rao.length
    assert np.abs(warm.tendon_tensions - cold.tendon_tensions).max() < 1e-9
    assert "warm_started" not in cold.extras


def test_other_states_are_refused_and_the_solve_is_cold(rao):
    run = get_model("spring_link")
    cold = run(rao, _load(1.0), OPTS)
    off_ray = run(rao, _load(0.5, force=(0.1, 0.0, 0.0)), OPTS).warm_state
    larger = run(rao, _load(1.5), OPTS).warm_state
    finer = run(rao, _load(0.5), replace(OPTS, n_elements=40)).warm_state
    for state in (off_ray, larger, finer, cold.positions.reshape(-1)):
        res = run(rao, _load(1.0), replace(OPTS, warm_state=state))
        assert res.extras["warm_started"] == 0.0
        assert np.array_equal(res.positions, cold.positions)
