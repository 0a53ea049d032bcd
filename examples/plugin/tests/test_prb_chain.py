"""Tests of the example plug-in trunk-workbench-prb: its model against independent references, its
declared capabilities against what the model enforces, its rows and its preset's sources.

Run from the repository root with the plug-in importable, e.g. installed (``pip install examples/plugin``)
or ``PYTHONPATH=.:examples/plugin/src python -m pytest -q examples/plugin/tests``; the workbench's
``tests/test_plugins.py`` runs it that way.
"""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest

from trunk_workbench_prb import chain, preset, rows
from workbench import registry
from workbench.models import SolverOptions
from workbench.reference.elastica import clamped_elastica
from workbench.robot import LoadCase, TendonActuation

L = 0.4


def _rod(**kw):
    return preset.prb_niti_pair(n_sections=1, section_length=L, **kw)


def _orders(errors):
    """Observed orders between successive doublings of the link count."""
    e = np.abs(np.asarray(errors))
    return np.log2(e[:-1] / e[1:])


def test_tendon_bending_turns_exactly_like_cc_and_its_tip_converges_at_order_2():
    from workbench.models import get_model

    robot = preset.prb_niti_pair()  # two sections: the inner section carries both pairs' moments
    load = LoadCase(actuation=TendonActuation("tension", (2.0, 0.0, 1.0, 0.0)))
    cc = get_model("cc")(robot, load, SolverOptions())
    errors = []
    for n in (4, 8, 16, 32):
        res = chain.run(robot, load, SolverOptions(n_elements=n))
        assert np.allclose(res.tip_frame[:3, :3], cc.tip_frame[:3, :3], atol=1e-12, rtol=0)
        errors.append(np.linalg.norm(res.tip_position - cc.tip_position))
    assert np.all(np.abs(_orders(errors) - 2.0) < 0.05), errors


@pytest.mark.parametrize("alpha,tabulated", [(1.0, 0.30172), (3.0, 0.60325)])
def test_tip_force_converges_at_order_2_to_the_elastica(alpha, tabulated):
    robot = _rod()
    ei = robot.sections[0].cross_section.EI
    force = alpha * ei / L**2
    exact = clamped_elastica(L, ei, tip_force=(0.0, force), stations=2).tip[1] / L
    assert abs(exact - tabulated) < 1e-5  # the reference reproduces the facts note's table
    tips = [chain.run(robot, LoadCase(tip_force=(force, 0.0, 0.0)), SolverOptions(n_elements=n)).tip_position[0] / L
            for n in (8, 16, 32, 64)]
    assert np.all(np.abs(_orders(np.subtract(tips, exact)) - rows.MODEL.order) < 0.05), tips
    assert abs(tips[-1] - exact) < 1e-4


def test_an_oblique_tip_force_and_a_tip_torque_converge_at_order_2_to_the_elastica():
    """Signs and directions: base (x, z) is the elastica's (b, a); a torque about base +y turns z towards x."""
    robot = _rod()
    ei = robot.sections[0].cross_section.EI
    force, torque = np.array([0.8, 0.0, -1.5]) * ei / L**2, 0.7 * ei / L
    ref = clamped_elastica(L, ei, tip_force=(force[2], force[0]), tip_moment=torque, stations=2).tip
    exact = np.array([ref[1], 0.0, ref[0]])
    errors = [np.linalg.norm(chain.run(robot, LoadCase(tip_force=tuple(force), tip_torque=(0.0, torque, 0.0)),
                                       SolverOptions(n_elements=n)).tip_position - exact) for n in (8, 16, 32, 64)]
    assert np.all(np.abs(_orders(errors) - 2.0) < 0.1), errors
    assert errors[-1] < 2e-4 * L


def test_self_weight_converges_at_order_2_to_the_elastica():
    mu = _rod().sections[0].cross_section.mass_per_length
    ei = _rod().sections[0].cross_section.EI
    g = 4.0 * ei / (mu * L**3)  # gravity parameter gamma = q L^3 / EI = 4: delta / L = 0.425159 (facts note)
    robot = _rod(gravity=g, base_orientation="horizontal")
    exact = -clamped_elastica(L, ei, distributed_load=(0.0, -mu * g), stations=2).tip[1] / L
    assert abs(exact - 0.425159) < 1e-5
    tips = [-chain.run(robot, LoadCase(), SolverOptions(n_elements=n)).tip_position[0] / L for n in (8, 16, 32, 64)]
    assert np.all(np.abs(_orders(np.subtract(tips, exact)) - 2.0) < 0.05), tips


def test_disk_weights_act_at_the_disks():
    """Heavy disks only (massless rod): small deflection equals Euler-Bernoulli's sum of point loads,
    ``sum P a^2 (3 L - a) / (6 EI)`` for loads ``P`` at ``a``, to the chain's discretisation error."""
    robot = _rod(density=1e-9, disk_mass=1e-4, gravity=9.81, base_orientation="horizontal")
    ei = robot.sections[0].cross_section.EI
    a = robot.disk_stations()
    linear = float(np.sum(1e-4 * 9.81 * a**2 * (3 * L - a) / (6 * ei)))
    tip = -chain.run(robot, LoadCase(), SolverOptions(n_elements=80)).tip_position[0]
    assert abs(tip - linear) < 2e-3 * linear, (tip, linear)


#: (what, case) the model does not represent: each is declared (validate refuses it) and refused by run
REFUSED = [
    ("dynamic", dict(load=dict(analysis="dynamic", duration=0.1))),
    ("length mode", dict(act=("length", (-1e-3, 0.0)))),
    ("eyelets", dict(tendon_model="eyelets")),
    ("off-plane tendons", dict(robot=dict(first_angle=math.pi / 2))),
    ("tapered tendons", dict(robot=dict(offset_tip=5e-3))),
    ("tip force along y", dict(load=dict(tip_force=(0.0, 0.1, 0.0)))),
    ("tip torque about z", dict(load=dict(tip_torque=(0.0, 0.0, 0.01)))),
    ("gravity along base y", dict(robot=dict(rotate=True))),
    ("payload offset", dict(robot=dict(payload_offset=(0.01, 0.0, 0.0)))),
]


def _case(robot=None, load=None, act=("tension", (1.0, 0.0)), tendon_model="continuum"):
    from workbench.robot import Payload, Robot, Section, TendonGroup

    kw = dict(robot or {})
    base = _rod(gravity=9.81)
    group = TendonGroup.evenly_spaced(2, 0.01, 1.48e4, kw.get("first_angle", 0.0), offset_tip=kw.get("offset_tip"))
    sec = base.sections[0]
    rotation = ((1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 1.0, 0.0)) if kw.get("rotate") else base.base_rotation
    robot = Robot(sections=(Section(sec.length, sec.cross_section, group, sec.n_disks, sec.disk_mass),),
                  gravity=base.gravity, base_rotation=rotation,
                  payload=Payload(0.01, kw.get("payload_offset", (0.0, 0.0, 0.0))))
    return robot, LoadCase(actuation=TendonActuation(*act), **(load or {})), \
        SolverOptions(n_elements=8, tendon_model=tendon_model)


@pytest.mark.parametrize("what,case", REFUSED, ids=[r[0] for r in REFUSED])
def test_each_declared_limit_is_declared_and_enforced(what, case):
    """The conformance test of a model plug-in: ``validate`` refuses exactly what ``run`` refuses."""
    from workbench.study.capabilities import case_features, unsupported

    robot, load, options = _case(**case)
    f = case_features(robot, load, {"robot": {}, "load": {}}, {"tendon_model": options.tendon_model})
    assert unsupported("prb_chain", rows.MODEL.capabilities, f), what
    with pytest.raises(ValueError, match="^prb_chain: planar static chain, cannot represent") as e:
        chain.run(robot, load, options)
    assert "\n" not in str(e.value)


def test_a_supported_case_passes_validation_and_runs():
    from workbench.study.capabilities import case_features, unsupported

    robot, load, options = _case(load=dict(tip_force=(0.05, 0.0, -0.02), tip_torque=(0.0, 0.001, 0.0)))
    f = case_features(robot, load, {"robot": {}, "load": {}}, {"tendon_model": "continuum"})
    assert unsupported("prb_chain", rows.MODEL.capabilities, f) == []
    res = chain.run(robot, load, options)
    assert res.solver.converged and res.positions.shape == (options.n_stations, 3)
    assert np.allclose(res.positions[:, 1], 0.0) and res.length_change == 0.0


def test_rows_have_the_built_in_row_types_and_resolve():
    assert type(rows.MODEL) is registry.ROW_TYPES["models"] and type(rows.PRESET) is registry.ROW_TYPES["presets"]
    assert registry.resolve(rows.MODEL.target) is chain.run
    assert registry.resolve(rows.PRESET) is preset.prb_niti_pair


def test_every_preset_parameter_has_exactly_one_source():
    params = set(inspect.signature(preset.prb_niti_pair).parameters)
    given, assumed, settings = set(preset.GIVEN), {a.key for a in preset.ASSUMED}, set(preset.SETTINGS)
    assert given | assumed | settings == params
    assert len(given) + len(assumed) + len(settings) == len(params)
