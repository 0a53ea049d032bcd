"""Regression tier: every committed study's headlines are converged and its report states question,
findings, assumptions and sensitivity (issue 13).

Runs on the small copies of the studies (the session's shared run, :func:`tests.conftest.small_study_run`);
their resolutions follow the committed studies' (see each small study's header).  The four sections
are built as the page builds them (:func:`workbench.report.findings.opening_sections`; figures are
not rasterised here).
"""

from __future__ import annotations

import re

import matplotlib
import pytest

from tests.regression.golden import SLOW_SMALL_STUDIES, small_study_paths
from workbench.compare.table import compare_table
from workbench.report.findings import opening_sections
from workbench.report.headline import headlines
from workbench.report.load import load_results
from workbench.report.style import STYLE, fmt

pytestmark = pytest.mark.regression


#: Studies whose headline is known not to converge at a size the default suite can afford (strict:
#: an unexpected pass fails, so the mark is removed when it is fixed).
KNOWN_NOT_CONVERGED: dict[str, str] = {}


def _params():
    """One case per small study; the slow ones (``SLOW_SMALL_STUDIES``) run with ``-m slow`` or ``-m regression``,
    as their golden tests do."""
    for p in small_study_paths():
        reason = KNOWN_NOT_CONVERGED.get(p.stem)
        marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
        yield pytest.param(p, id=p.stem, marks=marks + ([pytest.mark.slow] if p.stem in SLOW_SMALL_STUDIES else []))


def test_wire_delay_findings_give_peak_and_final_with_the_damping_assumption(small_study_run):
    """The snapped wire-delay case (damped, issue 13): its findings give the peak over time and the end
    value, converged, and the assumptions name the assumed move time and damping."""
    path = next(p for p in small_study_paths() if p.stem == "wire_delay")
    study = load_results(small_study_run(path))
    cmp = compare_table(study.results, baseline=study.baseline, derived=study.derived)
    with matplotlib.rc_context(STYLE):
        parts = opening_sections(study, cmp, lambda f: "")
    assert "peak tip error over time" in parts["findings"] and "NOT CONVERGED" not in parts["findings"]
    assert "at the end of that case" in parts["findings"]  # dynamics: peak and final value
    assert "move_time" in parts["assumptions"] and "damping" in parts["assumptions"]


@pytest.mark.parametrize("path", list(_params()))
def test_headlines_converged_and_four_sections(path, small_study_run):
    study = load_results(small_study_run(path))
    cmp = compare_table(study.results, baseline=study.baseline, derived=study.derived)
    heads = headlines(study, cmp)
    assert heads, f"{path.stem}: no headline"
    bad = [f"{h.baseline} vs {h.model}: {h.error_pct:.3g} % L ± {h.disc_pct:.3g} % L" for h in heads
           if h.cc_pair and not h.converged]
    assert not bad, f"{path.stem}: headline(s) not converged: {bad}"
    assert all(h.n_not_converged == 0 for h in heads if h.cc_pair), [
        (h.model, h.n_not_converged, h.n_cases) for h in heads]
    with matplotlib.rc_context(STYLE):
        parts = opening_sections(study, cmp, lambda f: f"<figure data-figure='{f.name}'></figure>")
    assert set(parts) == {"question", "findings", "assumptions", "sensitivity"}
    for key, html in parts.items():
        text = re.sub(r"<[^>]+>", " ", html).strip()
        assert len(text) > 20, f"{path.stem}: section {key} is empty: {html!r}"
    # every headline has its bar, or says that its model is exempt from the estimate (and is)
    assert "no error estimate" not in parts["findings"]
    for h in heads:
        said = "exempt from the error estimate" if h.exempt_only else f"± {fmt(h.disc_pct)} % L"
        assert said in parts["findings"], (path.stem, h.model, said)
