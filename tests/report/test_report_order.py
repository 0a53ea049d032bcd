"""Every figure, caption and table of a report is independent of the stored row order.

Rows are stored in completion order (a Dask run differs from a serial one).  The bug this
guards: shuffling the rows of ``bending`` changed 4 captions ("stays below 10 % of L for
ds/L <= 0.125" became "<= 0.25").  Reads the regression tier's run of the ``bending`` study.
"""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq

from tests.regression.golden import STUDIES_DIR
from workbench.report.build import build_report


def _shuffled_copy(src: Path, dst: Path, seed: int) -> Path:
    """``src`` with all its rows in one part file, in a random order (schema part and manifest kept)."""
    shutil.copytree(src, dst)
    table = pq.read_table(src)
    for part in dst.glob("part-*.parquet"):
        if not part.name.endswith("-schema.parquet"):
            part.unlink()
    perm = np.random.default_rng(seed).permutation(table.num_rows)
    pq.write_table(table.take(perm), dst / "part-9999999999999999999-shuffled.parquet")
    return dst


def _captions(html: str) -> list[str]:
    return re.findall(r"<figcaption>(.*?)</figcaption>", html, flags=re.S)


def _json_block(html: str, name: str):
    return json.loads(re.search(rf'<script type="application/json" id="{name}">(.*?)</script>', html, re.S).group(1))


def test_shuffled_rows_give_the_same_report(tmp_path, small_study_run):
    data = small_study_run(STUDIES_DIR / "bending.toml")
    ref_html = build_report(data, tmp_path / "reports" / "a", formats=()).read_text()
    html = build_report(_shuffled_copy(data, tmp_path / "data" / "shuffled", seed=1),
                        tmp_path / "reports" / "s", formats=()).read_text()
    assert _captions(html) == _captions(ref_html)
    assert _json_block(html, "wb-cases") == _json_block(ref_html, "wb-cases")
    assert _json_block(html, "wb-scenes") == _json_block(ref_html, "wb-scenes")
    # the figures themselves, pixel for pixel (inlined PNG)
    assert re.findall(r"src='(data:image/png[^']*)'", html) == re.findall(r"src='(data:image/png[^']*)'", ref_html)
