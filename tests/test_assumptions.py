"""workbench/assumptions.py: every preset, scenario and study kind declares its assumptions as one kind of data."""

from __future__ import annotations

import importlib
import types

import pytest

from workbench import registry
from workbench.assumptions import Assumption, declared_assumptions

TARGETS = sorted({*registry.PRESETS.values(), *registry.SCENARIOS.values(), *(k.target for k in registry.KINDS.values())})


@pytest.mark.parametrize("target", TARGETS)
def test_every_registered_module_declares_assumption_entries_with_a_source(target):
    module = importlib.import_module(target.partition(":")[0])
    declared = declared_assumptions(module)
    assert all(a.key and a.source.strip() for a in declared), target
    assert len({a.key for a in declared}) == len(declared), f"{target}: an assumption is declared twice"


def test_a_module_without_assumptions_declares_none_and_a_dict_is_refused():
    assert declared_assumptions(types.ModuleType("plain")) == ()
    old = types.ModuleType("old_style")
    old.ASSUMED = {"move_time": "4 s"}
    with pytest.raises(TypeError, match="old_style.ASSUMED must hold Assumption entries"):
        declared_assumptions(old)


def test_an_assumption_is_frozen():
    a = Assumption("robot.k", "assumed")
    with pytest.raises(AttributeError):
        a.key = "robot.j"  # type: ignore[misc]
    assert (a.what, a.value) == ("", "")
