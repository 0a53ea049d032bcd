"""Constant-curvature kinematics (numpy only). Module docstring completed below."""

from .arc import backbone_points, forward_kinematics, jacobian, section_transform
from .planar import planar_forward_kinematics, planar_from_spatial_transform, planar_jacobian, spatial_from_planar
from .tendons import arc_from_tendon_lengths, arcs_from_tendon_lengths, tendon_lengths_from_arc, tendon_lengths_from_arcs
from .redundancy import IKResult, PathResult, follow_path, line_path, planar_inverse_kinematics, spatial_inverse_kinematics
