"""Named base orientations for robots mounted in a gravity field along world -z."""

from __future__ import annotations


__all__ = ["BASE_ORIENTATIONS", "base_rotation_for"]

#: Rotation matrices world <- base for the named mounting orientations.
BASE_ORIENTATIONS = {
    # robot points up, against gravity
    "vertical": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
    # robot points along world +x; base x axis points up (world +z), so gravity acts
    # along base -x, i.e. in the phi = 0 bending plane of planar models
    "horizontal": ((0.0, 0.0, 1.0), (0.0, -1.0, 0.0), (1.0, 0.0, 0.0)),
    # robot hangs down, with gravity
    "upside_down": ((1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, -1.0)),
}


def base_rotation_for(name: str) -> tuple[tuple[float, float, float], ...]:
    """Rotation matrix world <- base for a named orientation.

    ``"vertical"``: backbone along world +z.  ``"horizontal"``: backbone along world +x
    with the base x axis pointing up, so gravity lies in the base x-z plane (phi = 0), the
    plane planar models bend in.  ``"upside_down"``: backbone along world -z.
    """
    try:
        R = BASE_ORIENTATIONS[name]
    except KeyError:
        raise ValueError(
            f"unknown base orientation {name!r}; expected one of {', '.join(BASE_ORIENTATIONS)}"
        ) from None
    return R
