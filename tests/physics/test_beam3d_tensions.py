"""``beam3d`` reports one tension per tendon or refuses (issue 28: tension arrays of the wrong length were
silently replaced by zeros in ``beam3d.run``)."""

import math

import numpy as np
import pytest

from workbench.models.result import ModelFailure, SolverOptions
from workbench.physics import _beam3d_system
from workbench.physics.beam3d import run
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

ROBOT = Robot(sections=(Section(length=0.3, cross_section=CrossSection.circular(2e-3),
                                tendons=TendonGroup((0.0, math.pi), 5e-3, 4e4), n_disks=4),))
OPTS = SolverOptions(n_elements=4, tendon_model="eyelets", n_stations=5)


def test_wrong_number_of_built_tensions_is_an_error(monkeypatch):
    """A built system whose tendon count differs from the robot's: ModelFailure naming both counts
    (main returned zeros for every tendon, converged)."""
    real = _beam3d_system.Beam3DSystem.tendon_state

    def one_short(self):
        T, stretch = real(self)
        return T[:-1], stretch[:-1]

    monkeypatch.setattr(_beam3d_system.Beam3DSystem, "tendon_state", one_short)
    with pytest.raises(ModelFailure, match=r"1 tendon tensions .* robot's 2 tendons"):
        run(ROBOT, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0))), OPTS)


def test_tensions_as_commanded_and_zero_without_tendon_loads():
    res = run(ROBOT, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0))), OPTS)
    np.testing.assert_allclose(res.tendon_tensions, [1.0, 0.0], atol=1e-12)
    res = run(ROBOT, LoadCase(tip_force=(0.01, 0.0, 0.0)), OPTS)  # no tendon objects built
    assert res.tendon_tensions.shape == (2,) and not np.any(res.tendon_tensions)
