"""Spring-link package layout: imports without Exudyn, the chain hooks, the static load ramp's steps."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from workbench.models.result import ModelFailure, SolverInfo, SolverOptions
from workbench.physics.spring_link import SpringLinkParams, run
from workbench.physics.spring_link.driver import static_ramp
from workbench.robot import LoadCase
from workbench.robot.presets import build_preset


def test_package_imports_without_exudyn():
    """The study layer imports spring-link helpers; Exudyn is imported only when a chain is built."""
    code = ("import sys, workbench.physics.spring_link, workbench.physics.spring_link.geometry, "
            "workbench.physics.spring_link.tree; print('exudyn' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_every_chain_provides_the_hooks():
    from workbench.physics.spring_link.chain import Chain
    from workbench.physics.spring_link.planar import PlanarChain
    from workbench.physics.spring_link.spatial import SpatialChain
    from workbench.physics.spring_link.tree import TreeChain

    for cls in (PlanarChain, SpatialChain, TreeChain):
        assert issubclass(cls, Chain)
        # the 3-D rigid bodies carry continuum tendons as ropes only (Chain._continuum_ropes)
        hooks = ("_build", "_eyelet_marker") + (() if cls is SpatialChain else ("_continuum_items", "_set_continuum"))
        for hook in hooks:
            assert getattr(cls, hook) is not getattr(Chain, hook), (cls.__name__, hook)
    assert PlanarChain.link_states is not Chain.link_states and SpatialChain.link_frames is not Chain.link_frames
    assert TreeChain.link_states is not Chain.link_states and TreeChain.link_frames is not Chain.link_frames
    assert PlanarChain.rigid_bodies and SpatialChain.rigid_bodies and not TreeChain.rigid_bodies


def test_ramp_policies():
    from workbench.physics._stepping import RampPolicy
    from workbench.physics.spring_link.driver import _STATIC_RAMP
    from workbench.physics.spring_link.tree import _TIP_RAMP

    # max_motion: the load-path check of issue 28 halves a first step that curls the chain
    assert _STATIC_RAMP == RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="one", min_increment=1e-6,
                                      max_motion=2.0)
    assert _TIP_RAMP == RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="one", min_increment=None)


# The step sequences pinned below were checked against the code before the package existed.
def _chain(max_load_steps=200):
    from workbench.physics.spring_link.geometry import chain_geometry_from_robot
    from workbench.physics.spring_link.planar import PlanarChain

    robot = build_preset("steel_rod")
    load = LoadCase(tip_torque=(0.0, 5.0, 0.0))
    opts = SolverOptions(n_elements=4, max_load_steps=max_load_steps)
    return PlanarChain(robot, load, opts, chain_geometry_from_robot(robot, 4)), opts


def _recording_apply(model, fail):
    import exudyn as exu

    trials = []

    def apply(lam):
        trials.append(lam)
        if fail(lam, trials):
            raise exu.SolverError("injected failure")
        model.set_external(lam)
        model.set_tendons(np.zeros(len(model.tendons)), lam)

    return apply, trials


def test_static_ramp_halves_on_failure_and_doubles_after_each_success():
    model, opts = _chain()
    # the first two trials above 0.3 fail: 1 (x), 0.5 (x), 0.25, 0.75, 1
    apply, trials = _recording_apply(model, lambda lam, t: lam > 0.3 and sum(x > 0.3 for x in t) <= 2)
    steps, its = static_ramp(model, opts, SpringLinkParams(), apply)
    assert trials == [1.0, 0.5, 0.25, 0.75, 1.0]
    assert steps == 5 and its > 0
    # the failed trials left no trace: the result is the one of a direct solve
    direct = run(model.robot, model.load, opts)
    assert np.abs(model.result(SolverInfo(True)).positions - direct.positions).max() < 1e-9


def test_static_ramp_failures_keep_their_messages():
    model, opts = _chain()
    apply, trials = _recording_apply(model, lambda lam, t: True)
    with pytest.raises(ModelFailure, match=r"^spring_link: static solve failed near load factor 0$"):
        static_ramp(model, opts, SpringLinkParams(), apply)
    assert trials[:3] == [1.0, 0.5, 0.25] and len(trials) == 20  # halved 20 times: 2**-20 < 1e-6
    model, opts = _chain(max_load_steps=3)
    apply, trials = _recording_apply(model, lambda lam, t: lam > 0.3)
    # on the rigid-body chain (``PlanarChain``) the message names the numerical cause and the solver key
    with pytest.raises(ModelFailure, match=r"^spring_link: static load ramp exceeded options.max_load_steps=3 "
                                           r"\(reached load factor 0\.25\); the rigid-body chain's static Newton "
                                           r".*solver\.spring_link_backend = \"tree\" or \"auto\"\)$"):
        static_ramp(model, opts, SpringLinkParams(), apply)
    assert trials == [1.0, 0.5, 0.25]


def test_static_ramp_propagates_a_non_positive_rest_length():
    model, opts = _chain()
    calls = []

    def apply(lam):
        calls.append(lam)
        raise ModelFailure("spring_link: tendon rest length -0.1 m <= 0 (command -0.9 m too short)")

    with pytest.raises(ModelFailure, match="rest length"):
        static_ramp(model, opts, SpringLinkParams(), apply)
    assert calls == [1.0]
