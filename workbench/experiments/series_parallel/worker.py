"""Per-case evaluation of a series-parallel study (pure: plain data in, result-table rows out).

Models (one row each, the row schema of ``docs/architecture.md``):

``target``
    The commanded platform poses (what the paper's configuration planning prescribes).
``series_parallel``
    Inverse kinematics of the Exudyn model for the target poses (:func:`module_inverse` /
    :func:`stack_inverse`), then forward kinematics (:func:`module_forward` /
    :func:`stack_forward`) of those insertion lengths from the home predictor: the row holds the
    FK platform poses, ``x.L<k>_<i>`` the insertion lengths [m] of leg i of module k, the IK
    residual, the FK-vs-target errors, the largest leg compression (``x.max_leg_compression`` [N],
    ``x.buckling_ratio``) and ``x.min_leg_gap``, the smallest surface gap between two legs of a
    module in the FK state [m] (negative: the rods would intersect; contact is not modelled), the
    largest leg stress and the discretisation-error estimate (:mod:`.estimate`: ``x.max_stress_backbone``,
    ``x.stress_ratio``, ``x.disc_*``); for ``bending`` / ``s_shape`` stacks ``x.backbone_max_error``,
    ``x.backbone_rms_error`` and ``x.polygon_max_error`` (:mod:`.backbone`).  A failed IK or FK is a failed
    row with the reason.
``cc_fit``
    The constant-curvature arc from the base, fitted through the FK platform origins
    (:func:`fit_constant_curvature`); ``x.cc_*`` its curvature, plane and fit errors.

``positions`` are the base origin followed by the platform origins (base frame, [m]); ``stations``
the nominal arc lengths ``k h``; ``robot_length = n h``; ``length_change`` the change of the
polyline (arc, for ``cc_fit``) length through those points; ``tip_twist`` the twist of the top
platform about the base z axis (swing-twist decomposition) [rad]; ``legs`` (series_parallel rows) the
FK leg centrelines (n, 6, N+1, 3) [m], base frame.  Non-finite results fail a row
by the rule of every study kind (:func:`workbench.study.rows.fail_non_finite`).

Checked by ``tests/experiments/series_parallel/test_run.py`` and ``tests/experiments/series_parallel/test_spec.py``.
"""

from __future__ import annotations

import math
import time
import traceback
from typing import Any, Mapping

import numpy as np

from ...physics.series_parallel import module_inverse, stack_inverse
from ...study.params import flatten_params
from ...study.rows import fail_non_finite, failed_rows
from .backbone import CURVE_SHAPES, backbone_errors
from .estimate import discretization_columns, stress_columns

__all__ = ["stack_targets", "module_target", "evaluate_pose_case", "evaluate_pose_batch", "evaluate_pose_rows",
           "MODELS"]

MODELS = ("target", "series_parallel", "cc_fit")


def module_target(height: float, axis: str, value: float, pivot: float = 1.0) -> np.ndarray:
    """``(4, 4)`` single-module target: home pose moved along / rotated about a base axis (Fig 6).

    Parameters
    ----------
    height : float
        Module height [m]; the home platform origin is ``(0, 0, height)``.
    axis : {"x", "y", "z", "rx", "ry", "rz"}
    value : float
        Translation [m] or rotation angle [rad].
    pivot : float
        Rotations turn the platform about an axis parallel to the base axis through
        ``(0, 0, pivot * height)``: 1 (default) is the platform centre (the rigid Stewart
        platform's convention, the platform does not move), 0.5 the module's mid-height (the
        platform also swings sideways, as in bending).  Irrelevant for ``rz`` and translations.
    """
    from ...physics.series_parallel import pose_from_xyz_rotvec

    home = np.array([0.0, 0.0, height])
    rv = np.zeros(3)
    k = "xyz".index(axis[-1])
    if axis.startswith("r"):
        rv[k] = value
        T = pose_from_xyz_rotvec(home, rv)
        c = np.array([0.0, 0.0, pivot * height])
        T[:3, 3] = c + T[:3, :3] @ (home - c)
        return T
    xyz = home.copy()
    xyz[k] += value
    return pose_from_xyz_rotvec(xyz, rv)


def _frame(theta: float, phi: float) -> np.ndarray:
    """Rotation by ``theta`` about ``(-sin phi, cos phi, 0)`` (tilts z towards the plane direction)."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_rotvec(theta * np.array([-math.sin(phi), math.cos(phi), 0.0])).as_matrix()


def stack_targets(shape: str, value: float, n_modules: int, height: float, plane: float = 0.0) -> np.ndarray:
    """``(n, 4, 4)`` platform poses of n modules for the paper's Fig 10 motions.

    Parameters
    ----------
    shape : {"translation", "s_shape", "bending"}
        ``translation``: platform k at lateral offset ``value k / n`` [m] in direction ``plane``,
        height ``k h``, parallel to the base.  ``bending``: platforms on one constant-curvature
        arc of length ``n h`` and total bend angle ``value`` [rad], at arc lengths ``k h``.
        ``s_shape``: two arcs of opposite curvature (each half of ``n h``), tangent angle
        ``value`` [rad] at mid-length, top platform parallel to the base.
    value : float
    n_modules : int
    height : float
        Module height h [m].
    plane : float
        Direction of the motion from base x [rad].
    """
    n, h = int(n_modules), float(height)
    S = n * h
    d = np.array([math.cos(plane), math.sin(plane), 0.0])
    out = np.tile(np.eye(4), (n, 1, 1))
    for k in range(1, n + 1):
        s = k * h
        if shape == "translation":
            p, th = value * k / n * d + np.array([0.0, 0.0, s]), 0.0
        elif shape == "bending":
            kap = value / S
            th = kap * s
            if abs(kap) < 1e-12:
                lat, z = 0.5 * kap * s * s, s
            else:
                lat, z = (1 - math.cos(th)) / kap, math.sin(th) / kap
            p = lat * d + np.array([0.0, 0.0, z])
        elif shape == "s_shape":
            kap = 2.0 * value / S
            if abs(kap) < 1e-12:
                lat, z, th = 0.0, s, 0.0
            elif s <= S / 2:
                th = kap * s
                lat, z = (1 - math.cos(th)) / kap, math.sin(th) / kap
            else:
                thm = kap * S / 2
                lat_m, z_m = (1 - math.cos(thm)) / kap, math.sin(thm) / kap
                th = thm - kap * (s - S / 2)
                lat = lat_m + (math.cos(th) - math.cos(thm)) / kap
                z = z_m + (math.sin(thm) - math.sin(th)) / kap
            p = lat * d + np.array([0.0, 0.0, z])
        else:
            raise ValueError(f"shape must be 'translation', 's_shape' or 'bending', got {shape!r}")
        out[k - 1, :3, :3] = _frame(th, plane)
        out[k - 1, :3, 3] = p
    return out


def _compression(geo, modules, targets, n, L) -> dict[str, float]:
    """Largest axial leg compression at the platform and its ratio to the clamped-clamped Euler load.

    ``n_i(L_i)`` is the force the platform exerts on rod i; the rod leaves the platform along the
    platform normal, so its axial force there is ``N_i = n_i . z_platform`` (compression < 0).
    Reference: ``P_cr = 4 pi^2 EI / L_i^2`` (both ends' tangents fixed).
    """
    EI = geo.rod_params().EI
    comp, ratio = 0.0, 0.0
    bases = [np.eye(4)] + [targets[k] @ geo.mount_transform() for k in range(n - 1)]
    for k, m in enumerate(modules):
        z = np.linalg.solve(bases[k], targets[k])[:3, 2]  # platform normal in the module base frame
        N = m.tip_forces @ z
        c = np.maximum(-N, 0.0)
        comp = max(comp, float(c.max()))
        ratio = max(ratio, float(np.max(c * L[k] ** 2 / (4.0 * math.pi**2 * EI))))
    return {"x.max_leg_compression": comp, "x.buckling_ratio": ratio}


def _twist(R: np.ndarray) -> float:
    """Twist angle about the base z axis (swing-twist decomposition) [rad]."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(R).as_quat()
    t = 2.0 * math.atan2(z, w)
    return float(math.atan2(math.sin(t), math.cos(t)))


def _shape_row(poses: np.ndarray, height: float) -> dict[str, Any]:
    n = poses.shape[0]
    P = np.vstack([np.zeros(3), poses[:, :3, 3]])
    return {
        "tip_x": float(P[-1, 0]), "tip_y": float(P[-1, 1]), "tip_z": float(P[-1, 2]),
        "tip_frame": poses[-1].reshape(-1).tolist(),
        "positions": P.reshape(-1).tolist(),
        "stations": (height * np.arange(n + 1)).tolist(),
        "length_change": float(np.sum(np.linalg.norm(np.diff(P, axis=0), axis=1)) - n * height),
        "tip_twist": _twist(poses[-1, :3, :3]),
    }


def _rot_angle(Ra: np.ndarray, Rb: np.ndarray) -> float:
    """Angle of ``Ra^T Rb`` [rad] (log map: accurate for tiny angles, unlike acos of the trace)."""
    from scipy.spatial.transform import Rotation

    return float(Rotation.from_matrix(Ra.T @ Rb).magnitude())


def _targets(m: Mapping[str, Any], n: int, h: float) -> np.ndarray:
    """``(n, 4, 4)`` target platform poses of a motion."""
    if m["kind"] == "module":
        return module_target(h, m["shape"], m["value"], m.get("pivot", 1.0))[None]
    return stack_targets(m["shape"], m["value"], n, h, m["plane"])


def _inverse(geo, targets: np.ndarray, n: int, sol: Mapping[str, Any]):
    """IK of the targets: ``(lengths (n, 6), success, reason, iterations, residual, leg solves, module IKs)``."""
    n_el = int(sol["n_elements"])
    if n == 1:
        ik = module_inverse(geo, targets[0], n_elements=n_el, length_tolerance=sol["length_tolerance"],
                            max_iterations=sol["max_iterations"])
        return ik.lengths[None], ik.success, ik.reason, int(ik.iterations), ik.residual, ik.leg_solves, [ik]
    ik = stack_inverse([geo] * n, targets, n_elements=n_el, length_tolerance=sol["length_tolerance"],
                       max_iterations=sol["max_iterations"])
    leg_solves = sum(getattr(x, "leg_solves", 0) for x in ik.modules if x is not None)
    return ik.lengths, ik.success, ik.reason, int(np.sum(ik.iterations)), ik.residual, leg_solves, list(ik.modules)


def _fk_errors(geo, fk, targets: np.ndarray, n: int) -> dict[str, float]:
    """FK-vs-target errors, the FK residual and the smallest leg gap of the FK state."""
    from ...physics.series_parallel import min_leg_gap

    return {
        "x.fk_position_error": float(np.max(np.linalg.norm(fk.poses[:, :3, 3] - targets[:, :3, 3], axis=1))),
        "x.fk_rotation_error": float(max(_rot_angle(a[:3, :3], b[:3, :3]) for a, b in zip(fk.poses, targets))),
        "x.fk_residual": float(fk.residual),
        "x.min_leg_gap": float(min(min_leg_gap(fk.leg_positions[k], geo.rod_diameter)[0] for k in range(n))),
    }


def _physics_row(row: dict[str, Any], state: dict[str, Any], geo, targets: np.ndarray, sol: Mapping[str, Any],
                 n: int, h: float, t0: float) -> None:
    """Fill the ``series_parallel`` row (IK, then FK of the IK lengths); ``state["fk_poses"]`` once FK converged."""
    from ...physics.series_parallel import stack_forward

    L, ik_ok, ik_reason, ik_its, ik_res, leg_solves, modules = _inverse(geo, targets, n, sol)
    if not ik_ok:
        row.update(status="failed", error=f"IK: {ik_reason}", wall_time=time.perf_counter() - t0,
                   converged=False, iterations=ik_its)
        return
    fk = stack_forward([geo] * n, L, n_elements=int(sol["n_elements"]), tolerance=sol["fk_tolerance"])
    extras: dict[str, float] = {
        "x.ik_residual": float(ik_res), "x.ik_iterations": float(ik_its), "x.leg_solves": float(leg_solves),
    }
    for k in range(n):
        for i in range(6):
            extras[f"x.L{k + 1}_{i + 1}"] = float(L[k, i])
    extras.update(_compression(geo, modules, targets, n, L))
    if not fk.converged:
        row.update(status="failed", error=f"FK of the IK lengths: {fk.reason}",
                   wall_time=time.perf_counter() - t0, converged=False, iterations=ik_its, **extras)
        return
    state["fk_poses"] = fk.poses  # kept for the CC fit even if what follows raises
    extras.update(_fk_errors(geo, fk, targets, n))
    if state.get("pose", {}).get("shape") in CURVE_SHAPES:  # stacks: distance from the commanded curve
        m = state["pose"]
        extras.update(backbone_errors(stack_targets, m["shape"], m["value"], n, h, m["plane"], fk.leg_positions,
                                      fk.poses[:, :3, 3]))
    extras.update(stress_columns(geo, modules))
    if sol.get("error_estimate", "richardson") != "none":  # discretisation error (estimate.py)
        extras.update(discretization_columns(geo, targets, sol, n, L, fk.poses, _inverse))
    legs = np.asarray(fk.leg_positions, dtype=float)  # (n, 6, N+1, 3): the report draws Huang's Figs 6 and 10
    row.update(status="ok", error="", wall_time=time.perf_counter() - t0, converged=True,
               iterations=ik_its + int(fk.iterations), **extras, **_shape_row(fk.poses, h),
               legs=legs.reshape(-1).tolist(), _shapes={"legs": [-1, 6, legs.shape[2], 3]})


def _series_parallel_row(base: Mapping[str, Any], geo, targets: np.ndarray, sol: Mapping[str, Any], n: int,
                         h: float, pose: Mapping[str, Any] | None = None) -> tuple[dict[str, Any], np.ndarray | None]:
    """The ``series_parallel`` row (any exception: a failed row with its reason) and the FK poses."""
    t0 = time.perf_counter()
    row = {**base, "model": "series_parallel"}
    state: dict[str, Any] = {"pose": dict(pose) if pose is not None and pose.get("kind") == "stack" else {}}
    try:
        _physics_row(row, state, geo, targets, sol, n, h, t0)
    except Exception as e:  # noqa: BLE001
        row.update(status="failed", error=f"{type(e).__name__}: {e} ({traceback.format_exc(limit=1).splitlines()[-1]})",
                   wall_time=time.perf_counter() - t0)
    return row, state.get("fk_poses")


def _cc_fit_row(base: Mapping[str, Any], fk_poses: np.ndarray | None, n: int, h: float) -> dict[str, Any]:
    """The ``cc_fit`` row: the constant-curvature arc from the base through the FK platform origins."""
    t0 = time.perf_counter()
    cc = {**base, "model": "cc_fit"}
    if fk_poses is None:
        cc.update(status="failed", error="no series_parallel platform poses to fit", wall_time=0.0)
        return cc
    try:
        from ...physics.series_parallel import fit_constant_curvature

        fit = fit_constant_curvature(fk_poses)
        from ...physics.series_parallel import arc_points  # the fitted arc's points and tangents

        Pa, ta = arc_points(fit.curvature, fit.phi, fit.arc_lengths)
        poses = np.tile(np.eye(4), (n, 1, 1))
        for k in range(n):
            poses[k, :3, :3] = _frame(fit.curvature * fit.arc_lengths[k], fit.phi)
            poses[k, :3, 3] = Pa[k]
        row = _shape_row(poses, h)
        row["length_change"] = float(fit.arc_lengths[-1] - n * h)
        cc.update(status="ok", error="", wall_time=time.perf_counter() - t0, converged=True, iterations=0, **row,
                  **{"x.cc_curvature": fit.curvature,
                     # bending plane: undefined for a straight arc (convention 0 there)
                     "x.cc_phi": fit.phi if fit.curvature * n * h > 1e-9 else 0.0,
                     "x.cc_rms_error": fit.rms_position_error, "x.cc_max_error": fit.max_position_error,
                     "x.cc_max_tangent_error": fit.max_tangent_error})
    except Exception as e:  # noqa: BLE001
        cc.update(status="failed", error=f"CC fit: {type(e).__name__}: {e}", wall_time=time.perf_counter() - t0)
    return cc


def evaluate_pose_case(case_id: str, params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The three rows (target, series_parallel, cc_fit) of one case.

    Nothing raises: any exception becomes a failed row with its reason (a target that cannot be
    built fails all three rows).
    """
    from ...physics.series_parallel import ModuleGeometry

    flat = flatten_params(params)
    m, sol = params["pose"], params["solver"]
    geo = ModuleGeometry(**{k: tuple(v) if isinstance(v, list) else v for k, v in params["geometry"].items()})
    n, h = int(m["n_modules"]), geo.height
    cells = {"robot_length": n * h, "robot_gravity": 0.0}
    base = {"case_id": case_id, **flat, **cells}

    t0 = time.perf_counter()
    try:
        targets = _targets(m, n, h)
    except Exception as e:  # noqa: BLE001 - recorded as a failed case
        return failed_rows(case_id, params, MODELS, f"target: {type(e).__name__}: {e}", wall_time=0.0, flat=flat,
                           extra=cells)
    rows = [{**base, "model": "target", "status": "ok", "error": "", "wall_time": time.perf_counter() - t0,
             "converged": True, "iterations": 0, **_shape_row(targets, h)}]
    sp, fk_poses = _series_parallel_row(base, geo, targets, sol, n, h, m)
    rows.append(fail_non_finite(sp))
    rows.append(fail_non_finite(_cc_fit_row(base, fk_poses, n, h)))
    return rows


def evaluate_pose_batch(batch: list[tuple[str, Mapping[str, Any]]]) -> list[list[dict[str, Any]]]:
    """A list of ``(case_id, params)`` -> one row list per case."""
    return [evaluate_pose_case(cid, p) for cid, p in batch]


def evaluate_pose_rows(payload: tuple[str, Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The kind's task: the three rows of one case ``payload = (case_id, params)``."""
    return evaluate_pose_case(*payload)
