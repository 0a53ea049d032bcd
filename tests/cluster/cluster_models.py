"""Models for the SLURM test: the real ones, each case made slower by a sleep (importable by workers).

``slow_lookup(name)`` returns ``workbench.models.get_model(name)`` wrapped so every call first
sleeps :data:`DELAY` seconds: the results are the real models' (bit for bit), but a small study
lasts long enough that a worker job can be cancelled while cases run.  With
``WORKBENCH_TEST_HANG_ABOVE_GRAVITY`` set, a case whose gravity magnitude [m/s^2] exceeds it hangs
(sleeps an hour): a case longer than any worker job's life, for the per-case limit test.
"""

from __future__ import annotations

import math
import os
import time

#: [s] per model call (``WORKBENCH_TEST_DELAY`` overrides it; batch jobs inherit the environment)
DELAY = float(os.environ.get("WORKBENCH_TEST_DELAY", "0.4"))


def slow_lookup(name: str):
    from workbench.models import get_model

    fn = get_model(name)

    hang_above = os.environ.get("WORKBENCH_TEST_HANG_ABOVE_GRAVITY")

    def run(robot, load, options):
        time.sleep(DELAY)
        if hang_above is not None and math.hypot(*robot.gravity) > float(hang_above):
            time.sleep(3600.0)
        return fn(robot, load, options)

    return run
