"""The README's Python examples run as written (a newcomer's first contact must not be stale)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


def test_readme_has_python_examples():
    assert len(BLOCKS) >= 3


@pytest.mark.parametrize("k", range(len(BLOCKS)))
def test_readme_example_runs(k, capsys):
    exec(compile(BLOCKS[k], f"README.md python block {k}", "exec"), {"__name__": "readme_example"})
    assert capsys.readouterr().out.strip()  # every example prints its result
