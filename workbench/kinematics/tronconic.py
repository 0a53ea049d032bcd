"""Cojocaru et al. tronconic 3-wire sections (papers/001_, Eq. 4-12 and 13-30).

A segment of height (backbone length) ``H`` bends by the angle ``theta`` (radius
``R = H/theta``, Eq. 4) in the direction given by ``alpha``. Its end discs have diameters
``D1`` (base) and ``D2`` (top); three wires pass through the discs at azimuths
``0, 120, 240 deg``. Eq. 10 defines the wire angles relative to ``alpha``:

``alpha_1 = -alpha``, ``alpha_2 = 120 deg - alpha``, ``alpha_3 = 240 deg - alpha``

(only ``cos alpha_n`` enters, so ``alpha_1 = +alpha`` gives the same lengths). Eq. 9 puts the
wire holes at distances ``L_n1 = R + D1/2 cos alpha_n``, ``L_n2 = R + D2/2 cos alpha_n`` from
the centre of curvature, Eq. 6 gives the chord ``A_n`` between them (law of cosines), Eq. 7
the wire radius ``R_n = A_n / (2 sin(theta/2))`` and Eq. 8/11 the wire length
``L_wn = R_n theta``. Hence ``alpha`` is the azimuth of the *convex* side (the wire at
azimuth ``alpha`` is the longest); in the convention of
:func:`~workbench.kinematics.section_transform` the same bend is ``kappa = theta/H``,
``phi = alpha + pi``.

Evaluated without ``R = H/theta`` (stable at ``theta = 0``):

``L_wn = sqrt( (a_n - b_n)^2 / sinc(theta/2)^2 + (H + a_n theta)(H + b_n theta) )``,
``a_n = D1/2 cos alpha_n``, ``b_n = D2/2 cos alpha_n``

(algebraically identical to Eq. 6-8). For a cylinder (``D1 = D2 = D``) this is
``L_wn = H + (D/2) theta cos alpha_n`` and, with ``sum_n cos alpha_n = 0`` (Eq. 12),
``mean(L_wn) = H`` exactly. For a tronconic segment the mean differs from ``H`` even in a
static, consistent pose: to leading order in ``D1 - D2``,
``mean(L_w) - H = (D1 - D2)^2 K / 24 sum_n cos^2(alpha_n) / (H + Dm theta cos(alpha_n)/2)``
with ``K = 1/sinc(theta/2)^2 - theta^2/4``, ``Dm = (D1 + D2)/2``; e.g. ``H = 0.35 m``,
``D1 = 0.10 m``, ``D2 = 0.08 m``, ``theta = alpha = 45 deg``: ``+67 um`` (``+0.019 %``, an
extension), two orders of magnitude below the delay effect of Sec. 5.1 (tested).

Errata / notes on the move equations: Eq. 14-15 and 19 write ``R - dR cos alpha`` while Eq. 9
writes ``R + D/2 cos alpha_n`` (the same model with ``alpha`` shifted by ``pi``); Eq. 9 is
used. Eq. 28 is garbled in the source (its denominator is not dimensionally consistent) and
is not used: for a cylinder the wire lengths are linear in ``(theta cos alpha,
theta sin alpha)``, so constant wire speeds move that point on a straight line at constant
speed (Eq. 24/29 solved in closed form; see :func:`plan_constant_speed_move`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._series import dsinc, sinc
from ._checks import as_float, broadcast_named, require_positive
from .tendons import arc_from_tendon_lengths

__all__ = [
    "wire_lengths_tronconic_paper",
    "wire_length_jacobian",
    "virtual_compression",
    "WireMove",
    "plan_constant_speed_move",
]

_WIRE_AZIMUTH = (0.0, 2.0 * np.pi / 3.0, 4.0 * np.pi / 3.0)


def _check_geometry(H, D1, D2):
    H = as_float("H", H)
    D1 = as_float("D1", D1)
    D2 = as_float("D2", D2)
    require_positive("H", H)
    if np.any(D1 < 0) or np.any(D2 < 0):
        raise ValueError("disc diameters D1, D2 must be >= 0 [m]")
    return H, D1, D2


def wire_lengths_tronconic_paper(theta, alpha, H, D1, D2) -> np.ndarray:
    """Lengths of the three control wires of a tronconic segment (Cojocaru Eq. 4-11), paper convention.

    Paper convention: direction ``alpha`` = azimuth of the convex side, disc *diameters*
    ``D1, D2``, wires at ``0, 120, 240 deg``.  The workbench convention (direction ``phi``
    towards the bend, offsets, wire angles ``sigma``) is the wire-delay experiment's
    ``wire_lengths_tronconic_workbench``.  Checked by ``tests/kinematics/test_kinematics_cables.py``.

    Parameters
    ----------
    theta : array_like, shape (...)
        Bending angle of the segment [rad], ``|theta| < 2 pi``.
    alpha : array_like, shape (...)
        Bending direction [rad] (azimuth of the convex side, see module docs).
    H : float or array_like, shape (...)
        Segment height = backbone length [m], ``> 0``.
    D1, D2 : float or array_like, shape (...)
        Diameters of the base and top discs [m] (the wires' hole circles).

    Returns
    -------
    L_w : ndarray, shape (..., 3)
        ``L_w1, L_w2, L_w3`` [m] for wires at ``alpha_n = (0, 120, 240 deg) - alpha`` (Eq. 10).

    Raises
    ------
    ValueError
        If ``|theta| >= 2 pi`` or the radius of curvature ``H/|theta|`` is smaller than a disc
        radius (a wire hole would cross the centre of curvature).
    """
    th = as_float("theta", theta)
    al = as_float("alpha", alpha)
    H, D1, D2 = _check_geometry(H, D1, D2)
    th, al, H, D1, D2 = broadcast_named(theta=th, alpha=al, H=H, D1=D1, D2=D2)
    if np.any(np.abs(th) >= 2 * np.pi):
        raise ValueError("|theta| must be < 2 pi (Eq. 7 divides by sin(theta/2))")
    if np.any(0.5 * np.maximum(D1, D2) * np.abs(th) >= H):
        raise ValueError("radius of curvature H/|theta| must exceed the disc radius max(D1, D2)/2")
    az = np.asarray(_WIRE_AZIMUTH)
    cos_n = np.cos(az - al[..., None])  # cos(alpha_n), alpha_n = azimuth_n - alpha
    a = 0.5 * D1[..., None] * cos_n
    b = 0.5 * D2[..., None] * cos_n
    t = th[..., None]
    sc = sinc(0.5 * t)
    return np.sqrt((a - b) ** 2 / (sc * sc) + (H[..., None] + a * t) * (H[..., None] + b * t))


def wire_length_jacobian(theta, alpha, H, D1, D2) -> np.ndarray:
    """Jacobian ``J_F = dL_w / d(theta, alpha)`` of the wire lengths (Cojocaru Eq. 23-24).

    Parameters
    ----------
    theta, alpha, H, D1, D2
        As in :func:`wire_lengths_tronconic_paper`.

    Returns
    -------
    J : ndarray, shape (..., 3, 2)
        ``J[..., n, 0] = dL_wn/dtheta`` [m/rad], ``J[..., n, 1] = dL_wn/dalpha`` [m/rad].

    Notes
    -----
    With ``L^2 = Q = (a - b)^2 / sinc(theta/2)^2 + (H + a theta)(H + b theta)``,
    ``a = D1/2 cos alpha_n``, ``b = D2/2 cos alpha_n`` and ``d alpha_n / d alpha = -1``:
    ``dL = dQ / (2 L)``,
    ``dQ/dtheta = -(a - b)^2 sinc'(theta/2) / sinc(theta/2)^3 + a (H + b theta) + b (H + a theta)``,
    ``dQ/dalpha = 2 (a - b)(a' - b') / sinc^2 + theta (a' (H + b theta) + b' (H + a theta))``
    with ``a' = D1/2 sin alpha_n``, ``b' = D2/2 sin alpha_n``. For a cylinder this reduces to
    ``dL_wn/dtheta = D/2 cos alpha_n``, ``dL_wn/dalpha = D/2 theta sin alpha_n``; Eq. 29
    (``qdot = J_F^-1 C``) is then solved in closed form by :func:`plan_constant_speed_move`.
    """
    L = wire_lengths_tronconic_paper(theta, alpha, H, D1, D2)  # validates
    th, al, H, D1, D2 = broadcast_named(
        theta=as_float("theta", theta), alpha=as_float("alpha", alpha), H=as_float("H", H),
        D1=as_float("D1", D1), D2=as_float("D2", D2),
    )
    ang = np.asarray(_WIRE_AZIMUTH) - al[..., None]  # alpha_n
    c, s = np.cos(ang), np.sin(ang)
    a, b = 0.5 * D1[..., None] * c, 0.5 * D2[..., None] * c
    da, db = 0.5 * D1[..., None] * s, 0.5 * D2[..., None] * s  # d/dalpha (d alpha_n/d alpha = -1)
    t = th[..., None]
    Hh = H[..., None]
    sc = sinc(0.5 * t)
    dsc = dsinc(0.5 * t)
    dQ_dt = -((a - b) ** 2) * dsc / sc**3 + a * (Hh + b * t) + b * (Hh + a * t)
    dQ_da = 2.0 * (a - b) * (da - db) / sc**2 + t * (da * (Hh + b * t) + db * (Hh + a * t))
    return np.stack([dQ_dt, dQ_da], axis=-1) / (2.0 * L[..., None])


def virtual_compression(wire_lengths, H) -> np.ndarray:
    """Virtual compression of the central bone (Cojocaru Eq. 12).

    Parameters
    ----------
    wire_lengths : array_like, shape (..., 3)
        Wire lengths [m].
    H : float or array_like, shape (...)
        Backbone length [m].

    Returns
    -------
    delta : ndarray, shape (...)
        ``mean(L_w) - H`` [m]: 0 for a consistent cylindrical segment (Eq. 12); negative =
        compression, positive = extension of the bone implied by the wires.
    """
    L = as_float("wire_lengths", wire_lengths)
    if L.ndim == 0 or L.shape[-1] != 3:
        raise ValueError(f"wire_lengths must have shape (..., 3); got {L.shape}")
    H = as_float("H", H)
    require_positive("H", H)
    return L.mean(axis=-1) - H


@dataclass(frozen=True, eq=False)
class WireMove:
    """Time series of a constant-wire-speed move (``k`` time samples).

    Attributes
    ----------
    t : ndarray, shape (k,)
        Time [s].
    wire_lengths : ndarray, shape (k, 3)
        ``L_w1..3(t)`` [m].
    wire_speeds : ndarray, shape (3,)
        Constant speeds ``C`` while each wire moves (Eq. 22/30) [m/s].
    start_lengths, end_lengths : ndarray, shape (3,)
        Wire lengths of the start and end poses (Eq. 20-21) [m].
    virtual_compression : ndarray, shape (k,)
        ``mean(L_w) - H`` [m] (Eq. 12; negative = compression).
    relative_compression : ndarray, shape (k,)
        ``(H - mean(L_w)) / H`` (positive = compression), e.g. 0.02 = 2 %.
    theta, alpha : ndarray, shape (k,) or None
        Pose implied by the wire lengths (least-squares fit of the cylinder model; exact for
        consistent lengths). Only for cylindrical segments (``D1 == D2``), else None.
    """

    t: np.ndarray
    wire_lengths: np.ndarray
    wire_speeds: np.ndarray
    start_lengths: np.ndarray
    end_lengths: np.ndarray
    virtual_compression: np.ndarray
    relative_compression: np.ndarray
    theta: np.ndarray | None
    alpha: np.ndarray | None


def plan_constant_speed_move(
    start,
    end,
    duration: float,
    *,
    H: float,
    D1: float,
    D2: float,
    delays=(0.0, 0.0, 0.0),
    t=None,
) -> WireMove:
    """Constant-wire-speed move of one segment between two poses (Cojocaru Eq. 13-30).

    Each wire moves at the constant speed ``C_n = (L_wn^f - L_wn^0) / duration`` (Eq. 22/30),
    starting ``delays[n]`` seconds late (then finishing late by the same amount):
    ``L_wn(t) = L_wn^0 + C_n clip(t - delay_n, 0, duration)``.

    Parameters
    ----------
    start, end : array_like, shape (2,)
        ``(theta, alpha)`` of the start and end pose [rad].
    duration : float
        Time each wire takes for its move [s], ``> 0``.
    H, D1, D2 : float
        Segment geometry [m] (see :func:`wire_lengths_tronconic_paper`).
    delays : array_like, shape (3,)
        Start delay of each wire [s], ``>= 0``.
    t : array_like, shape (k,), optional
        Sample times [s]; default 401 samples over ``[0, duration + max(delays)]``.

    Returns
    -------
    WireMove

    Notes
    -----
    Without delays and with ``D1 == D2`` the mean wire length stays ``H`` (Eq. 25-27): no
    virtual compression. With wire 1 delayed by ``tau`` and a cylinder, the mean lags by
    ``C_1 min(t, tau, ...)/3``; its peak relative value is
    ``|L_w1^f - L_w1^0| min(tau, duration) / (3 duration H)``.

    Paper experiment (Sec. 5.1, Fig. 9): ``theta 0 -> 45 deg``, ``alpha 0 -> 45 deg``, wire 1
    starting 3 s late, "compressed with approximately 2 %". The paper gives neither the
    geometry nor the duration. Computed here (tests) for a cylinder ``H = 0.35 m``
    (three segments of a > 1 m arm), ``D1 = D2 = 0.10 m``: ``|dL_w1| = 27.8 mm`` and the
    peak compression is ``7.93 % / duration[s]`` for ``duration >= 3 s``, i.e. **1.98 % for a
    4 s move** (2.64 % for any ``duration <= 3 s``).
    """
    st = as_float("start", start)
    en = as_float("end", end)
    if st.shape != (2,) or en.shape != (2,):
        raise ValueError(f"start and end must have shape (2,) = (theta, alpha); got {st.shape}, {en.shape}")
    T = float(as_float("duration", duration))
    if T <= 0:
        raise ValueError("duration must be > 0 [s]")
    H, D1, D2 = (float(v) for v in _check_geometry(H, D1, D2))
    dl = as_float("delays", delays)
    if dl.shape != (3,):
        raise ValueError(f"delays must have shape (3,) (one per wire, s); got {dl.shape}")
    if np.any(dl < 0):
        raise ValueError("delays must be >= 0 [s]")
    if t is None:
        t = np.linspace(0.0, T + dl.max(), 401)
    t = as_float("t", t)
    if t.ndim != 1:
        raise ValueError(f"t must have shape (k,); got {t.shape}")
    L0 = wire_lengths_tronconic_paper(st[0], st[1], H, D1, D2)
    Lf = wire_lengths_tronconic_paper(en[0], en[1], H, D1, D2)
    C = (Lf - L0) / T
    L = L0 + C * np.clip(t[:, None] - dl, 0.0, T)
    vc = L.mean(axis=-1) - H
    theta = alpha = None
    if D1 == D2 and D1 > 0:
        # cylinder: L_n = H + (D/2) theta cos(az_n - alpha) = tendon model with phi = alpha + pi
        k, phi, ell = arc_from_tendon_lengths(L, np.asarray(_WIRE_AZIMUTH), 0.5 * D1)
        theta = k * ell
        alpha = np.angle(np.exp(1j * (phi - np.pi)))
    return WireMove(
        t=t, wire_lengths=L, wire_speeds=C, start_lengths=L0, end_lengths=Lf,
        virtual_compression=vc, relative_compression=-vc / H, theta=theta, alpha=alpha,
    )
