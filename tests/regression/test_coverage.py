"""Every study has a small version and a golden, and every golden / small study has a study.

The set of stems of ``studies/*.toml`` must equal the stems of ``tests/regression/golden/*.csv``
and of ``tests/regression/studies/*.toml``.  ``studies/example.toml`` (the annotated format
example, not a research study) is the one explicit exception.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.regression.golden import GOLDEN_DIR, STUDIES_DIR

pytestmark = pytest.mark.regression

ROOT = Path(__file__).resolve().parents[2]
EXEMPT = {"example"}  # studies/example.toml: format example, no golden


def _stems(folder: Path, pattern: str) -> set[str]:
    return {p.stem for p in folder.glob(pattern)}


def test_every_study_has_a_golden_and_a_small_study():
    studies = _stems(ROOT / "studies", "*.toml") - EXEMPT
    goldens = _stems(GOLDEN_DIR, "*.csv")
    small = _stems(STUDIES_DIR, "*.toml")
    assert studies, "no studies found"
    problems = []
    problems += [f"studies/{s}.toml has no golden tests/regression/golden/{s}.csv" for s in sorted(studies - goldens)]
    problems += [f"studies/{s}.toml has no small study tests/regression/studies/{s}.toml" for s in sorted(studies - small)]
    problems += [f"golden {s}.csv has no study studies/{s}.toml" for s in sorted(goldens - studies)]
    problems += [f"small study {s}.toml has no study studies/{s}.toml" for s in sorted(small - studies)]
    problems += [f"{s}: exempt study has a golden or small study" for s in sorted(EXEMPT & (goldens | small))]
    assert not problems, "\n".join(problems)


def _models(path: Path) -> tuple[str, ...]:
    """The models every case of the study at ``path`` writes a row for (its kind decides)."""
    from workbench.study import get_kind, kind_of

    kind = get_kind(kind_of(path))
    return kind.models(kind.load(path))


def test_small_studies_use_the_full_studys_model_list():
    for p in sorted(STUDIES_DIR.glob("*.toml")):
        full = ROOT / "studies" / p.name
        if full.exists():
            a = _models(p)
            b = _models(full)
            assert a == b, f"{p.name}: small study models {a} differ from the full study's {b}"
