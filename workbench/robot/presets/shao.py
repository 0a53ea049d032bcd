"""Shao et al.'s harvester section (paper 002_): the formula of the parametric preset ``shao_harvester.toml``.

Its parameters (defaults, units, and where each value comes from: the paper's length and mass, the
assumed stiffnesses) are data in ``shao_harvester.toml`` (``docs/robot-format.md``, "Presets"); this
module holds the formula :func:`derive` that maps them to the :class:`Robot`, and
``build_preset("shao_harvester")``, the preset itself.  Checked by ``tests/robot/test_data_presets.py``.
"""

from __future__ import annotations

from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for

__all__ = ["derive"]


def derive(
    *,
    length: float,
    total_mass: float,
    bending_stiffness: float,
    axial_stiffness: float,
    torsional_stiffness: float,
    outer_diameter: float,
    actuator_offset: float,
    actuator_stiffness: float,
    n_plates: int,
    gravity: float,
    base_orientation: str,
    payload_mass: float,
) -> Robot:
    """Section II of Shao et al.'s harvester as a uniform rod with three equivalent tendons at 120 deg.

    The stiffness form of the cross-section (EI, EA, GJ given directly); the mass is spread
    uniformly (mass per length = ``total_mass / length``); ``n_plates`` plate intervals carry the
    tendons; gravity acts along world -z with magnitude ``gravity``; ``base_orientation`` as
    :func:`~workbench.robot.orientation.base_rotation_for`.  No stresses: the rod and its tendons
    are equivalents of pneumatic actuators (no stress geometry, no strengths).
    """
    m_per_l = float(total_mass) / float(length)
    cs = CrossSection(
        EI=bending_stiffness,
        EA=axial_stiffness,
        GJ=torsional_stiffness,
        mass_per_length=m_per_l,
        diameter=outer_diameter,
    )
    section = Section(
        length=length,
        cross_section=cs,
        tendons=TendonGroup.evenly_spaced(3, actuator_offset, actuator_stiffness),
        n_disks=n_plates,
    )
    return Robot(
        sections=(section,),
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="shao_harvester",
    )
