"""Huang et al.'s flexible series-parallel trunk: six-rod parallel modules stacked in series.

Source: Huang, Wang, Wang, Xia, Li, "Kinematic Analysis of Bionic Elephant Trunk Robot Based on
Flexible Series-Parallel Structure", Biomimetics 2022, 7, 228 (``/work/shared/papers/004_*``).

A module (their Fig 5) is a Stewart-like platform whose six legs are flexible rods, each clamped
in the moving platform and passing through a hole in the base platform; the free length between
hole and platform, the *insertion length* ``L_i``, is the actuator.  Each leg is a chain of
Exudyn ``ObjectBeamGeometricallyExact`` elements (the paper's Cosserat rod, Eq 18-20, section
stiffness ``diag(EA, GA, GA, GJ, EI, EI)``, no shear correction); the hole (Eq 21) fixes position
and tangent and leaves the rotation about the tangent free; the platform clamp (Eq 23-24) fixes
the rod tip to the rigid platform.  Forward kinematics is a static equilibrium, inverse
kinematics Newton over ``L`` on static leg solves; modules in series compose through a constant
mount transform (Eq 29-32).

One file per idea:

* ``geometry.py``   :class:`ModuleGeometry`, hole frames, attachment points, poses, input checks;
* ``predictor.py``  cubic-Hermite legs (start guesses);
* ``leg.py``        :class:`LegSolution`, :func:`leg_static` (one leg, with continuation);
* ``newton.py``     the platform balance (Eq 22) and Newton over ``L`` at a fixed pose;
* ``branch.py``     which IK solution branch a state is on (``det d(balance)/dL``);
* ``module.py``     :func:`module_inverse` (one module);
* ``stack.py``      :func:`stack_forward`, :func:`stack_inverse` (modules in series) and
  :func:`module_forward` (one module, a one-module stack);
* ``fit.py``        :func:`fit_constant_curvature`, :func:`arc_points` (the CC arc through the platforms);
* ``gap.py``        :func:`min_leg_gap` (leg interference);
* ``_systems.py``   the Exudyn systems (private).

Paper errata, the assumed geometry, the reachable range, the measured folds of the IK branch and
the chosen study range: ``docs/models.md``, "Series-parallel".  Checked by
``tests/physics/test_series_parallel.py`` and ``tests/reference/test_cosserat.py``.
"""

from __future__ import annotations

from .fit import ArcFit, arc_points, fit_constant_curvature
from .gap import min_leg_gap
from .geometry import (
    ModuleGeometry,
    attachment_points,
    hole_frames,
    home_pose,
    pose_from_xyz_rotvec,
    rotation_vector,
)
from .leg import LegSolution, leg_static
from .module import ModuleIK, module_inverse
from .predictor import leg_lengths_from_pose_hermite
from .stack import ModulePose, StackIK, StackPose, module_forward, stack_forward, stack_inverse

__all__ = [
    "ModuleGeometry",
    "ModulePose",
    "ModuleIK",
    "StackPose",
    "StackIK",
    "ArcFit",
    "LegSolution",
    "hole_frames",
    "attachment_points",
    "pose_from_xyz_rotvec",
    "home_pose",
    "leg_lengths_from_pose_hermite",
    "leg_static",
    "module_forward",
    "module_inverse",
    "stack_forward",
    "stack_inverse",
    "fit_constant_curvature",
    "arc_points",
    "min_leg_gap",
    "rotation_vector",
]
