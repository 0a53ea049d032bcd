"""Bad command lines and broken result folders: one line on stderr, exit 2, nothing written or lost."""

from __future__ import annotations

import shutil
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from runs_util import KILL_STUDY, ROOT, env
from workbench.cli import main

EXAMPLE = ROOT / "studies" / "example.toml"


def _one_line(capsys, rc_expected, argv) -> str:
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    err = [x for x in err if not x.startswith("warning: ")]  # the study's plausibility warnings are no error
    assert rc == rc_expected and len(err) == 1, (rc, err)
    assert "Traceback" not in err[0]
    return err[0]


@pytest.fixture(scope="module")
def good_folder(tmp_path_factory):
    """A complete result folder of a small study (CC only: pure numpy)."""
    tmp = tmp_path_factory.mktemp("good")
    study = tmp / "s.toml"
    study.write_text(KILL_STUDY.replace('models = ["cc", "ancf"]', 'models = ["cc"]')
                     .replace("[13.0, 0.0], ", ""))
    assert main(["run", str(study), "--out", str(tmp / "good"), "--in-process", "--no-report", "--progress",
                 "off"]) == 0
    return study, tmp / "good"


def test_bad_out_paths(tmp_path, capsys):
    (tmp_path / "afile").write_text("x")
    run = ["run", EXAMPLE, "--in-process", "--no-report", "--out"]
    assert _one_line(capsys, 2, run + [tmp_path / "afile"]).endswith("exists and is not a folder")
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "mine.txt").write_text("x")  # a folder of other files: its table would be unreadable
    line = _one_line(capsys, 2, run + [tmp_path / "notes", "--force"])
    assert line.endswith("not empty and not a study result folder (holds mine.txt); choose a new or empty folder")
    assert [p.name for p in (tmp_path / "notes").iterdir()] == ["mine.txt"]
    assert "is a file, not a folder" in _one_line(capsys, 2, run + [tmp_path / "afile" / "sub"])
    assert _one_line(capsys, 2, run + [""]).startswith("--out: empty path")
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        import os

        if os.geteuid() != 0:  # root may write anywhere
            assert "no permission to write" in _one_line(capsys, 2, run + [ro / "x"])
    finally:
        ro.chmod(0o700)
    assert not (tmp_path / "afile" / "sub").exists()


def test_bad_and_unreachable_scheduler_fail_fast_without_a_folder(tmp_path, capsys):
    with socket.socket() as sk:
        sk.bind(("127.0.0.1", 0))
        port = sk.getsockname()[1]
    out = tmp_path / "o"
    t0 = time.monotonic()
    line = _one_line(capsys, 2, ["run", EXAMPLE, "--out", out, "--no-report", "--scheduler", "tcp//nohost"])
    assert line == "--scheduler tcp//nohost: unknown protocol 'tcp//nohost' (use tcp://host:port)" or \
        "not an address" in line or "unknown host" in line, line
    line = _one_line(capsys, 2, ["run", EXAMPLE, "--out", out, "--no-report", "--scheduler",
                                 f"tcp://127.0.0.1:{port}"])
    assert line.startswith(f"--scheduler tcp://127.0.0.1:{port}: nothing answers at 127.0.0.1:{port}")
    assert time.monotonic() - t0 < 20 and not out.exists()


@pytest.mark.slow
def test_a_listening_non_dask_server_is_one_line_and_leaves_no_folder(tmp_path):
    """Something answers TCP but is no Dask scheduler: the client gives up; one line, exit 2, no folder."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen()
    port = srv.getsockname()[1]

    def serve():
        while True:
            try:
                conn, _ = srv.accept()
            except OSError:
                return
            conn.close()

    threading.Thread(target=serve, daemon=True).start()
    out = tmp_path / "o"
    try:
        r = subprocess.run([sys.executable, "-m", "workbench", "run", str(EXAMPLE), "--out", str(out), "--no-report",
                            "--scheduler", f"tcp://127.0.0.1:{port}"], env=env(), cwd=tmp_path, capture_output=True,
                           text=True, timeout=120)
    finally:
        srv.close()
    # the error is one line (the study's own stress warnings, printed before any run, are not errors)
    errors = [ln for ln in r.stderr.strip().splitlines() if not ln.startswith("warning:")]
    assert r.returncode == 2 and len(errors) == 1, r.stderr
    assert "cannot start Dask on tcp://127.0.0.1" in r.stderr and "nothing was run" in r.stderr
    assert not out.exists()


def test_corrupt_manifest_and_part_and_empty_folders(tmp_path, capsys, good_folder):
    study, good = good_folder
    bad_manifest = tmp_path / "bad_manifest"
    bad_manifest.mkdir()
    (bad_manifest / "_manifest.json").write_text("{not json")
    bad_part = tmp_path / "bad_part"
    shutil.copytree(good, bad_part)
    part = sorted(p for p in bad_part.glob("part-*.parquet") if "schema" not in p.name)[0]
    part.write_bytes(part.read_bytes()[:100])
    only_manifest = tmp_path / "only_manifest"
    only_manifest.mkdir()
    shutil.copy(good / "_manifest.json", only_manifest)
    for cmd in ("show", "report"):
        assert "corrupt manifest, not valid JSON" in _one_line(capsys, 2, [cmd, bad_manifest])
        assert _one_line(capsys, 2, [cmd, bad_part]).startswith(f"{part}: unreadable Parquet part")
        assert "no stored rows" in _one_line(capsys, 2, [cmd, only_manifest]) or cmd == "report"
        assert "not a study result folder" in _one_line(capsys, 2, [cmd, tmp_path / "missing"])
    line = _one_line(capsys, 2, ["run", study, "--out", bad_part, "--resume", "--in-process", "--no-report"])
    assert line.startswith(f"{part}: unreadable Parquet part") and "move it out of" in line
    assert part.exists()  # nothing deleted
    line = _one_line(capsys, 2, ["run", study, "--out", bad_manifest, "--resume", "--in-process", "--no-report"])
    assert "corrupt manifest" in line


def test_bad_study_files_are_one_line(tmp_path, capsys):
    non_utf8 = tmp_path / "latin1.toml"
    non_utf8.write_bytes(EXAMPLE.read_bytes() + b"\n# caf\xe9\n")
    assert "not UTF-8 text (byte 0xe9 on line" in _one_line(capsys, 2, ["validate", non_utf8])
    deep = tmp_path / "deep.toml"
    deep.write_text(EXAMPLE.read_text() + "\n[x]\ny = " + "[" * 3000 + "]" * 3000 + "\n")
    assert "nested too deeply" in _one_line(capsys, 2, ["validate", deep])
    assert "is a folder, not a TOML file" in _one_line(capsys, 2, ["validate", tmp_path])
    assert "cannot read file" in _one_line(capsys, 2, ["run", tmp_path / "missing.toml"])
    empty = tmp_path / "empty.toml"
    empty.write_text("")
    assert "the file is empty" in _one_line(capsys, 2, ["validate", empty])


def test_retry_failed_needs_resume(capsys):
    assert "--retry-failed: needs --resume" in _one_line(capsys, 2, ["run", EXAMPLE, "--retry-failed"])


@pytest.mark.parametrize("argv,words", [
    (["run"], "the following arguments are required: study"),
    (["run", EXAMPLE, "--worker", "2"], "unrecognized arguments: --worker 2; did you mean --workers?"),  # no prefix
    (["report", "data/x", "--format", "png"], "unrecognized arguments: --format png; did you mean --formats?"),
    (["run", EXAMPLE, "--workers", "two"], "invalid int value: 'two'"),
    (["run", EXAMPLE, "--workers", "0", "--no-report"], "--workers: must be >= 1"),
    (["run", EXAMPLE, "--force", "--resume"], "--force: not with --resume"),
    (["run", "nosuchstudy"], "nosuchstudy: no such study file (nor studies/nosuchstudy.toml); studies in studies/"),
    (["validate", "nosuchstudy"], "no such study file"),
    (["validate", "studies"], "studies: cannot read file: is a folder, not a TOML file"),
    (["validate", ""], "study: empty path"),
    (["validate", "example", "--max-cases", "-3"], "--max-cases: must be >= 1, got -3"),
    (["validate"], "the following arguments are required: study"),
    (["show"], "the following arguments are required: folder"),
    (["show", "reports/nothing_here"], "this looks like a report folder: results are in data/<name>"),
    (["report", "reports/nothing_here"], "this looks like a report folder"),
    (["report", "data/nothing_here", "--formats", "jpg"], "--formats: unknown figure format 'jpg'; choose from png"),
    (["validate", "example", "solver.n_elements"], "override 'solver.n_elements': expected <section>.<key>=<value>"),
    (["validate", "example", "solver.n_elementz=3"], "solver.n_elementz: unknown key; did you mean 'n_elements'?"),
    (["run", "example", "solver.n_elements=0", "--no-report"], "solver.n_elements: must be >= 1"),
    (["run", "example", "studies/quickstart.toml"], "studies/quickstart.toml: a second study file? run takes one"),
    (["list"], "the following arguments are required: topic"),
    (["list", "modles"], "invalid choice: 'modles'"),
    (["frobnicate"], "invalid choice: 'frobnicate'"),
    ([], "the following arguments are required: command"),
])
def test_every_subcommand_on_bad_input_is_one_line_and_exit_2(capsys, monkeypatch, argv, words):
    monkeypatch.chdir(ROOT)  # bare study names are looked up in ./studies
    line = _one_line(capsys, 2, argv)
    assert words in line, line


def test_version_list_and_bare_study_names(capsys, monkeypatch, tmp_path):
    from workbench import __version__

    assert main(["--version"]) == 0 and capsys.readouterr().out.startswith(f"workbench {__version__}")
    assert main(["list", "models"]) == 0
    out = capsys.readouterr().out
    assert "beam3d" in out and "tendons: tension/length via eyelets" in out and "ancf3d" in out
    for topic, name in (("presets", "steel_rod: length=0.8"), ("presets", "rao_2021: Rao et al. 2021"),
                        ("scenarios", "wire_delay: theta="), ("kinds", "series_parallel: ")):
        assert main(["list", topic]) == 0 and name in capsys.readouterr().out
    monkeypatch.chdir(ROOT)
    assert main(["validate", "example"]) == 0
    assert capsys.readouterr().out.startswith("studies/example.toml: ok: study 'example'")
    help_text = subprocess.run([sys.executable, "-m", "workbench", "run", "--help"], env=env(), cwd=ROOT,
                               capture_output=True, text=True).stdout
    assert "Default executor: one case after another in an isolated child process" in help_text
    assert "exit codes:" in help_text and "143" in help_text


def test_force_reruns_into_a_used_folder(tmp_path, capsys, good_folder):
    study, good = good_folder
    out = tmp_path / "o"
    shutil.copytree(good, out)
    run = ["run", study, "--out", out, "--in-process", "--no-report", "--progress", "off"]
    assert "use --resume to continue it, --force to discard them" in _one_line(capsys, 2, run)
    assert main([str(a) for a in run + ["--force"]]) == 0
    from workbench.study import read_manifest

    assert len(read_manifest(out)["runs"]) == 1  # the old run's record went with its results


def test_overrides_are_validated_applied_and_recorded(tmp_path, capsys, good_folder):
    import pandas as pd

    from workbench.study import read_manifest

    study, _ = good_folder
    out = tmp_path / "o"
    argv = ["run", study, "solver.n_stations=7", "study.max_cases=100", "--out", out, "--in-process", "--no-report",
            "--progress", "off"]
    assert main([str(a) for a in argv]) == 0
    df = pd.read_parquet(out)
    assert (df["p.solver.n_stations"] == 7).all() and df["positions"].map(len).eq(7 * 3).all()
    assert read_manifest(out)["runs"][0]["overrides"] == ["solver.n_stations=7", "study.max_cases=100"]
    # the override changes the config hash: resuming without it is refused (it would mix two studies)
    line = _one_line(capsys, 2, ["run", study, "--out", out, "--resume", "--in-process", "--no-report"])
    assert "--resume refused: the study's config hash" in line


def test_show_names_the_study_file_and_the_report_path(capsys, good_folder):
    study, good = good_folder
    assert main(["show", str(good)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == f"study 'killme' ({study}): {good}"
    assert out[-1] == f"  report: none yet in reports/{good.name}"
    assert main(["show", str(good), "--reports-dir", str(good.parent / "elsewhere")]) == 0  # as `run --reports-dir`
    assert capsys.readouterr().out.splitlines()[-1] == f"  report: none yet in {good.parent / 'elsewhere' / good.name}"


def test_a_closed_pipe_is_no_traceback():
    """`workbench list presets | head -1`: the reader leaves early; no traceback on stderr."""
    proc = subprocess.Popen([sys.executable, "-c", "from workbench.cli import main; "
                             "[main(['list', 'presets']) for _ in range(300)]"],  # > the 64 KiB pipe buffer
                            env=env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.readline()
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 0 and "Traceback" not in err, err


def test_validate_takes_several_study_files(capsys, monkeypatch):
    """``workbench validate tests/study/bad_configs/*.toml``: one line per file, exit 2 if any is bad."""
    monkeypatch.chdir(ROOT)
    bad = sorted(Path("tests/study/bad_configs").glob("*.toml"))[:5]
    assert main(["validate", "studies/example.toml", *map(str, bad), "solver.n_elements=8"]) == 2
    out, err = capsys.readouterr()
    assert out.startswith("studies/example.toml: ok: study 'example'") and "(with 1 override(s)" in out
    lines = [x for x in err.splitlines() if not x.startswith("warning: ")]
    assert [x.split(": ")[0] for x in lines] == [str(b) for b in bad], lines


def test_report_never_replaces_what_is_not_a_report(tmp_path, capsys, good_folder):
    """`report data/x --out data/x` deleted the results (exit 0) and `--out README.md` replaced the file."""
    _, good = good_folder
    data = tmp_path / "data" / "x"
    shutil.copytree(good, data)
    stored = sorted(p.name for p in data.iterdir())
    (tmp_path / "notes.md").write_text("mine")
    (tmp_path / "stuff").mkdir()
    (tmp_path / "stuff" / "keep.txt").write_text("mine")
    for out, words in ((data, "holds the results"), (data.parent, "holds the results"),
                       (tmp_path / "notes.md", "exists and is not a folder"),
                       (tmp_path / "stuff", "not empty and holds no report.html")):
        line = _one_line(capsys, 2, ["report", data, "--out", out, "--formats", "png"])
        assert words in line, line
    assert sorted(p.name for p in data.iterdir()) == stored  # the results untouched
    assert (tmp_path / "notes.md").read_text() == "mine" and (tmp_path / "stuff" / "keep.txt").read_text() == "mine"
    other = tmp_path / "data" / "y"
    shutil.copytree(good, other)
    assert "is a study result folder" in _one_line(capsys, 2, ["report", data, "--out", other])
    report = tmp_path / "reports" / "x"
    for _ in range(2):  # a report folder is replaced by the new report
        assert main(["report", str(data), "--out", str(report), "--formats", "png"]) == 0
        assert (report / "report.html").exists()
