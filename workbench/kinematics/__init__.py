"""Constant-curvature kinematics (numpy only). Module docstring completed below."""

from .arc import backbone_points, forward_kinematics, jacobian, section_transform

__all__ = ["section_transform", "forward_kinematics", "backbone_points", "jacobian"]
