"""Open a report in headless Chromium: console messages, the page's self-test line, a screenshot.

``open_report(html, shot)`` loads ``html#selftest`` (see ``workbench/report/assets/selftest.js``)
with the network off, saves a screenshot to ``shot`` and returns ``(selftest dict, other console
lines)``.  A report that works logs exactly one line, the self-test; anything else (an uncaught
error, a failed load) is another console line.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)

_CONSOLE = re.compile(r':CONSOLE:?\(?\d*\)?\]?\s*"(.*)", source: (.*)$')


def open_report(html: Path, shot: Path, width: int = 1280, height: int = 2400, timeout: float = 120) -> tuple[dict, list[str]]:
    with tempfile.TemporaryDirectory() as profile:
        cmd = [
            CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--disable-extensions", "--proxy-server=127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
            f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", "--virtual-time-budget=4000",
            f"--screenshot={shot}", f"--window-size={width},{height}",
            Path(html).resolve().as_uri() + "#selftest",
        ]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        raise RuntimeError(f"chromium exited {proc.returncode}: {proc.stderr[-2000:]}")
    selftest, other = None, []
    for line in proc.stderr.splitlines():
        if ":CONSOLE" not in line:
            continue
        m = _CONSOLE.search(line)
        msg = m.group(1) if m else line
        if msg.startswith("wb-selftest ") and selftest is None:
            selftest = json.loads(msg[len("wb-selftest "):])
        else:
            other.append(line)
    return selftest or {}, other
