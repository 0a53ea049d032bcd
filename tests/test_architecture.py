"""The package's layering, measured from the source: who may import whom, sizes, the registry.

Rules (``docs/architecture.md``, "Layers"):

- generic packages never import ``workbench.experiments`` (they find experiment code through the
  string rows of :mod:`workbench.registry`);
- no package imports another package's private names (a ``_name`` module or attribute);
- no import cycle between modules, lazy (function-level) imports included;
- ``workbench/registry.py`` imports nothing from the workbench, and every row resolves;
- no other module reads the registry's built-in constants: rows are read through
  ``registry.table(group)``, so a plug-in row is used wherever a built-in row is;
- files <= 600 lines, functions <= 80 code lines (span minus docstring), module docstrings <= 40 lines.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "workbench"
GENERIC = ("study", "report", "physics", "models", "compare", "kinematics", "robot", "reference", "measure")


def _modules() -> dict[str, tuple[Path, ast.Module]]:
    out = {}
    for p in sorted(PKG.rglob("*.py")):
        rel = p.relative_to(ROOT).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = (p, ast.parse(p.read_text(encoding="utf-8")))
    return out


MODULES = _modules()


def _imports(name: str, path: Path, tree: ast.Module) -> list[tuple[str, list[str], int]]:
    """(target module, imported names, line) for every workbench import, relative ones resolved."""
    out = []
    is_pkg = path.name == "__init__.py"
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, [], node.lineno) for a in node.names if a.name.startswith("workbench")]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if is_pkg else name.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("workbench"):
                out.append((target, [a.name for a in node.names], node.lineno))
    return out


def _package(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def test_generic_packages_never_import_experiments():
    bad = [f"{m}:{line} imports {t}" for m, (p, tree) in MODULES.items() if _package(m) in GENERIC
           for t, names, line in _imports(m, p, tree)
           if t.startswith("workbench.experiments") or (t == "workbench" and "experiments" in names)]
    assert not bad, "\n".join(bad)


def test_no_package_imports_another_packages_private_names():
    bad = []
    for m, (p, tree) in MODULES.items():
        for t, names, line in _imports(m, p, tree):
            if _package(t) == _package(m) or not _package(t):
                continue
            private_module = any(part.startswith("_") for part in t.split(".")[2:])
            private_names = [n for n in names if n.startswith("_")]
            # a private submodule of the target package imported as a name: "from workbench.physics import _exudyn"
            if private_module or private_names:
                bad.append(f"{m}:{line} imports {t} {private_names or ''}".rstrip())
    assert not bad, "\n".join(bad)


def _graph() -> dict[str, set[str]]:
    g: dict[str, set[str]] = {}
    for m, (p, tree) in MODULES.items():
        deps = set()
        for t, names, _ in _imports(m, p, tree):
            for cand in [t] + [f"{t}.{n}" for n in names]:
                if cand in MODULES and cand != m:
                    deps.add(cand)
        g[m] = deps
    return g


def _cycles(g: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan), ignoring a package and its own submodules."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in g[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            related = all(any(o.startswith(x + ".") or x.startswith(o + ".") for o in comp if o != x) for x in comp)
            if len(comp) > 1 and not related:
                out.append(sorted(comp))

    for v in sorted(g):
        if v not in index:
            visit(v)
    return out


def test_no_import_cycles():
    assert _cycles(_graph()) == []


def test_cycle_detector_finds_a_cycle():
    assert _cycles({"workbench.a.x": {"workbench.b.y"}, "workbench.b.y": {"workbench.a.x"}}) == [
        ["workbench.a.x", "workbench.b.y"]]


def test_registry_imports_nothing_from_the_workbench_and_every_row_resolves():
    from workbench import registry

    p, tree = MODULES["workbench.registry"]
    assert _imports("workbench.registry", p, tree) == []
    kinds, figures = registry.table("kinds").values(), registry.table("figures").values()
    targets = [m.target for m in registry.table("models").values() if m.target]
    targets += [*registry.table("presets").values(), *registry.table("scenarios").values()]
    targets += [k.target for k in kinds] + [t for f in figures for t in (f.matches, f.figures)]
    hooks = [t for r in (*kinds, *figures)
             for t in (getattr(r, "units", None), getattr(r, "lines", None), getattr(r, "axes", None)) if t]
    assert all(registry.resolve(t) is not None for t in hooks)
    for t in targets:
        assert callable(registry.resolve(t)) or t.endswith(("SWEEP", "KIND")), t
    with pytest.raises(ValueError):
        registry.resolve("no_colon")


_CONSTANTS = {"MODELS", "PRESETS", "SCENARIOS", "KINDS", "FIGURES"}


def _constant_reads(tree: ast.Module) -> list[int]:
    """Lines that read a built-in table of the registry (``registry.MODELS`` or ``from ..registry import MODELS``)."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr in _CONSTANTS and isinstance(node.value, ast.Name) \
                and node.value.id == "registry":
            out.append(node.lineno)
        elif isinstance(node, ast.ImportFrom) and (node.module or "").endswith("registry") \
                and _CONSTANTS & {a.name for a in node.names}:
            out.append(node.lineno)
    return out


def test_rows_are_read_through_the_registry_table():
    """Every module but the registry reads rows through ``registry.table`` (built-in + plug-ins), never the
    constants (which hold only the built-in rows)."""
    bad = [f"{m}:{line}" for m, (_, tree) in MODULES.items() if m != "workbench.registry"
           for line in _constant_reads(tree)]
    assert bad == []


def test_the_constant_read_detector_finds_both_forms():
    assert _constant_reads(ast.parse("from .. import registry\nx = registry.MODELS.get('cc')")) == [2]
    assert _constant_reads(ast.parse("from ..registry import KINDS as k")) == [1]
    assert _constant_reads(ast.parse("x = registry.table('models')\nfrom ..registry import table")) == []


def test_sizes():
    big, long_funcs, long_docs = [], [], []
    for m, (p, tree) in MODULES.items():
        n = p.read_text(encoding="utf-8").count("\n")
        if n > 600:
            big.append(f"{m}: {n} lines")
        doc = ast.get_docstring(tree, clean=False)
        if doc and doc.count("\n") > 40:
            long_docs.append(f"{m}: docstring {doc.count(chr(10))} lines")
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                d = ast.get_docstring(node, clean=False)
                code = node.end_lineno - node.lineno + 1 - (d.count("\n") + 1 if d else 0)
                if code > 80:
                    long_funcs.append(f"{m}.{node.name}: {code} code lines")
    assert not (big or long_funcs or long_docs), "\n".join(big + long_funcs + long_docs)


def test_no_module_imports_another_modules_underscore_names():
    """What modules share has a public name: no ``from X import _name`` where X is another module (any folder).

    Importing a public name from a module whose file name starts with an underscore (``from ._exudyn import
    quiet_exudyn``) is allowed inside its package; that case is the cross-package rule above.
    """
    bad = [f"{m}:{line} imports {t} {[n for n in names if n.startswith('_') and not n.startswith('__')]}"
           for m, (p, tree) in MODULES.items() for t, names, line in _imports(m, p, tree)
           if t != m and any(n.startswith("_") and not n.startswith("__") for n in names)]
    assert not bad, "\n".join(bad)


def test_the_underscore_rule_sees_a_violation():
    """The scan above flags ``from .x import _y`` in a made-up module (so it can fail)."""
    tree = ast.parse("from .store import _private\nfrom .store import public\n")
    found = [(t, names) for t, names, _ in _imports("workbench.study.fake", PKG / "study" / "fake.py", tree)]
    assert found == [("workbench.study.store", ["_private"]), ("workbench.study.store", ["public"])]
