#!/usr/bin/env python3
"""Notebook-style: step a case from Python, plot a field, then read a run directory back.

    PYTHONPATH=build/release/python python3 examples/python/run_and_plot_field.py --out runs/field
    ... --quick    # 5 ms of simulated time (the test runs this)

Cells (# %%) run one after the other in an editor that knows them (VS Code, Spyder, Jupytext).
"""
# %% Set-up
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import particula  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--out", default="runs/run_and_plot_field")
ap.add_argument("--quick", action="store_true")
args = ap.parse_args(sys.argv[1:])
os.makedirs(args.out, exist_ok=True)
case = os.path.join(ROOT, "cases", "falling_cylinder.toml")
overrides = {"resolution.d0": 2.5e-4}  # 10 particles across the cylinder
t_end = 0.005 if args.quick else 0.1

# %% Build the case and step it to t_end in this process
sim = particula.Simulation(case, overrides)
steps = sim.run_to(t_end)
print(sim, "after", steps, "steps")

# %% The fields are NumPy views of the solver's arrays (no copy): plot the fluid's speed and
# pressure, and the cylinder's surface particles.
fluid = sim.kind == particula.KIND_FLUID
cylinder = sim.body_index == 0
x, v, p = sim.positions, sim.velocity, sim.pressure
fig, axes = plt.subplots(1, 2, figsize=(8, 5.6), sharey=True)
for ax, values, label in ((axes[0], np.hypot(v[fluid, 0], v[fluid, 1]), "speed (m/s)"),
                          (axes[1], p[fluid], "pressure (Pa)")):
    sc = ax.scatter(x[fluid, 0], x[fluid, 1], c=values, s=2, cmap="viridis")
    ax.plot(x[cylinder, 0], x[cylinder, 1], ".", ms=2, color="w")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    fig.colorbar(sc, ax=ax, label=label, shrink=0.8)
axes[0].set_ylabel("y (m)")
b = sim.body_states()
fig.suptitle("%s, d0 = %g m, t = %.3g s: cylinder at y = %.4f m, vy = %.4f m/s"
             % (sim.name, sim.d0, sim.time, b["position"][0, 1], b["velocity"][0, 1]), fontsize=9)
fig.tight_layout()
png = os.path.join(args.out, "fields.png")
fig.savefig(png, dpi=120)
plt.close(fig)
print("fields:", png)

# %% The same case run as `particula run` does, into a run directory, and read back
run_dir = os.path.join(args.out, "run")
particula.run_case(case, run_dir, dict(overrides, **{"time.end": t_end}), plots=False, overwrite=True)
run = particula.read_run(run_dir)
cyl = run.body(0)
last = run.snapshots[-1]
print("%d snapshots of %d particles; the last at t = %g s" % (len(run.snapshots), last.num_points, last.time))
fig, ax = plt.subplots(figsize=(6.4, 3.6))
ax.plot(cyl["time"], cyl["vy"], "-")
ax.set_xlabel("t (s)")
ax.set_ylabel("cylinder vy (m/s)")
ax.set_title("bodies.csv of %s (d0 = %g m)" % (run_dir, run.case["resolution"]["d0"]), fontsize=9)
ax.grid(True, alpha=0.3)
fig.tight_layout()
png = os.path.join(args.out, "settling.png")
fig.savefig(png, dpi=120)
plt.close(fig)
print("settling:", png)
