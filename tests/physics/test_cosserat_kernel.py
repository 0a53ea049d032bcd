"""The Cosserat model's two right-hand sides: the numba kernel (:mod:`workbench.physics.cosserat.kernel`)
against the numpy one (:mod:`workbench.physics.cosserat.rod`).

The kernel's Python source is checked in every environment (``py_func`` under numba, the function
itself without it); the compiled kernel and the full solve through it only where numba is installed.
The numpy path stays tested: by these comparisons and by every cosserat test run without numba.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.physics.cosserat import Shooter, kernel, rod_problem
from workbench.physics.cosserat.rod import N_BASE, integrate_segments, kernel_arguments, segment_rhs
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup

TENSIONS = (4.0, 0.0, 1.0, 0.5, 2.0, 0.0)


def _robot() -> Robot:
    """Two sections, the second tapered (stiffness and tendon offset), self-weight under gravity:
    every term of the right-hand side is non-zero."""
    rod = CrossSection.circular(1.4e-3, 54e9, 6450.0, 0.3)
    thin = CrossSection.circular(1.0e-3, 54e9, 6450.0, 0.3)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=0.01, axial_stiffness=1e7)
    tapered = TendonGroup(angles=(0.3, 2.4, 4.5), offset=0.01, offset_tip=0.006, axial_stiffness=1e7)
    return Robot(sections=(Section(0.2, rod, tg, n_disks=10),
                           Section(0.2, rod, tapered, n_disks=10, cross_section_tip=thin)),
                 gravity=(0.0, -9.81, 0.0))


def _load() -> LoadCase:
    return LoadCase(actuation=TendonActuation("tension", TENSIONS), tip_force=(0.02, 0.0, -0.02))


def _states(rng: np.random.Generator, B: int, n_state: int) -> np.ndarray:
    """Random shots: any rotation, wrenches of the size the robot sees (tensions of a few N)."""
    y = rng.normal(size=(B, n_state))
    for b in range(B):
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        y[b, 3:12] = q.reshape(9)
    y[:, 12:15] *= 3.0
    y[:, 15:18] *= 0.1
    return y


@pytest.mark.parametrize("compiled", [False, True])
def test_kernel_right_hand_side_equals_numpy(compiled):
    """On both sections (six tendons, then three; tapered), at random states: the kernel's y' equals
    numpy's to round-off (the strain Newton converges to c delta^2 < 1e-16 in both)."""
    if compiled and not kernel.AVAILABLE:
        pytest.skip("numba is not installed")
    pb = rod_problem(_robot(), _load())
    tau = np.array(TENSIONS)
    n_state = N_BASE + 2 + pb.n_tendons
    rng = np.random.default_rng(0)
    checked = 0
    for sec, s in ((0, 0.13), (1, 0.31)):
        active = pb.tendon_ends >= pb.section_starts[sec] + pb.section_lengths[sec] - 1e-12
        y = _states(rng, 5, n_state).reshape(-1)
        ref = segment_rhs(pb, sec, active, tau, 0.7, 5, compiled=False)(s, y)
        if compiled:
            got = segment_rhs(pb, sec, active, tau, 0.7, 5, compiled=True)(s, y)
        else:
            py = getattr(kernel.segment_rhs, "py_func", kernel.segment_rhs)
            got = py(s, y, *kernel_arguments(pb, sec, active, tau, 0.7))
        assert np.all(np.isfinite(ref))
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * np.max(np.abs(ref)))
        checked += int(np.count_nonzero(active))
    assert checked == 9


def test_compiled_solve_equals_numpy_solve():
    """The same load path through both right-hand sides: base wrench and tip within the solve's
    tolerance (1e-9 scaled residual), Jacobian sign equal."""
    if not kernel.AVAILABLE:
        pytest.skip("numba is not installed")
    pb = rod_problem(_robot(), _load())
    tau = np.array(TENSIONS)
    tips = []
    for compiled in (False, True):
        sh = Shooter(pb, 1e-9, compiled=compiled)
        sh.go_to(tau, 20)
        tip, _ = integrate_segments(pb, sh.x[None], tau, 1.0, sh.rtol, compiled=compiled)
        tips.append((sh.x, tip[0, :3], sh.sign))
    (x0, p0, s0), (x1, p1, s1) = tips
    assert s0 == s1 == 1
    assert np.linalg.norm(p1 - p0) / pb.length < 1e-8
    assert np.max(np.abs(x1 - x0)) < 1e-7 * np.max(np.abs(x0))


def test_kernel_dop853_takes_scipys_steps():
    """integrate_segments through the kernel's DOP853 (steps and dense output in numba) against
    solve_ivp's DOP853 with the numpy right-hand side: tip and stations equal to round-off (1e-12),
    so the kernel integrator is scipy's algorithm, not a new discretisation."""
    if not kernel.AVAILABLE:
        pytest.skip("numba is not installed")
    pb = rod_problem(_robot(), _load())
    tau = np.array(TENSIONS)
    x = np.array([[0.05, -0.2, -0.1, 0.01, 0.02, -0.003]])
    X = np.vstack([x, x + 1e-4 * np.eye(6)])
    stations = np.linspace(0.0, pb.length, 17)
    ref, ref_at = integrate_segments(pb, X, tau, 1.0, 1e-10, stations, compiled=False)
    got, got_at = integrate_segments(pb, X, tau, 1.0, 1e-10, stations, compiled=True)
    no_stations, _ = integrate_segments(pb, X, tau, 1.0, 1e-10, compiled=True)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12)
    np.testing.assert_allclose(got_at, ref_at, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(no_stations, got)  # dense output does not move the steps
    assert np.abs(ref_at[-1] - ref).max() < 1e-12 and np.abs(ref_at[0, :, 12:18] - X).max() == 0.0
