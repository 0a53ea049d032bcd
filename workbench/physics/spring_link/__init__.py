"""Spring-link model: a chain of rigid links joined by rotational springs (Exudyn).

A segmented backbone (Hannan & Walker's trunk: a robot with joint springs ``k`` is described by
``EI = k * ds``) or the lumped equivalent of a continuous rod (``N`` links with springs ``N EI / L``).

* :mod:`.geometry` -- ``options.n_elements = N`` rigid links in the half-link layout: eyelet
  stations equally spaced within every section (``N`` a multiple of the number of sections),
  joint ``k`` half-way between eyelets ``k - 1`` and ``k`` with bending stiffness ``EI / ds``; link
  masses and inertias from the mass per length, the disk masses and the payload.
* :mod:`.params` -- :class:`SpringLinkParams` (dimension, torsion, axial springs, backend, Richardson
  extrapolation) and :func:`is_planar`.
* :mod:`.chain` -- the :class:`Chain` base every variant shares; :mod:`.planar` (``RigidBody2D``,
  the base x-z plane), :mod:`.spatial` (Euler-parameter bodies, spherical or Cardan joints) and
  :mod:`.tree` (one ``ObjectKinematicTree``, planar or Cardan; used for eyelet ropes).
* :mod:`.routing` -- tendons: ``tendon_model="eyelets"``, one frictionless rope per tendon through
  the robot's disks (constant-force segments in tension mode, one reeving rope with slack/taut
  switching in length mode); ``"continuum"`` on planar chains, the exact internal moment
  ``T d cos(alpha)`` at every joint the tendon passes (and its compression ``T`` with axial springs);
  in 3-D (and planar tapered length mode) a rope through an eyelet at every link, whose limit as the
  links grow is the continuous routing.  On the 3-D kinematic tree every tendon (and the tip load) is a
  generalised force of one generic object with its own Jacobian (:mod:`.linkrope`).
* :mod:`.lengthmode` -- planar continuum length mode with axial springs (default there): the tendon
  length includes the backbone's compression.
* :mod:`.driver` -- :func:`solve` and the registered :func:`run`: a static load ramp (gravity, tip
  loads and tendon commands together, on :func:`workbench.physics._stepping.load_ramp`); dynamics:
  equilibrium at ``t = 0``, then implicit generalised-alpha with the commands updated every step,
  joint damping ``options.damping * k``.
* :mod:`.richardson` -- ``richardson=True``: ``N / 2`` and ``N`` links extrapolated (order 2); :mod:`.shape`
  -- the result: stations along the links, tip frame, length change, tensions, joint angles, tip twist.
* Disks are point masses at their own stations (:mod:`.geometry`).

Checked by ``tests/physics/test_spring_link.py`` (order-2 convergence to the arc and the heavy
elastica, CC limit exact to 1e-12, 2-D = 3-D, tree = bodies, axial compression, dynamics settle to
statics), ``test_spring_link_eyelets.py`` (rope routing, convergence to the ANCF rope model),
``test_hannan_walker.py`` (Eq. 1 cable geometry, the link rope's chord lever arm),
``test_spring_link_layout.py`` (the chain hooks, the load ramp's steps) and
``test_spring_link_crossexam.py`` (3-D continuum tendons under external loads, disk weights and
length-mode tensions against the Cosserat rod and beam theory), ``test_spring_link_linkrope.py`` (the
vectorised rope forces and their Jacobian, Richardson).  Measured behaviour and limitations:
``docs/models.md``, "Spring-link".
"""

from __future__ import annotations

from .driver import run, solve
from .geometry import ChainGeometry, chain_geometry_from_robot
from .params import SpringLinkParams, is_planar, resolve_axial

__all__ = ["SpringLinkParams", "run", "solve", "is_planar", "resolve_axial", "chain_geometry_from_robot", "ChainGeometry"]
