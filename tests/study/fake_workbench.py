"""``python fake_workbench.py MODULE:LOOKUP ARGS...``: the real ``workbench ARGS...`` on fake models.

The sweep kind of the registry is replaced, in this process only, by
:func:`study_fakes.sweep_kind` of the model lookup ``MODULE:LOOKUP`` (e.g.
``study_fakes:lookup_spin_20ms``): its payloads carry the lookup, so isolated children and Dask
workers run the fake models too (they import the module; it must be on ``PYTHONPATH``).  ``run``
gets ``--no-cache`` (fake rows are not results of the registered models' code).  The subprocess
tests' way to test the command itself (signals, exit codes, messages) without physics.
"""

from __future__ import annotations

import dataclasses
import sys

from study_fakes import sweep_kind
from workbench import registry
from workbench.cli import main

KIND = None


def run(argv: list[str]) -> int:
    global KIND
    KIND = sweep_kind(registry.resolve(argv[0]))
    registry.KINDS["sweep"] = dataclasses.replace(registry.KINDS["sweep"], target=f"{__name__}:KIND")
    args = argv[1:]
    if args and args[0] == "run":
        args = [*args, "--no-cache"]
    return main(args)


if __name__ == "__main__":
    sys.exit(run(sys.argv[1:]))
