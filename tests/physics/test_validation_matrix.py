"""The validation matrix of issue 14 (cases and references in :mod:`tests.physics.validation_matrix`).

Every (row, model) cell either solves at two resolutions with the error and observed order its
family promises, or is declared unsupported -- and then the model rejects the case with a clear
error instead of answering.  The default suite keeps one cheap row per model; the rest is slow.
The table in ``docs/models.md`` is printed by ``python -m tests.physics.validation_matrix``.
"""

from __future__ import annotations

import math

import pytest

from workbench.models import get_model
from workbench.models.result import ModelFailure

from tests.physics.validation_matrix import MODEL_ORDER, ROWS, UNSUPPORTED, evaluate, setup

#: Observed order bounds per model family (ANCF: cubic Hermite, ~4; beam3d, spring_link: 2).
ORDER = {"ancf": (3.5, 4.6), "ancf3d": (3.5, 4.6), "beam3d": (1.8, 2.4), "spring_link": (1.8, 2.4)}
#: The one cell run before its asymptotic range (beam3d eyelets at 4 / 8 disks, kappa L = pi: the
#: 4-disk chords pass the backbone axis; 16 disks stall beam3d's Newton): measured order 1.79.
PRE_ASYMPTOTIC = {("planar_tendon", "beam3d"): (1.6, 2.4)}
#: One cheap row per model for the default suite (seconds: measured 0.0 / 1.4 / 3.5 / 0.8 / 0.5 / 0.7).
DEFAULT = {("spatial_tendon", "cc"), ("alpha", "ancf"), ("alpha", "beam3d"), ("alpha", "ancf3d"),
           ("spatial_tendon", "spring_link"), ("planar_tendon", "cosserat")}


def _cells():
    for row in ROWS:
        for model in MODEL_ORDER:
            if (model, row) in UNSUPPORTED:
                continue
            marks = () if (row, model) in DEFAULT else (pytest.mark.slow,)
            yield pytest.param(row, model, id=f"{row}-{model}", marks=marks)


def check_cell(row: str, model: str) -> None:
    """Assert the promise of ``model`` in ``row`` (see the module docstring)."""
    cell = evaluate(row, model)
    coarse, fine = cell.errors
    if model == "cc":  # exact arcs; CC neglects only the tendon compression T/EA (< 1e-5 here)
        assert fine < 1e-5, cell
        return
    if model == "cosserat":  # converged to its residual tolerance, or to the inextensible floor
        assert fine < max(1e-8, cell.floor), cell
        return
    lo, hi = PRE_ASYMPTOTIC.get((row, model), ORDER[model])
    if fine < 1e-12:  # exact (a pure moment on rotational coordinates): at both resolutions
        assert coarse < 1e-12, cell
    elif math.isnan(cell.order):  # at the floor of the inextensible reference: already when coarse
        assert coarse < 10.0 * cell.floor, cell
    else:
        assert lo <= cell.order <= hi, cell
        assert fine < coarse, cell


@pytest.mark.parametrize("row, model", list(_cells()))
def test_cell_converges_at_the_order_of_its_model(row, model):
    check_cell(row, model)


def _rejected():
    for model, row in sorted(k for k in UNSUPPORTED if k[0] != "cc"):
        slow = row == "spatial_tendon_force"  # its reference is a 5 s Cosserat solve
        yield pytest.param(model, row, id=f"{model}-{row}", marks=(pytest.mark.slow,) if slow else ())


@pytest.mark.parametrize("model, row", list(_rejected()))
def test_unsupported_cells_are_rejected_not_answered(model, row):
    """What the table calls unsupported fails at once with a clear error (CC is the exception:
    it answers every case by ignoring loads, which is what CC kinematics means)."""
    case, opts, _ = setup(row, model, 0)
    with pytest.raises((ModelFailure, ValueError)) as err:  # ancf: PlanarModelError(ValueError)
        get_model(model)(case.robot, case.load, opts)
    msg = str(err.value)
    assert msg and "\n" not in msg, msg  # one line naming the key and the reason
