"""Every committed study's report (regression-tier size) works in headless Chromium.

For each small study of ``tests/regression/studies`` (and ``studies/example.toml``, small already):
run it, build its report, open it (``tests/report/browser.py``) and check that the page logs no
console message but its self-test line, that its case table has one row per case x model, that
the 3-D view drew a non-blank canvas and that every figure is on the page.  The screenshot is
kept as a test artefact under ``$WORKBENCH_ARTIFACTS`` (default ``build/artifacts/browser/``).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pandas as pd
import pytest

from browser import CHROMIUM, open_report
from tests.regression.golden import SLOW_SMALL_STUDIES, small_study_paths
from workbench.report.build import build_report

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = Path(os.environ.get("WORKBENCH_ARTIFACTS", ROOT / "build" / "artifacts")) / "browser"
STUDIES = [pytest.param(p, id=p.stem, marks=[pytest.mark.slow] if p.stem in SLOW_SMALL_STUDIES else [])
           for p in small_study_paths() + [ROOT / "studies" / "example.toml"]]


@pytest.mark.browser
@pytest.mark.regression
@pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium not installed (apt-get install chromium)")
@pytest.mark.parametrize("study", STUDIES)
def test_committed_study_report_works_in_chromium(study, tmp_path, small_study_run):
    data = small_study_run(study)  # the regression tier's run of the same study
    page = build_report(data, tmp_path / "reports" / study.stem, formats=())
    shot = tmp_path / f"{study.stem}.png"
    selftest, console = open_report(page, shot)
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(shot, ARTIFACTS / shot.name)
    assert console == [], "console messages:\n" + "\n".join(console)
    rows = len(pd.read_csv(page.parent / "results.csv"))
    assert selftest.get("rows") == rows, (selftest, rows)                 # one row per case x model
    assert selftest.get("cases", 0) >= 1 and selftest.get("pixels", 0) > 2000, selftest   # the viewer drew
    n_fig = page.read_text().count("<figure id=")
    assert n_fig > 0 and selftest.get("figures") == n_fig, (selftest, n_fig)  # every figure on the page
