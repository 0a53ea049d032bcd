"""The load ramp of each Exudyn model, seen from the solver: the trial load factors it tries.

Every model ramps its loads through ``workbench.physics._stepping.load_ramp`` with its own policy.
These tests replace Exudyn's ``SolveStatic`` by a wrapper that solves, records the load factor
of the attempt and fails chosen attempts, and pin the resulting sequence (the same sequence the
models' own load loops produced before they moved onto ``load_ramp``).
"""

from __future__ import annotations

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")

from workbench.models import ModelFailure, SolverOptions  # noqa: E402
from workbench.physics import ancf, ancf3d, beam3d  # noqa: E402
from workbench.robot import LoadCase  # noqa: E402
from workbench.robot.presets import build_preset  # noqa: E402

#: a unit tip force (no gravity): every load vector component is 0 or +-lambda, exactly
LOAD = LoadCase(tip_force=(1.0, 0.0, 0.0))


@pytest.fixture
def solver(monkeypatch):
    """``(trials, fail_at)``: recorded load factors, and the attempt numbers to fail after solving."""
    trials: list[float] = []
    fail_at: set[int] = set()
    orig = exu.SolveStatic

    def solve(mbs, *args, **kwargs):
        n = len(trials)
        vecs = [np.abs(mbs.GetLoadParameter(i, "loadVector")) for i in range(mbs.systemData.NumberOfLoads())]
        trials.append(float(max(v.max() for v in vecs)))
        out = orig(mbs, *args, **kwargs)
        if n in fail_at:
            raise exu.SolverError("injected failure")
        return out

    monkeypatch.setattr(exu, "SolveStatic", solve)
    monkeypatch.setattr(exu.MainSystem, "SolveStatic", solve)
    return trials, fail_at


@pytest.mark.parametrize("model", [beam3d, ancf3d])
def test_3d_models_double_capped_at_the_remaining_load(solver, model):
    trials, fail_at = solver
    fail_at.update({0, 2, 4})
    res = model.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4))
    # after 0.75 the increment is capped at 0.25, so the retry after the failed 1.0 is 0.875
    ramp = [1.0, 0.5, 1.0, 0.75, 1.0, 0.875, 1.0]
    # beam3d ramps the rod with EA, GA scaled down, then raises them stage by stage at full load
    # (issue 18): one more solve at load factor 1 per predictor stage
    rod = build_preset("steel_rod")
    cs = rod.sections[0].cross_section
    n_stages = len(beam3d.auto_stiffness_stages([cs.EA] * 4, [cs.EI] * 4, [rod.length / 4] * 4)) if model is beam3d else 0
    assert (model is ancf3d) or n_stages > 0
    assert trials == ramp + [1.0] * n_stages
    assert res.extras["load_steps"] == 4.0 + n_stages and res.solver.iterations == 7 + n_stages


def test_beam3d_plain_ramp_without_stiffness_stages(solver):
    trials, fail_at = solver
    fail_at.update({0, 2, 4})
    res = beam3d.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4), stiffness_stages=())
    assert trials == [1.0, 0.5, 1.0, 0.75, 1.0, 0.875, 1.0]
    assert res.extras["load_steps"] == 4.0 and res.solver.iterations == 7


def test_ancf_doubles_after_two_successes_capped_at_one(solver):
    trials, fail_at = solver
    fail_at.update({0, 2, 4})
    res = ancf.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4))
    assert trials == [1.0, 0.5, 1.0, 0.75, 1.0, 0.875, 1.0]
    assert res.extras["static_steps"] == 7.0 and res.extras["failed_steps"] == 3.0
    trials.clear()
    fail_at.clear()
    fail_at.update({0, 1})  # after 0.25 the increment stays 0.25 until a second success doubles it
    ancf.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4))
    assert trials == [1.0, 0.5, 0.25, 0.5, 1.0]


@pytest.mark.parametrize("model, word", [(beam3d, "beam3d"), (ancf3d, "ancf3d"), (ancf, "ANCF")])
def test_ramp_limits_keep_each_models_wording(solver, model, word):
    trials, fail_at = solver
    fail_at.update(range(3))
    plain = {"stiffness_stages": ()} if model is beam3d else {}  # beam3d's staged ramp: the next test
    with pytest.raises(ModelFailure, match=rf"^{word}.*max_load_steps=3.*(lambda|load factor)[ =]0\b"):
        model.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4, max_load_steps=3), **plain)
    trials.clear()
    fail_at.update(range(100))
    with pytest.raises(ModelFailure, match=rf"^{word}.*(increment below|increment <) 1e-06"):
        model.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4, max_load_steps=100), **plain)
    assert len(trials) == 20  # 1, 1/2, ..., 2**-19; 2**-20 < 1e-6 stops


def test_beam3d_staged_ramp_falls_back_to_the_plain_ramp(solver):
    """A failed staged ramp (soft rod) is followed by the plain ramp, each capped by max_load_steps."""
    trials, fail_at = solver
    fail_at.update(range(3))
    res = beam3d.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4, max_load_steps=3))
    assert trials == [1.0, 0.5, 0.25, 1.0]  # three failed staged attempts, then the plain ramp at once
    assert res.solver.converged
    trials.clear()
    fail_at.update(range(6))
    with pytest.raises(ModelFailure, match=r"^beam3d.*max_load_steps=3"):
        beam3d.run(build_preset("steel_rod"), LOAD, SolverOptions(n_elements=4, max_load_steps=3))
    assert trials == [1.0, 0.5, 0.25] * 2
