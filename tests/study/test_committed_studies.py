"""Every committed study file validates (exit 0) with the code it is committed with.

Guards the interaction of independently written checks and studies: e.g. the models'
capability declarations (issue 16) must not refuse a study whose kind computes its rows with
its own tasks (the grasp kind's fluidic scoop puts chambers at +-120 deg).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from workbench.cli import main

STUDIES = sorted((Path(__file__).parents[2] / "studies").glob("*.toml"))


def test_there_are_committed_studies():
    assert len(STUDIES) >= 8


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_committed_study_validates(path, capsys):
    rc = main(["validate", str(path)])
    out, err = capsys.readouterr()
    assert rc == 0, err
    assert "ok: study" in out, out


@pytest.mark.parametrize("path", STUDIES, ids=[p.stem for p in STUDIES])
def test_committed_study_validates_with_an_override(path, capsys):
    """``solver.n_elements=8`` applies to every committed study, or ``validate`` says in one line why not."""
    rc = main(["validate", str(path), "solver.n_elements=8"])
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    if rc == 0:
        assert "(with 1 override(s): solver.n_elements=8)" in out, out
    else:
        assert rc == 2 and len(err.strip().splitlines()) == 1 and "n_elements" in err, err
