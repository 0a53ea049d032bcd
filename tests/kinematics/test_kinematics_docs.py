"""Docstring examples run, and every public function has a numpydoc docstring."""

import doctest
import importlib

import pytest

import workbench.kinematics as kin

MODULES = ["workbench.kinematics", "workbench.kinematics.arc"]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    mod = importlib.import_module(name)
    res = doctest.testmod(mod, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0


@pytest.mark.parametrize("name", kin.__all__)
def test_public_api_documented(name):
    obj = getattr(kin, name)
    doc = obj.__doc__ or ""
    assert len(doc) > 40, name
    if callable(obj) and not isinstance(obj, type):
        assert "Returns" in doc and "Parameters" in doc, name
