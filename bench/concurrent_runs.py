#!/usr/bin/env python3
"""Two particula processes into one run directory at once, many times: whether a run directory
survives concurrent use (no crash, no file lost, never two runs' files mixed).

Each pair starts two commands into the same directory at the same moment:
  - "overwrite": two `particula run CASE --out DIR --overwrite` over a completed run of the case;
  - "resume":    two `particula resume DIR --set time.end=...` of one interrupted run.
After each pair it checks: no process ended on a signal; each exit code is 0 or 2 (refused: the
directory in use); at least one succeeded; the directory holds one complete run (summary.json
"completed", every output row's time at most its end, no duplicated row time in bodies.csv or
walls.csv, no temporary or left-aside files); the files of the previous run are either all there
unchanged (both refused) or replaced by the new run's as a whole.

    python3 bench/concurrent_runs.py [--binary build/release/particula] [--pairs 50] [--out DIR]

Prints one line per pair and a summary; exit 1 when any pair fails a check.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
CASE = os.path.join(ROOT, "cases", "couette.toml")
BASE = ["--quiet", "--no-plots", "--threads", "1"]


def tree(d):
    """{relative path: bytes} of every file under d."""
    out = {}
    for dirpath, _, files in os.walk(d):
        for f in files:
            p = os.path.join(dirpath, f)
            with open(p, "rb") as fh:
                out[os.path.relpath(p, d)] = fh.read()
    return out


def rows_times(path):
    with open(path) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head, body = rows[0], rows[1:]
    it = head.index("time")
    key = [i for i, h in enumerate(head) if h in ("body", "wall")]
    return [(float(r[it]),) + tuple(r[i] for i in key) for r in body]


def complete_run_problems(d, t_end):
    """What is wrong with run directory d as one complete run to t_end ([] when nothing)."""
    problems = []
    try:
        with open(os.path.join(d, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError) as e:
        return ["no readable summary.json (%s)" % e]
    if summary.get("status") != "completed":
        problems.append("status %r" % summary.get("status"))
    if abs(summary.get("end_time", -1) - t_end) > 1e-9:
        problems.append("end_time %r, not %r" % (summary.get("end_time"), t_end))
    for name in ("bodies.csv", "walls.csv"):
        p = os.path.join(d, name)
        if not os.path.exists(p):
            continue
        times = rows_times(p)
        if len(times) != len(set(times)):
            problems.append("%s has duplicated rows" % name)
        if times and max(t[0] for t in times) > t_end + 1e-9:
            problems.append("%s has rows after the end" % name)
    parent = os.path.dirname(d)
    for f in os.listdir(parent):
        if f.startswith(".") and (".new." in f or ".old." in f):
            problems.append("left behind: %s" % f)
    for dirpath, _, files in os.walk(d):
        for f in files:
            if ".tmp." in f:
                problems.append("temporary file left: %s" % os.path.relpath(os.path.join(dirpath, f), d))
    return problems


def start(binary, args):
    return subprocess.Popen([binary] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def pair(binary, kind, work, i):
    """Runs one pair; returns (ok, line)."""
    d = os.path.join(work, "pair%03d" % i, "run")
    t0, t1 = 0.01, 0.02
    first = subprocess.run([binary, "run", CASE, "--out", d, "--set", "time.end=%g" % t0,
                            "--set", "output.checkpoint_interval=0.005"] + BASE, capture_output=True, text=True)
    if first.returncode != 0:
        return False, "setup failed: %s" % first.stdout
    before = tree(d)
    if kind == "overwrite":
        args = ["run", CASE, "--out", d, "--overwrite", "--set", "time.end=%g" % t1] + BASE
    else:
        args = ["resume", d, "--set", "time.end=%g" % t1] + BASE
    procs = [start(binary, args), start(binary, args)]
    codes = [p.wait() for p in procs]
    texts = [p.stdout.read() for p in procs]
    problems = []
    if any(c < 0 for c in codes):
        problems.append("a process ended on signal %d" % -min(codes))
    if any(c not in (0, 2) for c in codes):
        problems.append("exit codes %s: %s" % (codes, " | ".join(t.strip() for t in texts)))
    if 0 not in codes:
        # both refused: the old run must be there untouched (the lock file aside)
        after = tree(d)
        after.pop(".particula-lock", None)
        before.pop(".particula-lock", None)
        if after != before:
            problems.append("both refused, yet the directory changed")
    else:
        problems += complete_run_problems(d, t1)
    shutil.rmtree(os.path.dirname(d), ignore_errors=True)
    return not problems, "%s pair %d: exit codes %s%s" % (kind, i, codes, "" if not problems else
                                                          ": FAIL: " + "; ".join(problems))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "release", "particula"))
    ap.add_argument("--pairs", type=int, default=50, help="pairs in all, half of each kind")
    ap.add_argument("--out", default=None, help="work directory (default: a temporary one)")
    args = ap.parse_args(argv)
    work = args.out or tempfile.mkdtemp(prefix="particula-concurrent-")
    os.makedirs(work, exist_ok=True)
    failed, counts = 0, {}
    for i in range(args.pairs):
        kind = "overwrite" if i % 2 == 0 else "resume"
        ok, line = pair(args.binary, kind, work, i)
        print(line, flush=True)
        failed += not ok
        key = line.split(": exit codes ")[1].split(":")[0]
        counts[(kind, key)] = counts.get((kind, key), 0) + 1
    print("%d pairs, %d failed; exit codes per kind: %s" % (
        args.pairs, failed, ", ".join("%s %s x%d" % (k, c, n) for (k, c), n in sorted(counts.items()))))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
