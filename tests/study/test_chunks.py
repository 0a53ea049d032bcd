"""Chunks of units: the sandbox runs several units per message and still blames each crash and timeout
on its own unit (every unit answered exactly once, in order); the Dask executor's adaptive chunk size
follows the measured time per unit within its bounds."""

from __future__ import annotations

import pytest
import study_fakes as fakes
from workbench.study import DaskExecutor
from workbench.study.sandbox import _AHEAD_BYTES, Sandbox


def test_a_unit_that_kills_the_child_is_blamed_alone_and_the_rest_of_its_chunk_runs():
    with Sandbox(memory=0) as box:
        outs = list(box.run_many(fakes.die_on_one, [0, 1, 2, 3]))
    assert [i for i, _ in outs] == [0, 1, 2, 3]
    assert [o.rows for _, o in outs] == [[0, 0], [1], [2, 4], [3, 9]]
    assert [o.crash.kind if o.crash else None for _, o in outs] == [None, "killed", None, None]


def test_messages_sent_ahead_keep_every_unit_answered_once_in_order_across_a_crash():
    # 2 units per message: [0, 1] [2, 3] [4, 5]; [2, 3] is already in the pipe when unit 1 kills the
    # child, so 2 and 3 (and 4, 5) must be answered by a fresh child
    with Sandbox(memory=0) as box:
        outs = list(box.run_many(fakes.die_on_one, [0, 1, 2, 3, 4, 5], chunk=2))
        assert [i for i, _ in outs] == [0, 1, 2, 3, 4, 5]
        assert [o.rows for _, o in outs] == [[0, 0], [1], [2, 4], [3, 9], [4, 16], [5, 25]]
        assert [o.crash.kind if o.crash else None for _, o in outs] == [None, "killed", None, None, None, None]
        # a message too large to send ahead waits until the child is idle, and still arrives
        big = [b"x" * (_AHEAD_BYTES + 1), b"y" * (_AHEAD_BYTES + 1)]
        outs = list(box.run_many(fakes.lengths, big, chunk=1))
        assert [o.rows for _, o in outs] == [[_AHEAD_BYTES + 1], [_AHEAD_BYTES + 1]]


@pytest.mark.parametrize("chunk", [None, 1])  # one message; a message per unit, the next one queued
def test_the_time_limit_applies_to_each_unit_of_a_chunk(chunk):
    with Sandbox(memory=0) as box:
        outs = dict(box.run_many(fakes.sleepy, [0.0, 30, 0.6, 0.6], seconds=1.0, chunk=chunk))
    assert outs[1].crash.kind == "timeout" and outs[1].rows == [30]
    # 0.6 s each: together longer than the limit, each within it
    assert [outs[i].rows for i in (0, 2, 3)] == [[0.0, -0.0], [0.6, -0.6], [0.6, -0.6]]
    assert all(outs[i].crash is None for i in (0, 2, 3))


def test_leaving_a_chunk_early_stops_its_child_and_the_next_chunk_gets_a_fresh_one():
    with Sandbox(memory=0) as box:
        it = box.run_many(fakes.sleepy, [0.0, 5.0, 5.0])
        first = next(it)
        it.close()
        assert first[0] == 0 and box._proc is None
        assert box.run(fakes.sleepy, 0.0).rows == [0.0, -0.0]


def test_adaptive_chunks_follow_the_time_per_unit_within_their_bounds():
    ex = DaskExecutor(n_workers=2)
    ex.task_seconds = 0.5
    assert ex._chunk(4, 256, None, 1000, 2) == 4  # nothing measured yet: the first size
    assert ex._chunk(4, 4, 1e-3, 1000, 2) == 4  # fixed size (no room to adapt)
    assert ex._chunk(4, 256, 1e-3, 10_000, 2) == 256  # 500 wanted, capped
    assert ex._chunk(4, 256, 1e-2, 10_000, 2) == 50  # 0.5 s of work
    assert ex._chunk(4, 256, 1e-3, 100, 2) == 13  # a quarter of what is left per slot
    assert ex._chunk(4, 256, 10.0, 10_000, 2) == 1  # long cases: one per task
