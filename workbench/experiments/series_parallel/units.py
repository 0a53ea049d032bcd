"""Names and units of the series-parallel study's keys: the commanded pose (``pose.*``) and the leg extras.

Registered as the ``units`` of the ``series_parallel`` row of ``workbench.registry.KINDS``
(the generic unit table, :mod:`workbench.units`, holds no study keys).  The amplitude's unit
is set by the pose: metres for a translation, radians for a rotation or a bend.  Data only
(the study messages read it).  Checked by ``tests/report/test_units.py``.
"""

from __future__ import annotations

from ...units import UnitBy

__all__ = ["QUANTITIES"]

#: key (without ``p.``) -> (readable name, unit), as in :data:`workbench.units.UNITS`
QUANTITIES = {
    "pose.kind": ("motion kind", None), "pose.shape": ("motion", None),
    "pose.value": ("motion amplitude", UnitBy("pose.shape", {
        "x": "m", "y": "m", "z": "m", "rx": "rad", "ry": "rad", "rz": "rad",
        "translation": "m", "s_shape": "rad", "bending": "rad"})),
    "pose.pivot": ("pivot height / module height", ""), "pose.n_modules": ("modules", ""),
    "pose.plane": ("motion plane", "rad"),
    "x.max_leg_compression": ("largest leg compression", "N"), "x.buckling_ratio": ("compression / Euler load", ""),
    "x.min_leg_gap": ("smallest gap between legs", "m"), "x.fk_position_error": ("FK position error", "m"),
    "x.fk_rotation_error": ("FK rotation error", "rad"), "x.cc_rms_error": ("CC fit RMS error", "m"),
    "x.cc_max_error": ("CC fit max error", "m"), "x.cc_curvature": ("CC fit curvature", "1/m"),
    # the module geometry ([geometry] of the study file)
    "geometry.base_radius": ("base hole circle radius", "m"), "geometry.platform_radius": ("platform radius", "m"),
    "geometry.base_angles_deg": ("base hole angles", "deg"), "geometry.platform_angles_deg": ("platform angles", "deg"),
    "geometry.height": ("module height", "m"), "geometry.rod_diameter": ("rod diameter", "m"),
    "geometry.youngs_modulus": ("Young's modulus E", "Pa"), "geometry.poisson_ratio": ("Poisson ratio", ""),
    "geometry.density": ("density", "kg/m³"), "geometry.platform_mass": ("platform mass", "kg"),
    "geometry.mount_offset": ("mount offset", "m"), "geometry.mount_twist_deg": ("mount twist", "deg"),
    "geometry.yield_strength": ("yield strength", "Pa"),
}
