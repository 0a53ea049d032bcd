"""``workbench run --cluster``: the dry run, option errors as one line, a scheduler that refuses jobs.

No batch system is needed: the dry run submits nothing, and the refusing scheduler is a fake
``qsub`` on ``PATH`` (the real SLURM is in ``test_slurm.py``).
"""

from __future__ import annotations

import os
import stat
import textwrap
from pathlib import Path

import pytest

from workbench.cli import main

STUDY = textwrap.dedent("""\
    [study]
    name = "clu"
    models = ["cc"]
    [robot]
    preset = "steel_rod"
    [load]
    tensions = [1.0, 0.0]
    [sweep]
    product = { "load.tensions" = [[1.0, 0.0], [2.0, 0.0], [3.0, 0.0]] }
    """)


@pytest.fixture
def study(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "xdg"))  # no user config from the home folder
    monkeypatch.chdir(tmp_path)
    p = tmp_path / "s.toml"
    p.write_text(STUDY)
    return p


def _run(capsys, *argv):
    rc = main(["run", *map(str, argv)])
    out, err = capsys.readouterr()
    return rc, out, err


def test_dry_run_prints_plan_and_job_script_and_writes_nothing(study, tmp_path, capsys):
    rc, out, err = _run(capsys, study, "--out", tmp_path / "o", "--cluster", "slurm", "--max-jobs", "8",
                        "--cores", "2", "--walltime", "04:00:00", "--partition", "short", "--dry-run")
    assert rc == 0, err
    assert "dry run: study 'clu', 3 cases x 1 models (cc)" in out
    assert "executor: dask-jobqueue slurm: 1-8 jobs (adaptive) x 2 core(s), 2 worker(s), 4GB, walltime 04:00:00" in out
    assert "#SBATCH -p short" in out and "#SBATCH -t 04:00:00" in out and "--nworkers 2" in out
    assert "cluster config: (none: command line and defaults)" in out
    assert "per case: max_case_seconds = 3600 s" in out  # the default; half a 4-h worker's life is more
    assert "on this cluster:" not in out
    assert not (tmp_path / "o").exists()


def test_dry_run_shows_the_case_limit_a_worker_life_allows(study, tmp_path, capsys):
    rc, out, err = _run(capsys, study, "--cluster", "slurm", "--walltime", "01:00:00", "--dry-run")
    assert rc == 0, err
    line = next(ln for ln in out.splitlines() if "on this cluster:" in ln)
    assert "max_case_seconds = 3600 s is more than half a worker's life (3240 s" in line
    assert line.endswith("cases are stopped after 1620 s")


def test_dry_run_reads_the_user_config(study, tmp_path, capsys):
    cfg = tmp_path / "xdg" / "workbench" / "cluster.toml"
    cfg.parent.mkdir(parents=True)
    cfg.write_text('[cluster]\naccount = "lab"\n[cluster.pbs]\nqueue = "workq"\nprologue = ["module load x"]\n')
    rc, out, err = _run(capsys, study, "--cluster", "pbs", "--dry-run")
    assert rc == 0, err
    assert f"cluster config: {cfg}" in out
    assert "#PBS -q workq" in out and "#PBS -A lab" in out and "module load x" in out


@pytest.mark.parametrize("argv, line", [
    (["--jobs", "2"], "--jobs: only with --cluster slurm|pbs|sge|lsf"),
    (["--cluster-config", "c.toml"], "--cluster-config: only with --cluster slurm|pbs|sge|lsf"),
    (["--cluster", "slurm", "--cores", "0"], "--cores: must be >= 1, got 0"),
    (["--cluster", "sge", "--memory", "4 gigs"], "--memory: must be an amount of memory such as '4GB' or '500MB', "
                                                  "got '4 gigs'"),
    (["--cluster", "lsf", "--jobs", "2", "--max-jobs", "4"],
     "--jobs: give either jobs (a fixed number) or min_jobs/max_jobs (adaptive), not both"),
    (["--cluster", "slurm", "--cluster-config", "missing.toml"], "missing.toml: cannot read file"),
])
def test_bad_cluster_options_are_one_line(study, capsys, argv, line):
    rc, out, err = _run(capsys, study, *argv, "--dry-run")
    assert rc == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(line), err


def test_cluster_excludes_the_other_executors(study, capsys):
    rc = main(["run", str(study), "--cluster", "slurm", "--workers", "2"])  # usage errors: one line, exit 2
    err = capsys.readouterr().err
    assert rc == 2 and len(err.strip().splitlines()) == 1, err
    assert "not allowed with argument" in err


def test_missing_submit_command_fails_before_the_folder(study, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path / "empty-bin"))
    rc, out, err = _run(capsys, study, "--out", tmp_path / "o", "--cluster", "lsf", "--no-report")
    assert rc == 2
    assert err.strip() == "--cluster lsf: 'bsub' not found on PATH (run on a login node of the LSF cluster)"
    assert not (tmp_path / "o").exists()


def _fake_qsub(folder: Path) -> None:
    folder.mkdir()
    q = folder / "qsub"
    q.write_text("#!/bin/sh\necho 'qsub: Unknown queue MSG=requested queue not found' >&2\nexit 1\n")
    q.chmod(q.stat().st_mode | stat.S_IEXEC)


def test_refused_job_ends_the_run_with_one_line(study, tmp_path, capsys, monkeypatch):
    """A scheduler without a pre-flight check (PBS) refusing the first job: one line, exit 2, not a 10-minute wait."""
    _fake_qsub(tmp_path / "bin")
    monkeypatch.setenv("PATH", f"{tmp_path / 'bin'}{os.pathsep}{os.environ['PATH']}")
    rc, out, err = _run(capsys, study, "--out", tmp_path / "o", "--cluster", "pbs", "--queue", "nosuch",
                        "--no-report", "--progress", "off")
    assert rc == 2, err
    last = err.strip().splitlines()[-1]
    assert last.startswith("--cluster pbs: a worker job was refused: qsub: Unknown queue"), err
    assert last.endswith("nothing was run") and "Traceback" not in err
    assert not (tmp_path / "o").exists()
