"""The per-case table: one row per case x model, parameters with units, errors, figure links."""

from __future__ import annotations

import json
import re

from synth_study import write_study
from workbench.report.build import build_report


def _block(html: str, name: str):
    return json.loads(re.search(rf'<script type="application/json" id="{name}">(.*?)</script>', html, re.S).group(1))


def test_table_has_every_case_and_model_with_errors_and_links(tmp_path):
    data = write_study(tmp_path / "data" / "s1d", "1d")
    page = build_report(data, tmp_path / "rep", formats=())
    html = page.read_text()
    table = _block(html, "wb-cases")
    import pandas as pd

    res = pd.read_csv(page.parent / "results.csv")
    assert len(table["rows"]) == len(res)                                   # one row per case x model
    keys = {(r["case"], r["cells"]["model"]) for r in table["rows"]}
    assert keys == {(str(c), m) for c, m in zip(res["case_id"], res["model"])}
    labels = [c["label"] for c in table["columns"]]
    assert "tip error [% L]" in labels and "status" in labels and "reason" in labels
    # the failed ANCF run is listed with its reason and no errors
    failed = [r for r in table["rows"] if r["cells"]["status"] != "ok"]
    assert len(failed) == 1 and "Newton did not converge" in failed[0]["cells"]["error"]
    assert failed[0]["cells"].get("tip_error_pct") is None and not failed[0]["view"]
    # errors against the reference: the metrics CSV's numbers
    m = pd.read_csv(page.parent / "metrics.csv")
    one = m[(m["reference"] == "cc") & (m["model"] == "ancf")].iloc[0]
    row = next(r for r in table["rows"] if r["case"] == str(one["case_id"]) and r["cells"]["model"] == "ancf")
    assert abs(row["cells"]["tip_error_pct"] - one["tip_error_pct"]) < 1e-12
    assert abs(row["cells"]["tip_error"] - 1e3 * one["tip_error"]) < 1e-9   # shown in mm
    # rows of the cases drawn in the shapes figure link to it; every ok row opens the 3-D view
    assert any("shapes" in r["figures"] for r in table["rows"])
    assert all(r["view"] for r in table["rows"] if r["cells"]["status"] == "ok")


def test_downloads_are_embedded_and_match_the_files(tmp_path):
    import base64
    import io

    import pandas as pd

    data = write_study(tmp_path / "data" / "s2d", "2d")
    page = build_report(data, tmp_path / "rep", formats=())
    html = page.read_text()
    links = dict(re.findall(r"<a download='([^']+)' href='data:[^;]+;base64,([^']+)'>", html))
    assert set(links) == {"results.csv", "metrics.csv", "summary.csv", "failed.csv", "results.parquet"}
    assert base64.b64decode(links["results.csv"]) == (page.parent / "results.csv").read_bytes()
    full = pd.read_parquet(io.BytesIO(base64.b64decode(links["results.parquet"])))
    assert len(full) == len(pd.read_csv(page.parent / "results.csv")) and "positions" in full.columns


def test_figure_points_link_to_existing_table_rows(tmp_path):
    data = write_study(tmp_path / "data" / "s2d", "2d")
    html = build_report(data, tmp_path / "rep", formats=()).read_text()
    table = _block(html, "wb-cases")
    rows = {f"case-{r['case']}-{r['cells']['model']}" for r in table["rows"]}
    links = re.findall(r"<a class='pt' href='#([^']+)' title='[^']*' style='left:([\d.]+)%;top:([\d.]+)%'>", html)
    assert len(links) > 20
    assert {h for h, _, _ in links} <= rows                               # every point opens a real row
    assert all(0 <= float(x) <= 100 and 0 <= float(y) <= 100 for _, x, y in links)
