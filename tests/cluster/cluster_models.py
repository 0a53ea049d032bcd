"""Models for the SLURM test: the real ones, each case made slower by a sleep (importable by workers).

``slow_lookup(name)`` returns ``workbench.models.get_model(name)`` wrapped so every call first
sleeps :data:`DELAY` seconds: the results are the real models' (bit for bit), but a small study
lasts long enough that a worker job can be cancelled while cases run.
"""

from __future__ import annotations

import os
import time

#: [s] per model call (``WORKBENCH_TEST_DELAY`` overrides it; batch jobs inherit the environment)
DELAY = float(os.environ.get("WORKBENCH_TEST_DELAY", "0.4"))


def slow_lookup(name: str):
    from workbench.models import get_model

    fn = get_model(name)

    def run(robot, load, options):
        time.sleep(DELAY)
        return fn(robot, load, options)

    return run
