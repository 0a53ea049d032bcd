"""The study key ``[solver] spring_link_richardson`` (``SpringLinkParams.richardson``).

Validated before anything runs (one line naming the key: static only, a link count the two chains
and the error estimate's re-solves can split), recorded as a case parameter, and run: on a quarter
circle bent by a tip moment (exact arc) the extrapolated tip is far closer than the plain chain's,
and the study's discretisation error bar of the extrapolated row (declared order 2, re-solves
extrapolated too) still covers its true error.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from workbench.cli import main
from workbench.study import load_study
from workbench.study.build import build_options

EI, L = 13.36, 0.8  # the steel_rod preset's defaults (checked below)


def study(solver: str, load: str = "", sweep: str = "") -> str:
    text = f"""\
        [study]
        name = "richardson_key"
        models = ["spring_link"]

        [robot]
        preset = "steel_rod"

        [load]
        mode = "tension"
        tensions = [0.0, 0.0]
        tip_torque = [0.0, {0.5 * math.pi * EI / L!r}, 0.0]
        {load}

        [solver]
        n_stations = 9
        {solver}
        """
    if sweep:
        text += f"\n[sweep]\nproduct = {{ {sweep} }}\n"
    return textwrap.dedent(text)


@pytest.mark.parametrize("solver, load, line", [
    ("n_elements = 6\nspring_link_richardson = true", "",
     "solver.spring_link_richardson: model 'spring_link' richardson=True needs n_elements a multiple of 4 x 1 "
     "sections (the error estimate's half-resolution solve extrapolates n_elements / 4 and n_elements / 2 links), "
     "got 6"),
    ('n_elements = 5\nspring_link_richardson = true\nerror_estimate = "none"', "",
     "solver.spring_link_richardson: model 'spring_link' richardson=True needs n_elements a multiple of 2 x 1 "
     "sections (the coarse chain has n_elements / 2 links), got 5"),
    ("n_elements = 8\n[solver.by_model.spring_link]\nspring_link_richardson = true",
     'analysis = "dynamic"\nduration = 0.1',
     "solver.by_model.spring_link.spring_link_richardson: model 'spring_link' richardson=True extrapolates static "
     "solves only"),
    ("n_elements = 8\nspring_link_richardson = 1", "",
     "solver.spring_link_richardson: input should be a valid boolean"),
])
def test_bad_settings_are_one_line_naming_the_key(tmp_path, capsys, solver, load, line):
    p = tmp_path / "bad.toml"
    p.write_text(study(solver, load))
    rc = main(["validate", str(p)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1, err
    assert err[0].startswith(f"{p}: {line}"), err


def test_good_settings_validate_and_reach_the_model(tmp_path, capsys):
    for solver in ("n_elements = 8\nspring_link_richardson = true",
                   'n_elements = 6\nspring_link_richardson = true\nerror_estimate = "none"',
                   "n_elements = 6\nspring_link_richardson = false"):
        p = tmp_path / "good.toml"
        p.write_text(study(solver))
        assert main(["validate", str(p)]) == 0, capsys.readouterr()
    assert build_options({"spring_link_richardson": True}).settings("spring_link") == {"richardson": True}
    assert build_options({"spring_link_richardson": None}).settings("spring_link") == {}


def test_recorded_and_extrapolated_with_a_covering_error_bar(tmp_path):
    from workbench.results import load
    from workbench.robot.presets import build_preset
    from workbench.study import RunConfig, SerialExecutor, run_study

    cs = build_preset("steel_rod").sections[0].cross_section
    assert (cs.EI, build_preset("steel_rod").length) == pytest.approx((EI, L), rel=1e-3)
    p = tmp_path / "s.toml"
    p.write_text(study("n_elements = 16\nspring_link_richardson = false", sweep='"solver.spring_link_richardson" = [false, true]'))
    run_study(load_study(p), tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    df = load(tmp_path / "out").set_index("p.solver.spring_link_richardson")
    assert (df["status"] == "ok").all() and sorted(df.index) == [False, True]
    theta = 0.5 * math.pi * EI / L * L / cs.EI  # the moment's exact bend angle
    R = L / theta
    exact = np.array([R * (1 - math.cos(theta)), 0.0, R * math.sin(theta)])
    err = {k: float(np.linalg.norm(df.loc[k, ["tip_x", "tip_y", "tip_z"]].to_numpy(float) - exact)) for k in df.index}
    assert err[False] > 1e-4 * L  # the 16-link chain's own error
    assert err[True] < 0.05 * err[False]
    # the estimate re-solved extrapolated chains: its bar covers the extrapolated row's true error
    assert err[True] <= df.loc[True, "x.disc_tip_error"] < err[False]
    assert df.loc[True, "x.disc_order"] <= 2.0
