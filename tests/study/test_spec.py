"""Study-file validation: the malformed corpus, one line per problem, before any case runs."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from workbench.cli import main
from workbench.models.result import SolverOptions
from workbench.study import StudyError, count_cases, load_study
from workbench.study.build import PipelineOptions, build_options, build_pipeline_options
from workbench.study.schema import LIMIT_KEYS, SolverSection

HERE = Path(__file__).parent
BAD = sorted((HERE / "bad_configs").glob("*.toml"))
ROOT = HERE.parents[1]


def _expectation(path: Path) -> tuple[str, str]:
    first = path.read_bytes().split(b"\n")[0].decode("utf-8")  # (non_utf8.toml is not UTF-8 further down)
    assert first.startswith("# expect: "), f"{path} lacks its '# expect: key | reason' line"
    key, _, reason = first[len("# expect: "):].partition(" | ")
    return key.strip(), reason.strip()


def test_corpus_is_large_enough():
    assert len(BAD) >= 60


@pytest.mark.parametrize("path", BAD, ids=[p.stem for p in BAD])
def test_malformed_study_rejected_with_one_line(path):
    key, reason = _expectation(path)
    with pytest.raises(StudyError) as ei:
        load_study(path)
    problems = ei.value.problems
    assert len(problems) == 1, problems
    line = problems[0]
    assert "\n" not in line
    assert line.startswith(f"{path}: {key}"), line  # names file and key path
    assert reason in line, line  # and the reason


def test_all_problems_reported_together(write_study):
    p = write_study("""
        [derived]
        gravity_parameter = nan
        """, base=(HERE / "bad_configs" / "unknown_key_robot.toml").read_text().replace("n_elements = 8", "n_elements = 0")
                                   .replace('preset = "steel_rod"', 'preset = "steel_rod"\ndiameter = -1.0'))
    with pytest.raises(StudyError) as ei:
        load_study(p)
    text = "\n".join(ei.value.problems)
    assert "robot.lenght" in text and "solver.n_elements" in text and "robot.diameter" in text
    assert "derived.gravity_parameter: must be finite" in text
    assert len(ei.value.problems) == 4


def _keys(path, text) -> list[str]:
    path.write_text(textwrap.dedent(text))
    with pytest.raises(StudyError) as ei:
        load_study(path)
    lines = ei.value.problems
    assert all(x.startswith(f"{path}: ") and "\n" not in x for x in lines), lines
    return [x[len(f"{path}: "):].split(" ")[0].rstrip(":") for x in lines]


def test_schema_error_does_not_hide_case_checks(tmp_path):
    """Schema errors in [solver] and [robot], a bad sweep value and a capability error: four lines, one pass."""
    keys = _keys(tmp_path / "s.toml", """
        [study]
        name = "op"
        models = ["cc", "beam3d"]
        [robot]
        preset = "steel_rod"
        lenght = 0.8
        [load]
        mode = "tension"
        tensions = [1.0, 0.0]
        [solver]
        n_elements = 0
        [sweep]
        product = { "robot.length" = [0.5, -1.0], "robot.tendon_offset" = [0.01, 0.02] }
        """)
    assert keys == ["solver.n_elements", "robot.lenght", 'sweep.product["robot.length"][1]', "solver.tendon_model"]


def test_load_and_sweep_schema_errors_do_not_hide_a_capability_error(tmp_path):
    keys = _keys(tmp_path / "s.toml", """
        [study]
        name = "op"
        models = ["cc", "ancf"]
        [robot]
        preset = "steel_rod"
        first_tendon_angle = 0.3
        [load]
        pretension = -1.0
        tip_force = [0.0, 0.0]
        [sweep]
        prodcut = { "robot.length" = [0.5, 1.0] }
        """)
    assert keys == ["load.pretension", "load.tip_force", "sweep.prodcut", "robot.first_tendon_angle"]


@pytest.mark.parametrize("models,tables,key", [
    # a typo in the value: no second line about the default ('continuum') beam3d cannot use
    ('"cc", "beam3d"', 'mode = "tension"\ntensions = [1.0, 0.0]\n[solver]\ntendon_model = "eyelet"', "solver.tendon_model"),
    # a bad tendon count: no line about the tension count against the default count
    ('"cc"', 'mode = "tension"\ntensions = [1.0, 0.0, 0.0]\n[robot]\npreset = "steel_rod"\ntendon_count = -3',
     "robot.tendon_count"),
    # a bad mode: no line "needs mode = ..." about the default mode
    ('"cc"', 'mode = "lenght"\nlength_changes = [-0.01, 0.0]', "load.mode"),
], ids=["tendon_model_typo", "bad_tendon_count", "bad_mode"])
def test_no_knock_on_lines_from_a_key_at_its_default(tmp_path, models, tables, key):
    robot = "" if "[robot]" in tables else '[robot]\npreset = "steel_rod"\n'
    text = f'[study]\nname = "op"\nmodels = [{models}]\n{robot}[load]\n{tables}\n'
    assert _keys(tmp_path / "s.toml", text) == [key]


def test_cli_validate_bad_exit_2_no_traceback(capsys):
    path = HERE / "bad_configs" / "negative_length.toml"
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.strip().splitlines() == [f"{path}: robot.length: must be > 0 [m], got -0.8"]
    assert "Traceback" not in err


def test_cli_run_bad_config_runs_nothing(tmp_path, capsys):
    out = tmp_path / "out"
    path = HERE / "bad_configs" / "nan_in_sweep_axis.toml"
    rc = main(["run", str(path), "--out", str(out), "--in-process"])
    assert rc == 2
    assert not out.exists()
    assert "must be finite" in capsys.readouterr().err


def test_cli_subprocess_exit_code_and_single_line():
    path = HERE / "bad_configs" / "unknown_model.toml"
    r = subprocess.run([sys.executable, "-m", "workbench", "validate", str(path)], capture_output=True,
                       text=True, cwd=ROOT, timeout=60)
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [f"{path}: study.models[1]: unknown model 'ancff'; did you mean 'ancf'?"]


def test_solver_section_mirrors_solver_and_pipeline_options():
    """[solver] = the SolverOptions fields (``spring_link_backend``: the spring-link model's own setting)
    + the PipelineOptions fields + the per-case limits (which never reach the case parameters)."""
    fields = {f.name: f.default for f in dataclasses.fields(SolverOptions)
              if f.name not in ("model_settings", "warm_state")}  # warm_state: a run-time value, no study key
    fields.update({f.name: f.default for f in dataclasses.fields(PipelineOptions)})
    fields["spring_link_backend"] = "auto"  # SpringLinkParams.backend's default
    fields["spring_link_axial"] = None  # SpringLinkParams.axial's default (the model's own rule)
    fields["spring_link_richardson"] = None  # unset: SpringLinkParams.richardson's default (off)
    fields["by_model"] = {}  # the per-model tables (workbench.study.by_model)
    section = SolverSection()
    assert set(SolverSection.model_fields) == set(fields) | set(LIMIT_KEYS)
    # tuples are lists in the section
    assert section.model_dump(exclude=set(LIMIT_KEYS)) == {
        k: list(v) if isinstance(v, tuple) else v for k, v in fields.items()}
    options = build_options(section.model_dump(exclude=set(LIMIT_KEYS)))
    assert options.settings("spring_link") == {"backend": "auto"} and options.settings("cc") == {}
    assert build_options({"spring_link_axial": False}).settings("spring_link") == {"axial": False}
    assert build_options({"by_model": {"ancf": {"n_elements": 32}}}).n_elements == 16  # the pipeline's key
    assert build_pipeline_options({"by_model": {"ancf": {"error_estimate": "none"}}}).error_estimate == "richardson"


def test_good_study_and_defaults(write_study):
    study = load_study(write_study())
    assert study.models == ("cc", "ancf")
    assert study.base["robot"]["length"] == 0.8 and study.base["robot"]["diameter"] == 6e-3
    assert study.base["solver"]["n_elements"] == 8
    assert study.base["load"]["tip_force"] == [0.0, 0.0, 0.0]
    assert count_cases(study) == 1


def test_int_accepted_for_float_parameter(write_study):
    a = load_study(write_study("", base=_good_with("length = 1")))
    b = load_study(write_study("", base=_good_with("length = 1.0")))
    assert a.base["robot"]["length"] == 1.0 and isinstance(a.base["robot"]["length"], float)
    assert a.config_hash == b.config_hash


def _good_with(line: str) -> str:
    from study_fakes import GOOD

    return GOOD.replace("length = 0.8", line)


def test_max_cases_override(write_study):
    p = write_study("""
        [sweep]
        product = { "robot.length" = [0.5, 0.6, 0.7], "solver.n_elements" = [4, 8] }
        """)
    assert count_cases(load_study(p)) == 6
    with pytest.raises(StudyError, match="6 cases exceed the limit max_cases = 5"):
        load_study(p, max_cases=5)


def test_example_study_is_valid():
    study = load_study(ROOT / "studies" / "example.toml")
    assert study.name == "example" and count_cases(study) == 9
