"""Plug-ins by entry points (issue 29, ``docs/plugins.md``).

1. Discovery, in this process, with small distributions written to a temporary folder on ``sys.path``
   (a ``<name>-<version>.dist-info`` folder with ``METADATA`` and ``entry_points.txt`` is what an
   installed package is to :mod:`importlib.metadata`): a plug-in row is used wherever a built-in row
   is; a name registered twice is one error naming both packages; a broken entry point is one
   warning line naming its package and entry point while the built-ins keep working.
2. The example plug-in ``examples/plugin`` (trunk-workbench-prb), installed by pip into a temporary
   folder (``--no-deps --no-build-isolation --no-index``: offline, nothing into the environment):
   its own tests pass; ``workbench list`` names its package; its study validates and runs under the
   default executor (an isolated child process per case) and under a Dask LocalCluster (two worker
   processes), with the same rows -- every process finds the plug-in the same way.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from workbench import registry
from workbench.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "plugin"


@pytest.fixture
def plugins(tmp_path, monkeypatch):
    """``install(dist, version, entry_points, modules)``: a distribution in ``tmp_path`` on ``sys.path``;
    discovery looks again after each install and after the test."""
    monkeypatch.syspath_prepend(str(tmp_path))

    def install(dist: str, version: str, entry_points: dict[str, dict[str, str]], modules: dict[str, str]) -> None:
        for name, text in modules.items():
            (tmp_path / f"{name}.py").write_text(textwrap.dedent(text), encoding="utf-8")
        info = tmp_path / f"{dist.replace('-', '_')}-{version}.dist-info"
        info.mkdir()
        (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: {version}\n", encoding="utf-8")
        (info / "entry_points.txt").write_text("".join(
            f"[trunk_workbench.{group}]\n" + "".join(f"{k} = {v}\n" for k, v in rows.items())
            for group, rows in entry_points.items()), encoding="utf-8")
        registry.discover.cache_clear()

    yield install
    registry.discover.cache_clear()


ROWS = """
    from workbench.registry import ModelInfo

    MODEL = ModelInfo("{module}:run", "Fake")
    PRESET = "{module}:preset"
    SCENARIO = "{module}:scenario"


    def run(robot, load, options):
        raise NotImplementedError


    def preset(*, length=0.5):
        from workbench.robot.presets import build_preset

        return build_preset("steel_rod", length=length)


    def scenario(robot, *, tension=1.0):
        return {{"mode": "tension", "tensions": [tension] + [0.0] * (robot.n_tendons - 1)}}
"""


def test_a_plugin_row_is_used_wherever_a_built_in_row_is(plugins):
    from workbench.models import get_model, model_names
    from workbench.robot.presets import build_preset, preset_names
    from workbench.study.scenarios import SCENARIOS

    plugins("fake-plug", "1.2", {"models": {"fake": "fakeplug_rows:MODEL"}, "presets": {"fake_rod": "fakeplug_rows:PRESET"},
                                 "scenarios": {"fake_pull": "fakeplug_rows:SCENARIO"}},
            {"fakeplug_rows": ROWS.format(module="fakeplug_rows")})
    models = registry.table("models")
    assert list(models)[:len(registry.MODELS)] == list(registry.MODELS) and list(models)[-1] == "fake"
    assert registry.package("models", "fake") == "fake-plug 1.2" and registry.package("models", "cc") == "built-in"
    assert "fake" in model_names() and get_model("fake").__module__ == "fakeplug_rows"
    assert "fake_rod" in preset_names() and build_preset("fake_rod", length=0.3).length == pytest.approx(0.3)
    assert "fake_pull" in SCENARIOS and SCENARIOS["fake_pull"](build_preset("fake_rod"))["tensions"] == [1.0, 0.0]


def test_a_name_registered_twice_is_one_error_naming_both_packages(plugins, capsys):
    plugins("fake-plug", "1.2", {"models": {"cc": "fakeplug_twice:MODEL"}},
            {"fakeplug_twice": ROWS.format(module="fakeplug_twice")})
    with pytest.raises(registry.PluginError) as e:
        registry.table("models")
    assert str(e.value) == ("trunk_workbench.models: 'cc' is registered twice, by the workbench (built-in) and by "
                            "plug-in fake-plug 1.2 (entry point trunk_workbench.models:cc); uninstall or rename one")
    for args in (["list", "models"], ["validate", str(ROOT / "studies" / "quickstart.toml")]):
        assert main(args) == 2
        assert capsys.readouterr().err.splitlines() == [str(e.value)], args
    assert registry.table("presets") == registry.PRESETS  # other groups are not affected


def test_two_plugins_registering_one_name_are_named_both(plugins):
    plugins("first-plug", "1.0", {"presets": {"twin": "twin_a:PRESET"}}, {"twin_a": ROWS.format(module="twin_a")})
    plugins("second-plug", "2.0", {"presets": {"twin": "twin_b:PRESET"}}, {"twin_b": ROWS.format(module="twin_b")})
    with pytest.raises(registry.PluginError, match=r"'twin' is registered twice, by plug-in (first|second)-plug "):
        registry.table("presets")
    with pytest.raises(registry.PluginError) as e:
        registry.table("presets")
    assert "first-plug 1.0" in str(e.value) and "second-plug 2.0" in str(e.value) and "\n" not in str(e.value)


def test_a_broken_plugin_is_one_warning_line_each_and_the_built_ins_keep_working(plugins, capsys):
    plugins("broken-plug", "0.1", {"models": {"gone": "no_such_module_xyz:MODEL", "wrong": "brokenplug_rows:PRESET"},
                                   "kinds": {"crash": "brokenplug_crash:KIND"}},
            {"brokenplug_rows": ROWS.format(module="brokenplug_rows"), "brokenplug_crash": "raise RuntimeError('boom')\n"})
    problems = registry.discover().problems
    assert problems == (
        "plug-in broken-plug 0.1: entry point trunk_workbench.models:gone = 'no_such_module_xyz:MODEL' cannot be "
        "loaded (ModuleNotFoundError: No module named 'no_such_module_xyz'); ignored",
        "plug-in broken-plug 0.1: entry point trunk_workbench.models:wrong = 'brokenplug_rows:PRESET' is a str, not a "
        "ModelInfo (the row type of trunk_workbench.models); ignored",
        "plug-in broken-plug 0.1: entry point trunk_workbench.kinds:crash = 'brokenplug_crash:KIND' cannot be loaded "
        "(RuntimeError: boom); ignored")
    assert registry.table("models") == registry.MODELS and registry.table("kinds") == registry.KINDS
    assert main(["list", "kinds"]) == 0
    out, err = capsys.readouterr()
    assert err.splitlines() == [f"warning: {p}" for p in problems] and "sweep: " in out


def test_unknown_group_is_named():
    with pytest.raises(KeyError, match="unknown registry group 'model'; groups: presets, models, scenarios"):
        registry.table("model")


# ---------------------------------------------------------------------------------------------
# the example plug-in, installed into a temporary folder
# ---------------------------------------------------------------------------------------------
def _can_build_wheels() -> str:
    """Why pip cannot build the example here without an index ('' when it can)."""
    import importlib.util

    if importlib.util.find_spec("setuptools") is None:
        return "setuptools is not installed"
    try:
        import setuptools.command.bdist_wheel  # noqa: F401 - setuptools >= 70.1 builds wheels itself
    except ImportError:
        if importlib.util.find_spec("wheel") is None:
            return "setuptools < 70.1 without the 'wheel' package"
    return ""


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The example plug-in installed by pip into a temporary folder (built from a copy: no build files in the tree)."""
    why = _can_build_wheels()
    if why:
        pytest.skip(f"cannot build the example plug-in offline: {why} (pip install -e '.[test]' brings setuptools)")
    tmp = tmp_path_factory.mktemp("plugin")
    src = shutil.copytree(EXAMPLE, tmp / "src", ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    target = tmp / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "--no-index",
                        "--disable-pip-version-check", "--quiet", "--target", str(target), str(src)],
                       capture_output=True, text=True, timeout=300, cwd=tmp)
    assert r.returncode == 0, r.stdout + r.stderr
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(target)]))
    return tmp, env


def _workbench(env, cwd, *args, timeout=600):
    return subprocess.run([sys.executable, "-m", "workbench", *args], env=env, cwd=cwd, capture_output=True,
                          text=True, timeout=timeout)


def test_the_example_plugins_own_tests_pass(installed):
    tmp, env = installed
    # -o addopts=: in one process (not the workbench's -n 2, from the pyproject.toml found above the example)
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-o", "addopts=",
                        str(EXAMPLE / "tests")],
                       env=env, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "18 passed" in r.stdout, r.stdout[-500:]


def test_workbench_list_names_the_plugins_package(installed):
    tmp, env = installed
    r = _workbench(env, tmp, "list", "models")
    assert r.returncode == 0 and r.stderr == "", r.stderr
    line = next(x for x in r.stdout.splitlines() if x.startswith("prb_chain "))
    assert line.endswith("[trunk-workbench-prb 0.1.0]") and "PRB chain: planar; tendons: tension via continuum" in line
    r = _workbench(env, tmp, "list", "presets")
    assert any(x.startswith("prb_niti_pair: section_length=0.2,") and x.endswith("[trunk-workbench-prb 0.1.0]")
               for x in r.stdout.splitlines()), r.stdout
    assert "steel_rod: length=0.8" in r.stdout and "[built-in]" in r.stdout


def test_the_example_study_runs_the_same_under_the_default_executor_and_dask(installed):
    tmp, env = installed
    study = str(EXAMPLE / "studies" / "prb_chain.toml")
    r = _workbench(env, tmp, "validate", study)
    assert r.returncode == 0 and "ok: study 'prb_chain', 4 cases x 2 models (cc, prb_chain)" in r.stdout, r.stderr
    runs = {"isolated": ["--out", str(tmp / "isolated")],
            "dask": ["--out", str(tmp / "dask"), "--workers", "2", "--no-cache"]}
    for name, args in runs.items():
        r = _workbench(env, tmp, "run", study, *args, "--no-report", "--progress", "off")
        assert r.returncode == 0, f"{name}: {r.stdout[-2000:]}{r.stderr[-2000:]}"
        assert "ok 4, failed 0" in r.stdout and ("dask" in r.stdout) == (name == "dask"), r.stdout
    import numpy as np

    from workbench import results

    a, b = (results.load(tmp / n).sort_values(["case_id", "model"]).reset_index(drop=True) for n in runs)
    assert list(a["model"]) == ["cc", "prb_chain"] * 4 and (a["status"] == "ok").all()
    for col in ("tip_x", "tip_z", "x.disc_tip_error"):  # the same plug-in code ran in the child and in the workers
        assert np.array_equal(a[col], b[col], equal_nan=True), col
    prb = a[a["model"] == "prb_chain"]
    assert (prb["x.disc_tip_error"] > 0).all()  # its declared order gave it an error bar
