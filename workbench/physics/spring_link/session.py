"""A spring-link chain kept alive between static solves: every solve starts from the last equilibrium.

A controller in the loop (``workbench/experiments/closed_loop``) re-solves the same robot under
slightly changed tendon commands at every control step.  :func:`.driver.solve` builds a new Exudyn
system each call and ramps every load from the straight reference; :class:`StaticSession` builds
the chain once (the same variant :func:`.driver.solve` would choose), solves the first load case as
:func:`.driver.solve` does, and then ramps only the tendon commands from their current values to
the new ones (the same ramp, :func:`.driver.static_ramp`), starting Newton at the current state.
The time it saves on the Hannan & Walker closed loop is a result in ``docs/models.md`` ("Closed
loop").

Static length or tension commands only (no dynamics).  Checked by
``tests/experiments/test_closed_loop.py`` (a session equals fresh solves).
"""

from __future__ import annotations

from dataclasses import replace

import time

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .._stepping import path_fields
from .driver import build_chain, ramp_to, static_ramp
from .geometry import chain_geometry_from_robot
from .params import SpringLinkParams, is_planar, resolve_axial

__all__ = ["StaticSession"]


class StaticSession:
    """Warm-started static solves of one spring-link chain under changing tendon commands.

    Parameters
    ----------
    robot : Robot
    load : LoadCase
        Static load with a tendon actuation; its commands are solved first (as
        :func:`.driver.solve` does, ramped from the straight reference with gravity and tip loads).
    options : SolverOptions
    params : SpringLinkParams

    Raises
    ------
    ModelFailure
        A dynamic load case, no actuation, or the first solve failed.
    """

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions,
                 params: SpringLinkParams = SpringLinkParams()) -> None:
        from .._exudyn import quiet_exudyn

        check_model_inputs(robot, load, options)
        if load.analysis != "static" or load.actuation is None:
            raise ModelFailure("spring_link StaticSession: needs a static load case with a tendon actuation")
        if params.richardson:
            raise ModelFailure("spring_link StaticSession: keeps one chain warm; richardson=True (two chains) is "
                               "for single solves")
        planar, why = is_planar(robot, load)
        if params.dimension == "2d" and not planar:
            raise ModelFailure(f"spring_link: dimension='2d' requested but the case is not planar: {why}")
        use_2d = params.dimension == "2d" or (params.dimension == "auto" and planar)
        params = replace(params, axial=resolve_axial(params, robot, load, options.tendon_model, use_2d))
        self.params, self.solves = params, 0
        self.values = np.asarray(load.actuation.values, dtype=float)
        t0 = time.perf_counter()
        with quiet_exudyn():
            self.chain = build_chain(robot, load, options, chain_geometry_from_robot(robot, options.n_elements),
                                      params, use_2d)
            if self.chain.lagged_length:
                raise ModelFailure("spring_link StaticSession: planar continuum tendons in length mode with axial "
                                   "springs are not warm-started; use tendon_model='eyelets' or "
                                   "SpringLinkParams(axial=False)")
            steps, its = ramp_to(self.chain, params, self.values)
        self._last = self._result(steps, its, t0)

    def _result(self, steps: int, its: int, t0: float) -> PhysicsResult:
        self.solves += 1
        info = SolverInfo(converged=True, iterations=its, wall_time=time.perf_counter() - t0,
                          message=f"{steps} load steps (warm start)", **path_fields(self.chain.ramps[-1]))
        return self.chain.result(info)

    @property
    def result(self) -> PhysicsResult:
        """The equilibrium of the last solve."""
        return self._last

    def solve(self, values) -> PhysicsResult:
        """Equilibrium under new tendon commands (same mode and length as the load case's), warm-started.

        The commands are ramped from the current ones (gravity and tip loads stay applied); a failed
        ramp raises ``ModelFailure`` and leaves the session at its last equilibrium.
        """
        from .._exudyn import quiet_exudyn

        new = np.asarray(values, dtype=float).reshape(-1)
        if new.shape != self.values.shape:
            raise ValueError(f"values must have shape {self.values.shape}, got {new.shape}")
        old, chain, state = self.values.copy(), self.chain, self.chain.save_state()

        def apply(lam: float) -> None:
            chain.set_external(1.0)
            chain.set_tendons(old + lam * (new - old), 1.0)

        t0 = time.perf_counter()
        try:
            with quiet_exudyn():
                steps, its = static_ramp(chain, chain.options, self.params, apply)
        except ModelFailure:
            chain.restore_state(state)
            chain.set_tendons(old, 1.0)
            raise
        self.values = new
        self._last = self._result(steps, its, t0)
        return self._last
