import textwrap
from pathlib import Path

import pytest

HERE = Path(__file__).parent

GOOD = textwrap.dedent("""\
    [study]
    name = "good"
    seed = 3
    models = ["cc", "ancf"]

    [robot]
    preset = "steel_rod"
    length = 0.8

    [load]
    mode = "tension"
    tensions = [1.0, 0.0]

    [solver]
    n_elements = 8
    n_stations = 9
    """)


@pytest.fixture
def write_study(tmp_path):
    """write_study(extra_toml, base=GOOD) -> path of a study file in tmp_path."""
    counter = iter(range(10_000))

    def _write(extra: str = "", base: str = GOOD) -> Path:
        p = tmp_path / f"study{next(counter)}.toml"
        p.write_text(base + textwrap.dedent(extra))
        return p

    return _write
