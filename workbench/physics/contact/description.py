"""What the planar contact model needs to know about the object and the contact law (plain data).

:class:`RigidCircle` is a rigid cylinder whose axis is normal to the bending plane (a circle in the
base x-z plane); :class:`ContactLaw` the penalty law of Exudyn's ``ObjectContactFrictionCircleCable2D``
expressed per unit length of backbone, so the contact does not stiffen when the mesh is refined.
Frozen and validated on construction (bad input: one-line :class:`ValueError` naming the field).
Checked by ``tests/physics/test_contact.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["RigidCircle", "ContactLaw"]

#: Exudyn's limit on contact segments per cable element (``ObjectContact*CircleCable2D``).
MAX_SEGMENTS = 12


def _finite(name: str, v: float, *, low: float | None = None, strict: bool = True) -> float:
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {v!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if low is not None and (x <= low if strict else x < low):
        raise ValueError(f"{name} must be {'>' if strict else '>='} {low}, got {x}")
    return x


@dataclass(frozen=True)
class RigidCircle:
    """A rigid circular object in the bending plane.

    Parameters
    ----------
    radius : float
        Object radius [m] (the arm's surface touches it: contact radius = radius + half the
        local backbone diameter).
    centre : tuple of 2 float
        Reference position of the centre ``(x, z)`` in the robot's base frame [m].
    mass : float
        Object mass [kg]; its weight (robot gravity) acts once the object is released.
    friction : float
        Coulomb friction coefficient between arm and object (0: frictionless).
    """

    radius: float
    centre: tuple[float, float]
    mass: float = 0.0
    friction: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", _finite("RigidCircle.radius", self.radius, low=0.0))
        c = tuple(self.centre)
        if len(c) != 2:
            raise ValueError(f"RigidCircle.centre must be (x, z) in the base frame, got {self.centre!r}")
        object.__setattr__(self, "centre", tuple(_finite("RigidCircle.centre", v) for v in c))
        object.__setattr__(self, "mass", _finite("RigidCircle.mass", self.mass, low=0.0, strict=False))
        object.__setattr__(self, "friction", _finite("RigidCircle.friction", self.friction, low=0.0, strict=False))


@dataclass(frozen=True)
class ContactLaw:
    """Penalty contact between the backbone's surface and the circle.

    Parameters
    ----------
    stiffness : float
        Normal penalty per unit length of backbone [N/m^2]: a penetration ``g`` over a length
        ``ds`` pushes back with ``stiffness * g * ds`` (Exudyn's per-segment stiffness is
        ``stiffness * element length / segments``).
    friction_stiffness : float or None
        Tangential (stick) penalty per unit length [N/m^2]; ``None``: ``stiffness / 100`` (a stiffer
        stick penalty made Exudyn's stick-slip iteration cycle without converging, ``docs/models.md``).
    segments : int
        Straight contact segments per element (1 ... 12, Exudyn's limit).
    """

    stiffness: float = 1.0e8
    friction_stiffness: float | None = None
    segments: int = 8

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _finite("ContactLaw.stiffness", self.stiffness, low=0.0))
        if self.friction_stiffness is not None:
            object.__setattr__(self, "friction_stiffness",
                               _finite("ContactLaw.friction_stiffness", self.friction_stiffness, low=0.0))
        if isinstance(self.segments, bool) or int(self.segments) != self.segments or not 1 <= self.segments <= MAX_SEGMENTS:
            raise ValueError(f"ContactLaw.segments must be an integer in [1, {MAX_SEGMENTS}], got {self.segments!r}")
        object.__setattr__(self, "segments", int(self.segments))

    @property
    def tangential(self) -> float:
        """The tangential penalty per unit length [N/m^2]."""
        return 0.01 * self.stiffness if self.friction_stiffness is None else self.friction_stiffness
