"""The sandbox of the process executors: rows stream out before a crash, a timeout kills only its unit
(the next unit gets a fresh child and its own full time), the memory cap turns a runaway allocation into
a ``memory`` crash, and a child that raises outside ``fn`` is reported, not hung on."""

from __future__ import annotations

import time

import study_fakes as fakes
from workbench.study.sandbox import Sandbox


def _boom(x):
    yield x
    raise RuntimeError("task bug")


def _hog(x):
    yield x
    import numpy as np

    np.ones(int(x) * 2**27)  # x GiB of float64 ones
    yield -x


def test_timeout_kills_only_its_unit_and_the_clock_starts_when_the_child_is_up():
    with Sandbox(memory=0) as box:
        t0 = time.monotonic()
        out = box.run(fakes.sleepy, 30, seconds=1.0)
        took = time.monotonic() - t0
        assert out.rows == [30] and out.crash.kind == "timeout"  # the row before the hang is kept
        assert out.crash.reason.startswith("stopped after max_case_seconds = 1 s")
        assert took < 20  # stopped, not waited for (start-up of the child included)
        again = box.run(fakes.sleepy, 0.1, seconds=5.0)  # a fresh child, a fresh clock
        assert again.rows == [0.1, -0.1] and again.crash is None


def test_a_task_that_raises_is_a_crash_and_the_child_keeps_serving():
    with Sandbox(memory=0) as box:
        out = box.run(_boom, 7)
        assert out.rows == [7] and out.crash.kind == "crash" and "task raised RuntimeError: task bug" in out.crash.reason
        assert box.run(fakes.sleepy, 0.0).rows == [0.0, -0.0]


def test_memory_cap_turns_a_runaway_allocation_into_a_memory_failure():
    with Sandbox(memory=1.5 * 2**30) as box:
        out = box.run(_hog, 4)  # 4 GiB under a 1.5 GiB cap
        assert out.rows == [4] and out.crash.kind == "memory" and "max_case_memory: 1.5 GiB" in out.crash.reason
        assert box.run(_hog, 0.25).rows == [0.25, -0.25]  # a quarter GiB fits
