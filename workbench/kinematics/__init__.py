"""Constant-curvature (CC) kinematics of continuum robots -- numpy only.

Conventions (SI units: m, rad, 1/m). A robot is a chain of ``n`` constant-curvature sections,
each described by ``(kappa, phi, ell)``: curvature, bending-plane angle from the section's base
``x`` axis, arc length; the backbone tangent at a section's base is its base ``z`` axis and
the arc bends *towards* ``phi`` (Webster & Jones 2010, robot-independent mapping). Every
function is vectorised over leading batch dimensions ``(..., n)``, checks its inputs once
(errors state the expected shape), and is exact and smooth as ``kappa -> 0`` (series
branches for ``sin x/x`` and ``(1 - cos x)/x``).

Modules: :mod:`.arc` (section transforms, FK, backbone points, the 6 x 3n Jacobian), :mod:`.planar`
(Hannan & Walker Eq. 6-9, App. B errata fixed), :mod:`.redundancy` (resolved-rate IK, null space, Eq.
10-11), :mod:`.tendons` (tendon lengths <-> arcs), :mod:`.hannan_walker` (cable geometry, Eq. 1-3),
:mod:`.tronconic` (Cojocaru Eq. 4-30), :mod:`.centre_of_arc` (Shao Eq. 1-5, corrected).

Example
-------
>>> import numpy as np
>>> from workbench import kinematics as kin
>>> kappa = np.array([2.0, -1.0, 0.0])          # 1/m  (the third section is straight)
>>> phi = np.array([0.0, np.pi / 2, 0.3])       # rad
>>> ell = np.array([0.3, 0.3, 0.2])             # m
>>> T = kin.forward_kinematics(kappa, phi, ell)  # tip frame, shape (4, 4)
>>> T.shape, bool(np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3)))
((4, 4), True)
>>> pts = kin.backbone_points(kappa, phi, ell, s=np.linspace(0.0, 0.8, 5))
>>> pts.shape, bool(np.allclose(pts[-1], T[:3, 3]))
((5, 3), True)
>>> kin.jacobian(kappa, phi, ell).shape           # (kappa_1, phi_1, ell_1, kappa_2, ...)
(6, 9)
>>> L = kin.tendon_lengths_from_arc(5.0, 0.4, 0.2, sigma=[0.0, 2.0944, 4.1888], d=0.01)
>>> k, p, l = kin.arc_from_tendon_lengths(L, [0.0, 2.0944, 4.1888], 0.01)
>>> [round(float(v), 6) for v in (k, p, l)]
[5.0, 0.4, 0.2]
>>> hw = np.full(4, 0.8382 / 4)                 # Hannan & Walker trunk, 4 sections
>>> target = kin.planar_forward_kinematics([2.0, 1.0, 0.5, 1.0], hw)[:2, 3]
>>> res = kin.planar_inverse_kinematics(target, np.zeros(4), hw, kappa_d=np.zeros(4))
>>> res.success, res.residual < 1e-10
(True, True)
"""

from .arc import backbone_points, forward_kinematics, jacobian, section_transform
from .centre_of_arc import SingularConfiguration, centre_of_arc_jacobian, centre_of_arc_pose
from .hannan_walker import (
    cable_change_from_joint_angle,
    curvature_from_cable_change,
    curvature_from_joint_angle,
    joint_angle_from_cable_change,
    joint_angle_from_curvature,
)
from .planar import (
    planar_forward_kinematics,
    planar_from_spatial_transform,
    planar_jacobian,
    spatial_from_planar,
)
from .redundancy import (
    IKResult,
    PathResult,
    follow_path,
    line_path,
    planar_inverse_kinematics,
    resolved_rate_step,
    spatial_inverse_kinematics,
)
from .tendons import (
    arc_from_tendon_lengths,
    arcs_from_tendon_lengths,
    tendon_lengths_from_arc,
    tendon_lengths_from_arcs,
)
from .tronconic import (
    WireMove,
    plan_constant_speed_move,
    virtual_compression,
    wire_length_jacobian,
    wire_lengths_tronconic_paper,
)

__all__ = [
    "section_transform",
    "forward_kinematics",
    "backbone_points",
    "jacobian",
    "planar_forward_kinematics",
    "planar_jacobian",
    "spatial_from_planar",
    "planar_from_spatial_transform",
    "IKResult",
    "PathResult",
    "planar_inverse_kinematics",
    "spatial_inverse_kinematics",
    "follow_path",
    "line_path",
    "resolved_rate_step",
    "tendon_lengths_from_arc",
    "arc_from_tendon_lengths",
    "tendon_lengths_from_arcs",
    "arcs_from_tendon_lengths",
    "joint_angle_from_cable_change",
    "cable_change_from_joint_angle",
    "curvature_from_joint_angle",
    "joint_angle_from_curvature",
    "curvature_from_cable_change",
    "wire_lengths_tronconic_paper",
    "wire_length_jacobian",
    "virtual_compression",
    "WireMove",
    "plan_constant_speed_move",
    "SingularConfiguration",
    "centre_of_arc_pose",
    "centre_of_arc_jacobian",
]
