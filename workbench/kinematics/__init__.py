"""Constant-curvature kinematics (numpy only). Module docstring completed below."""

from .arc import backbone_points, forward_kinematics, jacobian, section_transform
from .planar import planar_forward_kinematics, planar_from_spatial_transform, planar_jacobian, spatial_from_planar
