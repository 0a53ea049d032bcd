"""Per-model settings ``[solver.by_model.<model>]``: the messages of bad tables, each model checked and run
with its own settings, and one study comparing cc, cosserat, beam3d (eyelets) and spring_link."""

from __future__ import annotations

import textwrap

import pytest

from workbench.study import StudyError, load_study
from workbench.study.by_model import by_model_problems, per_model_options, solver_for_model

MODELS = ("cc", "cosserat", "beam3d", "spring_link")

MIXED = textwrap.dedent("""\
    [study]
    name = "mixed_models"
    models = ["cc", "cosserat", "beam3d", "spring_link"]

    [robot]
    preset = "steel_rod"
    length = 0.5
    tendon_count = 3
    disks_per_section = 10
    gravity = 0.0

    [load]
    mode = "tension"
    tensions = [2.0, 0.0, 0.0]

    [solver]
    tendon_model = "continuum"
    n_elements = 16

    [solver.by_model.beam3d]
    tendon_model = "eyelets"

    [sweep]
    product = { "load.tensions[0]" = [1.0, 3.0] }

    [report]
    reference = "cosserat"
    """)


@pytest.mark.parametrize("table, line", [
    ({"ancf": {"n_elements": 8}}, "solver.by_model.ancf: 'ancf' is not one of study.models (cc, cosserat, beam3d, "
                                  "spring_link)"),
    ({"cc": 3}, "solver.by_model.cc: must be a table of [solver] options, got int 3"),
    ({"cc": {"n_elemnts": 8}}, "solver.by_model.cc.n_elemnts: unknown option; did you mean 'n_elements'?"),
    ({"cc": {"max_case_seconds": 8.0}}, "solver.by_model.cc.max_case_seconds: not a per-model option (set it in "
                                        "[solver] for the whole study)"),
    ({"cc": {"error_estimate": "none"}}, "solver.by_model.cc.error_estimate: not a per-model option (set it in "
                                         "[solver] for the whole study)"),
    ({"cc": {"n_elements": 0}}, "solver.by_model.cc.n_elements: must be >= 1, got 0"),
    ({"cc": {"n_elements": 8.0}}, "solver.by_model.cc.n_elements: input should be a valid integer, got float 8.0"),
    ({"beam3d": {"tendon_model": "rope"}}, "solver.by_model.beam3d.tendon_model: must be 'continuum' or 'eyelets', "
                                           "got 'rope'"),
])
def test_bad_tables_are_one_line_naming_the_key(table, line):
    assert by_model_problems(table, MODELS) == [line]


def test_not_a_table():
    assert by_model_problems(5, MODELS) == [
        "solver.by_model: must be a table of model names ([solver.by_model.<model>]), got int"]


def test_solver_for_model_puts_the_table_over_solver():
    solver = {"n_elements": 16, "tendon_model": "continuum", "by_model": {"beam3d": {"tendon_model": "eyelets"}}}
    assert solver_for_model(solver, "beam3d")["tendon_model"] == "eyelets"
    assert solver_for_model(solver, "beam3d")["n_elements"] == 16
    assert solver_for_model(solver, "cc") == solver and solver_for_model({"n_elements": 4}, "cc") == {"n_elements": 4}
    assert "tendon_model" in per_model_options() and "by_model" not in per_model_options()


def _write(tmp_path, text):
    p = tmp_path / "mixed.toml"
    p.write_text(text)
    return p


def test_each_model_is_validated_against_its_own_settings(tmp_path):
    """Without the beam3d table the study is refused for beam3d (continuum tendons); with it, it is valid;
    a table that gives cosserat eyelets in length mode is refused naming that table's key."""
    study = load_study(_write(tmp_path, MIXED))
    assert study.base["solver"]["by_model"] == {"beam3d": {"tendon_model": "eyelets"}}
    without = MIXED.replace('[solver.by_model.beam3d]\ntendon_model = "eyelets"\n', "")
    with pytest.raises(StudyError) as e:
        load_study(_write(tmp_path, without))
    assert len(e.value.problems) == 1 and "solver.tendon_model (every case" in e.value.problems[0] \
        and "model 'beam3d' supports loaded tendons only with tendon_model = 'eyelets'" in e.value.problems[0]
    # cosserat carries eyelets under tension control only: in length mode its table's key is the one refused
    wrong = MIXED.replace("[solver.by_model.beam3d]", "[solver.by_model.cosserat]").replace(
        'mode = "tension"\ntensions = [2.0, 0.0, 0.0]', 'mode = "length"\nlength_changes = [-1e-3, 0.0, 0.0]').replace(
        '"load.tensions[0]" = [1.0, 3.0]', '"load.length_changes[0]" = [-1e-3, -2e-3]')
    with pytest.raises(StudyError) as e:
        load_study(_write(tmp_path, wrong))
    lines = e.value.problems
    assert any("solver.by_model.cosserat.tendon_model (every case" in p and "model 'cosserat'" in p
               for p in lines), lines


def test_all_problems_in_one_pass_without_knock_ons(tmp_path):
    """A bad table, a bad [solver] key and a bad sweep value: each one line; beam3d, whose table is bad, is not
    also reported for running continuum tendons (it would, with its table unset)."""
    bad = MIXED.replace('tendon_model = "eyelets"', 'tendon_model = "rope"\nn_elemnts = 3').replace(
        "n_elements = 16", "n_elements = 16\nn_stationz = 3").replace("[1.0, 3.0]", "[1.0, -3.0]")
    path = _write(tmp_path, bad)
    with pytest.raises(StudyError) as e:
        load_study(path)
    assert e.value.problems == [f"{path}: {p}" for p in (
        "solver.n_stationz: unknown key; did you mean 'n_stations'?",
        "solver.by_model.beam3d.n_elemnts: unknown option; did you mean 'n_elements'?",
        "solver.by_model.beam3d.tendon_model: must be 'continuum' or 'eyelets', got 'rope'",
        'sweep.product["load.tensions[0]"][1]: must be >= 0 [N], got -3')]


def test_a_sweep_axis_or_override_that_every_table_shadows_is_refused(tmp_path):
    tables = "".join(f"[solver.by_model.{m}]\nn_elements = 8\n" for m in MODELS)
    every = MIXED.replace('[solver.by_model.beam3d]\ntendon_model = "eyelets"\n',
                          tables.replace("beam3d]\n", 'beam3d]\ntendon_model = "eyelets"\n'))
    path = _write(tmp_path, every.replace('product = { "load.tensions[0]" = [1.0, 3.0] }',
                                          'product = { "solver.n_elements" = [8, 16] }'))
    with pytest.raises(StudyError) as e:
        load_study(path)
    assert e.value.problems == [f'{path}: sweep.product["solver.n_elements"]: every model sets n_elements in '
                                f"[solver.by_model] (cc, cosserat, beam3d, spring_link), so this axis changes "
                                f'nothing; sweep "solver.by_model.<model>.n_elements" instead']
    path = _write(tmp_path, every)
    with pytest.raises(StudyError) as e:
        load_study(path, overrides=["solver.n_elements=32"])
    assert e.value.problems == [f"{path}: override 'solver.n_elements=32': every model sets n_elements in "
                                f"[solver.by_model] (cc, cosserat, beam3d, spring_link), so it would not apply; "
                                f"override solver.by_model.<model>.n_elements instead"]
    study = load_study(path, overrides=["solver.by_model.cc.n_elements=32"])
    assert study.base["solver"]["by_model"]["cc"] == {"n_elements": 32}


@pytest.mark.slow
def test_cc_cosserat_beam3d_spring_link_in_one_table(tmp_path):
    """The acceptance study: four models, beam3d with eyelets, one table compared with cosserat."""
    from workbench.compare.table import compare_table
    from workbench.results import load
    from workbench.study import RunConfig, SerialExecutor, run_study

    study = load_study(_write(tmp_path, MIXED))
    run_study(study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    df = load(tmp_path / "out")
    assert (df["status"] == "ok").all() and len(df) == 8
    ran = dict(zip(df["model"], df["p.solver.tendon_model"]))
    assert ran == {"cc": "continuum", "cosserat": "continuum", "beam3d": "eyelets", "spring_link": "continuum"}
    assert df["p.load.tensions[0]"].dtype == float and sorted(set(df["p.load.tensions[0]"])) == [1.0, 3.0]
    cmp = compare_table(df, baseline="cosserat")
    vs = cmp[cmp["reference"] == "cosserat"]
    assert sorted(set(vs["model"])) == ["beam3d", "cc", "spring_link"] and len(vs) == 6
    # a 0.5 m steel rod bent by 1-3 N: every model within 1e-3 % of L of the Cosserat rod's tip
    assert (vs["tip_error_pct"] < 1e-3).all(), vs[["model", "tip_error_pct"]]


def test_a_per_model_time_step_counts_for_the_step_bound(tmp_path):
    dyn = MIXED.replace('tensions = [2.0, 0.0, 0.0]',
                        'tensions = [2.0, 0.0, 0.0]\nanalysis = "dynamic"\nduration = 10.0')
    dyn = dyn.replace('models = ["cc", "cosserat", "beam3d", "spring_link"]', 'models = ["cc", "beam3d"]').replace(
        'reference = "cosserat"', 'reference = "cc"')
    load_study(_write(tmp_path, dyn))  # 10 s at the default 2 ms: 5000 steps
    with pytest.raises(StudyError, match=r"load.duration / time_step = 1e\+08 steps exceeds 1e\+07"):
        load_study(_write(tmp_path, dyn.replace('tendon_model = "eyelets"',
                                                'tendon_model = "eyelets"\ntime_step = 1e-7')))
