"""Report built from synthetic study folders (Parquet parts + manifest written in tmp_path)."""

from __future__ import annotations

import base64
import json
import re
from html.parser import HTMLParser
from pathlib import Path

import pandas as pd
import pytest

from synth_study import write_study
from workbench.report.build import build_report
from workbench.report.load import load_results


class _Collector(HTMLParser):
    def __init__(self):
        super().__init__()
        self.figures = []  # data-figure names
        self.images = []  # img src
        self.svgs = 0
        self.stack = []
        self.captions = []
        self._in_caption = False
        self.links = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "figure" and "data-figure" in a:
            self.figures.append(a["data-figure"])
        if tag == "img":
            self.images.append(a.get("src", ""))
        if tag == "svg":
            self.svgs += 1
        if tag in ("script", "link", "iframe"):
            self.links.append((tag, a))
        if tag == "figcaption":
            self._in_caption = True
            self.captions.append("")

    def handle_endtag(self, tag):
        if tag == "figcaption":
            self._in_caption = False

    def handle_data(self, data):
        if self._in_caption:
            self.captions[-1] += data


def _parse(path: Path) -> tuple[_Collector, str]:
    text = path.read_text(encoding="utf-8")
    p = _Collector()
    p.feed(text)
    p.close()
    return p, text


EXPECTED = {
    "1d": {"shapes", "error_vs_kappaL"},
    "2d": {"shapes", "error_vs_gamma", "error_vs_kappaL", "validity_map"},
    "none": {"shapes"},
    "single": {"shapes"},
    "dynamic": {"shapes", "error_vs_actuation_delay", "compression_split"},
}


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    root = tmp_path_factory.mktemp("studies")
    out = {}
    for kind in EXPECTED:
        data = write_study(root / "data" / kind, kind)
        out[kind] = build_report(data, root / "reports" / kind, formats=("png",))
    return out


@pytest.mark.parametrize("kind", list(EXPECTED))
def test_html_self_contained_with_expected_figures(reports, kind):
    path = reports[kind]
    parsed, text = _parse(path)
    got = set(parsed.figures)
    assert EXPECTED[kind] <= got, f"missing figures {EXPECTED[kind] - got}"
    if kind == "dynamic":
        assert sum(n.startswith("timeseries_") for n in got) == 2
    # every figure is an inlined PNG that decodes
    assert len(parsed.images) == len(parsed.figures)
    for src in parsed.images:
        assert src.startswith("data:image/png;base64,")
        raw = base64.b64decode(src.split(",", 1)[1], validate=True)
        assert raw[:8] == b"\x89PNG\r\n\x1a\n"
    assert not re.search(r"https?://", text, flags=re.I)
    # no external scripts, stylesheets or frames: scripts are inline (no src), nothing is linked
    assert all(tag == "script" and "src" not in a for tag, a in parsed.links), parsed.links
    assert not re.search(r"<(link|iframe)\b", text)
    # each figure carries a generated text summary
    assert len(parsed.captions) == len(parsed.figures)
    assert all(len(c) > 40 for c in parsed.captions)
    # files for papers
    figdir = path.parent / "figures"
    assert {p.stem for p in figdir.glob("*.png")} == got
    for csv in ("metrics.csv", "summary.csv", "results.csv", "failed.csv"):
        assert (path.parent / csv).exists()


def test_failed_rows_listed_with_reasons_and_excluded(reports):
    path = reports["1d"]
    _, text = _parse(path)
    assert "Newton did not converge after 200 load steps" in text
    failed = pd.read_csv(path.parent / "failed.csv")
    assert list(failed["model"]) == ["ancf"]
    metrics = pd.read_csv(path.parent / "metrics.csv")
    bad_case = failed["case_id"].iloc[0]
    pairs = set(zip(metrics.loc[metrics["case_id"] == bad_case, "reference"], metrics.loc[metrics["case_id"] == bad_case, "model"]))
    assert pairs == {("cc", "spring_link")}  # the failed ANCF run is in no comparison
    # 8 cases x 3 pairs, minus the two pairs involving the failed ANCF run
    assert len(metrics) == 8 * 3 - 2


def test_header_provenance(reports):
    _, text = _parse(reports["2d"])
    for needle in ("synthetic_2d", "3f2a9c01d4e5", "0123456789abcdef", "exudyn 1.13.6", "205.0 s", "ModelFailure: joint limit exceeded"):
        assert needle in text, needle
    # the URL from the manifest is shown defused, not as a reference
    assert "example.org" in text


def test_validity_map_summary_mentions_thresholds(reports):
    parsed, _ = _parse(reports["2d"])
    cap = parsed.captions[parsed.figures.index("validity_map")]
    assert "below 1 % of L" in cap and "γ" in cap and "κL" in cap


def test_one_d_summary_statement_matches_metrics(reports):
    path = reports["1d"]
    parsed, _ = _parse(path)
    cap = parsed.captions[parsed.figures.index("error_vs_kappaL")]
    m = pd.read_csv(path.parent / "metrics.csv")
    sub = m[(m.reference == "cc") & (m.model == "ancf")].sort_values("p.load.bend_angle")
    below = sub[sub.tip_error_pct < 1.0]["p.load.bend_angle"]
    # statement: "stays below 1 % of L for κL ≤ <largest bend angle before first exceedance>"
    first_bad = sub[sub.tip_error_pct >= 1.0]["p.load.bend_angle"].min()
    expected = below[below < first_bad].max()
    assert f"CC vs ANCF: tip error stays below 1 % of L for κL ≤ {expected:.3g} rad" in cap  # value with its unit


def test_default_out_dir_is_the_run_folder_name(tmp_path, monkeypatch):
    """The report of a run lives with its run: data/x2 -> reports/x2, never over reports/<study name>."""
    data = write_study(tmp_path / "data" / "folder_name_differs", "none")
    monkeypatch.chdir(tmp_path)
    path = build_report(data, formats=())
    assert path == Path("reports/folder_name_differs/report.html")
    assert (tmp_path / path).exists()
    assert not (tmp_path / "reports" / "synthetic_none").exists()


def test_load_results_axes_from_manifest_and_fallback(tmp_path):
    data = write_study(tmp_path / "d2", "2d")
    st = load_results(data)
    assert st.axes == ("gamma", "kappaL")  # report.axes names derived columns
    (data / "_manifest.json").write_text(json.dumps({"study": {}}))  # no name, no sweep, no report section
    st = load_results(data)
    assert set(st.axes) == {"kappaL", "p.robot.gamma"}  # p.* columns that vary; bend angle as kappa L
    assert st.name == "d2"


def test_missing_folder_and_columns_raise_clear_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="does not exist"):
        build_report(tmp_path / "nope")
    (tmp_path / "empty").mkdir()
    with pytest.raises(FileNotFoundError, match="no _manifest.json"):
        build_report(tmp_path / "empty")
    (tmp_path / "empty" / "_manifest.json").write_text("{}")
    with pytest.raises(FileNotFoundError, match="Parquet"):
        build_report(tmp_path / "empty")
    pd.DataFrame({"case_id": ["a"], "status": ["ok"]}).to_parquet(tmp_path / "empty" / "part-0.parquet")
    with pytest.raises(ValueError, match="model"):
        build_report(tmp_path / "empty")


def test_study_runner_layout(tmp_path):
    from synth_study import write_runner_study

    data = write_runner_study(tmp_path / "data" / "whatever")
    st = load_results(data)
    assert st.name == "runner_layout"
    assert st.axes == ("kappaL", "gamma")  # bend angle and derived.gravity_parameter as groups
    path = build_report(data, tmp_path / "out", formats=("png",))
    parsed, text = _parse(path)
    assert {"shapes", "error_vs_kappaL", "error_vs_gamma", "validity_map"} <= set(parsed.figures)
    for needle in ("feedfacecafe (uncommitted changes)", "hostA, hostB", "90.5 s over 2 runs", "CC vs ANCF on a two-section rod"):
        assert needle in text, needle
    m = pd.read_csv(path.parent / "metrics.csv")
    # two sections from the steel_rod preset: per-section curvatures, CC value = bend angle / L
    assert {"kappa_ref_0", "kappa_ref_1"} <= set(m.columns)
    assert (m["kappa_ref_0"] - m["p.load.bend_angle"] / 0.5).abs().max() < 1e-6
    assert m["compression_shape"].isna().all()  # tension mode: no virtual-compression split


def test_categorical_sweep_axis(tmp_path):
    """A non-numeric swept parameter (e.g. solver.tendon_model) is plotted with category ticks."""
    import json

    data = write_study(tmp_path / "d", "1d")
    df = pd.concat([pd.read_parquet(p) for p in sorted(data.glob("*.parquet"))])
    other = df.copy()
    other["case_id"] = other["case_id"] + "b"
    df["p.solver.tendon_model"], other["p.solver.tendon_model"] = "continuum", "eyelets"
    for p in data.glob("*.parquet"):
        p.unlink()
    pd.concat([df, other]).to_parquet(data / "part-0.parquet")
    man = json.loads((data / "_manifest.json").read_text())
    man["study"]["sweep"] = {"product": {"solver.tendon_model": ["continuum", "eyelets"], "load.bend_angle": [0.1]}}
    (data / "_manifest.json").write_text(json.dumps(man))
    st = load_results(data)
    assert st.categories == {"p.solver.tendon_model": ("continuum", "eyelets")}
    path = build_report(data, tmp_path / "out", formats=("png",))
    parsed, text = _parse(path)
    assert {"error_vs_solver_tendon_model", "error_vs_kappaL", "validity_map"} <= set(parsed.figures)
    cap = parsed.captions[parsed.figures.index("error_vs_solver_tendon_model")]
    assert "continuum" in cap and "eyelets" in cap
