"""Headless-Chromium smoke test: the report renders offline and a screenshot is saved."""

from __future__ import annotations

import shutil
import subprocess

import pytest

from synth_study import write_study
from workbench.report.build import build_report

CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)


@pytest.mark.browser
@pytest.mark.skipif(CHROMIUM is None, reason="headless Chromium not installed (apt-get install chromium)")
def test_report_renders_in_headless_chromium(tmp_path):
    data = write_study(tmp_path / "data" / "study2d", "2d")
    html = build_report(data, tmp_path / "reports" / "study2d", formats=("png",))
    shot = tmp_path / "screenshot.png"
    profile = tmp_path / "profile"
    profile.mkdir()
    cmd = [
        CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        f"--user-data-dir={profile}", f"--screenshot={shot}", "--window-size=1280,2000",
        html.resolve().as_uri(),
    ]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert shot.exists() and shot.stat().st_size > 20_000  # a blank page is a few kB
    from matplotlib.image import imread

    img = imread(shot)
    assert img.shape[0] == 2000 and img.shape[1] == 1280
    # the page is not blank: plenty of non-white pixels (figures rendered)
    nonwhite = (img[..., :3].mean(axis=-1) < 0.9).mean()
    assert nonwhite > 0.05, nonwhite
