"""CC-vs-physics metrics as pure numpy functions (no pandas, no plotting).

Every function checks its inputs once and raises ``ValueError`` naming the argument and the
expected shape.  Units are SI: metres, radians unless a name says ``_deg``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "tip_position_error",
    "orientation_error_deg",
    "resample_backbone",
    "shape_error",
    "best_fit_plane",
    "out_of_plane_distance",
    "best_fit_curvature",
    "section_curvatures",
    "polyline_length",
    "tendon_stretch_from_tension",
    "CompressionSplit",
    "compression_split",
]


def _points(name: str, value, *, min_rows: int = 1) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 3 or arr.shape[0] < min_rows:
        raise ValueError(f"{name} must have shape (m, 3) with m >= {min_rows}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return arr


def tip_position_error(p_ref, p) -> np.ndarray | float:
    """Euclidean distance between two tip positions.

    Parameters
    ----------
    p_ref, p : array_like, shape (..., 3)
        Reference and compared tip positions [m] (broadcastable).

    Returns
    -------
    float or ndarray, shape (...)
        ``|p - p_ref|`` [m].
    """
    a = np.asarray(p_ref, dtype=float)
    b = np.asarray(p, dtype=float)
    if a.shape[-1:] != (3,) or b.shape[-1:] != (3,):
        raise ValueError(f"tip positions must have shape (..., 3), got {a.shape} and {b.shape}")
    d = np.linalg.norm(b - a, axis=-1)
    return float(d) if d.ndim == 0 else d


def orientation_error_deg(R_ref, R) -> np.ndarray | float:
    """Angle of the relative rotation ``R_ref^T R`` in degrees.

    Parameters
    ----------
    R_ref, R : array_like, shape (..., 3, 3) or (..., 4, 4)
        Rotation matrices or homogeneous transforms (the rotation block is used).

    Returns
    -------
    float or ndarray, shape (...)
        ``arccos((trace(R_ref^T R) - 1) / 2)`` in [0, 180] deg, evaluated with the
        numerically robust ``atan2(|vee(skew part)|, (trace - 1) / 2)``.
    """
    a = np.asarray(R_ref, dtype=float)
    b = np.asarray(R, dtype=float)
    for name, m in (("R_ref", a), ("R", b)):
        if m.ndim < 2 or m.shape[-2:] not in ((3, 3), (4, 4)):
            raise ValueError(f"{name} must have shape (..., 3, 3) or (..., 4, 4), got {m.shape}")
    a = a[..., :3, :3]
    b = b[..., :3, :3]
    rel = np.swapaxes(a, -1, -2) @ b
    c = (np.trace(rel, axis1=-2, axis2=-1) - 1.0) / 2.0
    v = np.stack(
        [rel[..., 2, 1] - rel[..., 1, 2], rel[..., 0, 2] - rel[..., 2, 0], rel[..., 1, 0] - rel[..., 0, 1]],
        axis=-1,
    )
    s = np.linalg.norm(v, axis=-1) / 2.0
    ang = np.degrees(np.arctan2(s, c))
    return float(ang) if ang.ndim == 0 else ang


def resample_backbone(stations, positions, new_stations) -> np.ndarray:
    """Backbone points at other arc-length stations (piecewise-linear interpolation).

    Parameters
    ----------
    stations : array_like, shape (m,)
        Reference arc-length stations [m], strictly increasing.
    positions : array_like, shape (m, 3)
        Backbone points at ``stations`` [m].
    new_stations : array_like, shape (k,)
        Stations to evaluate, within ``[stations[0], stations[-1]]`` (a relative
        tolerance of 1e-9 of the length is accepted at the ends).

    Returns
    -------
    ndarray, shape (k, 3)
    """
    s = np.asarray(stations, dtype=float).reshape(-1)
    pos = _points("positions", positions, min_rows=2)
    if pos.shape[0] != s.size:
        raise ValueError(f"positions must have shape ({s.size}, 3) to match stations, got {pos.shape}")
    if np.any(np.diff(s) <= 0):
        raise ValueError("stations must be strictly increasing")
    q = np.asarray(new_stations, dtype=float).reshape(-1)
    tol = 1e-9 * max(abs(s[-1] - s[0]), 1e-300)
    if q.size and (q.min() < s[0] - tol or q.max() > s[-1] + tol):
        raise ValueError(
            f"new_stations must lie in [{s[0]}, {s[-1]}], got [{q.min()}, {q.max()}] (no extrapolation)"
        )
    q = np.clip(q, s[0], s[-1])
    return np.stack([np.interp(q, s, pos[:, k]) for k in range(3)], axis=-1)


def shape_error(pos_ref, pos, stations_ref=None, stations=None) -> tuple[float, float]:
    """Maximum and RMS distance between two backbones at matched arc-length stations.

    Parameters
    ----------
    pos_ref, pos : array_like, shape (m, 3) and (n, 3)
        Backbone points [m].  Without stations both must have the same shape and row ``i``
        of each is taken at the same (reference) arc length.
    stations_ref, stations : array_like, shape (m,) and (n,), optional
        Reference arc-length stations of each backbone.  When given (both), ``pos`` is
        linearly interpolated onto ``stations_ref`` (stations outside the overlap are
        dropped), so backbones reported at different stations can be compared.

    Returns
    -------
    (max, rms) : tuple of float
        ``max_i |pos_i - pos_ref_i|`` and ``sqrt(mean_i |pos_i - pos_ref_i|^2)`` [m].
    """
    a = _points("pos_ref", pos_ref)
    b = _points("pos", pos)
    if (stations_ref is None) != (stations is None):
        raise ValueError("give both stations_ref and stations, or neither")
    if stations_ref is not None:
        sa = np.asarray(stations_ref, dtype=float).reshape(-1)
        sb = np.asarray(stations, dtype=float).reshape(-1)
        if sa.size != a.shape[0]:
            raise ValueError(f"stations_ref must have shape ({a.shape[0]},), got {sa.shape}")
        if sb.size != b.shape[0]:
            raise ValueError(f"stations must have shape ({b.shape[0]},), got {sb.shape}")
        keep = (sa >= sb[0] - 1e-12) & (sa <= sb[-1] + 1e-12)
        if not np.any(keep):
            raise ValueError("the two backbones share no arc-length range")
        a = a[keep]
        b = resample_backbone(sb, b, sa[keep])
    elif a.shape != b.shape:
        raise ValueError(
            f"pos_ref and pos must have the same shape without stations, got {a.shape} and {b.shape}"
        )
    d = np.linalg.norm(b - a, axis=-1)
    return float(d.max()), float(np.sqrt(np.mean(d**2)))


def best_fit_plane(points) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares plane through points (SVD of the centred cloud).

    Parameters
    ----------
    points : array_like, shape (m, 3)

    Returns
    -------
    centroid : ndarray, shape (3,)
    basis : ndarray, shape (3, 3)
        Rows: two in-plane directions (largest spread first) and the unit normal.
    """
    p = _points("points", points)
    c = p.mean(axis=0)
    _, _, vt = np.linalg.svd(p - c, full_matrices=True)
    return c, vt


def out_of_plane_distance(points) -> float:
    """Largest distance of the points from their least-squares plane [m].

    Zero for any planar curve (arcs, straight lines); positive for twisted / spatial shapes.
    """
    p = _points("points", points)
    if p.shape[0] < 4:
        return 0.0
    c, basis = best_fit_plane(p)
    return float(np.max(np.abs((p - c) @ basis[2])))


def best_fit_curvature(points) -> float:
    """Curvature of the least-squares circle through 3-D points [1/m]; 0 for a straight line.

    The points are projected onto their least-squares plane, then the circle
    ``A (x^2 + y^2) + B x + C y + D = 0`` is fitted algebraically under Pratt's constraint
    ``B^2 + C^2 - 4 A D = 1`` (V. Pratt, "Direct least-squares fitting of algebraic
    surfaces", SIGGRAPH 1987).  The radius is ``sqrt(B^2+C^2-4AD) / (2|A|) = 1 / (2|A|)``, so
    the curvature is ``2 |A|`` -- finite and exactly zero for collinear points, where centre
    based fits break down.  Exact for points on a circle arc of any opening angle; for
    non-planar point sets this is the curvature of the projection.

    Parameters
    ----------
    points : array_like, shape (m, 3), m >= 3

    Returns
    -------
    float
        Curvature ``kappa >= 0`` [1/m].
    """
    p = _points("points", points, min_rows=3)
    c, basis = best_fit_plane(p)
    xy = (p - c) @ basis[:2].T
    scale = float(np.sqrt(np.mean(np.sum(xy**2, axis=1))))
    if scale == 0.0:
        raise ValueError("points must not all coincide")
    xy = xy / scale
    z = np.sum(xy**2, axis=1)
    Z = np.column_stack([z, xy[:, 0], xy[:, 1], np.ones_like(z)])
    # Pratt fit via SVD (Chernov, "Circular and linear regression", 2010, Sec. 5.5)
    _, S, Vt = np.linalg.svd(Z, full_matrices=False)
    if S[-1] < 1e-10 * S[0]:
        # exact fit: the null vector of Z is the circle (or line, A = 0)
        coef = Vt[-1]
    else:
        Y = Vt.T @ np.diag(S) @ Vt
        Binv = np.array([[0, 0, 0, -0.5], [0, 1, 0, 0], [0, 0, 1, 0], [-0.5, 0, 0, 0]])
        M = Y @ Binv @ Y
        w, v = np.linalg.eig(M)
        w = np.real(w)
        v = np.real(v)
        pos = np.where(w > 0)[0]
        k = pos[np.argmin(w[pos])]
        coef = np.linalg.lstsq(Y, v[:, k], rcond=None)[0]
    A, B, C, D = coef
    norm = B * B + C * C - 4.0 * A * D
    if norm <= 0:
        raise ValueError("circle fit failed (degenerate point set)")
    kappa = 2.0 * abs(A) / np.sqrt(norm)
    return float(kappa / scale)


def section_curvatures(stations, positions, section_ends) -> np.ndarray:
    """Best-fit constant curvature of each section of a backbone.

    Parameters
    ----------
    stations : array_like, shape (m,)
        Reference arc-length stations [m].
    positions : array_like, shape (m, 3)
        Backbone points [m].
    section_ends : array_like, shape (n_sections,)
        Reference arc length at the end of each section [m], increasing; the last equals L.

    Returns
    -------
    ndarray, shape (n_sections,)
        :func:`best_fit_curvature` of the points of each section (both section ends
        included; a section with fewer than 3 stations is resampled at 5 stations).
    """
    s = np.asarray(stations, dtype=float).reshape(-1)
    pos = _points("positions", positions, min_rows=2)
    ends = np.asarray(section_ends, dtype=float).reshape(-1)
    if ends.size == 0 or np.any(np.diff(ends) <= 0):
        raise ValueError(f"section_ends must be a non-empty increasing array, got {ends.tolist()}")
    if pos.shape[0] != s.size:
        raise ValueError(f"positions must have shape ({s.size}, 3) to match stations, got {pos.shape}")
    starts = np.concatenate([[s[0]], ends[:-1]])
    tol = 1e-9 * max(ends[-1], 1e-300)
    out = np.empty(ends.size)
    for j, (a, b) in enumerate(zip(starts, ends)):
        sel = (s >= a - tol) & (s <= b + tol)
        pts = pos[sel]
        if pts.shape[0] < 3:
            pts = resample_backbone(s, pos, np.linspace(a, min(b, s[-1]), 5))
        out[j] = best_fit_curvature(pts)
    return out


def polyline_length(positions) -> float:
    """Length of the polyline through backbone points [m]."""
    p = _points("positions", positions, min_rows=2)
    return float(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))


def tendon_stretch_from_tension(tensions, lengths, axial_stiffness) -> np.ndarray:
    """Elastic elongation of tendons, ``T l / EA_t`` [m] (Hooke's law).

    Parameters
    ----------
    tensions : array_like, shape (n,)
        Tendon tensions [N] (>= 0).
    lengths : array_like, shape (n,) or scalar
        Loaded tendon lengths [m].
    axial_stiffness : array_like, shape (n,) or scalar
        Tendon axial stiffness ``EA_t`` [N].
    """
    T = np.asarray(tensions, dtype=float)
    l = np.broadcast_to(np.asarray(lengths, dtype=float), T.shape)
    ea = np.broadcast_to(np.asarray(axial_stiffness, dtype=float), T.shape)
    if np.any(ea <= 0):
        raise ValueError("axial_stiffness must be > 0")
    return T * l / ea


@dataclass(frozen=True)
class CompressionSplit:
    """Where the CC "virtual compression" of a section goes in a physics model [m].

    ``virtual == backbone + tendon_stretch + shape`` holds exactly (``shape`` is the residual).

    Attributes
    ----------
    virtual : float
        CC virtual compression: the backbone length change that constant curvature needs
        to match the commanded mean tendon length (Cojocaru et al., Eq 12, second line).
    backbone : float
        Physical backbone length change (negative = compressed).
    tendon_stretch : float
        Part taken up by elastic tendon elongation, ``-mean_i(T_i l_i / EA_t)`` (a stretched
        tendon lets the backbone shorten less than commanded, hence the minus sign).
    shape : float
        Residual: part taken up by the shape leaving the CC family (twist, out-of-plane
        bending, non-constant curvature), which changes the mean tendon path length.
    """

    virtual: float
    backbone: float
    tendon_stretch: float
    shape: float


def compression_split(virtual_compression, backbone_length_change, mean_tendon_stretch) -> CompressionSplit:
    """Split the CC virtual compression into backbone compression, tendon stretch and shape.

    Derivation.  A tendon at offset ``d`` whose free length is commanded to change by
    ``dl_i`` has loaded path length ``l_i = L0 + dl_i + e_i`` with elastic stretch ``e_i``.
    For equally spaced tendons around a constant-curvature backbone the mean path length
    equals the backbone length, so CC attributes ``mean_i dl_i`` entirely to the backbone:
    the *virtual compression* ``v``.  In a physics model ``mean_i l_i - L0 = dL + g`` where
    ``dL`` is the backbone length change and ``g`` the deviation caused by the shape
    leaving the CC family.  Hence ``v = dL - mean_i e_i + g``.

    Parameters
    ----------
    virtual_compression : float
        ``v`` [m]: CC backbone length change (the CC model's ``length_change``).
    backbone_length_change : float
        ``dL`` [m]: the physics model's ``length_change``.
    mean_tendon_stretch : float
        ``mean_i e_i`` [m] (>= 0 for tensioned tendons), e.g. from
        :func:`tendon_stretch_from_tension`.

    Returns
    -------
    CompressionSplit
        With ``shape = v - dL + mean_i e_i``.
    """
    v = float(virtual_compression)
    dL = float(backbone_length_change)
    e = float(mean_tendon_stretch)
    for name, x in (("virtual_compression", v), ("backbone_length_change", dL), ("mean_tendon_stretch", e)):
        if not np.isfinite(x):
            raise ValueError(f"{name} must be finite, got {x}")
    return CompressionSplit(virtual=v, backbone=dL, tendon_stretch=-e, shape=v - dL + e)
