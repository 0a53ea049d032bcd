import textwrap
from pathlib import Path

import pytest

from study_fakes import GOOD

HERE = Path(__file__).parent

@pytest.fixture
def write_study(tmp_path):
    """write_study(extra_toml, base=GOOD) -> path of a study file in tmp_path."""
    counter = iter(range(10_000))

    def _write(extra: str = "", base: str = GOOD) -> Path:
        p = tmp_path / f"study{next(counter)}.toml"
        p.write_text(base + textwrap.dedent(extra))
        return p

    return _write
