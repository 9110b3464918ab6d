#!/usr/bin/env python3
"""Terminal settling speed of the falling cylinder (paper case 7.2) against its density ratio.

Runs cases/falling_cylinder.toml once per density ratio rho_s / rho_f, each in its own process
(one OpenMP thread each, --jobs at a time), into OUT/ratio_<r>/ as `particula run` would, reads
each run's bodies.csv back and plots the peak settling speed against the ratio into
OUT/terminal_speed.png (the table in OUT/terminal_speed.csv).

    PYTHONPATH=build/release/python python3 examples/python/sweep_terminal_speed.py --out runs/sweep
    ... --quick    # two ratios, 10 ms of settling each (a few seconds; the test runs this)

The settling speed is the largest downward speed of the cylinder in the run: its terminal speed
when the run is long enough to reach it (0.5 s at the default resolution for ratios up to about
2) and before the floor slows it down. At ratio 1.25 the published value is 0.0554 m/s
(Glowinski et al. 2001); at this coarse level (10 particles across) expect a few percent more.
"""
import argparse
import concurrent.futures
import csv
import multiprocessing
import os
import sys

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def settle(case_file, ratio, out, overrides):
    """One run (in a worker process): the case with the body's density set to ratio * rho0.
    Returns (ratio, peak settling speed in m/s, exit code)."""
    import particula
    rho0 = particula.load_case(case_file, overrides)["fluid"]["rho0"]
    sets = dict(overrides, **{"body.0.density": ratio * rho0})
    result = particula.run_case(case_file, out, sets, threads=1, plots=False, overwrite=True, check=False)
    vy = particula.read_run(out).body(0)["vy"]
    return ratio, float(-vy.min()), result.exit_code


def sweep(case_file, ratios, out_dir, overrides, jobs):
    """The runs in parallel processes ("spawn": a fresh interpreter per worker, no OpenMP state
    inherited from this one); results in the order of `ratios`."""
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
        futures = [pool.submit(settle, case_file, r, os.path.join(out_dir, "ratio_%g" % r), overrides)
                   for r in ratios]
        return [f.result() for f in futures]


def plot(results, png, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ratio = np.array([r[0] for r in results])
    speed = np.array([r[1] for r in results])
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(ratio, speed, "o-", label="particula")
    ax.plot([1.25], [0.0554], "s", color="k", label="Glowinski et al. 2001 (terminal speed)")
    ax.set_xlabel("density ratio rho_s / rho_f")
    ax.set_ylabel("peak settling speed (m/s)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", default=os.path.join(ROOT, "cases", "falling_cylinder.toml"))
    ap.add_argument("--out", default="runs/sweep_terminal_speed")
    ap.add_argument("--ratios", type=float, nargs="+", default=[1.1, 1.25, 1.5, 2.0])
    ap.add_argument("--d0", type=float, default=2.5e-4, help="particle spacing (m); 2.5e-4 is 10 across the cylinder")
    ap.add_argument("--end", type=float, default=0.5, help="simulated time of each run (s)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count(), help="runs at a time (processes)")
    ap.add_argument("--quick", action="store_true", help="ratios 1.25 and 2, 10 ms each: a smoke test")
    args = ap.parse_args(argv)
    if args.quick:
        args.ratios, args.end = [1.25, 2.0], 0.01
    os.makedirs(args.out, exist_ok=True)
    overrides = {"resolution.d0": args.d0, "time.end": args.end}
    results = sweep(args.case, args.ratios, args.out, overrides, max(1, args.jobs))
    with open(os.path.join(args.out, "terminal_speed.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["ratio", "peak_settling_speed", "exit_code"])
        w.writerows(results)
    for ratio, speed, code in results:
        print("ratio %-5g peak settling speed %.5g m/s%s" % (ratio, speed, "" if code == 0 else " (exit %d)" % code))
    png = os.path.join(args.out, "terminal_speed.png")
    plot(results, png, "%s, d0 = %g m, %g s per run" % (os.path.basename(args.case), args.d0, args.end))
    print("plot:", png)
    return 0 if all(code == 0 for _, _, code in results) else 3


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
