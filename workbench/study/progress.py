"""Progress of a run: a tqdm bar on a terminal, plain log lines otherwise.

:class:`Progress` is what :class:`~workbench.study.session.RunSession` updates after every
finished case.  ``show=True`` draws a tqdm bar on stderr (``ok=.. failed=..`` as postfix);
``show=None`` (the default) draws the bar when stderr is a terminal and otherwise prints a
log line to stderr every ``every_cases`` cases (10 % of the run) or ``every_seconds``
seconds, whichever comes first, so a batch job's log shows that the run is alive::

    quickstart: 8/20 cases (ok 8, failed 0), 4.1 s elapsed, about 6.2 s left

While no case finishes, :meth:`Progress.tick` (called on a timer by the run session) prints a
line every ``every_seconds`` naming what is still computing::

    hannan_walker: 8/48 cases (ok 8, failed 0), 31.0 s elapsed, in progress: case 3fa2c81d0b9e4a17 (models cc,
    spring_link, ancf), 39 more to go

``show=False`` prints nothing.  Checked by ``tests/study/test_executors.py`` (bar) and
``tests/study/test_session.py`` (log lines, the timer's lines with a slow fake model).
"""

from __future__ import annotations

import sys
import threading
import time
from typing import Any

__all__ = ["Progress"]


class Progress:
    """Progress of ``total`` cases of study ``name`` (see the module docstring)."""

    def __init__(self, total: int, name: str, show: bool | None = None, every_seconds: float = 30.0,
                 stream: Any = None) -> None:
        self.total, self.name = int(total), str(name)
        self.stream = stream if stream is not None else sys.stderr
        self.bar = None
        self.log = False
        self.every_seconds = float(every_seconds)
        self.every_cases = max(1, -(-self.total // 10))
        self._t0 = self._last = time.monotonic()
        self._done = self._logged = 0
        self._n_ok = self._n_failed = 0
        self._lock = threading.Lock()  # update (main thread) and tick (the session's timer) both print
        tty = bool(getattr(self.stream, "isatty", lambda: False)())
        if self.total and (show is True or (show is None and tty)):
            from tqdm import tqdm

            self.bar = tqdm(total=self.total, unit="case", dynamic_ncols=True, file=self.stream)
        elif self.total and show is None:
            self.log = True

    def update(self, n_ok: int, n_failed: int) -> None:
        """One more case finished (``n_ok`` / ``n_failed``: the run's counts so far)."""
        self._done += 1
        if self.bar is not None:
            self.bar.set_postfix_str(f"ok={n_ok} failed={n_failed}", refresh=False)
            self.bar.update(1)
            return
        if not self.log:
            return
        with self._lock:
            self._n_ok, self._n_failed = n_ok, n_failed
            now = time.monotonic()
            if (self._done - self._logged >= self.every_cases or now - self._last >= self.every_seconds
                    or self._done == self.total):
                elapsed = now - self._t0
                left = elapsed / self._done * (self.total - self._done)
                tail = f", about {left:.1f} s left" if self._done < self.total else ""
                self._print(f"{elapsed:.1f} s elapsed{tail}", now)

    def tick(self, running: str) -> None:
        """A log line if none was printed for ``every_seconds`` (log mode only), ending with ``running``
        (what is still computing, e.g. ``in progress: case ... (models ...)``)."""
        if not self.log or self._done >= self.total:
            return
        with self._lock:
            now = time.monotonic()
            if now - self._last >= self.every_seconds:
                self._print(f"{now - self._t0:.1f} s elapsed, {running}", now)

    def _print(self, tail: str, now: float) -> None:
        print(f"{self.name}: {self._done}/{self.total} cases (ok {self._n_ok}, failed {self._n_failed}), {tail}",
              file=self.stream, flush=True)
        self._logged, self._last = self._done, now

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None
