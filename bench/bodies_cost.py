#!/usr/bin/env python3
"""The cost of bodies (`make bench-bodies`): a step with many free bodies against a step of fluid only.

Writes both cases with bench/many_bodies.py, then times them with particula_bench_e2e in
alternating rounds (bodies, fluid only, bodies, ...) and compares the mean seconds per step.
One pair of runs is not enough on a shared or virtual machine: here a run's step time varies
by 10-20 % from one run to the next (docs/performance.md, "The cost of bodies"), as much as
the cost being measured, so the rounds alternate and the summary gives the ratio of the means,
the spread of the rounds' own ratios and the mean time of each phase of the step. Arguments
this script does not know (e.g. `--threads 1`) go to particula_bench_e2e. Usage:

  bench/bodies_cost.py [--rounds N] [--steps N] [--advance T] [--bodies N] [BENCH ARGS...]
"""
import argparse
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = ("many_bodies", "no_bodies")
# the phases of particula_bench_e2e's RESULT line (seconds over the timed steps)
PHASES = ("neighbors", "geometry", "operators", "wall_pressure", "bodies", "integration", "shifting")


def result_fields(output):
    """The key=value pairs of particula_bench_e2e's RESULT line."""
    for line in output.splitlines():
        if line.startswith("RESULT "):
            return dict(item.split("=", 1) for item in line.split()[1:])
    raise RuntimeError("no RESULT line in the benchmark's output")


def time_case(bench, case_file, a, extra):
    cmd = [bench, "--case", case_file, "--advance", str(a.advance), "--steps", str(a.steps),
           "--warmup", str(a.warmup)] + extra
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.stderr.write(run.stdout + run.stderr)
        raise SystemExit(f"error: {' '.join(cmd)} exited with {run.returncode}")
    r = result_fields(run.stdout)
    steps = int(r["steps"])
    return {"step": float(r["wall_s"]) / steps,
            "phases": {p: float(r[p]) / steps for p in PHASES if p in r},
            "builds": int(r.get("band_builds", 0)), "steps": steps, "particles": int(r["particles"]),
            "threads": int(r["threads"])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", default="build/release/bench/particula_bench_e2e")
    ap.add_argument("--dir", default="build/bench-bodies", help="where the two case files are written")
    ap.add_argument("--bodies", type=int, default=1000)
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds (one run of each case per round)")
    ap.add_argument("--steps", type=int, default=30, help="timed steps per run")
    ap.add_argument("--warmup", type=int, default=5)
    ap.add_argument("--advance", type=float, default=0.04,
                    help="simulated time run untimed first, so that the timed steps are those of a developed flow")
    a, extra = ap.parse_known_args()
    if a.rounds < 1 or a.steps < 1 or a.warmup < 0 or a.advance < 0 or a.bodies < 1:
        ap.error("--rounds, --steps and --bodies must be positive, --warmup and --advance not negative")
    subprocess.run([sys.executable, os.path.join(HERE, "many_bodies.py"), a.dir, "--bodies", str(a.bodies)],
                   check=True)
    runs = {c: [] for c in CASES}
    print("round  case          s/step   bodies phase  band builds")
    for k in range(a.rounds):
        for c in CASES:
            t = time_case(a.bench, os.path.join(a.dir, c + ".toml"), a, extra)
            runs[c].append(t)
            print(f"{k + 1:5d}  {c:12s}  {t['step']:.4f}   {t['phases']['bodies']:.4f}        {t['builds']} of {t['steps']}",
                  flush=True)
    mean = {c: statistics.fmean(t["step"] for t in runs[c]) for c in CASES}
    ratios = sorted(b["step"] / f["step"] for b, f in zip(runs["many_bodies"], runs["no_bodies"]))
    first = runs["many_bodies"][0]
    print(f"particles {first['particles']} with bodies, {runs['no_bodies'][0]['particles']} fluid only; "
          f"{first['threads']} threads; {a.rounds} rounds of {a.steps} steps from t = {a.advance:g} s")
    print(f"mean s/step: {mean['many_bodies']:.4f} with {a.bodies} bodies, {mean['no_bodies']:.4f} fluid only: "
          f"a step with bodies costs {100 * (mean['many_bodies'] / mean['no_bodies'] - 1):+.1f} %")
    print("phase          s/step with bodies   fluid only   difference")
    for p in PHASES:
        b, f = (statistics.fmean(t["phases"].get(p, 0.0) for t in runs[c]) for c in CASES)
        print(f"{p:13s}  {b:.5f}              {f:.5f}      {b - f:+.5f}")
    print(f"rounds' own ratios: min {ratios[0]:.3f}, median {statistics.median(ratios):.3f}, max {ratios[-1]:.3f}")
    print(f"RESULT bodies={a.bodies} rounds={a.rounds} steps={a.steps} advance={a.advance:g} "
          f"threads={first['threads']} bodies_s_per_step={mean['many_bodies']:.6g} "
          f"fluid_s_per_step={mean['no_bodies']:.6g} cost={mean['many_bodies'] / mean['no_bodies'] - 1:.4f}")


if __name__ == "__main__":
    main()
