"""Unit tests of the shared tendon helpers (pure numpy)."""

import numpy as np
import pytest

from workbench.physics.tendon_loads import (
    solve_length_controlled, tendon_path_compliance, tendon_rest_lengths, tension_from_stretch,
)


def test_rest_length_gives_pretension_exactly():
    l0 = tendon_rest_lengths([0.8, 0.4], [0.0, -0.01], 20.0, 4e4)
    assert np.allclose(tension_from_stretch([0.8], l0[:1], 4e4), 20.0)
    assert l0[1] == pytest.approx(0.4 / (1 + 20 / 4e4) - 0.01)
    with pytest.raises(ValueError, match="rest lengths"):
        tendon_rest_lengths([0.1], [-0.2], 0.0, 1e4)


def test_slack_rope_carries_nothing():
    T = tension_from_stretch([0.7, 0.9], [0.8, 0.8], 1e4)
    assert T[0] == 0.0 and T[1] == pytest.approx(1e4 * 0.1 / 0.8, rel=1e-12)


def test_compliance_matches_closed_form():
    s = np.linspace(0, 1.0, 2001)
    y = np.array([np.full_like(s, 0.02), np.full_like(s, -0.02)])
    C = tendon_path_compliance(s, np.full_like(s, 10.0), np.full_like(s, 1e6), y, [1.0, 0.5])
    assert C[0, 0] == pytest.approx(-(0.02**2 / 10 + 1e-6))
    assert C[0, 1] == pytest.approx(-0.5 * (-(0.02**2) / 10 + 1e-6))
    assert C[1, 0] == pytest.approx(C[0, 1])


def test_length_solver_on_a_nonlinear_spring_model():
    # l(T) = L - c T - b T^2 (a softening structure); tendon law T = EA (l - l0)/l0
    L, c, b, EA = 1.0, 1e-5, 1e-9, 1e5

    def eq(T):
        return L - c * T - b * T**2

    l0 = np.array([0.99, 1.02])  # second tendon slack
    info = solve_length_controlled(eq, l0, EA, -c * np.eye(2), tol=1e-12)
    T = info.tensions
    assert T[1] == 0.0
    assert T[0] == pytest.approx(EA * (eq(T)[0] - l0[0]) / l0[0], rel=1e-10)
    assert info.iterations < 15


def test_stiff_co_contracting_cables_of_the_hannan_walker_trunk_converge():
    # Hannan & Walker's line, snapshot 1, at the sensitivity value EA_t = 1.6e6 N: both cables of a section
    # are taut and stiff; the secant (Broyden) compliance alone crept for 50 iterations / 226 equilibria and
    # failed (before the forward-difference rebuild); now the row is ok and obeys the tendon law
    from workbench.study import SWEEP
    from workbench.study.evaluate import evaluate_case

    from pathlib import Path

    study = SWEEP.load(str(Path(__file__).resolve().parents[2] / "studies" / "hannan_walker.toml"))
    case = next(c for c in SWEEP.expand(study) if c.params["robot"]["tendon_stiffness"] == 1.6e6
                and c.params["scenario"]["shape"] == "line" and c.params["scenario"]["sample"] == 1)
    row = evaluate_case(case.case_id, case.params, ["ancf"])[0]
    assert row["status"] == "ok", row["error"]
    assert max(row["tendon_tensions"]) > 1000.0  # stiff co-contraction: kN tensions


def test_a_step_whose_equilibrium_fails_is_shortened_and_a_persistent_failure_propagates():
    L, c, EA = 1.0, 1e-5, 1e5

    refused = []

    def eq(T):
        if np.max(T) > 800.0:  # the structure has no equilibrium under so large a tension
            refused.append(T.copy())
            raise ArithmeticError("no equilibrium")
        return L - c * T

    l0 = np.array([0.99, 0.995])
    # a compliance estimate 100x too soft makes the first step overshoot (~1000 N; the answer is ~502 N)
    info = solve_length_controlled(eq, l0, EA, -0.01 * c * np.eye(2), tol=1e-12)
    assert refused, "the test must exercise a failed trial step"
    assert info.tensions == pytest.approx(EA * (eq(info.tensions) - l0) / l0, rel=1e-9)

    def broken(T):
        if np.any(T > 0):
            raise ArithmeticError("no equilibrium")
        return L - c * T

    with pytest.raises(ArithmeticError):
        solve_length_controlled(broken, l0, EA, -c * np.eye(2), tol=1e-12)
