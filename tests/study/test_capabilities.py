"""Capability and plausibility checks of ``validate`` (issue 16).

1. The corpus: new users' typical mistakes -- a model asked for what it cannot do, a typo in
   ``[report]``, values far outside the physical range -- each rejected (exit 2) or warned
   (exit 0) with one line naming the key and the model, before anything runs.
2. One pass: a file with mistakes in several sections reports all of them at once.
3. Honest declarations: every limit declared in ``registry.MODELS`` is one the model itself
   enforces (the real model, Exudyn included, refuses the probe case), so ``validate`` refuses
   only what would fail at run time.
"""

from __future__ import annotations

import textwrap

import pytest

from workbench.cli import main
from workbench.study import StudyError, load_study


def study(models='"cc"', robot="", load='mode = "tension"\ntensions = [1.0, 0.0]', solver="", report="",
          sweep="", name='"caps"', preset="steel_rod") -> str:
    parts = [f"[study]\nname = {name}\nmodels = [{models}]\n", f'[robot]\npreset = "{preset}"\n{robot}\n',
             f"[load]\n{load}\n", f"[solver]\nn_elements = 8\nn_stations = 9\n{solver}\n"]
    if report:
        parts.append(f"[report]\n{report}\n")
    if sweep:
        parts.append(f"[sweep]\n{sweep}\n")
    return "\n".join(textwrap.dedent(p) for p in parts)


LENGTH = 'mode = "length"\nlength_changes = [-0.001, 0.0]'
ARC = 'mode = "tension"\nbend_angle = 1.0'
TAPERED = 'mode = "tension"\ntensions = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]'  # cojocaru: 3 x 3 wires
E, W = "error", "warning"

#: (id, file text, error or warning, expected key, expected words of the line)
CORPUS = [
    ("beam3d_continuum_tension", study('"cc", "beam3d"'), E, "solver.tendon_model", "model 'beam3d' supports"),
    ("beam3d_continuum_length", study('"beam3d"', load=LENGTH), E, "solver.tendon_model", "'eyelets'"),
    ("beam3d_continuum_arc", study('"beam3d"', load=ARC), E, "solver.tendon_model", "(got 'continuum')"),
    ("beam3d_swept_tendon_model", study('"beam3d"', sweep='product = { "solver.tendon_model" = ["eyelets", '
                                                           '"continuum"] }'), E, "solver.tendon_model", "beam3d"),
    ("cosserat_eyelets_length", study('"cosserat"', load=LENGTH, solver='tendon_model = "eyelets"'), E,
     "solver.tendon_model", "model 'cosserat' supports"),
    ("cosserat_dynamic", study('"cosserat"', load='analysis = "dynamic"\nduration = 0.1'), E, "load.analysis",
     "supports only static analysis"),
    ("ancf3d_tension", study('"ancf3d"'), E, "load.tensions", "model 'ancf3d' cannot carry tendon loads"),
    ("ancf3d_length", study('"ancf3d"', load=LENGTH), E, "load.length_changes", "cannot carry tendon loads"),
    ("ancf3d_arc", study('"ancf3d"', load=ARC), E, "load.bend_angle", "cannot carry tendon loads"),
    ("ancf3d_pretension", study('"ancf3d"', load='mode = "tension"\ntensions = [0.0, 0.0]\npretension = 2.0'), E,
     "load.pretension", "cannot carry tendon loads"),
    ("ancf3d_tip_torque", study('"ancf3d"', load='tip_torque = [0.0, 0.01, 0.0]'), E, "load.tip_torque",
     "model 'ancf3d' cannot carry a tip torque"),
    ("ancf3d_one_swept_case", study('"ancf3d"', load='mode = "tension"\ntensions = [0.0, 0.0]',
                                    sweep='product = { "load.tensions" = [[0.0, 0.0], [1.0, 0.0]] }'), E,
     "load.tensions", "(case 1: "),
    ("ancf_tendon_angle", study('"cc", "ancf"', robot="first_tendon_angle = 0.3"), E, "robot.first_tendon_angle",
     "model 'ancf' is planar only"),
    ("ancf_three_tendons", study('"ancf"', robot="tendon_count = 3", load='mode = "tension"\ntensions = [1.0, 0.0, '
                                                                           '0.0]'), E, "robot.tendon_count",
     "not in the base x-z plane"),
    ("ancf_tip_force_y", study('"ancf"', load='tip_force = [0.0, 0.1, 0.0]'), E, "load.tip_force", "has a y component"),
    ("ancf_tip_torque_z", study('"ancf"', load='tip_torque = [0.0, 0.0, 0.01]'), E, "load.tip_torque",
     "is not about base y"),
    ("ancf_swept_angle", study('"ancf"', sweep='product = { "robot.first_tendon_angle" = [0.0, 3.141592653589793, '
                                                '1.0] }'), E, "robot.first_tendon_angle", "(case 2: "),
    ("report_axis_typo", study(report='axes = ["kapaL"]'), E, "report.axes[0]", "did you mean 'kappaL'?"),
    ("report_axis_parameter_typo", study(report='axes = ["p.robot.lenght"]'), E, "report.axes[0]",
     "did you mean 'p.robot.length'?"),
    ("report_axis_nonsense", study(report='axes = ["zzz"]'), E, "report.axes[0]", "use a case parameter"),
    ("report_label_typo", study(report='labels = { gama = "g" }'), E, 'report.labels["gama"]',
     "did you mean 'gamma'?"),
    ("report_reference_not_a_model", study(report='reference = "ancf"'), E, "report.reference", "ancf"),
    ("report_frame", study(report='frame = "side"'), E, "report.frame", "'world'"),
    ("report_unknown_key", study(report='axis = ["kappaL"]'), E, "report.axis", "unknown key"),
    ("fat_rod", study(robot="diameter = 6.0"), W, "robot.diameter", "is no slender rod"),
    ("spring_link_length_inextensible", study('"spring_link"', load=LENGTH, solver='tendon_model = "eyelets"'), W,
     "solver.spring_link_axial", "model 'spring_link' solves these length-controlled tendons on an inextensible chain"),
    ("short_rod", study(robot="length = 0.02"), W, "robot.diameter", "length / diameter = 3.33"),
    ("huge_tension_backbone", study(load='mode = "tension"\ntensions = [3340.0, 0.0]'), W, "load.tensions",
     "stresses the backbone of section 0 to 3268 MPa (bending EI kappa / W 3150 MPa + axial sum T / A 118 MPa), "
     "2.72 x its yield strength 1200 MPa (robot.yield_strength of preset 'steel_rod': hardened and tempered"),
    ("huge_tension_wire", study(load='mode = "tension"\ntensions = [3340.0, 0.0]'), W, "load.tensions",
     "the CC tension 3340 N of tendon 0 (section 0) on its 0.19 mm^2 wire is a stress T / A_t = 17535 MPa, 7.28 x "
     "the tendon strength 2410 MPa (robot.tendon_strength of preset 'steel_rod': music wire ASTM A228"),
    ("wire_breaks_backbone_holds", study(load='mode = "tension"\ntensions = [500.0, 0.0]'), W, "load.tensions",
     "1.09 x the tendon strength 2410 MPa"),
    ("weak_wire_set_in_study", study(robot="tendon_strength = 1e8", load='mode = "tension"\ntensions = [50.0, 0.0]'),
     W, "load.tensions", "2.62 x the tendon strength 100 MPa (robot.tendon_strength set in the study)"),
    ("more_than_a_turn", study(load='mode = "tension"\nbend_angle = 7.0'), W, "load.bend_angle", "full turns"),
    ("one_huge_swept_tension", study(sweep='product = { "load.tensions" = [[1.0, 0.0], [3340.0, 0.0], '
                                           '[2.0, 0.0]] }'), W, "load.tensions", "(case 1: "),
    ("huge_length_change", study(load='mode = "length"\nlength_changes = [-0.15, 0.0]'), W, "load.length_changes",
     "to 3259 MPa (bending EI kappa / W; CC predicts no tendon forces under length control), 2.72 x its yield"),
]

#: supported combinations: accepted without a word (the checks do not over-reach)
CONTROLS = [
    ("cc_everything", study('"cc"', robot="first_tendon_angle = 0.3", load='mode = "tension"\ntensions = [1.0, 0.0]\n'
                                                                           'tip_torque = [0.0, 0.0, 0.01]')),
    ("beam3d_eyelets", study('"cc", "beam3d"', solver='tendon_model = "eyelets"')),
    ("cosserat_eyelets", study('"cc", "cosserat"', solver='tendon_model = "eyelets"')),
    ("ancf3d_tip_force", study('"ancf3d"', load='tip_force = [0.01, 0.02, 0.0]')),
    ("ancf_pi_tendon", study('"ancf"', robot="first_tendon_angle = 3.141592653589793")),
    ("spring_link_spatial_length_continuum", study('"spring_link"', robot="first_tendon_angle = 0.3", load=LENGTH,
                                                   solver="spring_link_axial = true")),
    ("spring_link_spatial_length_eyelets", study('"spring_link"', robot="first_tendon_angle = 0.3", load=LENGTH,
                                                 solver='tendon_model = "eyelets"\nspring_link_axial = true')),
    ("report_ok", study(report='axes = ["kappaL", "p.robot.length", "tip_x"]\nlabels = { kappaL = "k" }')),
]


def test_corpus_is_large_enough():
    assert len(CORPUS) >= 30


@pytest.mark.parametrize("name,text,kind,key,words", CORPUS, ids=[c[0] for c in CORPUS])
def test_mistake_is_one_line_naming_the_key(tmp_path, capsys, name, text, kind, key, words):
    p = tmp_path / f"{name}.toml"
    p.write_text(text)
    rc = main(["validate", str(p)])
    out, err = capsys.readouterr()
    if kind == E:
        lines = err.strip().splitlines()
        assert rc == 2 and len(lines) == 1, (rc, out, err)
    else:
        lines = [x.strip()[len("warning: "):] for x in out.splitlines() if x.strip().startswith("warning: ")]
        assert rc == 0 and lines, (rc, out, err)
        lines = [x for x in lines if words in x][:1] or lines
    assert lines[0].startswith(f"{p}: {key}"), lines
    assert words in lines[0], lines


@pytest.mark.parametrize("name,text", CONTROLS, ids=[c[0] for c in CONTROLS])
def test_supported_combinations_pass_without_warnings(tmp_path, name, text):
    p = tmp_path / f"{name}.toml"
    p.write_text(text)
    s = load_study(p)
    assert s.warnings == ()


def test_every_problem_of_a_file_in_one_pass(tmp_path):
    """A [study] mistake, a [report] typo and two models' capability problems: four lines at once."""
    p = tmp_path / "many.toml"
    p.write_text(study('"cc", "beam3d", "ancf3d", "nosuch"', report='axes = ["kapaL"]'))
    with pytest.raises(StudyError) as ei:
        load_study(p)
    keys = [line[len(f"{p}: "):].split(" ")[0].rstrip(":") for line in ei.value.problems]
    assert sorted(keys) == sorted(["study.models[3]", "report.axes[0]", "solver.tendon_model", "load.tensions"]), \
        ei.value.problems


# ---------------------------------------------------------------------------------------------
# the declarations are honest: the models themselves refuse what validate refuses
# ---------------------------------------------------------------------------------------------
PROBES = [  # (model, corpus id): validate refuses it, so must the model
    ("beam3d", "beam3d_continuum_tension"),
    ("ancf3d", "ancf3d_tension"), ("ancf3d", "ancf3d_pretension"), ("ancf3d", "ancf3d_tip_torque"),
    ("ancf", "ancf_tendon_angle"), ("ancf", "ancf_tip_force_y"), ("ancf", "ancf_tip_torque_z"),
    ("cosserat", "cosserat_eyelets_length"), ("cosserat", "cosserat_dynamic"),
]


@pytest.mark.parametrize("model,cid", PROBES, ids=[f"{m}-{c}" for m, c in PROBES])
def test_declared_limit_is_enforced_by_the_model(tmp_path, model, cid):
    from workbench.models import get_model
    from workbench.models.result import ModelFailure
    from workbench.study.build import build_load, build_options, build_robot
    from workbench.study.spec import parse_study
    import tomllib

    text = dict((c[0], c[1]) for c in CORPUS)[cid]
    raw = tomllib.loads(text.replace(text.split("\n")[2], 'models = ["cc"]'))  # the same case, CC only: valid
    s = parse_study(raw, source=cid)
    base = s.base
    robot = build_robot(base["robot"], base["derived"])
    load = build_load(robot, base["load"])
    options = build_options(base["solver"])
    with pytest.raises((ModelFailure, ValueError)):
        get_model(model)(robot, load, options)


# ---------------------------------------------------------------------------------------------
# limits no preset reaches from a study file (user robots, issue 28): features -> one line naming the
# key, and the model itself refuses the same case
# ---------------------------------------------------------------------------------------------
def _rao_planar(*, rotated=False, offset_tip=None, angles=(0.0, 3.141592653589793)):
    """Rao et al.'s NiTi robot (planar variant, issue 28); ``rotated``: base turned 90 deg about x, so gravity
    lies along base y, out of the planar models' plane."""
    from workbench.robot import CrossSection, Robot, Section, TendonGroup

    cs = CrossSection.circular(diameter=1.4e-3, youngs_modulus=54e9, density=6450.0, poisson_ratio=0.3)
    tg = TendonGroup(angles=angles, offset=10e-3, axial_stiffness=1e7, offset_tip=offset_tip)
    sec = Section(length=0.2, cross_section=cs, tendons=tg, n_disks=10, disk_mass=0.5e-3)
    rot = ((1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 1.0, 0.0)) if rotated else \
        ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    return Robot(sections=(sec, sec), gravity=(0.0, 0.0, -9.81), base_rotation=rot)


def _act(mode, n=4):
    from workbench.robot import TendonActuation

    return TendonActuation(mode, (-1e-3 if mode == "length" else 1.0,) + (0.0,) * (n - 1))


#: (id, model, robot kwargs, (mode or None, n tendons), tendon_model, expected key, words)
API_PROBES = [
    ("ancf_gravity_out_of_plane", "ancf", dict(rotated=True), (None, 4), "continuum", "robot.gravity",
     "model 'ancf' is planar and refuses gravity out of the base x-z plane (base y component -9.81 m/s^2)"),
    ("contact_gravity_out_of_plane", "contact", dict(rotated=True), (None, 4), "continuum", "robot.gravity",
     "model 'contact' is planar and refuses gravity out of the base x-z plane"),
]
#: supported: no line, and the model runs
API_CONTROLS = [
    ("ancf", dict(offset_tip=5e-3), ("length", 4), "continuum"),
    ("spring_link", dict(offset_tip=5e-3), ("tension", 4), "continuum"),
    ("contact", dict(offset_tip=5e-3), ("tension", 4), "continuum"),
    ("spring_link_cardan", dict(offset_tip=5e-3), ("tension", 4), "eyelets"),
    # tapered continuum tendons on the chains: ropes through every link eyelet (spring28), no longer refused
    ("spring_link", dict(offset_tip=5e-3), ("length", 4), "continuum"),
    ("spring_link_cardan", dict(offset_tip=5e-3), ("tension", 4), "continuum"),
]


def _api_case(kw, act, tendon_model):
    from workbench.models.result import SolverOptions
    from workbench.robot import LoadCase
    from workbench.study.capabilities import case_features

    robot = _rao_planar(**kw)
    load = LoadCase(actuation=None if act[0] is None else _act(*act))
    params = {"robot": {"preset": "rao", "gravity": 9.81}, "load": {}}
    f = case_features(robot, load, params, {"tendon_model": tendon_model})
    return robot, load, SolverOptions(n_elements=8, tendon_model=tendon_model), f


@pytest.mark.parametrize("cid,model,kw,act,tm,key,words", API_PROBES, ids=[p[0] for p in API_PROBES])
def test_api_limit_is_declared_and_enforced(cid, model, kw, act, tm, key, words):
    from workbench.models import get_model
    from workbench.models.result import ModelFailure
    from workbench.registry import MODELS
    from workbench.study.capabilities import unsupported

    robot, load, options, f = _api_case(kw, act, tm)
    lines = unsupported(model, MODELS[model].capabilities, f)
    assert len(lines) == 1 and lines[0].startswith(f"{key}: ") and words in lines[0], lines
    with pytest.raises((ModelFailure, ValueError)):
        get_model(model)(robot, load, options)


@pytest.mark.parametrize("model,kw,act,tm", API_CONTROLS, ids=[c[0] for c in API_CONTROLS])
def test_api_supported_case_passes_and_runs(model, kw, act, tm):
    from workbench.models import get_model
    from workbench.registry import MODELS
    from workbench.study.capabilities import unsupported

    robot, load, options, f = _api_case(kw, act, tm)
    assert unsupported(model, MODELS[model].capabilities, f) == []
    assert get_model(model)(robot, load, options).solver.converged


# ---------------------------------------------------------------------------------------------
# stress vs strength: only against a declared strength
# ---------------------------------------------------------------------------------------------
def _solid_rod_robot(yield_strength=None, strength=None):
    from workbench.robot import CrossSection, Robot, Section, TendonGroup

    rod = CrossSection.circular(6e-3, yield_strength=yield_strength)
    tendons = TendonGroup((0.0, 3.141592653589793), 0.02, 4e4, area=1.905e-7, strength=strength)
    return Robot(sections=(Section(length=0.8, cross_section=rod, tendons=tendons),))


@pytest.mark.parametrize("yield_strength,strength", [(None, None), (1.2e9, None), (None, 2.41e9), (1.2e9, 2.41e9)])
def test_stress_warnings_only_where_a_strength_is_declared(yield_strength, strength):
    from workbench.robot import LoadCase, TendonActuation
    from workbench.study.plausibility import plausibility_warnings

    params = {"robot": {"preset": "steel_rod", "diameter": 6e-3, "youngs_modulus": 210e9},
              "load": {"tensions": [3340.0, 0.0]}}
    lines = plausibility_warnings(_solid_rod_robot(yield_strength, strength),
                                  LoadCase(actuation=TendonActuation("tension", (3340.0, 0.0))), params)
    assert any("stresses the backbone" in x for x in lines) == (yield_strength is not None), lines
    assert any("the wire would break" in x for x in lines) == (strength is not None), lines
    # the surface-strain fallback speaks for a solid rod whose yield strength is unknown (1.5 % here)
    assert any("surface strain kappa d / 2 = 1.5 %" in x for x in lines) == (yield_strength is None), lines
    assert all(x.startswith("load.tensions: ") for x in lines), lines


# ---------------------------------------------------------------------------------------------
# docs/models.md's "What each model represents" is the table generated from the capabilities
# ---------------------------------------------------------------------------------------------
def test_models_md_table_is_the_generated_one():
    """Regenerate with ``workbench list represents`` and paste it between the markers."""
    from pathlib import Path

    from workbench.registry import MODELS
    from workbench.study.capabilities import represents_table

    text = (Path(__file__).resolve().parents[2] / "docs" / "models.md").read_text()
    begin, end = "<!-- represents-table:begin -->\n", "<!-- represents-table:end -->"
    assert begin in text and end in text
    # the built-in models only (MODELS): an installed plug-in's rows are in `workbench list represents`, not the docs
    assert text.split(begin, 1)[1].split(end, 1)[0] == represents_table(MODELS)


def test_represents_table_has_a_row_per_declared_model_and_the_cli_prints_it(capsys):
    from workbench.registry import MODELS
    from workbench.study.capabilities import represents_table

    rows = represents_table(MODELS).splitlines()[2:]
    assert [r.split("|")[1].strip() for r in rows] == [f"`{n}`" for n, i in MODELS.items() if i.capabilities]
    assert main(["list", "represents"]) == 0
    assert capsys.readouterr().out == represents_table()
