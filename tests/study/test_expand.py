"""Expansion: determinism, case_id stability, block semantics, seeded samples."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.study import case_id_for, count_cases, expand, load_study

SWEEP = """
[sweep]
product = { "robot.length" = [0.5, 0.8], "solver.n_elements" = [4, 8, 16] }
zip = { "load.ramp_time" = [1.0, 2.0], "load.pretension" = [0.0, 1.0] }
cases = [ { "robot.tendon_offset" = 0.01 }, { "robot.tendon_offset" = 0.02 } ]
random = { n = 3, "robot.diameter" = { low = 4e-3, high = 8e-3 }, "solver.n_stations" = { low = 5, high = 9 } }
latin_hypercube = { n = 5, "load.bend_plane" = { low = 0.0, high = 1.0 }, "robot.density" = { low = 1000.0, high = 8000.0 } }
"""


def test_expansion_count_and_blocks(write_study):
    study = load_study(write_study(SWEEP))
    cases = expand(study)
    assert len(cases) == count_cases(study) == 2 * 3 * 2 * 2 * 3 * 5
    # zip pairs values, product crosses them
    pairs = {(c.swept["load.ramp_time"], c.swept["load.pretension"]) for c in cases}
    assert pairs == {(1.0, 0.0), (2.0, 1.0)}
    assert {(c.swept["robot.length"], c.swept["solver.n_elements"]) for c in cases} == {
        (a, b) for a in (0.5, 0.8) for b in (4, 8, 16)}
    # swept values land in the resolved parameters; unswept ones keep the base
    c = cases[0]
    assert c.params["robot"]["length"] == c.swept["robot.length"]
    assert c.params["solver"]["newton_tolerance"] == 1e-9
    assert len({c.case_id for c in cases}) == len(cases)


def test_expansion_is_deterministic_and_ids_stable(write_study):
    a = expand(load_study(write_study(SWEEP)))
    b = expand(load_study(write_study(SWEEP)))
    assert [c.case_id for c in a] == [c.case_id for c in b]
    assert [c.params for c in a] == [c.params for c in b]
    # id is the hash of the parameters only
    for c in a[:5]:
        assert c.case_id == case_id_for(c.params)


def test_case_id_independent_of_order_name_and_models(write_study):
    from study_fakes import GOOD

    base = {c.case_id for c in expand(load_study(write_study(SWEEP)))}
    reordered = SWEEP.replace('"robot.length" = [0.5, 0.8], "solver.n_elements" = [4, 8, 16]',
                              '"solver.n_elements" = [16, 8, 4], "robot.length" = [0.8, 0.5]')
    other = GOOD.replace('name = "good"', 'name = "other"').replace('models = ["cc", "ancf"]', 'models = ["cc"]')
    assert {c.case_id for c in expand(load_study(write_study(reordered)))} == base
    assert {c.case_id for c in expand(load_study(write_study(SWEEP, base=other)))} == base


def test_case_id_changes_with_any_parameter(write_study):
    from study_fakes import GOOD

    one = expand(load_study(write_study()))[0].case_id
    assert expand(load_study(write_study(base=GOOD.replace("n_stations = 9", "n_stations = 11"))))[0].case_id != one
    assert expand(load_study(write_study(base=GOOD.replace("length = 0.8", "length = 0.8000000001"))))[0].case_id != one


def test_seed_changes_samples_only(write_study):
    from study_fakes import GOOD

    s3 = expand(load_study(write_study(SWEEP)))
    s4 = expand(load_study(write_study(SWEEP, base=GOOD.replace("seed = 3", "seed = 4"))))
    d3 = sorted({c.swept["robot.diameter"] for c in s3})
    d4 = sorted({c.swept["robot.diameter"] for c in s4})
    assert d3 != d4
    assert all(4e-3 <= d <= 8e-3 for d in d3 + d4)
    assert all(isinstance(c.swept["solver.n_stations"], int) and 5 <= c.swept["solver.n_stations"] <= 9 for c in s3)


def test_latin_hypercube_one_sample_per_stratum(write_study):
    n = 7
    study = load_study(write_study(f"""
        [sweep]
        latin_hypercube = {{ n = {n}, "load.bend_plane" = {{ low = 0.0, high = 1.0 }}, "robot.length" = {{ low = 0.5, high = 1.5 }} }}
        """))
    cases = expand(study)
    for key, lo in (("load.bend_plane", 0.0), ("robot.length", 0.5)):
        strata = sorted(int(np.floor((c.swept[key] - lo) * n)) for c in cases)
        assert strata == list(range(n)), key


@pytest.mark.parametrize("block", ["random", "latin_hypercube", "sobol"])
def test_samples_reproducible(write_study, block):
    text = f"""
        [sweep]
        {block} = {{ n = 4, "robot.length" = {{ low = 0.5, high = 1.5 }} }}
        """
    a = [c.swept["robot.length"] for c in expand(load_study(write_study(text)))]
    b = [c.swept["robot.length"] for c in expand(load_study(write_study(text)))]
    assert a == b and len(set(a)) == 4


def test_duplicate_cases_rejected(write_study):
    from workbench.study import StudyError

    with pytest.raises(StudyError, match="identical parameters"):
        load_study(write_study("""
            [sweep]
            cases = [ { "robot.length" = 0.5 }, { "robot.length" = 0.5 } ]
            """))


def test_sobol_points_are_balanced_and_n_must_be_a_power_of_two(write_study):
    """Scrambled Sobol (scipy.stats.qmc): 8 points put exactly one in each eighth of every axis."""
    from workbench.study import StudyError

    study = load_study(write_study("""
        [sweep]
        sobol = { n = 8, "load.bend_plane" = { low = 0.0, high = 1.0 }, "robot.length" = { low = 0.5, high = 1.5 } }
        """))
    cases = expand(study)
    for key, lo in (("load.bend_plane", 0.0), ("robot.length", 0.5)):
        assert sorted(int(np.floor((c.swept[key] - lo) * 8)) for c in cases) == list(range(8)), key
    with pytest.raises(StudyError, match=r"sweep.sobol.n: a Sobol sequence is balanced only for a power of 2, "
                                         r"got 6 \(use 4 or 8\)"):
        load_study(write_study("""
            [sweep]
            sobol = { n = 6, "robot.length" = { low = 0.5, high = 1.5 } }
            """))


def test_sweep_keys_name_every_block_in_order_once():
    from workbench.study.expand import sweep_keys

    sweep = {"product": {"load.bend_angle": [0.1, 0.2], "robot.length": [0.5]},
             "zip": {"robot.gravity": [0.0, 9.81], "load.bend_angle": [1.0, 2.0]},
             "cases": [{"solver.tendon_model": "eyelets"},
                       {"solver.tendon_model": "continuum", "robot.n_sections": 2}],
             "random": {"n": 4, "robot.tendon_offset": {"low": 0.01, "high": 0.02}}}
    assert sweep_keys(sweep) == ["load.bend_angle", "robot.length", "robot.gravity", "solver.tendon_model",
                                 "robot.n_sections", "robot.tendon_offset"]
    assert sweep_keys(None) == sweep_keys({}) == sweep_keys({"product": 3}) == []  # unvalidated: no key
