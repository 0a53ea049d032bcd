"""Robot descriptions (frozen dataclasses, SI units), actuation/load cases and presets."""

from .actuation import LoadCase, TendonActuation
from .orientation import BASE_ORIENTATIONS, base_rotation_for
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
    "CrossSection",
    "LoadCase",
    "Payload",
    "Robot",
    "RobotDescriptionError",
    "Section",
    "TendonActuation",
    "TendonGroup",
]
