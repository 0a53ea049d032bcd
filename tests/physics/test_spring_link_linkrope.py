"""The vectorised rope forces of the 3-D kinematic tree (``workbench/physics/spring_link/linkrope.py``).

Three independent checks: the batched forces (ropes and tip loads) equal a plain loop over joints, links
and tendons written here from the rope law; the batched central-difference Jacobian (rigid rotations of the distal part)
equals column-by-column differences of the re-chained forces; and a solve with the rope forces as the
generic object's user function equals the same tree with one constant-force rope connector per segment
(``routing.add_eyelet_rope``) and Exudyn's tip loads on the tree marker, eyelets and length mode included.  Also the link-count Richardson
extrapolation (``workbench/physics/spring_link/richardson.py``) against an exact arc.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.models.result import ModelFailure, SolverOptions
from workbench.physics.spring_link import solve
from workbench.physics.spring_link.driver import ramp_to
from workbench.physics.spring_link.geometry import chain_geometry_from_robot
from workbench.physics.spring_link.linkrope import (axis_rotation, generalised_force_jacobian, generalised_forces,
                                                    rope_layout)
from workbench.physics.spring_link.params import SpringLinkParams
from workbench.physics.spring_link.routing import route_tendons
from workbench.physics.spring_link.tree import TreeChain, joint_axes
from workbench.robot import CrossSection, LoadCase, Robot, Section, TendonActuation, TendonGroup


def rao(n_disks: int = 10) -> Robot:
    """The Rao et al. 2021 two-section NiTi robot (``../shared/notes/peer-benchmark.md``)."""
    cs = CrossSection.circular(diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.3)
    tg = TendonGroup(angles=(math.pi / 2, -math.pi / 6, 7 * math.pi / 6), offset=10e-3, axial_stiffness=1e7)
    return Robot(sections=tuple(Section(0.2, cs, tg, n_disks=n_disks) for _ in range(2)))


def loop_forces(geo, axes, q, tendons, tension_of, tip) -> np.ndarray:  # noqa: ANN001
    """Generalised forces by plain loops: chain the joint rotations, place every eyelet and the tip, sum
    ``(p - o) x F`` (and the tip torque)."""
    N, P, R, A = geo.n_links, [], [], []
    Rk, pk, i = np.eye(3), np.array([0.0, 0.0, geo.joints[0]]), 0
    for k in range(N):
        if k > 0:
            pk = pk + geo.link_lengths[k - 1] * Rk[:, 2]
        for ax in axes[k]:
            A.append((Rk @ {"X": np.eye(3)[0], "Y": np.eye(3)[1], "Z": np.eye(3)[2]}[ax], k))
            Rk = Rk @ axis_rotation(ax, float(q[i]))
            i += 1
        P.append(pk)
        R.append(Rk)
    forces = []  # (link, point, force)
    for j, t in enumerate(tendons):
        u = np.array([math.cos(t.sigma), math.sin(t.sigma), 0.0])
        pts = []
        for link, z, d in zip(t.eye_link, t.eye_z, t.eye_d):
            loc = d * u + np.array([0.0, 0.0, z])
            pts.append(loc if link < 0 else P[link] + R[link] @ loc)
        length = sum(np.linalg.norm(b - a) for a, b in zip(pts[:-1], pts[1:]))
        T = tension_of(j, length)
        for e, (a, b) in enumerate(zip(pts[:-1], pts[1:])):
            f = T * (b - a) / np.linalg.norm(b - a)
            forces += [(t.eye_link[e], a, f), (t.eye_link[e + 1], b, -f)]
    forces.append((N - 1, P[-1] + R[-1] @ np.array([0.0, 0.0, geo.link_lengths[-1]]), tip[0]))
    Q = np.zeros(len(A))
    for i, (a, k) in enumerate(A):
        Q[i] = sum(a @ np.cross(p - P[k], f) for link, p, f in forces if link >= k) + a @ tip[1]
    return Q


@pytest.mark.parametrize("per", [2, 3])
@pytest.mark.parametrize("model", ["eyelets", "continuum"])
def test_vectorised_rope_forces_equal_a_plain_loop(per, model):
    robot = rao()
    geo = chain_geometry_from_robot(robot, 12)
    tendons = route_tendons(robot, geo, model)
    axes = [joint_axes(per, k) for k in range(geo.n_links)]
    lay = rope_layout(geo, axes, tendons)
    q = np.random.default_rng(per).normal(0.0, 0.3, per * geo.n_links)
    L0 = np.array([0.99 * t.reference_length for t in tendons])
    law = [lambda i, L: (4.0, 0.0, 1.5, 0.5, 2.0, 3.0)[i], lambda i, L: 1e4 * (L - L0[i]) / L0[i]]
    vec = [lambda L: np.broadcast_to(np.array([4.0, 0.0, 1.5, 0.5, 2.0, 3.0]), L.shape), lambda L: 1e4 * (L - L0) / L0]
    for loop_law, vec_law, tip in zip(law, vec, [(np.zeros(3), np.zeros(3)), (np.array([0.1, -0.2, 0.05]),
                                                                           np.array([0.01, 0.0, -0.02]))]):
        ref = loop_forces(geo, axes, q, tendons, loop_law, tip)
        assert np.max(np.abs(ref)) > 1e-3
        np.testing.assert_allclose(generalised_forces(lay, q, vec_law, tip), ref, rtol=0,
                                   atol=1e-12 * np.max(np.abs(ref)))


def test_rope_jacobian_equals_differences_of_the_rechained_forces():
    robot = rao()
    geo = chain_geometry_from_robot(robot, 8)
    tendons = route_tendons(robot, geo, "eyelets")
    lay = rope_layout(geo, [joint_axes(3, k) for k in range(geo.n_links)], tendons)
    q = np.random.default_rng(1).normal(0.0, 0.3, 3 * geo.n_links)
    L0 = np.array([0.99 * t.reference_length for t in tendons])
    law = lambda L: 1e4 * (L - L0) / L0  # noqa: E731 - length mode: the tension depends on q too
    tip = (np.array([0.1, -0.2, 0.05]), np.array([0.01, 0.0, -0.02]))
    h = 1e-6
    ref = np.stack([(generalised_forces(lay, q + h * e, law, tip) - generalised_forces(lay, q - h * e, law, tip))
                    / (2 * h) for e in np.eye(len(q))], axis=1)
    J = generalised_force_jacobian(lay, q, law, tip)
    assert np.max(np.abs(ref)) > 1.0
    np.testing.assert_allclose(J, ref, rtol=0, atol=1e-7 * np.max(np.abs(ref)))


class _ConnectorTree(TreeChain):
    """The same tree with the ropes as constant-force rope connectors on tree markers."""

    def _build(self, mbs) -> None:  # noqa: ANN001
        self.link_ropes = False
        super()._build(mbs)


@pytest.mark.parametrize("model,mode", [("eyelets", "tension"), ("eyelets", "length")])
def test_user_function_ropes_equal_rope_connectors(model, mode):
    robot = rao(n_disks=4)
    values = (3.0, 0.0, 0.0, 0.0, 1.5, 0.5) if mode == "tension" else (-4e-3, 0.0, 0.0, 0.0, -2e-3, 0.0)
    load = LoadCase(actuation=TendonActuation(mode, values), tip_force=(0.02, 0.0, -0.03),
                    tip_torque=(0.0, 2e-3, 1e-3))
    opts = SolverOptions(n_elements=8, tendon_model=model)
    geo = chain_geometry_from_robot(robot, 8)
    tips, tensions = [], []
    for cls in (TreeChain, _ConnectorTree):
        chain = cls(robot, load, opts, geo, spatial=True, torsion="spring")
        assert chain.link_ropes == (cls is TreeChain)
        ramp_to(chain, SpringLinkParams(), np.asarray(values))
        tips.append(chain.link_frames()[0][-1])  # the last joint
        tensions.append(chain.tensions())
    assert np.linalg.norm(tips[0] - tips[1]) < 1e-9 * robot.length
    np.testing.assert_allclose(tensions[0], tensions[1], rtol=1e-7, atol=1e-9)
    assert np.max(tensions[0]) > 0.3
    assert np.linalg.norm(tips[0] - np.array([0.0, 0.0, geo.joints[-1]])) > 0.02  # it bends


def test_richardson_extrapolation_beats_the_fine_chain_on_an_exact_arc():
    """A tip moment M = (pi/2) EI / L bends the rod into a quarter circle (exact); the chain's tip
    error falls ~4x per link doubling, the extrapolated tip is far closer and the bar is the fine
    chain's own error."""
    robot = rao()
    EI = robot.sections[0].cross_section.EI
    L = robot.length
    theta = math.pi / 2
    R = L / theta
    exact = np.array([R * (1 - math.cos(theta)), 0.0, R * math.sin(theta)])
    load = LoadCase(tip_torque=(0.0, theta * EI / L, 0.0))
    fine = solve(robot, load, SolverOptions(n_elements=16))
    ext = solve(robot, load, SolverOptions(n_elements=16), SpringLinkParams(richardson=True))
    e_fine = np.linalg.norm(fine.tip_position - exact)
    e_ext = np.linalg.norm(ext.tip_position - exact)
    assert e_fine > 1e-4 * L
    assert e_ext < 0.05 * e_fine
    assert 0.7 * e_fine < ext.extras["richardson_tip_bar"] < 1.3 * e_fine
    assert np.linalg.norm(ext.positions[-1] - ext.tip_position) < 1e-12
    assert "Richardson of 8 and 16 links" in ext.solver.message


def test_richardson_refuses_odd_link_counts_and_dynamics():
    robot = rao()
    with pytest.raises(ModelFailure, match="multiple of 2 x 2 sections"):
        solve(robot, LoadCase(), SolverOptions(n_elements=18), SpringLinkParams(richardson=True))
    with pytest.raises(ModelFailure, match="static solves only"):
        solve(robot, LoadCase(analysis="dynamic", duration=0.1), SolverOptions(n_elements=16),
              SpringLinkParams(richardson=True))
