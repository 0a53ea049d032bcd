"""Bad command lines and broken result folders: one line on stderr, exit 2, nothing written or lost."""

from __future__ import annotations

import shutil
import socket
import subprocess
import sys
import threading
import time

import pytest

from runs_util import KILL_STUDY, ROOT, env
from workbench.cli import main

EXAMPLE = ROOT / "studies" / "example.toml"


def _one_line(capsys, rc_expected, argv) -> str:
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
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
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
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
