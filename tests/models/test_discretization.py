"""The discretisation-error estimate against the true error (elastica, pure-moment arc) and its arithmetic.

The true error is the distance of the model's tip to an independent reference: the project's
inextensible elastica BVP (tip load alpha = P L^2 / EI = 2) and the closed-form circular arc of a
pure end moment (kappa L = pi / 2).  At two resolutions per model the Richardson estimate (the
model's declared order, three solves) must bracket the true error within a factor of 3; where
the model is exact (beam3d under a pure moment: round-off) the estimate must be at round-off too.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from workbench import registry
from workbench.models import get_model
from workbench.models.discretization import (
    coarsened_options,
    effective_order,
    estimate_discretization,
    estimate_from_values,
    observed_order,
    peak_distance,
    richardson_error,
)
from workbench.models.result import SolverOptions
from workbench.reference.elastica import clamped_elastica
from workbench.robot import CrossSection, LoadCase, Robot, Section
from workbench.robot.orientation import base_rotation_for

L = 0.8
STEEL = CrossSection.circular(6e-3)
EI = STEEL.EI
# nearly inextensible for the planar / cable models (EA 1e4 x steel); beam3d's Newton does not
# converge from the first increment with EA 100 x steel or more, so it keeps steel's EA (the
# axial strain P / EA = 1.8e-5 moves its tip by ~1e-7 m, far below the errors compared here)
STIFF = CrossSection(EI=EI, EA=STEEL.EA * 1e4, GJ=STEEL.GJ, mass_per_length=STEEL.mass_per_length)
P = 2.0 * EI / L**2
M = EI * (math.pi / 2) / L


def _robot(cs):
    return Robot(sections=(Section(length=L, cross_section=cs),), base_rotation=base_rotation_for("horizontal"))


@functools.lru_cache(maxsize=1)
def _elastica_tip() -> np.ndarray:
    a, b = clamped_elastica(L, EI, tip_force=(0.0, P), stations=2).tip
    return np.array([b, 0.0, a])  # elastica (along, lateral) = base (z, x)


def _arc_tip() -> np.ndarray:
    k = M / EI
    return np.array([(1 - math.cos(k * L)) / k, 0.0, math.sin(k * L) / k])


CASES = [  # model, load, resolutions (each solved with N/2 and N/4 for the estimate)
    ("ancf", "tip", (8, 16)), ("ancf", "arc", (8, 16)),
    ("ancf3d", "tip", (8, 16)),  # ancf3d has no rotational coordinates: no tip torque (it refuses)
    ("spring_link", "tip", (8, 16)), ("spring_link", "arc", (8, 16)),
    ("beam3d", "tip", (4, 8)),
    pytest.param("beam3d", "arc", (4, 8), marks=pytest.mark.slow),  # exact arc; ~20 s of slow statics
]


@pytest.mark.parametrize("model,case,resolutions", CASES)
def test_estimate_brackets_the_true_error(model, case, resolutions):
    run = get_model(model)
    robot = _robot(STEEL if model == "beam3d" else STIFF)
    load = LoadCase(tip_force=(P, 0.0, 0.0)) if case == "tip" else LoadCase(tip_torque=(0.0, M, 0.0))
    exact = _elastica_tip() if case == "tip" else _arc_tip()
    for n in resolutions:
        opts = SolverOptions(n_elements=n, newton_tolerance=1e-10 if model != "beam3d" else 1e-9, max_load_steps=400)
        res = run(robot, load, opts)
        est = estimate_discretization(run, robot, load, opts, res, registry.MODELS[model].order)
        true = float(np.linalg.norm(res.tip_position - exact))
        assert est.status == "ok" and est.resolutions == (n, n // 2, n // 4), est
        if model == "beam3d" and case == "arc":  # exact up to round-off (facts note: ~1e-16)
            assert true < 1e-12 and est.error < 1e-12, (true, est)
            continue
        assert 1.0 / 3.0 <= est.error / true <= 3.0, (model, case, n, true, est)
        # the declared order is what the three resolutions show (within 0.4)
        assert abs(est.order_observed - registry.MODELS[model].order) < 0.4, est


# --------------------------------------------------------------------------- arithmetic
def test_richardson_and_observed_order_on_a_known_sequence():
    # q(h) = q* + C h^p with p = 3: exact recovery from three resolutions
    qstar, C, p = 1.0, 0.7, 3.0
    q = {n: qstar + C * (1.0 / n) ** p for n in (4, 8, 16)}
    d1, d2 = abs(q[16] - q[8]), abs(q[8] - q[4])
    assert observed_order(d1, d2) == pytest.approx(p, rel=1e-12)
    assert richardson_error(d1, 2.0, p) == pytest.approx(abs(q[16] - qstar), rel=1e-12)
    # uneven ratios (12 -> 8 -> 4): the general formula
    q = {n: qstar + C * (1.0 / n) ** p for n in (4, 8, 12)}
    assert observed_order(abs(q[12] - q[8]), abs(q[8] - q[4]), 1.5, 2.0) == pytest.approx(p, rel=1e-9)


def test_effective_order_never_less_conservative_than_declared():
    assert effective_order(4.0, 3.2) == 3.2
    assert effective_order(2.0, 3.9) == 2.0
    assert effective_order(2.0, -0.5) == 1.0
    assert effective_order(float("nan"), float("nan")) == 1.0
    assert effective_order(4.0, float("nan")) == 4.0


def test_non_monotone_sequence_is_flagged():
    est = estimate_from_values([0.10, 0.13, 0.12], [16, 8, 4], 2.0, noise=1e-9)
    assert est.order_used == 1.0 and est.error == pytest.approx(0.03)
    assert "outside the asymptotic range" in est.status


def test_differences_at_solver_precision_give_no_observed_order():
    est = estimate_from_values([1.0, 1.0 + 1e-13, 1.0 + 3e-13], [16, 8, 4], 4.0, noise=1e-9)
    assert math.isnan(est.order_observed) and est.order_used == 4.0 and est.error < 1e-14


def test_coarsened_options_rules():
    o = SolverOptions(n_elements=16, time_step=2e-3)
    assert coarsened_options(o, 4, 2, dynamic=False).n_elements == 8
    assert coarsened_options(o, 4, 4, dynamic=False).n_elements == 4
    assert coarsened_options(o, 4, 4, dynamic=False).time_step == 2e-3
    d = coarsened_options(SolverOptions(n_elements=12, time_step=5e-3), 1, 4, dynamic=True)
    assert d.n_elements == 3 and d.time_step == pytest.approx(2e-2)
    assert coarsened_options(SolverOptions(n_elements=6), 4, 2, dynamic=False) is None  # 3 < 4 sections
    assert coarsened_options(SolverOptions(n_elements=1), 1, 2, dynamic=False) is None


def test_peak_distance_interpolates_onto_the_first_history():
    ta = np.linspace(0, 1, 11)
    tb = np.linspace(0, 1, 101)
    pa = np.zeros((11, 3))
    pb = np.column_stack([np.sin(np.pi * tb), 0 * tb, 0 * tb])
    assert peak_distance(ta, pa, tb, pb) == pytest.approx(1.0, abs=1e-12)  # sin peaks at t = 0.5, a sample of ta
