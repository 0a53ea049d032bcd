"""models/_console.py: Exudyn's console is silenced only when Exudyn is already imported."""

from __future__ import annotations

import os
import subprocess
import sys
import types
from pathlib import Path

from workbench.models import quiet_if_loaded


def test_silences_and_restores_a_loaded_exudyn(monkeypatch):
    fake = types.SimpleNamespace(config=types.SimpleNamespace(printToConsole=True))
    monkeypatch.setitem(sys.modules, "exudyn", fake)
    with quiet_if_loaded():
        assert fake.config.printToConsole is False
    assert fake.config.printToConsole is True
    try:
        with quiet_if_loaded():
            raise KeyError("x")
    except KeyError:
        pass
    assert fake.config.printToConsole is True


def test_never_imports_exudyn():
    code = ("import sys\nfrom workbench.models import quiet_if_loaded\n"
            "with quiet_if_loaded():\n    pass\nprint('exudyn' in sys.modules)")
    root = str(Path(__file__).resolve().parents[2])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([root, os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.strip() == "False"
