"""Shared timing helper of the benchmark scripts (imported as ``_timing`` when a script runs from this folder)."""

from __future__ import annotations

import time


def best_of(fn, repeat: int):
    """Call ``fn`` ``repeat`` times; return (best wall time [s], best CPU time of this process [s], last result)."""
    wall, cpu, out = [], [], None
    for _ in range(max(1, int(repeat))):
        c0, t0 = time.process_time(), time.perf_counter()
        out = fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return min(wall), min(cpu), out
