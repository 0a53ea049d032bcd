"""``workbench robot show`` for a series-parallel study: the module as resolved, its derived quantities, a picture.

Registered as the ``robot_show`` hook of the ``series_parallel`` row of ``workbench.registry.KINDS``
(:class:`workbench.registry.KindInfo`).  :func:`show` prints the study's
:class:`~workbench.physics.series_parallel.ModuleGeometry` (``[geometry]``, defaults filled in) with
units, the number of stacked modules its motions use, the leg rest lengths at the home pose (the
inverse kinematics of the kind's own solver, :func:`~workbench.physics.series_parallel.module_inverse`,
with the study's ``[solver]`` settings: the lengths every case starts from), and the derived
quantities of :func:`derived_quantities`; its figure draws the legs of the home pose.  Without gravity
or external load the stack's home is each module's home repeated (the legs of module k+1 exert no
net wrench on platform k), so the picture stacks the one solved module by the mount transform.
Checked by ``tests/study/test_robot_show.py`` (every committed study; the derived numbers against
hand values).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ...units import unit_of

__all__ = ["show", "derived_quantities", "LegDerived", "home_figure"]

#: ``[geometry]`` key -> unit printed (angles in degrees, as the study file gives them)


@dataclass(frozen=True)
class LegDerived:
    """Derived quantities of one module's legs (solid circular rods) and of a stack of ``n_modules``.

    Attributes
    ----------
    EA, EI, GJ : float
        Per rod: axial [N], bending [N m²] and torsional [N m²] stiffness (``ModuleGeometry.rod_params``).
    mass_per_length : float
        rho A [kg/m].
    axial_stiffness : ndarray, shape (6,)
        EA / L_i of each leg at its home rest length L_i [N/m].
    bending_stiffness : ndarray, shape (6,)
        3 EI / L_i³: tip stiffness of a cantilever of length L_i under a lateral tip force [N/m].
    module_mass, total_mass : float
        Six legs (rho A sum L_i) plus one platform [kg]; ``total_mass`` for ``n_modules`` modules.
    """

    EA: float
    EI: float
    GJ: float
    mass_per_length: float
    axial_stiffness: np.ndarray
    bending_stiffness: np.ndarray
    module_mass: float
    total_mass: float


def derived_quantities(geometry, lengths, n_modules: int) -> LegDerived:
    """:class:`LegDerived` of ``geometry`` (a ModuleGeometry) with home rest lengths ``lengths`` (6,) [m]."""
    rod = geometry.rod_params()
    L = np.asarray(lengths, dtype=float)
    module = rod.weight_per_length * float(L.sum()) + geometry.platform_mass
    return LegDerived(EA=rod.EA, EI=rod.EI, GJ=rod.GJ, mass_per_length=rod.weight_per_length,
                      axial_stiffness=rod.EA / L, bending_stiffness=3.0 * rod.EI / L**3,
                      module_mass=module, total_mass=n_modules * module)


def _n_modules(spec) -> int:
    """The most modules any motion of the study stacks (1 for single-module motions)."""
    return max([1] + [int(m.get("n_modules", 3)) for m in spec.motions.get("stack", [])])


def _text(v: Any) -> str:
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(format(float(x), ".6g") for x in v) + "]"
    return format(float(v), ".6g")


def _per_leg(v) -> str:
    """Six per-leg values, or one with "(each leg)" when they agree to 1e-9 (a symmetric home pose)."""
    v = np.asarray(v, dtype=float)
    return f"{v[0]:.6g} (each leg)" if np.allclose(v, v[0], rtol=1e-9, atol=0.0) else _text(v)


def _lines(spec, geometry, ik, d: LegDerived, n: int) -> list[str]:
    L = ik.lengths
    out = [f"series-parallel trunk of study {spec.path}: {n} module(s) of six rods (Huang et al. 2022)",
           "geometry (as resolved: [geometry] with the ModuleGeometry defaults)"]
    out += [f"  geometry.{k} = {_text(v)} [{unit_of(f'geometry.{k}') or '-'}]" for k, v in spec.geometry.items()]
    out += ["", f"home pose: platform {geometry.height:.4g} m above the base, no rotation; leg rest lengths L_i "
                f"(inverse kinematics, {spec.solver['n_elements']} GE-beam elements per leg; "
                f"{'converged' if ik.success else 'NOT converged: ' + ik.reason})",
            "  L_i [m] = " + _per_leg(L), "",
            "derived quantities (per rod, solid circular section d; G = E / (2 + 2 nu))",
            f"  EA = E pi d²/4 = {d.EA:.4g} N;  EI = E pi d⁴/64 = {d.EI:.4g} N m²;  GJ = G pi d⁴/32 = {d.GJ:.4g} N m²",
            f"  mass per length rho pi d²/4 = {d.mass_per_length:.4g} kg/m",
            f"  one leg at home: axial EA/L_i = {_per_leg(d.axial_stiffness)} N/m",
            f"  one leg at home: bending 3EI/L_i³ (cantilever, lateral tip force) = {_per_leg(d.bending_stiffness)} N/m",
            f"  mass: one module (legs rho A sum L_i + platform {geometry.platform_mass:.4g} kg) {d.module_mass:.4g} kg; "
            f"the trunk of {n} module(s) {d.total_mass:.4g} kg"]
    return out


def home_figure(legs: np.ndarray, geometry, n_modules: int, title: str = "") -> Figure:
    """x-z and y-z views of ``n_modules`` stacked home modules: legs ``(6, N+1, 3)`` as lines, platforms as circles."""
    fig = Figure(figsize=(7.0, 7.5), layout="constrained")
    axes = fig.subplots(1, 2)
    T = np.eye(4)
    T[:3, :3] = [[math.cos(t := math.radians(geometry.mount_twist_deg)), -math.sin(t), 0.0],
                 [math.sin(t), math.cos(t), 0.0], [0.0, 0.0, 1.0]]
    T[2, 3] = geometry.height + geometry.mount_offset
    phi = np.linspace(0.0, 2.0 * math.pi, 73)
    B = np.eye(4)
    for k in range(n_modules):
        pts = legs @ B[:3, :3].T + B[:3, 3]
        for ax, (i, name) in zip(axes, ((0, "x"), (1, "y"))):
            for leg in pts:
                ax.plot(leg[:, i], leg[:, 2], color="C0", lw=1.2)
            for r, z in ((geometry.base_radius, 0.0), (geometry.platform_radius, geometry.height)):
                c = np.stack([r * np.cos(phi), r * np.sin(phi), np.full_like(phi, z)], axis=1) @ B[:3, :3].T + B[:3, 3]
                ax.plot(c[:, i], c[:, 2], color="k" if z == 0.0 and k == 0 else "C1", lw=1.0)
            ax.set_xlabel(f"{name} [m]")
            ax.set_ylabel("z [m]")
            ax.set_aspect("equal")
            rmax = max(geometry.base_radius, geometry.platform_radius)
            ax.set_xticks([-rmax, rmax])
            ax.set_title(f"{name}-z view")
        B = B @ T
    if title:
        fig.suptitle(title)
    return fig


def show(spec) -> tuple[list[str], Figure]:
    """``(lines, figure)`` of a :class:`~.spec.SeriesParallelStudy` (see the module docstring)."""
    from ...physics.series_parallel import ModuleGeometry, home_pose, module_inverse

    geometry = ModuleGeometry(**{k: tuple(v) if isinstance(v, list) else v for k, v in spec.geometry.items()})
    ik = module_inverse(geometry, home_pose(geometry), n_elements=spec.solver["n_elements"],
                        length_tolerance=spec.solver["length_tolerance"],
                        max_iterations=spec.solver["max_iterations"])
    n = _n_modules(spec)
    d = derived_quantities(geometry, ik.lengths, n)
    fig = home_figure(ik.leg_positions, geometry, n,
                      f"{spec.name}: {n} module(s) at home, {d.total_mass:.4g} kg\n(legs blue, platforms orange)")
    return _lines(spec, geometry, ik, d, n), fig
