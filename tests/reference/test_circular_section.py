"""One circular-section formula for the three rod-section types (bit for bit what each computed before).

``robot.CrossSection.circular``, ``reference.cosserat.RodStiffness.circular`` and
``physics.series_parallel.ModuleGeometry.rod_params`` all take A, I and J from
``robot.description.circular_section``; each result must equal the expression its type used
before the formulas were shared (written out here).
"""

from __future__ import annotations

import math

import numpy as np

from workbench.physics.series_parallel import ModuleGeometry
from workbench.reference.cosserat import RodStiffness
from workbench.robot.description import CrossSection, circular_section


def _cases(n=300):
    rng = np.random.default_rng(5)
    d = 10.0 ** rng.uniform(-4, -1, n)
    E = 10.0 ** rng.uniform(6, 12, n)
    nu = rng.uniform(-0.9, 0.49, n)
    return [(float(a), float(b), float(c)) for a, b, c in zip(d, E, nu)] + [(0.006, 200e9, 0.3), (6e-3, 210e9, 0.3)]


def test_formula():
    A, I, J = circular_section(0.006)
    assert A == math.pi * 0.006**2 / 4.0 and I == math.pi * 0.006**4 / 64.0 and J == 2.0 * I


def test_cross_section_is_unchanged_bitwise():
    for d, E, nu in _cases():
        cs = CrossSection.circular(d, youngs_modulus=E, density=7850.0, poisson_ratio=nu)
        area, inertia = math.pi * d**2 / 4.0, math.pi * d**4 / 64.0
        G = E / (2.0 * (1.0 + nu))
        assert (cs.EI, cs.EA, cs.GJ, cs.mass_per_length) == (E * inertia, E * area, G * 2.0 * inertia, 7850.0 * area)
        assert cs.GA == 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu) * G * area


def test_rod_stiffness_is_unchanged_bitwise():
    for d, E, nu in _cases():
        G = E / 2.6
        k = RodStiffness.circular(d, E, G)
        A, I = math.pi * d**2 / 4.0, math.pi * d**4 / 64.0
        assert (k.EA, k.GA, k.EI, k.GJ) == (E * A, G * A, E * I, G * 2.0 * I)


def test_module_rod_params_are_unchanged_bitwise():
    for d, E, nu in _cases():
        geo = ModuleGeometry(rod_diameter=d, youngs_modulus=E, poisson_ratio=nu, density=7850.0)
        rod = geo.rod_params()
        A, I = math.pi * d**2 / 4.0, math.pi * d**4 / 64.0
        G = geo.shear_modulus
        assert (rod.EA, rod.GA, rod.EI, rod.GJ, rod.weight_per_length) == (E * A, G * A, E * I, G * 2.0 * I, 7850.0 * A)


def test_the_three_types_agree():
    geo = ModuleGeometry()
    rod = geo.rod_params()
    k = RodStiffness.circular(geo.rod_diameter, geo.youngs_modulus, geo.shear_modulus)
    cs = CrossSection.circular(geo.rod_diameter, geo.youngs_modulus, geo.density, geo.poisson_ratio)
    assert (rod.EA, rod.GA, rod.EI, rod.GJ) == (k.EA, k.GA, k.EI, k.GJ)
    assert (cs.EA, cs.EI, cs.GJ, cs.mass_per_length) == (rod.EA, rod.EI, rod.GJ, rod.weight_per_length)
