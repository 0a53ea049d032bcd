"""The study package's own layering: validation imports no execution code, and no module imports
``workbench.experiments`` (the study kinds are found through ``workbench.registry.KINDS``)."""

from __future__ import annotations

import ast
from pathlib import Path

STUDY = Path(__file__).resolve().parents[2] / "workbench" / "study"
#: modules that validate or expand a study file
VALIDATION = ("spec", "schema", "checks", "messages", "build", "expand", "params")
#: modules that execute a run
EXECUTION = ("evaluate", "runner", "executors", "store", "session", "kinds", "rows")


def _study_imports(module: str) -> set[str]:
    """Names of the ``workbench.study`` modules (and other workbench modules) ``module`` imports."""
    tree = ast.parse((STUDY / f"{module}.py").read_text(encoding="utf-8"))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1:
                out.add(node.module or "")
                if node.module is None:
                    out.update(a.name for a in node.names)
            elif node.level == 2:
                out.add(f"workbench.{node.module}")
            elif node.module and node.module.startswith("workbench"):
                out.add(node.module)
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.startswith("workbench"))
    return out


def test_validation_imports_no_execution_code():
    bad = {m: sorted(_study_imports(m) & set(EXECUTION)) for m in VALIDATION}
    assert not any(bad.values()), bad


def test_no_study_module_imports_an_experiment():
    bad = {p.stem: sorted(i for i in _study_imports(p.stem) if "experiments" in i) for p in STUDY.glob("*.py")}
    assert not any(bad.values()), bad


def test_every_validation_and_execution_module_exists():
    assert all((STUDY / f"{m}.py").exists() for m in VALIDATION + EXECUTION)

