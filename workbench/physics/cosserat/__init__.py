"""Cosserat rod with continuously routed tendons (Rucker & Webster 2011) or eyelets: model ``"cosserat"``.

The standard statics model of tendon-driven continuum robots: a geometrically exact rod
(bending, torsion, shear and extension, ``K_se = diag(GA, GA, EA)``, ``K_bt = diag(EI, EI, GJ)``)
with frictionless tendons routed continuously at given offsets (constant or tapered), any number
of sections (a tendon terminates at the end of its section), self-weight, disk masses (point
weights at the disks), a tip payload, tip force and torque; solved as a boundary-value problem by
shooting (DOP853, Newton on the clamp wrench; scipy's integrator, or the same algorithm compiled with the right-hand side by numba where installed).  No Exudyn: the model is independent of
the Exudyn models it is compared with.

* :mod:`.problem` -- :class:`RodProblem` from a robot and a load case (base frame, SI units).
* :mod:`.rod` -- the strain law with tendons and the integration of the total force and moment.
* :mod:`.shooting` -- :class:`Shooter`: batched-shot Newton, the load ramp.
* :mod:`.kernel` -- the right-hand side and scipy's DOP853 steps compiled with numba (optional; numpy and
  ``solve_ivp`` in :mod:`.rod` without it).
* :mod:`.eyelets` -- ``tendon_model = "eyelets"``: tendons straight between the disks, point loads there
  (the subsegment rod of Rao et al. 2021), the chords solved per segment inside each shot.
* :mod:`.model` -- :func:`run`: tension or length control, results.

Where it differs from the Exudyn models: the tendon is continuous by default (``beam3d``, ``ancf``,
``spring_link`` and its own eyelets converge to it as the disk count grows, order 2), the rod is
a continuum (no elements: ``options.n_elements`` is unused, the accuracy follows
``options.newton_tolerance``), and it is static only.  Limits: a shooting method needs a
predictor close enough to the solution; the load ramp provides it (``options.max_load_steps``
attempts).  Validation: ``tests/physics/test_cosserat_model.py`` and the validation matrix
(``tests/physics/test_validation_matrix.py``, ``docs/models.md``).
"""

from __future__ import annotations

from .model import run, straight_compliance
from .problem import RodProblem, rod_problem
from .rod import strains
from .shooting import Shooter, ShootingFailure

__all__ = ["run", "RodProblem", "rod_problem", "strains", "Shooter", "ShootingFailure", "straight_compliance"]
