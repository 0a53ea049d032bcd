"""Small shared helpers for building and solving Exudyn systems quietly.

Nothing here runs at import except importing Exudyn itself; every system is built inside
the caller from plain parameters.
"""

from __future__ import annotations

import contextlib
from typing import Iterator

import exudyn as exu

from ..models.result import SolverOptions

__all__ = ["quiet_exudyn", "static_settings", "dynamic_settings", "SolverError"]

SolverError = exu.SolverError


@contextlib.contextmanager
def quiet_exudyn() -> Iterator[None]:
    """Silence Exudyn's console output inside the block.

    ``exu.config.printToConsole`` is process-global, so it is saved and restored.
    """
    old = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = old


def _no_files(settings: "exu.SimulationSettings") -> None:
    sol = settings.solution
    sol.file.write = False
    sol.restart.write = False
    sol.sensors.writePeriod = 1e30
    sol.file.information = ""
    settings.show.computationTime = False
    settings.show.statistics = False
    settings.show.globalTimers = False


def static_settings(options: SolverOptions, n_load_steps: int = 1) -> "exu.SimulationSettings":
    """Static-solver settings: Newton converged on the step size, quiet, file-free."""
    s = exu.SimulationSettings()
    _no_files(s)
    st = s.staticSolver
    st.verboseMode = 0
    st.numberOfLoadSteps = int(n_load_steps)
    st.newton.relativeTolerance = options.newton_tolerance
    st.newton.absoluteTolerance = 1e-12
    st.newton.residualMode = 1
    st.newton.maxIterations = 50
    return s


def dynamic_settings(options: SolverOptions, end_time: float) -> "exu.SimulationSettings":
    """Implicit generalised-alpha settings with the options' time step, quiet, file-free."""
    s = exu.SimulationSettings()
    _no_files(s)
    ti = s.timeIntegration
    ti.verboseMode = 0
    ti.endTime = float(end_time)
    ti.numberOfSteps = max(1, int(round(end_time / options.time_step)))
    ti.generalizedAlpha.spectralRadius = options.spectral_radius
    ti.newton.relativeTolerance = options.newton_tolerance
    ti.newton.absoluteTolerance = 1e-12
    ti.newton.residualMode = 1
    return s
