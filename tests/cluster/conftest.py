"""The single-node SLURM cluster of the cluster tests (``local_slurm``), started here when none is running.

CI (``.ci/run``) starts one with ``.ci/slurm-up`` and exports its ``SLURM_CONF`` (and
``WORKBENCH_REQUIRE_SLURM=1``: there a cluster that does not answer fails the tests instead of
skipping them).  Elsewhere the fixture starts a private cluster in a temporary folder on free ports
(``tests/cluster/slurm-local.sh``) and stops it afterwards, so parallel test sessions do not share
one; it skips, saying why, where SLURM cannot start (not installed, not root, daemons failing).
"""

from __future__ import annotations

import os
import random
import shutil
import socket
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).parent
SCRIPT = HERE / "slurm-local.sh"


def _answers(conf: str) -> bool:
    env = dict(os.environ, SLURM_CONF=conf)
    try:
        r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], env=env, capture_output=True, text=True, timeout=15)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return r.returncode == 0 and r.stdout.split()[:1] in (["idle"], ["mixed"], ["allocated"])


def _free_port_pair() -> int:
    for _ in range(200):
        p = random.randint(20000, 40000)
        try:
            for q in (p, p + 1):
                with socket.socket() as s:
                    s.bind(("", q))
        except OSError:
            continue
        return p
    raise RuntimeError("no free port pair")


def _cannot(reason: str):
    if os.environ.get("WORKBENCH_REQUIRE_SLURM"):
        pytest.fail(f"SLURM is required here (WORKBENCH_REQUIRE_SLURM) but {reason}")
    pytest.skip(f"no SLURM test cluster: {reason}")


@pytest.fixture(scope="session")
def local_slurm(tmp_path_factory):
    """``{"SLURM_CONF": path}`` of a running single-node SLURM cluster (partition ``debug``)."""
    conf = os.environ.get("SLURM_CONF")
    if conf and _answers(conf):
        yield {"SLURM_CONF": conf}
        return
    if conf and os.environ.get("WORKBENCH_REQUIRE_SLURM"):
        _cannot(f"the cluster of SLURM_CONF={conf} does not answer")
    if shutil.which("sbatch") is None or not (shutil.which("slurmctld") or Path("/usr/sbin/slurmctld").exists()):
        _cannot("SLURM is not installed (Debian packages slurm-wlm and munge; .ci/slurm-up installs them)")
    if os.geteuid() != 0:
        _cannot("starting a local SLURM cluster needs root (slurmd and munged run as root in this setup)")
    d = tmp_path_factory.mktemp("slurm")
    env = dict(os.environ, WORKBENCH_SLURM_DIR=str(d), WORKBENCH_SLURM_PORT=str(_free_port_pair()))
    r = subprocess.run(["bash", str(SCRIPT), "up"], env=env, capture_output=True, text=True, timeout=180)
    if r.returncode != 0:
        subprocess.run(["bash", str(SCRIPT), "down"], env=env, capture_output=True, timeout=60)
        last = (r.stderr.strip().splitlines() or ["(no message)"])[0]
        _cannot(f"the local cluster did not start: {last}")
    try:
        yield {"SLURM_CONF": str(d / "slurm.conf")}
    finally:
        subprocess.run(["bash", str(SCRIPT), "down"], env=env, capture_output=True, timeout=60)
