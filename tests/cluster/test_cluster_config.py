"""``[cluster]`` config files and job options: the malformed corpus, one line per problem; precedence."""

from __future__ import annotations

from pathlib import Path

import pytest

from workbench.study import StudyError
from workbench.study.cluster_config import (
    default_config_path,
    format_walltime,
    load_cluster_config,
    parse_memory,
    parse_walltime,
    resolve_cluster,
)

HERE = Path(__file__).parent
BAD = sorted((HERE / "bad_cluster_configs").glob("*.toml"))


def _expectation(path: Path) -> tuple[str, str]:
    first = path.read_text().splitlines()[0]
    assert first.startswith("# expect: "), f"{path} lacks its '# expect: key | reason' line"
    key, _, reason = first[len("# expect: "):].partition(" | ")
    return key.strip(), reason.strip()


def _resolve_file(path: Path, scheduler: str = "slurm", **overrides):
    return resolve_cluster(scheduler, load_cluster_config(path), str(path), overrides)


def test_corpus_is_large_enough():
    assert len(BAD) >= 30


@pytest.mark.parametrize("path", BAD, ids=[p.stem for p in BAD])
def test_malformed_cluster_config_rejected_with_one_line(path):
    key, reason = _expectation(path)
    with pytest.raises(StudyError) as ei:
        _resolve_file(path)
    problems = ei.value.problems
    assert len(problems) == 1, problems
    line = problems[0]
    assert "\n" not in line
    assert line.startswith(f"{path}: {key}"), line  # names the file and the key
    assert reason in line, line


def test_every_problem_of_a_file_in_one_pass(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text('[cluster]\ncores = 0\nmemory = "lots"\nwalltim = "1"\n[cluster.lsf]\njobs = -1\n')
    with pytest.raises(StudyError) as ei:
        _resolve_file(p)
    assert [ln.split(": ")[1] for ln in ei.value.problems] == [
        "cluster.cores", "cluster.memory", "cluster.walltim", "cluster.lsf.jobs"]


def test_defaults():
    c = resolve_cluster("slurm")
    assert (c.min_jobs, c.max_jobs, c.cores, c.processes, c.memory, c.walltime_seconds) == (1, 1, 1, 1, "2GB", 3600)
    assert (c.queue, c.account, c.source, c.adaptive) == (None, None, None, False)
    assert c.worker_lifetime == 3300 and c.queue_timeout == 600 and c.allowed_failures == 2
    assert resolve_cluster("pbs", overrides={"cores": 4}).memory == "8GB"  # 2 GB per core


def test_file_then_scheduler_table_then_command_line(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text('[cluster]\ncores = 4\nqueue = "short"\naccount = "lab"\nmax_jobs = 10\n'
                 '[cluster.slurm]\nqueue = "debug"\njobs = 3\n[cluster.pbs]\nqueue = "workq"\n')
    s = _resolve_file(p, "slurm")
    assert (s.cores, s.queue, s.account, s.min_jobs, s.max_jobs, s.source) == (4, "debug", "lab", 3, 3, str(p))
    b = _resolve_file(p, "pbs")  # the pbs table's queue, the common scaling: adaptive 1..10
    assert (b.queue, b.min_jobs, b.max_jobs, b.adaptive) == ("workq", 1, 10, True)
    c = _resolve_file(p, "slurm", cores=2, max_jobs=6, min_jobs=2, queue=None)
    assert (c.cores, c.queue, c.min_jobs, c.max_jobs) == (2, "debug", 2, 6)  # CLI scaling replaces the file's


def test_command_line_problems_name_the_option():
    with pytest.raises(StudyError) as ei:
        resolve_cluster("slurm", overrides={"cores": 0, "queue_timeout": -5.0, "walltime": "1 day"})
    assert ei.value.problems == ["--cores: must be >= 1, got 0",
                                 "--queue-timeout: must be > 0.0, got -5",
                                 "--walltime: must be a walltime '[D-]HH:MM:SS' such as '01:00:00', got '1 day'"]
    with pytest.raises(StudyError) as ei:
        resolve_cluster("slurm", overrides={"min_jobs": 4, "max_jobs": 2})
    assert ei.value.problems == ["--min-jobs: must be <= max_jobs (2), got 4"]
    with pytest.raises(StudyError) as ei:
        resolve_cluster("condor")
    assert ei.value.problems == ["--cluster: must be one of slurm, pbs, sge, lsf, got 'condor'"]


def test_unreadable_file_is_one_line(tmp_path):
    with pytest.raises(StudyError) as ei:
        load_cluster_config(tmp_path / "missing.toml")
    assert len(ei.value.problems) == 1 and "cannot read file" in ei.value.problems[0]


def test_default_path_follows_xdg(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    assert default_config_path() == tmp_path / "workbench" / "cluster.toml"


@pytest.mark.parametrize("text, seconds", [("01:00:00", 3600), ("00:30", 1800), ("2-00:00", 172800),
                                           ("36:00:00", 129600), ("1-02:03:04", 93784)])
def test_parse_walltime(text, seconds):
    assert parse_walltime(text) == seconds


def test_walltime_as_each_scheduler_writes_it():
    assert format_walltime(93784, "slurm") == "26:03:04"
    assert format_walltime(93784, "pbs") == "26:03:04"
    assert format_walltime(93784, "lsf") == "26:03"  # LSF: hours:minutes, rounded down
    assert format_walltime(30, "lsf") == "00:01"  # at least a minute


@pytest.mark.parametrize("text, n", [("4GB", 4_000_000_000), ("500MB", 500_000_000), ("1.5 GiB", 1.5 * 2**30),
                                     ("64kB", 64_000)])
def test_parse_memory(text, n):
    assert parse_memory(text) == int(n)
