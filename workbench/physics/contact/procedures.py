"""The quasi-static steps of a whole-arm grasp, on a :class:`~.system.PlanarContactSystem`.

* :func:`close_on_held_object` -- the fixture holds the object at its reference position while
  actuation and gravity ramp from 0 to 1 (the arm closes around it);
* :func:`release` -- an object that touches nothing is first lowered along its weight until the
  arm carries it (displacement control through the contact onset); then the fixture is replaced
  by springs whose stiffness is halved step by step (a homotopy from held to free), then removed:
  the object settles where the arm's contact forces balance its weight, or it slips out
  (``held = False``: a result, not a failure);
* :func:`pull_out` -- one centre coordinate is driven away in small steps (displacement control,
  the other coordinate free): the pull force against displacement, and the holding force = its
  largest value on the static path.  Displacement control follows the path past the peak as far
  as a static equilibrium exists; where none exists (the arm snaps open) the path ends and the
  last force is a lower bound (``peak_resolved = False``);
* :func:`move_through` -- a sequence of actuation states with the object free (carrying it);
* :func:`contact_summary`, :func:`surface_gap` -- contact arc, forces, penetration.

Friction: Exudyn's stick-slip model keeps a sticking position per contact segment from step to step,
so the friction forces depend on the load path; every step here is small and monotone, and the
path is recorded.  Checked by ``tests/physics/test_contact.py`` (cantilever on a cylinder against
beam theory, capstan friction, release of a cradled object, pull-out).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np

from ...models.result import ModelFailure

__all__ = ["HoldResult", "PullResult", "close_on_held_object", "release", "pull_out", "move_through",
           "contact_summary", "surface_gap", "contact_force_on_object"]


def contact_force_on_object(sysm) -> np.ndarray:
    """Net contact force ``(x, z)`` [N, base] the arm exerts on the object (from its equilibrium).

    The object is in equilibrium: contact + fixture/springs + weight + external force = 0.
    """
    return -(sysm.fixture_force() + sysm.object_load())


def close_on_held_object(sysm, apply_actuation: Callable[[float], None], max_steps: int) -> int:
    """Hold the object at its reference and ramp ``apply_actuation(lam)`` and gravity together; returns steps.

    The arm closes **frictionlessly**; friction is switched on once it is closed, with sticking
    starting there (an idealisation: the arm slides closed freely, friction acts on the grasp).
    The grip depends on that path: with friction during the closing, the H&W wrap of a 6 cm object
    at squeeze 1.2 and mu 0.3 closes with 248 N of normal force instead of 185 N (measured,
    ``docs/models.md``, "Whole-arm grasp").
    """
    sysm.hold((0.0, 0.0))
    sysm.set_friction(False)

    def apply(lam: float) -> None:
        apply_actuation(lam)
        sysm.set_gravity(lam)

    steps = sysm.load_ramp(apply, max_steps)
    sysm.set_friction(True)
    return steps


@dataclass(frozen=True)
class HoldResult:
    """Outcome of :func:`release`.

    Attributes
    ----------
    held : bool
        The object settled in the arm (False: it slipped out while the springs softened).
    displacement : (2,) ndarray
        Centre displacement from the reference [m, base (x, z)] when settled (or when it left).
    spring_steps : int
        Spring stiffness halvings used.
    residual_force : float
        Spring force [N] when the springs were removed (the homotopy's last error).
    """

    held: bool
    displacement: np.ndarray
    spring_steps: int
    residual_force: float


def release(sysm, *, escape_distance: float | None = None, force_tolerance: float = 1e-7,
            max_halvings: int = 80) -> HoldResult:
    """Release the held object into the arm (module docstring).

    Parameters
    ----------
    escape_distance : float, optional
        A centre displacement beyond this [m] counts as slipped out (default: the object radius).
    force_tolerance : float
        Remove the springs once their force is below this fraction of the fixture force they
        replaced (or of the object's weight, whichever is larger).
    max_halvings : int
        Cap on stiffness halvings.
    """
    c = sysm.circle
    escape = c.radius if escape_distance is None else float(escape_distance)
    ref = np.asarray(c.centre)
    lowered = _lower_into_arm(sysm, escape)
    if lowered is not None:
        return HoldResult(False, lowered, 0, float("nan"))
    F0 = float(np.linalg.norm(sysm.fixture_force()))
    W = float(np.linalg.norm(c.mass * sysm.pb.gravity))
    scale = max(F0, W, 1e-9)
    k = scale / (1e-3 * c.radius)
    sysm.spring(k)
    sysm.solve()
    steps = 0
    factor = 0.5
    while True:
        d = sysm.object_centre() - ref
        if np.linalg.norm(d) > escape:
            return HoldResult(False, d, steps, float(k * np.linalg.norm(d)))
        if k * np.linalg.norm(d) < force_tolerance * scale or steps >= max_halvings:
            break
        state = sysm.save()
        try:
            sysm.spring(k * factor)
            sysm.solve()
            k *= factor
            steps += 1
            factor = max(factor * factor, 0.5)
        except ModelFailure:
            sysm.restore(state)
            sysm.spring(k)
            factor = np.sqrt(factor)
            if factor > 0.99:
                raise ModelFailure(f"releasing the object failed at spring stiffness {k:.3g} N/m "
                                   f"(centre {1e3 * np.linalg.norm(d):.3g} mm from its reference)") from None
    residual = float(k * np.linalg.norm(sysm.object_centre() - ref))
    sysm.free()
    sysm.solve()
    return HoldResult(True, sysm.object_centre() - ref, steps, residual)


def _lower_into_arm(sysm, escape: float, step_fraction: float = 0.05, max_steps: int = 400) -> np.ndarray | None:
    """If the held object touches nothing, move the fixture along its weight until the arm carries it.

    Displacement control through the contact onset (a spring release would let the object fall
    onto the arm in one solve).  Returns ``None`` when the arm carries the weight (or the object
    touches already, or has no weight), else the displacement at which it fell beyond ``escape``.
    """
    w = sysm.object_load()
    W = float(np.linalg.norm(w))
    if W == 0.0 or contact_summary(sysm)["normal_force"] > 0.0:
        return None
    e = w / W
    cap = step_fraction * sysm.circle.radius
    u, du = 0.0, cap
    for _ in range(max_steps):
        if u >= escape:
            return u * e
        state = sysm.save()
        try:
            sysm.hold(tuple((u + du) * e))
            sysm.solve()
        except ModelFailure:
            sysm.restore(state)
            sysm.hold(tuple(u * e))
            du *= 0.5
            if du < 1e-6 * sysm.circle.radius:
                raise ModelFailure(f"lowering the object into the arm failed {1e3 * u:.3g} mm below its "
                                   f"reference") from None
            continue
        u += du
        if float(-sysm.fixture_force() @ e) <= 0.0:  # the fixture no longer holds the object up
            return None
        # in contact: steps of at most a quarter of the free-fall step, else grow back to it
        du = min(2.0 * du, 0.25 * cap if contact_summary(sysm)["normal_force"] > 0.0 else cap)
    raise ModelFailure(f"lowering the object into the arm did not finish in {max_steps} steps "
                       f"({1e3 * u:.3g} mm below its reference)")


@dataclass(frozen=True)
class PullResult:
    """A guided pull-out (:func:`pull_out`).

    Attributes
    ----------
    displacement : (k,) ndarray
        Pull displacement [m] from the released position along the pull direction.
    force : (k,) ndarray
        Force [N] the guide exerts on the object along the pull direction (the pull load).
    lateral : (k,) ndarray
        Displacement of the free coordinate [m] (base frame).
    normal_force : (k,) ndarray
        Sum of the contact normal forces [N].
    holding_force : float
        Largest pull force on the path [N].
    peak_resolved : bool
        The force fell after its peak (or contact was lost): the peak is a maximum of the static
        path, not its last point (then the holding force is only a lower bound).
    end : str
        Why the path ended: ``"distance"``, ``"contact lost"``, ``"no equilibrium"`` or ``"snap"``.
    """

    displacement: np.ndarray
    force: np.ndarray
    lateral: np.ndarray
    normal_force: np.ndarray
    holding_force: float
    peak_resolved: bool
    end: str
    info: dict = field(default_factory=dict)


def pull_out(sysm, axis: str, sign: float, distance: float, step: float, *, min_step: float | None = None,
             snap_factor: float = 20.0) -> PullResult:
    """Pull the (released) object along base ``axis`` (``"x"``/``"z"``) in direction ``sign`` (+1/-1).

    The path ends at ``distance``, when contact is lost, when no static equilibrium is found
    even with the step halved to ``min_step`` (default ``step / 64``), or at a snap: a step after
    which some backbone node moved more than ``snap_factor`` times the pull increment (the solve
    jumped to another equilibrium branch; that state is discarded).
    """
    k = {"x": 0, "z": 1}[axis]
    other = 1 - k
    ref = np.asarray(sysm.circle.centre)
    d0 = sysm.object_centre() - ref
    min_step = step / 64.0 if min_step is None else float(min_step)
    us, fs, lat, fn = [0.0], [float(sign * sysm.fixture_force()[k])], [float(d0[other])], [contact_summary(sysm)["normal_force"]]
    u, du, end = 0.0, float(step), "distance"
    sysm.guide(axis, float(d0[k]))
    shape = sysm.node_coords()[:, :2]
    while u < distance - 1e-15:
        trial = min(u + du, distance)
        state = sysm.save()
        try:
            sysm.guide(axis, float(d0[k] + sign * trial))
            sysm.solve()
        except ModelFailure:
            sysm.restore(state)
            du *= 0.5
            if du < min_step:
                end = "no equilibrium"
                break
            continue
        d = sysm.object_centre() - ref
        jump = float(np.max(np.abs(sysm.node_coords()[:, :2] - shape)))
        if jump > snap_factor * (trial - u) + 1e-9:
            # the solve landed on another equilibrium branch: the arm snapped (a fold of the path)
            sysm.restore(state)
            end = "snap"
            break
        shape = sysm.node_coords()[:, :2]
        u = trial
        summ = contact_summary(sysm)
        us.append(u)
        fs.append(float(sign * sysm.fixture_force()[k]))
        lat.append(float(d[other]))
        fn.append(summ["normal_force"])
        if summ["normal_force"] == 0.0:
            end = "contact lost"
            break
        du = min(2.0 * du, step)
    f = np.array(fs)
    i = int(np.argmax(f))
    resolved = bool(i < f.size - 1 or end == "contact lost")
    return PullResult(np.array(us), f, np.array(lat), np.array(fn), float(f[i]), resolved, end)


def move_through(sysm, states: Sequence[Callable[[float], None]], max_steps: int,
                 record: Callable[[], dict] | None = None) -> list[dict]:
    """Ramp from one actuation state to the next (object as it is: free, held or guided).

    ``states[i](lam)`` sets the actuation between state ``i - 1`` (``lam = 0``) and state ``i``
    (``lam = 1``); returns ``record()`` after each state.
    """
    out = []
    for apply in states:
        sysm.load_ramp(apply, max_steps)
        out.append(record() if record is not None else {})
    return out


def contact_summary(sysm) -> dict[str, float]:
    """Contact arc [m] (reference length of the touching segments), first and last touching arc length [m],
    total normal force [N], largest normal force per length [N/m] and deepest penetration [m]."""
    seg = sysm.contact_segments()
    if seg["s"].size == 0:
        return {"arc": 0.0, "first": np.nan, "last": np.nan, "normal_force": 0.0, "peak_line_load": 0.0,
                "penetration": 0.0}
    ds = np.repeat(np.diff(sysm.pb.s_nodes) / sysm.law.segments, sysm.law.segments)
    on = seg["f_n"] > 0
    return {
        "arc": float(ds[on].sum()),
        "first": float(seg["s"][on].min()) if on.any() else np.nan,
        "last": float(seg["s"][on].max()) if on.any() else np.nan,
        "normal_force": float(seg["f_n"][on].sum()),
        "peak_line_load": float((seg["f_n"] / ds).max()),
        "penetration": float(max(0.0, -seg["gap"][on].min())) if on.any() else 0.0,
    }


def surface_gap(points_xz: np.ndarray, half_width: np.ndarray, centre_xz, radius: float) -> np.ndarray:
    """Signed gap [m] between the arm's surface and the object at backbone points (base x, z):
    ``|p - c| - (radius + half_width)``; < 0 means the arm would penetrate the object."""
    p = np.asarray(points_xz, float)
    return np.linalg.norm(p - np.asarray(centre_xz, float), axis=-1) - (radius + np.asarray(half_width, float))
