#!/usr/bin/env python3
"""Hindered settling: the mean settling speed of 1, 5, 20 and 50 circles in a closed box against
their area fraction, with the cases built in code (particula.Case) rather than in TOML files.

Each case is the same box of fluid with N circles (D = 1 mm, rho_s = 1200 kg/m^3) placed on a
jittered grid in its upper half (seeded, so every run of the script places them alike). Each runs
in its own process (one OpenMP thread each, --jobs at a time) into OUT/n_<N>/, as `particula run`
would; the script reads bodies.csv back and plots the mean settling speed of the bodies over the
second half of the run against the area fraction N pi D^2 / 4 / (W H) into OUT/settling.png (the
table in OUT/settling.csv). The speeds fall as the fraction grows: the fluid the circles push
down must come back up between them (Richardson-Zaki's hindered settling).

    PYTHONPATH=build/release/python python3 examples/python/settling_circles.py --out runs/settling
    ... --quick    # 1 and 5 circles, 5 ms each (seconds; the test runs this)

At the default level (10 particles across a circle, 0.25 s) each case takes minutes to tens of
minutes on one core, the 50 circles the longest.
"""
import argparse
import concurrent.futures
import csv
import math
import multiprocessing
import os
import random
import sys

D = 1e-3  # circle diameter (m)
W, H = 0.012, 0.024  # the box (m)


def box_case(n, d0, t_end, seed=1):
    """The case: a closed W x H box of fluid under gravity with n circles placed in its upper half
    on a jittered grid, at least a quarter diameter apart and from the walls."""
    import particula
    case = particula.Case({
        "name": "settling_%d" % n,
        "description": "%d circles settling in a closed box (examples/python/settling_circles.py)" % n,
        "domain": {"min": [0.0, 0.0], "max": [W, H]},
        "resolution": {"d0": d0},
        "fluid": {"rho0": 1000.0, "nu": 1e-5, "c": 0.2, "gravity": [0.0, -9.81]},  # c: 15 times the settling speed
        "time": {"end": t_end},
        "output": {"interval": t_end / 50},
    })
    corners = [(0, 0), (W, 0), (W, H), (0, H)]
    for i, name in enumerate(("bottom", "right", "top", "left")):
        case.add_wall({"name": name, "from": list(corners[i]), "to": list(corners[(i + 1) % 4])})
    rng = random.Random(seed)
    columns = max(1, int(W / (1.5 * D)))
    pitch_x, pitch_y = W / columns, 1.5 * D
    for k in range(n):
        row, col = divmod(k, columns)
        jitter = 0.125 * D
        x = (col + 0.5) * pitch_x + rng.uniform(-jitter, jitter)
        y = H - D - row * pitch_y + rng.uniform(-jitter, jitter)
        if y < H / 2:
            raise ValueError("%d circles do not fit the upper half of the box" % n)
        case.add_body(name="c%d" % k, shape="circle", radius=D / 2, center=[x, y], density=1200.0)
    return case


def run_one(n, d0, t_end, out):
    """Runs the case of n circles into out/n_<n>; returns (n, area fraction, mean settling speed,
    exit code)."""
    import numpy as np
    import particula
    case = box_case(n, d0, t_end)
    result = particula.run_case(case, os.path.join(out, "n_%d" % n), threads=1, overwrite=True, plots=False,
                                check=False)
    bodies = result.read().bodies
    late = bodies["time"] >= 0.5 * t_end
    speed = float(np.mean(-bodies["vy"][late]))
    fraction = n * math.pi * D * D / 4 / (W * H)
    return n, fraction, speed, result.exit_code


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="runs/settling_circles")
    ap.add_argument("--quick", action="store_true", help="1 and 5 circles, 5 ms each")
    ap.add_argument("--jobs", type=int, default=max(1, (os.cpu_count() or 1)))
    args = ap.parse_args(argv)
    counts = (1, 5) if args.quick else (1, 5, 20, 50)
    d0, t_end = D / 10, 0.005 if args.quick else 0.25
    os.makedirs(args.out, exist_ok=True)
    # Each run in its own process: particula runs one case at a time per process.
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs, mp_context=context) as pool:
        rows = sorted(pool.map(run_one, counts, [d0] * len(counts), [t_end] * len(counts),
                               [args.out] * len(counts)))
    with open(os.path.join(args.out, "settling.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["circles", "area_fraction", "mean_settling_speed", "exit_code"])
        w.writerows(rows)
    for n, fraction, speed, code in rows:
        print("%3d circles, area fraction %.4f: mean settling speed %.4g m/s (exit %d)" % (n, fraction, speed, code))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot([r[1] for r in rows], [r[2] for r in rows], "o-")
    for n, fraction, speed, _ in rows:
        ax.annotate(str(n), (fraction, speed), textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("area fraction of the circles")
    ax.set_ylabel("mean settling speed (m/s)")
    ax.set_title("Circles settling in a box, t > %g s" % (0.5 * t_end))
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "settling.png"), dpi=120)
    return 0 if all(r[3] == 0 for r in rows) else 3


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
