"""Huang Figs 6 and 10 counterparts: the stored FK leg centrelines drawn per motion / stack shape."""

from __future__ import annotations

import numpy as np

from tests.regression.golden import STUDIES_DIR
from workbench.experiments.series_parallel.leg_figures import leg_shape_figures, row_legs
from workbench.report.load import load_results


def test_leg_figures_from_the_stored_legs(small_study_run):
    st = load_results(small_study_run(STUDIES_DIR / "series_parallel.toml"))
    sp = st.ok[st.ok["model"] == "series_parallel"]
    assert len(sp)
    for r in sp.to_dict("records"):
        legs = row_legs(r)
        n_mod = len(r["stations"]) - 1
        assert legs.shape[:2] == (n_mod, 6) and legs.shape[3] == 3
        # each leg starts on the base (z = 0 for module 1) and ends at its module's platform height
        P = np.asarray(r["positions"], float).reshape(-1, 3)
        np.testing.assert_allclose(legs[0, :, 0, 2], 0.0, atol=1e-9)
        np.testing.assert_allclose(legs[-1, :, -1, :].mean(axis=0)[2], P[-1, 2], atol=0.05 * P[-1, 2])
    figs = {f.name: f for f in leg_shape_figures(st.results)}
    assert set(figs) == {"module_legs", "stack_legs"}
    assert set(figs["module_legs"].cases) <= set(sp["case_id"]) and figs["stack_legs"].cases
    assert "Fig 6" in figs["module_legs"].summary and "Fig 10" in figs["stack_legs"].summary
