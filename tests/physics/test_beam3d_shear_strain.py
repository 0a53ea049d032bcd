"""Shear strains of the geometrically exact beam (``Beam3DSystem.element_strains``) against Timoshenko theory.

A short cantilever (L = 5 cm, steel d = 6 mm: tip rotation ~1e-2 rad) carries a lateral tip force
F.  Every cross-section transmits the shear force F cos(theta) ~ F, so the engineering shear strain
of every element is ``gamma = F / GA`` with ``GA = kappa_s G A`` (Timoshenko beam theory, the
shear coefficient of :meth:`workbench.robot.CrossSection.circular`), in the cross-section axis the
force points along, and zero in the other one; the axial strain is ``F sin(theta) / EA`` ~ 0.
Before the fix ``element_strains`` read entries 1 and 2 of Exudyn's Voigt ``StrainLocal`` (always
zero for this beam) and reported no shear at all.
"""

from __future__ import annotations

import numpy as np
import pytest

from workbench.models import SolverOptions
from workbench.physics import _beam3d_system, beam3d
from workbench.robot import LoadCase
from workbench.robot.presets import build_preset


def _final_strains(monkeypatch, robot, load, n_elements):
    """Run beam3d; return its result, the system and the element strains ``(g, k)`` of its last read-out."""
    seen = []
    real = _beam3d_system.Beam3DSystem.element_strains

    def spy(self):
        out = real(self)
        seen.append((self, out))
        return out

    monkeypatch.setattr(_beam3d_system.Beam3DSystem, "element_strains", spy)
    res = beam3d.run(robot, load, SolverOptions(n_elements=n_elements))
    return res, *seen[-1]


@pytest.mark.parametrize("axis", [0, 1])
def test_tip_loaded_short_cantilever_shear_strain_is_F_over_GA(monkeypatch, axis):
    rod = build_preset("steel_rod", length=0.05)
    cs = rod.sections[0].cross_section
    F = 100.0
    force = [0.0, 0.0, 0.0]
    force[axis] = F
    res, _system, (g, _k) = _final_strains(monkeypatch, rod, LoadCase(tip_force=tuple(force)), 8)
    theta_tip = F * rod.length**2 / (2 * cs.EI)  # Euler-Bernoulli tip rotation, ~9e-3 rad
    assert 5e-3 < theta_tip < 2e-2
    shear = np.hypot(g[:, 1], g[:, 2])
    # cos(theta) >= 1 - theta_tip^2 / 2: relative deviation from F / GA below 5e-5
    np.testing.assert_allclose(shear, F / cs.GA, rtol=1e-4)
    # all of it in one cross-section axis, none in the other
    main = int(np.argmax(np.abs(g[0, 1:]))) + 1
    assert np.all(np.abs(g[:, 3 - main]) < 1e-6 * F / cs.GA)
    # axial strain F sin(theta) / EA, far below the shear strain
    assert np.all(np.abs(g[:, 0]) < theta_tip * F / cs.EA * 1.01)
    # the tip moves along the force (bending plus the shear part F L / GA of Timoshenko theory)
    expected = F * rod.length**3 / (3 * cs.EI) + F * rod.length / cs.GA
    assert res.tip_position[axis] == pytest.approx(expected, rel=2e-2)


def test_length_change_counts_the_shear_strain(monkeypatch):
    """``shape_scalars``: the centreline stretch per element is ``|(1 + eps, gamma_y, gamma_z)|``."""
    rod = build_preset("steel_rod", length=0.05)
    _res, system, (g, k) = _final_strains(monkeypatch, rod, LoadCase(tip_force=(0.0, 100.0, 0.0)), 8)
    dl, _tw = system.shape_scalars((g, k))
    axial_only = float(np.sum(system.elem_len * g[:, 0]))
    shear_part = float(np.sum(system.elem_len * 0.5 * (g[:, 1] ** 2 + g[:, 2] ** 2)))
    assert shear_part > 0.0
    assert dl - axial_only == pytest.approx(shear_part, rel=1e-3)
