"""Robot descriptions (frozen dataclasses, SI units), actuation/load cases and presets."""

from .actuation import LoadCase, TendonActuation
from .orientation import BASE_ORIENTATIONS, base_rotation_for
from .frames import base_points_to_world, base_vectors_to_world, world_from_base, world_vectors_to_base
from .description import (
    CrossSection,
    Payload,
    Robot,
    RobotDescriptionError,
    Section,
    TendonGroup,
)

__all__ = [
    "BASE_ORIENTATIONS",
    "base_rotation_for",
    "base_points_to_world",
    "base_vectors_to_world",
    "world_from_base",
    "world_vectors_to_base",
    "CrossSection",
    "LoadCase",
    "Payload",
    "Robot",
    "RobotDescriptionError",
    "Section",
    "TendonActuation",
    "TendonGroup",
]
