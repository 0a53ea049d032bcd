"""Exudyn's console output off while a model runs, without importing Exudyn.

Exudyn prints solver progress through a process-global flag, ``exudyn.config.printToConsole``.
:func:`quiet_if_loaded` switches it off for the duration of a ``with`` block and restores the old
value afterwards -- but only when Exudyn is already imported (``sys.modules``), so callers that
run pure-numpy models (CC) never pay for importing Exudyn.  The study workers wrap every model
call in it (:func:`workbench.study.evaluate.evaluate_case`).

Checked by ``tests/study/test_console.py``.
"""

from __future__ import annotations

import contextlib
import sys
from typing import Iterator

__all__ = ["quiet_if_loaded"]


@contextlib.contextmanager
def quiet_if_loaded() -> Iterator[None]:
    """Exudyn console output off inside the block (saved and restored), if Exudyn is loaded.

    Does nothing when ``"exudyn"`` is not in ``sys.modules``; never imports it.
    """
    exu = sys.modules.get("exudyn")
    if exu is None:
        yield
        return
    old = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = old
