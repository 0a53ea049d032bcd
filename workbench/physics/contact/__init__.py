"""Planar backbone in contact with a rigid circle (Exudyn 2-D ANCF cable + circle contact).

A physics capability, not study glue: a tendon- or fluid-driven planar backbone (actuation as
prescribed strains) that touches, wraps, holds and releases a rigid cylinder whose axis is
normal to the bending plane.  One idea per file:

* :mod:`.description` -- :class:`RigidCircle` (the object) and :class:`ContactLaw` (penalty per length);
* :mod:`.system` -- :class:`PlanarContactSystem`, the Exudyn system (backbone, loads, object,
  fixture, contact elements) and its static solves;
* :mod:`.model` -- robot -> planar setup, tendon / chamber strains, the registry model ``"contact"``;
* :mod:`.procedures` -- the steps a grasp is made of: close the arm on a held object, release it
  into the arm, pull it out along an axis, and the summaries (contact arc, penetration).

Frames: every input and output is in the robot's base frame (x, z); Exudyn's plane is
(X, Y) = (base z, base x).  Measured behaviour and the choice of Exudyn's contact element:
``docs/models.md``, "Planar contact".  Checked by ``tests/physics/test_contact.py``.
"""

from .description import ContactLaw, RigidCircle
from .model import chamber_strains, planar_setup, run, section_tendon_strains, tendon_strains, without_tendons
from .system import PlanarContactSystem

__all__ = ["ContactLaw", "RigidCircle", "PlanarContactSystem", "chamber_strains", "planar_setup", "run",
           "section_tendon_strains", "tendon_strains", "without_tendons"]
