"""Robustness measurements of the study pipeline (issue 19): malformed inputs, kills, concurrent runs.

Not a test module (pytest does not collect it); run from the repository root::

    python -m tests.study.robustness inputs [--quick]    # mutated study files + bad CLI input
    python -m tests.study.robustness kills [--n 10]      # SIGKILL / SIGTERM mid-run, then --resume
    python -m tests.study.robustness concurrent [--n 4]  # two runs into one folder at once

``inputs`` mutates every leaf of every committed study (``studies/*.toml``: wrong type, NaN, inf,
negative, zero, huge, empty or nested lists, ...), adds file-level breakage (non-UTF-8, deep
nesting, syntax errors, missing or unknown sections, a 10^6-case sweep) and bad command lines
(bad ``--out``, corrupt manifest or part files, unknown formats), runs ``workbench`` in-process
on each and counts: rejected with one-line messages (exit 2), accepted (exit 0; listed, to judge
by eye), tracebacks (an exception escaped), slow (over the time budget) and messages of more than
one line for one mistake.  ``kills`` runs a 30-case study of fake 20 ms models
(``tests/study/study_fakes.py``) through the CLI, kills it at seeded random moments, resumes
until done and compares the table with an uninterrupted run bit for bit.  ``concurrent`` starts
two runs into one folder at the same moment and counts trials where exactly one ran and no row
is stored twice.  The counts are what issue 19 asks to report; nothing here asserts.

Last measured (2026-12-02, 2 shared cores): ``inputs``: 1 141 configs tried, 915 rejected with
exit 2, 226 accepted (valid mutations, listed), 0 tracebacks, 0 over the 20 s budget (the 10^6-case
sweep included), 7 with two lines for one mistake, 11 whose line does not name the mutated key
(scenario parameters that make the scenario infeasible: the line names ``scenario``); 21 bad
command lines / broken folders: 21 one line + exit 2, 0 tracebacks.  ``kills --n 10``: 30
interruptions (20 SIGKILL, 10 SIGTERM: 10 of 10 exit 143), every trial completed by ``--resume``:
10 of 10 tables bit-identical to the uninterrupted run, 0 duplicate rows.  ``concurrent --n 4``:
4 of 4 trials exactly one run, the other refused with one line, 0 duplicate rows, 0 tracebacks.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import random
import resource
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
import traceback
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

# ----------------------------------------------------------------------------------------------
# TOML writing (small: the study files are tables of scalars, lists and inline tables)
# ----------------------------------------------------------------------------------------------


def _val(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_val(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{json.dumps(k)} = {_val(x)}" for k, x in v.items()) + " }"
    raise TypeError(type(v))


def to_toml(data: dict) -> str:
    lines = []
    for sec, body in data.items():
        if not isinstance(body, dict):
            lines.append(f"{sec} = {_val(body)}")
            continue
        lines.append(f"[{sec}]")
        for k, v in body.items():
            lines.append(f"{json.dumps(k) if '.' in k else k} = {_val(v)}")
        lines.append("")
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------------------------------------
# mutations
# ----------------------------------------------------------------------------------------------
def _leaf_mutations(v) -> list[tuple[str, object]]:
    if isinstance(v, bool):
        return [("int", 1), ("string", "yes")]
    if isinstance(v, (int, float)):
        out = [("string", "1.0"), ("nan", float("nan")), ("inf", float("inf")), ("negative", -abs(v) - 1),
               ("zero", 0 if isinstance(v, int) else 0.0), ("list", [v])]
        out += [("huge", 10**9), ("int64", 2**63)] if isinstance(v, int) else [("huge", 1e30)]
        return out
    if isinstance(v, str):
        return [("number", 42), ("unknown", "nonsense_value"), ("empty", "")]
    if isinstance(v, list):
        out = [("empty", []), ("nested", [v]), ("strings", ["a"] * max(1, len(v)))]
        if v and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
            out += [("nan_inside", [float("nan")] + list(v[1:])), ("inf_inside", list(v[:-1]) + [float("inf")])]
        return out
    if isinstance(v, dict):
        return [("scalar", 1)]
    return []


def mutations(study: Path):
    """(label, file text or bytes) pairs derived from one study file."""
    data = tomllib.loads(study.read_text())
    for sec, body in data.items():
        if not isinstance(body, dict):
            continue
        for key, v in body.items():
            if sec == "sweep" and isinstance(v, dict):  # sweep blocks: mutate the axis values
                for axis, vals in v.items():
                    if isinstance(vals, list) and vals:
                        for tag, bad in _leaf_mutations(vals[0]):
                            d = json.loads(json.dumps(data, allow_nan=True))
                            d[sec][key][axis] = [bad] + vals[1:]
                            yield f"{sec}.{key}[{axis}][0]={tag}", to_toml(d), f"{axis}"
                continue
            if sec == "motions" and isinstance(v, list):
                for i, entry in enumerate(v[:1]):
                    for k2, v2 in entry.items():
                        for tag, bad in _leaf_mutations(v2):
                            d = json.loads(json.dumps(data))
                            d[sec][key][i][k2] = bad
                            yield f"{sec}.{key}[{i}].{k2}={tag}", to_toml(d), k2
                continue
            for tag, bad in _leaf_mutations(v):
                d = json.loads(json.dumps(data))
                d[sec][key] = bad
                yield f"{sec}.{key}={tag}", to_toml(d), key
        d = json.loads(json.dumps(data))
        d[sec]["bogus_key"] = 1
        yield f"{sec}.bogus_key", to_toml(d), "bogus_key"
        d = json.loads(json.dumps(data))
        del d[sec]
        yield f"drop [{sec}]", to_toml(d), None
    text = study.read_text()
    yield "unknown section", text + "\n[bogus]\nx = 1\n", "bogus"
    yield "non-utf8", text.encode() + b"\n# \xff\xfe caf\xe9\n", None
    yield "deep nesting", text + "\n[bogus_deep]\nx = " + "[" * 3000 + "]" * 3000 + "\n", None
    yield "syntax error", text + "\n[study\n", None
    yield "empty file", "", None


def extra_configs():
    """File-level cases not derived from one key: gravity conflicts, a 10^6 sweep, a tiny bad sweep."""
    q = tomllib.loads((ROOT / "studies" / "quickstart.toml").read_text())
    d = json.loads(json.dumps(q))
    d["robot"]["gravity"] = 9.81
    del d["derived"]
    yield "swept gamma + robot.gravity", to_toml(d), "gravity"
    d = json.loads(json.dumps(q))
    d["study"]["max_cases"] = 10**6
    d["sweep"] = {"product": {"load.bend_angle": [0.01 * i for i in range(1, 1001)],
                              "solver.n_stations": list(range(3, 1003))}}
    yield "1e6-case sweep (max_cases 1e6)", to_toml(d), None
    d = json.loads(json.dumps(q))
    d["robot"]["tendon_count"] = 3
    d["load"]["tensions"] = [1.0, 2.0]
    d["load"].pop("bend_angle")
    d["sweep"] = {"product": {"derived.gravity_parameter": [0.1, 1.0, 10.0]}}
    yield "tension count per case", to_toml(d), "tensions"
    for stem in ("quickstart", "sag_validity"):
        d = json.loads(json.dumps(tomllib.loads((ROOT / "studies" / f"{stem}.toml").read_text())))
        d["solver"]["n_elements"] = 10**9
        yield f"{stem}: n_elements 1e9", to_toml(d), "n_elements"


def _run_cli_here(argv) -> tuple[int | str, str]:
    from workbench.cli import main

    err, out = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            rc = main(argv)
    except SystemExit as e:  # argparse
        rc = e.code if isinstance(e.code, int) else 2
    except BaseException:  # noqa: BLE001 - counted
        rc = "traceback"
        err.write(traceback.format_exc())
    return rc, err.getvalue()


def _run_cli(argv, budget: float) -> tuple[int | str, str, float]:
    """``workbench`` in a forked copy of this (warm) process, killed after ``budget`` seconds.

    Returns ``(rc, stderr, seconds)``; rc is ``"traceback"`` when an exception escaped and
    ``"slow"`` when the budget ran out (a fork isolates hangs and memory blow-ups).
    """
    r, w = os.pipe()
    t0 = time.perf_counter()
    pid = os.fork()
    if pid == 0:  # child
        os.close(r)
        try:
            resource.setrlimit(resource.RLIMIT_AS, (3 * 2**30, resource.RLIM_INFINITY))
            res = _run_cli_here(argv)
        except BaseException as e:  # noqa: BLE001
            res = ("traceback", repr(e))
        with os.fdopen(w, "w") as f:
            json.dump(res, f)
        os._exit(0)
    os.close(w)
    deadline = time.monotonic() + budget
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if time.monotonic() > deadline:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            os.close(r)
            return "slow", "", time.perf_counter() - t0
        time.sleep(0.01)
    with os.fdopen(r) as f:
        text = f.read()
    try:
        rc, err = json.loads(text)
    except json.JSONDecodeError:
        rc, err = "traceback", f"child died: status {status}"
    return rc, err, time.perf_counter() - t0


def cmd_inputs(quick: bool, budget: float) -> int:
    import workbench.cli  # noqa: F401 - warm the imports once: every command runs in a fork
    import workbench.study  # noqa: F401
    counts = {"tried": 0, "rejected": 0, "accepted": 0, "traceback": 0, "slow": 0, "multi_line": 0,
              "key_not_named": 0}
    accepted, tracebacks, multi, unnamed, slow = [], [], [], [], []
    configs = []
    for study in sorted((ROOT / "studies").glob("*.toml")):
        for label, text, key in mutations(study):
            configs.append((f"{study.stem}: {label}", text, key))
    configs += list(extra_configs())
    if quick:
        configs = configs[::7]
    with tempfile.TemporaryDirectory() as tmp:
        for i, (label, text, key) in enumerate(configs):
            p = Path(tmp) / f"c{i}.toml"
            (p.write_bytes if isinstance(text, bytes) else p.write_text)(text)
            rc, err, dt = _run_cli(["validate", str(p)], budget)
            counts["tried"] += 1
            lines = [x for x in err.splitlines() if x.strip()]
            if rc == "traceback":
                counts["traceback"] += 1
                tracebacks.append((label, lines[-1] if lines else ""))
            elif rc == "slow":
                counts["slow"] += 1
                slow.append(label)
            elif rc == 0:
                counts["accepted"] += 1
                accepted.append(label)
            else:
                counts["rejected"] += 1
                if len(lines) > 1:
                    counts["multi_line"] += 1
                    multi.append((label, len(lines), lines[0][:160]))
                if key and not any(key in x for x in lines):
                    counts["key_not_named"] += 1
                    unnamed.append((label, lines[0][:160] if lines else ""))
            print(f"{i:4d} {str(rc):>9} {dt:6.2f}s {label}", file=sys.stderr, flush=True)
    cli_counts, cli_tb = _cli_inputs(budget)
    print(json.dumps({"configs": counts, "cli": cli_counts}, indent=1))
    for title, items in (("TRACEBACKS", tracebacks), ("SLOW", slow), ("MULTI-LINE", multi),
                         ("KEY NOT NAMED", unnamed), ("ACCEPTED", accepted), ("CLI TRACEBACKS", cli_tb)):
        print(f"== {title} ({len(items)})")
        for it in items:
            print("  ", it)
    return 0


def _cli_inputs(budget: float):
    """Bad command lines and broken result folders: (counts, tracebacks)."""
    study = str(ROOT / "studies" / "example.toml")
    counts = {"tried": 0, "one_line_exit_2": 0, "other": 0, "traceback": 0}
    tbs = []
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        (t / "afile").write_text("x")
        good = t / "good"
        rc, err, _ = _run_cli(["run", study, "--out", str(good), "--in-process", "--no-report", "--progress", "off"],
                              300)
        assert rc == 0, err
        bad_manifest = t / "bad_manifest"
        bad_manifest.mkdir()
        (bad_manifest / "_manifest.json").write_text("{not json")
        bad_part = t / "bad_part"
        subprocess.run(["cp", "-r", str(good), str(bad_part)], check=True)
        part = sorted(p for p in bad_part.glob("part-*.parquet") if "schema" not in p.name)[0]
        part.write_bytes(part.read_bytes()[:100])
        only_manifest = t / "only_manifest"
        only_manifest.mkdir()
        (only_manifest / "_manifest.json").write_text((good / "_manifest.json").read_text())
        runs = [
            ["run", study, "--out", str(t / "afile"), "--in-process", "--no-report"],
            ["run", study, "--out", str(t / "afile" / "sub"), "--in-process", "--no-report"],
            ["run", study, "--out", "/proc/forbidden/x", "--in-process", "--no-report"],
            ["run", study, "--out", "", "--in-process", "--no-report"],
            ["run", study, "--out", str(bad_manifest), "--resume", "--in-process", "--no-report"],
            ["run", study, "--out", str(bad_part), "--resume", "--in-process", "--no-report"],
            ["run", str(t / "missing.toml")],
            ["run", str(t)],
            ["run", study, "--scheduler", "tcp//nohost", "--out", str(t / "s1"), "--no-report"],
            ["run", study, "--scheduler", "tcp://127.0.0.1:9", "--out", str(t / "s2"), "--no-report"],
            ["run", study, "--workers", "0", "--out", str(t / "s3")],
            ["show", str(bad_manifest)], ["show", str(bad_part)], ["show", str(only_manifest)],
            ["show", str(t / "missing")], ["report", str(bad_manifest)], ["report", str(only_manifest)],
            ["report", str(good), "--formats", "jpg", "--out", str(t / "r1")],
            ["report", str(t / "missing")], ["validate", str(t / "missing.toml")], ["validate", str(t)],
        ]
        for argv in runs:
            rc, err, _ = _run_cli(argv, budget)
            counts["tried"] += 1
            lines = [x for x in err.splitlines() if x.strip()]
            if rc == "traceback":
                counts["traceback"] += 1
                tbs.append((" ".join(argv[:2]), lines[-1] if lines else ""))
            elif rc == 2 and len(lines) == 1:
                counts["one_line_exit_2"] += 1
            else:
                counts["other"] += 1
                tbs.append((" ".join(a.replace(tmp, "T") for a in argv), rc, lines[:2]))
    return counts, tbs


# ----------------------------------------------------------------------------------------------
# kills and concurrent runs
# ----------------------------------------------------------------------------------------------
sys.path.insert(0, str(Path(__file__).resolve().parent))  # tests/study: runs_util, also under python -m
from runs_util import KILL_STUDY  # noqa: E402 - the study the kill tests use


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(HERE), env.get("PYTHONPATH", "")])
    return env


def _run_args(study: Path, out: Path, *extra: str, executor: str = "--in-process") -> list[str]:
    return [sys.executable, str(HERE / "fake_workbench.py"), "study_fakes:lookup_spin_20ms", "run", str(study),
            "--out", str(out), executor, "--no-report", "--progress", "off", *extra]


def _table(folder: Path):
    import pandas as pd

    df = pd.read_parquet(folder).drop(columns=["wall_time"])
    return df.sort_values(["case_id", "model"]).reset_index(drop=True)[sorted(df.columns)]


def _same(a, b) -> bool:
    return list(a.columns) == list(b.columns) and len(a) == len(b) and all(
        a[c].map(repr).tolist() == b[c].map(repr).tolist() for c in a.columns)


def cmd_kills(n: int, seed: int) -> int:
    rng = random.Random(seed)
    counts = {"kills": 0, "sigterm": 0, "sigterm_exit_143": 0, "resumes": 0, "identical": 0, "trials": 0,
              "duplicates_seen": 0}
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        study = t / "killme.toml"
        study.write_text(KILL_STUDY)
        ref = t / "ref"
        subprocess.run(_run_args(study, ref), env=_env(), cwd=t, capture_output=True, check=False, timeout=300)
        ref_table = _table(ref)
        for trial in range(n):
            executor = "--in-process" if trial % 2 else None  # odd trials in-process, even: isolated child
            out = t / f"k{trial}"
            counts["trials"] += 1
            for attempt in range(3):  # up to 3 interruptions per trial
                args = _run_args(study, out, *(["--resume"] if out.exists() else []))
                if executor is None:
                    args.remove("--in-process")
                proc = subprocess.Popen(args, env=_env(), cwd=t, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
                time.sleep(rng.uniform(1.0, 2.5))
                if proc.poll() is None:
                    sig = signal.SIGTERM if attempt == 1 else signal.SIGKILL
                    proc.send_signal(sig)
                    rc = proc.wait(timeout=60)
                    if sig == signal.SIGTERM:
                        counts["sigterm"] += 1
                        counts["sigterm_exit_143"] += int(rc == 143)
                    else:
                        counts["kills"] += 1
                else:
                    proc.wait()
                    break
                if out.exists():
                    import pandas as pd

                    try:
                        df = pd.read_parquet(out)
                        counts["duplicates_seen"] += int(df.duplicated(["case_id", "model"]).any())
                    except Exception:  # noqa: BLE001 - a folder with only the manifest
                        pass
            r = subprocess.run(_run_args(study, out, "--resume"), env=_env(), cwd=t, capture_output=True,
                               text=True, timeout=300)
            counts["resumes"] += 1
            same = _same(_table(out), ref_table)
            counts["identical"] += int(same)
            print(f"trial {trial}: rc {r.returncode}, identical {same}", file=sys.stderr, flush=True)
    print(json.dumps(counts, indent=1))
    return 0


def cmd_concurrent(n: int) -> int:
    import pandas as pd

    counts = {"trials": 0, "exactly_one_ran": 0, "refused_one_line": 0, "duplicate_rows": 0, "tracebacks": 0}
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        study = t / "killme.toml"
        study.write_text(KILL_STUDY)
        for trial in range(n):
            out = t / f"c{trial}"
            resume = trial % 2 == 1  # odd trials: a run plus a concurrent --resume
            procs = [subprocess.Popen(_run_args(study, out, *(["--resume"] if resume and k else [])), env=_env(),
                                      cwd=t, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                     for k in range(2)]
            res = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
            counts["trials"] += 1
            ran = [rc in (0, 1) for rc, _ in res]
            refused = [rc == 2 and len(err.strip().splitlines()) == 1 for rc, err in res]
            counts["exactly_one_ran"] += int(sum(ran) == 1 and sum(refused) == 1)
            counts["refused_one_line"] += int(sum(refused) == 1)
            counts["tracebacks"] += sum("Traceback" in err for _, err in res)
            df = pd.read_parquet(out)
            counts["duplicate_rows"] += int(df.duplicated(["case_id", "model"]).sum())
            print(f"trial {trial}: {[rc for rc, _ in res]} {[e.strip()[:120] for _, e in res]}", file=sys.stderr)
    print(json.dumps(counts, indent=1))
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m tests.study.robustness", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    a = sub.add_parser("inputs")
    a.add_argument("--quick", action="store_true")
    a.add_argument("--budget", type=float, default=20.0, help="seconds per command before it counts as slow")
    k = sub.add_parser("kills")
    k.add_argument("--n", type=int, default=10)
    k.add_argument("--seed", type=int, default=19)
    c = sub.add_parser("concurrent")
    c.add_argument("--n", type=int, default=4)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(HERE))
    if args.cmd == "inputs":
        return cmd_inputs(args.quick, args.budget)
    if args.cmd == "kills":
        return cmd_kills(args.n, args.seed)
    return cmd_concurrent(args.n)


if __name__ == "__main__":
    sys.exit(main())
