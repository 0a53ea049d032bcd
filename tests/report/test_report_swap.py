"""Where a report goes and how it is written: reports/<run folder>, temp folder swapped in, banner."""

from __future__ import annotations

import json
import os

import pytest

from synth_study import write_study
from workbench.report.build import build_report
from workbench.report import build as build_mod


def test_failed_build_leaves_the_old_report_whole(tmp_path, monkeypatch):
    data = write_study(tmp_path / "data" / "s", "none")
    out = tmp_path / "reports" / "s"
    first = build_report(data, out, formats=())
    before = first.read_text()

    def boom(*a, **k):
        raise KeyboardInterrupt("killed while writing")

    monkeypatch.setattr(build_mod, "render_page", boom)
    with pytest.raises(KeyboardInterrupt):
        build_report(data, out, formats=())
    assert first.read_text() == before                                  # the old report, whole
    assert sorted(p.name for p in out.parent.iterdir()) == ["s"]         # no temp folder left behind


def test_a_kill_between_the_renames_is_recovered(tmp_path):
    data = write_study(tmp_path / "data" / "s", "none")
    out = tmp_path / "reports" / "s"
    build_report(data, out, formats=())
    os.replace(out, out.with_name(".s.old-123"))                          # killed after the first rename
    path = build_report(data, out, formats=())
    assert path.exists() and sorted(p.name for p in out.parent.iterdir()) == ["s"]


def test_partial_run_gets_an_incomplete_banner(tmp_path):
    data = write_study(tmp_path / "data" / "p", "1d")
    man = json.loads((data / "_manifest.json").read_text())
    man["n_cases"] = 12                                                   # the synthetic 1d study has 8 cases
    (data / "_manifest.json").write_text(json.dumps(man))
    html = build_report(data, tmp_path / "rep", formats=()).read_text()
    assert "Incomplete: 4 of 12 cases not run" in html
    man["n_cases"] = 8
    (data / "_manifest.json").write_text(json.dumps(man))
    assert "Incomplete" not in build_report(data, tmp_path / "rep", formats=()).read_text()
