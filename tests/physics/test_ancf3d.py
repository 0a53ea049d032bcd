"""Spatial ANCF cable model (``workbench.physics.ancf3d``): references and rejections."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models import ModelFailure, SolverOptions
from workbench.physics import ancf3d, beam3d
from workbench.robot import LoadCase, Payload, Robot, TendonActuation
from workbench.robot.presets import build_preset


def _tilted(rod: Robot, angle: float) -> Robot:
    """Same rod with gravity rotated about the base z axis by ``angle`` (horizontal mount)."""
    R = np.asarray(rod.base_rotation)
    c, s = math.cos(angle), math.sin(angle)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    return Robot(sections=rod.sections, gravity=rod.gravity, payload=rod.payload,
                 base_rotation=tuple(map(tuple, R @ Rz)), name=rod.name)


@pytest.mark.parametrize("angle", [0.0, 1.1])
def test_sag_in_any_plane_matches_euler_bernoulli(angle):
    rod = _tilted(build_preset("steel_rod", gravity=1.0, base_orientation="horizontal"), angle)
    cs, L = rod.sections[0].cross_section, rod.length
    g = rod.gravity_in_base()
    q = cs.mass_per_length * np.linalg.norm(g)
    res = ancf3d.run(rod, LoadCase(), SolverOptions(n_elements=8))
    expected = q * L**4 / (8 * cs.EI) * g / np.linalg.norm(g)
    np.testing.assert_allclose(res.tip_position[:2], expected[:2], rtol=1e-4, atol=1e-12)


def test_large_sag_with_payload_agrees_with_beam3d():
    """gamma = qL^3/EI = 1.47 plus a 10 g payload (tip sag 0.34 m of 1 m).  ANCF is converged
    (4e-7 m between 16 and 32 elements); the GE beam converges to it at 2nd order: measured
    tip distance 7.4e-4 / 1.85e-4 / 4.6e-5 m at 8 / 16 / 32 elements."""
    rod = build_preset("steel_rod", length=1.0, diameter=2e-3, gravity=9.81, base_orientation="horizontal",
                       payload_mass=0.01)
    a = ancf3d.run(rod, LoadCase(), SolverOptions(n_elements=16))
    assert -a.tip_position[0] > 0.3  # genuinely nonlinear (linear theory: 0.55 m)
    d = []
    for n in (8, 16):
        b = beam3d.run(rod, LoadCase(), SolverOptions(n_elements=n))
        d.append(np.linalg.norm(a.tip_position - b.tip_position))
    assert d[1] < 2.5e-4
    assert d[0] / d[1] > 3.5
    assert np.max(np.linalg.norm(a.positions - b.positions, axis=1)) < 3e-4
    np.testing.assert_allclose(a.tip_frame[:3, :3], b.tip_frame[:3, :3], atol=5e-4)


def test_tip_force_matches_linear_cantilever():
    rod = build_preset("steel_rod")
    cs, L = rod.sections[0].cross_section, rod.length
    F = np.array([0.06, -0.08, 0.0])
    res = ancf3d.run(rod, LoadCase(tip_force=tuple(F)), SolverOptions(n_elements=8))
    np.testing.assert_allclose(res.tip_position[:2], F[:2] * L**3 / (3 * cs.EI), rtol=2e-4)
    assert res.tip_twist == 0.0


def test_axial_force_length_change():
    rod = build_preset("steel_rod")
    cs, L = rod.sections[0].cross_section, rod.length
    res = ancf3d.run(rod, LoadCase(tip_force=(0.0, 0.0, -500.0)), SolverOptions(n_elements=4))
    assert res.length_change == pytest.approx(-500.0 * L / cs.EA, rel=1e-6)


def test_rejects_loaded_tendons_torque_and_payload_offset():
    rod = build_preset("steel_rod", tendon_count=3)
    with pytest.raises(ModelFailure, match="beam3d"):
        ancf3d.run(rod, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0))), SolverOptions())
    with pytest.raises(ModelFailure, match="pretension"):
        ancf3d.run(rod, LoadCase(actuation=TendonActuation("length", (0.0, 0.0, 0.0), pretension=5.0)),
                   SolverOptions())
    with pytest.raises(ModelFailure, match="tip_torque"):
        ancf3d.run(rod, LoadCase(tip_torque=(0.0, 0.1, 0.0)), SolverOptions())
    off = Robot(sections=rod.sections, payload=Payload(mass=0.1, offset=(0.01, 0, 0)))
    with pytest.raises(ModelFailure, match="offset"):
        ancf3d.run(off, LoadCase(), SolverOptions())
    # unloaded tendons are fine
    res = ancf3d.run(rod, LoadCase(actuation=TendonActuation("tension", (0.0, 0.0, 0.0))),
                     SolverOptions(n_elements=4))
    np.testing.assert_allclose(res.tendon_tensions, 0.0)
