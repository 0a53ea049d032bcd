"""Cojocaru Fig 7 counterpart: wire lengths vs bending direction at theta = 45 deg."""

from __future__ import annotations

import numpy as np

from workbench.experiments.wire_delay.fig7 import fig7_curves, wire_lengths_figure


def test_cylindrical_section_wires_average_to_the_height_and_are_120_deg_apart():
    H, d = 0.35, 0.03
    alpha, L = fig7_curves(H, d, d)                  # D1 = D2: L_n = H + (D/2) theta cos(alpha_n), alpha_n = az_n - alpha
    np.testing.assert_allclose(L.mean(axis=1), H, atol=1e-12)
    np.testing.assert_allclose(L[:, 0], H + d * (np.pi / 4) * np.cos(0.0 - alpha), atol=1e-12)
    shortest = np.degrees(alpha[np.argmin(L, axis=0)])
    np.testing.assert_allclose(shortest, [180.0, 300.0, 60.0], atol=1.0)   # opposite each wire's own azimuth


def test_tronconic_figure_states_the_assumed_geometry():
    from workbench.study.params import flatten_params

    row = flatten_params({"robot": {"preset": "cojocaru_tronconic", "n_sections": 1}})
    f = wire_lengths_figure(row)
    assert f.name == "cojocaru_fig7" and "θ = 45°" in f.summary and "assumed" in f.summary
    lines = f.figure.axes[0].get_lines()[:3]
    y = np.array([ln.get_ydata() for ln in lines])
    assert y.shape[0] == 3 and np.ptp(y) > 10        # mm: the wires change by centimetres
