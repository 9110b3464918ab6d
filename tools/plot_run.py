#!/usr/bin/env python3
"""Draws the plots of a particula run directory into DIR/plots/.

  plot_run.py DIR [--format png|svg|pdf]

Every figure's title names the case, its resolution (d0 and particles across the first body,
or across the domain), the run's --set overrides (summary.json) and, for a run that failed or
was interrupted, where it stopped.
- probe_<name>.csv: for a line probe, velocity profiles at up to 8 written times (with the exact
  solution where the case declares one, and the profile error in time); for a probe at points,
  the velocity at each point in time;
- flow_<name>.csv: the flow rate through each line probe in time (flow_rates.png);
- bodies.csv: position, angle and velocity of every moving body (a fixed body has none to show)
  and the hydrodynamic force on every body, against the published reference of the case, drawn
  only when the run's physics is that of the shipped case it belongs to (plot_references.py); each
  panel spans at least a physically meaningful range (a position one body diameter, an angle
  0.1 rad, a velocity a tenth of the largest speed) and states the range of a smaller drift;
- coefficients.csv: drag and lift coefficients in time (coefficients.png);
- particles/*.vtp: the last snapshot's particles coloured by pressure and by each velocity
  component, like the paper's contour figures (snapshot_fields.png).
Reads the run with particula's own reader (python/particula/reader.py: NumPy, no VTK), loaded
from its file so that the compiled module is not needed; draws with Debian's python3-matplotlib.
"""
import importlib.util
import math
import os
import sys
import textwrap

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError:  # pragma: no cover - reported to the user by the caller
    sys.stderr.write("plot_run.py: matplotlib is not installed (apt-get install python3-matplotlib); no plots\n")
    sys.exit(4)

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_references  # noqa: E402  (next to this script)

# The image formats (particula plot --format; src/run/plots.cpp's plot_formats()), the first the default.
FORMATS = ("png", "svg", "pdf")
# The format save() writes, set by main().
OUTPUT = {"format": FORMATS[0]}


def load_reader():
    """particula's run-directory reader (pure Python + NumPy), without the compiled module."""
    path = os.path.join(ROOT, "python", "particula", "reader.py")
    spec = importlib.util.spec_from_file_location("particula_reader", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


reader = load_reader()

# ---- the case: sizes, names, titles ---------------------------------------------------------------

def body_area(b):
    """Exact area of a [[body]] table (m^2), or None for an unknown shape."""
    shape = b.get("shape", "circle")
    if shape == "circle":
        return math.pi * b["radius"] ** 2
    if shape == "half_disc":
        return 0.5 * math.pi * b["radius"] ** 2
    if shape == "ellipse":
        return math.pi * b["semi_axes"][0] * b["semi_axes"][1]
    if shape == "polygon":
        v = b["vertices"]
        return 0.5 * abs(sum(v[i][0] * v[(i + 1) % len(v)][1] - v[(i + 1) % len(v)][0] * v[i][1] for i in range(len(v))))
    return None


def body_size(b):
    """The smallest dimension of a [[body]] (m): a diameter, twice the smaller semi-axis, or the
    smaller side of a polygon's bounding box; None for an unknown shape."""
    shape = b.get("shape", "circle")
    if shape == "circle":
        return 2 * b["radius"]
    if shape == "half_disc":
        return b["radius"]
    if shape == "ellipse":
        return 2 * min(b["semi_axes"])
    if shape == "polygon":
        xs, ys = [v[0] for v in b["vertices"]], [v[1] for v in b["vertices"]]
        return min(max(xs) - min(xs), max(ys) - min(ys))
    return None


def resolution_text(case):
    """'d0 = 2.5e-04 m, 10 particles across cylinder' (the first moving body, else the first
    body, else the domain's smaller side)."""
    d0 = case.get("resolution", {}).get("d0")
    if not d0:
        return ""
    bodies = case.get("body", [])
    moving = [b for b in bodies if b.get("motion", "free") != "fixed"] or bodies
    if moving and body_size(moving[0]):
        across = "%.3g particles across %s" % (body_size(moving[0]) / d0, moving[0].get("name", "body 0"))
    else:
        lo, hi = case.get("domain", {}).get("min", [0, 0]), case.get("domain", {}).get("max", [0, 0])
        across = "%.3g particles across the domain" % (min(hi[0] - lo[0], hi[1] - lo[1]) / d0)
    return "d0 = %.3g m, %s" % (d0, across)


def overrides_text(summary):
    """'--set body.0.density=1500 --set time.end=0.5' from summary.json's overrides, or ''."""
    return " ".join("--set %s" % o for o in summary.get("overrides") or [])


def title(run, what):
    """'<what>: case '<name>'' and below it 'd0 = ..., N particles across ...[, FAILED at t = ...]'
    and, for a run with overrides, a line '--set key=value ...'."""
    case, summary = run.case, run.summary or {}
    parts = [resolution_text(case)]
    status = summary.get("status", "")
    if status == "failed":
        parts.append("FAILED at t = %.4g s (exit 3)" % (summary.get("failure") or {}).get("time", summary.get("end_time", 0)))
    elif status == "interrupted":
        parts.append("interrupted at t = %.4g s" % summary.get("end_time", 0))
    elif status and status != "completed":
        parts.append("%s at t = %.4g s" % (status, summary.get("end_time", 0)))
    text = "%s: case '%s'\n%s" % (what, case.get("name", "") or run.dir, ", ".join(p for p in parts if p))
    overrides = overrides_text(summary)
    return text + "\n" + overrides if overrides else text


def save(fig, out, stem):
    """Writes the figure as out/<stem>.<format> (the format main() was given)."""
    fig.savefig(os.path.join(out, "%s.%s" % (stem, OUTPUT["format"])), dpi=110)
    plt.close(fig)


def eng(value, unit):
    """A magnitude with an SI prefix: eng(7e-5, 'm') = '70 um'."""
    if value == 0 or not math.isfinite(value):
        return "0 %s" % unit
    if unit == "-":
        return "%.3g" % value
    for factor, prefix in ((1, ""), (1e-3, "m"), (1e-6, "u"), (1e-9, "n")):
        if abs(value) >= factor:
            return "%.3g %s%s" % (value / factor, prefix, unit)
    return "%.3g %s" % (value, unit)


def min_span(ax, values, span, unit, label):
    """Keeps the y axis at least `span` wide around `values` (a drift far below the physically
    meaningful range must not fill the panel) and, when widened, states the drift's range."""
    values = [v for v in values if math.isfinite(v)]
    if not values or not span or span <= 0:
        return
    lo, hi = min(values), max(values)
    if hi - lo >= span:
        return
    mid = 0.5 * (lo + hi)
    ax.set_ylim(mid - 0.6 * span, mid + 0.6 * span)
    ax.text(0.02, 0.04, "%s varies by %s only" % (label, eng(hi - lo, unit)), transform=ax.transAxes, fontsize=8,
            color="0.3")


# ---- probes -----------------------------------------------------------------------------------

def probe_spec(case, name):
    for p in case.get("probe", []):
        if p.get("name") == name:
            return p
    return {}


def plot_line_probe(run, name, out):
    p = run.probe(name)
    times = list(p["time"])
    # at most 8 profiles, evenly spread over the run, the last included
    step = max(1, int(math.ceil((len(times) - 1) / 7.0)))
    shown = list(range(0, len(times), step))
    if shown[-1] != len(times) - 1:
        shown.append(len(times) - 1)
    has_exact = "vx_exact" in p
    # the velocity component the exact solution is about (vy for a radius of the spin-up case)
    comp = "vx"
    if has_exact and "vy_exact" in p and np.max(np.abs(p["vy_exact"])) > np.max(np.abs(p["vx_exact"])):
        comp = "vy"
    spec = probe_spec(run.case, name)
    vertical = abs(spec.get("to", [0, 1])[1] - spec.get("from", [0, 0])[1]) >= \
        abs(spec.get("to", [1, 0])[0] - spec.get("from", [0, 0])[0])
    pos, pos_label = (p["y"], "y (m)") if vertical else (p["x"], "x (m)")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    cmap = plt.get_cmap("viridis")
    for k, i in enumerate(shown):
        color = cmap(k / max(1, len(shown) - 1))
        if vertical:
            ax.plot(p[comp][i], pos, "o", ms=3, color=color, label="t = %.4g s" % times[i])
        else:
            ax.plot(pos, p[comp][i], "o", ms=3, color=color, label="t = %.4g s" % times[i])
        if has_exact:
            args = (p[comp + "_exact"][i], pos) if vertical else (pos, p[comp + "_exact"][i])
            ax.plot(*args, "-", lw=1, color=color, label="exact" if k == len(shown) - 1 else None)
    ax.set_xlabel(comp + " (m/s)" if vertical else pos_label)
    ax.set_ylabel(pos_label if vertical else comp + " (m/s)")
    ax.grid(True, alpha=0.3)
    ax.set_title(title(run, "probe '%s': %s along the line%s" % (name, comp, " (lines: exact)" if has_exact else "")),
                 fontsize=9, wrap=True)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, out, "probe_%s_profiles" % name)
    if has_exact and len(times) > 1:
        peak = max(1e-300, float(np.max(np.abs(p[comp + "_exact"]))))
        err = np.sqrt(np.mean((p[comp] - p[comp + "_exact"]) ** 2, axis=1)) / peak
        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        ax.semilogy(times[1:], np.maximum(err[1:], 1e-12), "o-")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("L2 error of %s / peak speed (-)" % comp)
        ax.set_title(title(run, "probe '%s': profile error" % name), fontsize=9, wrap=True)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        save(fig, out, "probe_%s_error" % name)


def plot_point_probe(run, name, out):
    p = run.probe(name)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    speed = float(np.max(np.hypot(p["vx"], p["vy"])))
    for ax, col in zip(axes, ("vx", "vy")):
        for k in range(len(p["x"])):
            ax.plot(p["time"], p[col][:, k], "o-", ms=3, label="(%.4g, %.4g) m" % (p["x"][k], p["y"][k]))
        min_span(ax, [float(v) for v in p[col].ravel()], 0.1 * speed, "m/s", col)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("%s (m/s)" % col)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(title(run, "probe '%s': velocity at its points" % name), fontsize=10)
    fig.tight_layout()
    save(fig, out, "probe_%s_points" % name)


def plot_flows(run, out):
    if not run.flows:
        return
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    for name, t in sorted(run.flows.items()):
        ax.plot(t["time"], t["flow_rate"], "o-", ms=3, label="probe '%s'" % name)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("flow rate (m^2/s, per unit depth)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title(run, "flow rate through the line probes"), fontsize=9, wrap=True)
    fig.tight_layout()
    save(fig, out, "flow_rates")


# ---- bodies -----------------------------------------------------------------------------------

def excess_weight_y(case, b):
    """The y force a settling body's hydrodynamic load balances at terminal speed: its weight
    less buoyancy, -(rho_s - rho_f) A g_y (the whole weight -rho_s A g_y when gravity acts in the
    fluid, whose pressure then carries the buoyancy). None for a body that is not free or falls
    under no gravity."""
    fluid = case.get("fluid", {})
    g = fluid.get("gravity", [0.0, 0.0])[1]
    area = body_area(b)
    if b.get("motion", "free") != "free" or g == 0 or area is None:
        return None
    rho_f = fluid.get("rho0", 1000.0)
    rho_s = b.get("density", 0.0)
    return -(rho_s * area * g if fluid.get("gravity_in_fluid", False) else (rho_s - rho_f) * area * g)


def plot_reference(ax, col, refs):
    """Draws the reference curves of `refs` that compare with bodies.csv column `col`."""
    for (fname, xc, yc, rcol, label) in refs:
        if rcol != col:
            continue
        path = os.path.join(plot_references.REFERENCE_DIR, fname)
        if not os.path.exists(path):
            continue
        ref = reader.read_csv(path)
        if "body" in ref:
            for rb in sorted(set(int(v) for v in ref["body"])):
                sel = ref["body"] == rb
                ax.plot(ref[xc][sel], ref[yc][sel], "o", ms=4, label="%s, body %d" % (label, rb))
        else:
            ax.plot(ref[xc], ref[yc], "ko", ms=4, label=label)


def plot_bodies(run, out):
    if run.bodies is None or run.bodies.rows == 0:
        return
    case = run.case
    specs = case.get("body", [])
    bodies = sorted(set(int(b) for b in run.bodies["body"]))
    spec = {b: (specs[b] if b < len(specs) else {}) for b in bodies}
    names = {b: spec[b].get("name", "body %d" % b) for b in bodies}
    moving = [b for b in bodies if spec[b].get("motion", "free") != "fixed"]
    refs, no_reference = plot_references.references_for(case)
    series = {b: run.body(b) for b in bodies}
    t_last = float(np.max(run.bodies["time"]))
    sizes = [body_size(spec[b]) for b in moving if body_size(spec[b])]
    size = min(sizes) if sizes else None
    speed = max([float(np.max(np.hypot(series[b]["vx"], series[b]["vy"]))) for b in moving] + [0.0])
    # one panel per quantity, each on its own scale; trajectories only for bodies that move
    panels = []
    if moving:
        panels += [("x", "x (m)", size, "m"), ("y", "y (m)", size, "m"), ("angle", "angle (rad), counter-clockwise", 0.1, "rad"),
                   ("vx", "vx (m/s)", 0.1 * speed, "m/s"), ("vy", "vy (m/s)", 0.1 * speed, "m/s")]
    panels.append(("force", "hydrodynamic force (N/m)", None, "N/m"))
    ncol = 3 if len(panels) > 2 else len(panels)
    nrow = int(math.ceil(len(panels) / float(ncol)))
    fig, axes = plt.subplots(nrow, ncol, figsize=(max(8.0, 4.8 * ncol), 3.9 * nrow + 0.8), squeeze=False)
    flat = [a for row in axes for a in row]
    for ax, (col, label, span, unit) in zip(flat, panels):
        if col == "force":
            weights = {}
            for b in bodies:
                ax.plot(series[b]["time"], series[b]["fx"], label="%s fx" % names[b])
                ax.plot(series[b]["time"], series[b]["fy"], "--", label="%s fy" % names[b])
                w = excess_weight_y(case, spec[b])
                if w is not None:
                    weights.setdefault(round(w, 12), []).append(names[b])
            for w, who in weights.items():
                ax.axhline(w, color="0.4", ls=":", lw=1.2,
                           label="weight - buoyancy of %s (fy at terminal speed)" % ", ".join(who))
        else:
            for k, b in enumerate(moving):
                ax.plot(series[b]["time"], series[b][col], color="C%d" % k, label=names[b])
            plot_reference(ax, col, refs)
            if no_reference and any(r[3] == col for r in plot_references.REFERENCES.get(case.get("name"), [])):
                ax.plot([], [], " ", label=textwrap.fill(no_reference, 48))  # a legend line, no curve
            min_span(ax, [float(v) for b in moving for v in series[b][col]], span, unit, col)
        if col == "angle" and any(np.any(series[b]["omega"] != 0) for b in moving):
            tw = ax.twinx()
            for k, b in enumerate(moving):
                tw.plot(series[b]["time"], series[b]["omega"], ":", lw=1, color="C%d" % k, label="%s omega" % names[b])
            tw.set_ylabel("omega (rad/s), dotted")
        # the run's time span: reference points after its end would only squeeze the curves
        if t_last > 0:
            ax.set_xlim(0, t_last * 1.02)
        ax.set_xlabel("t (s)")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, framealpha=0.7)
    for ax in flat[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(title(run, "bodies"), fontsize=11)
    fig.tight_layout()
    save(fig, out, "bodies")


def plot_coefficients(run, out):
    c = run.coefficients
    if c is None or c.rows == 0:
        return
    specs = run.case.get("body", [])
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for k, b in enumerate(sorted(set(int(v) for v in c["body"]))):
        rows = run.coefficient(b)
        name = specs[b].get("name", "body %d" % b) if b < len(specs) else "body %d" % b
        axes[0].plot(rows["time"], rows["cd"], color="C%d" % k, label="%s (Re = %.3g)" % (name, rows["re"][-1]))
        axes[1].plot(rows["time"], rows["cl"], color="C%d" % k, label=name)
    # a lift far below the drag must not fill its panel
    cd_max = float(np.max(np.abs(c["cd"])))
    min_span(axes[1], [float(v) for v in c["cl"]], 0.1 * cd_max, "-", "C_L")
    for ax, label in zip(axes, ("drag coefficient C_D (-)", "lift coefficient C_L (-)")):
        ax.set_xlabel("t (s)")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title(run, "coefficients (C = F / (0.5 rho0 U^2 L))"), fontsize=10)
    fig.tight_layout()
    save(fig, out, "coefficients")


# ---- the last snapshot ------------------------------------------------------------------------

def pressure_label(case):
    """What the snapshot's pressure is: the equation of state's p = p0 + c^2 (rho - rho0), shown
    as p - p0; without gravity in the fluid it has no hydrostatic part (dynamic pressure)."""
    fluid = case.get("fluid", {})
    g = fluid.get("gravity", [0.0, 0.0])
    if fluid.get("gravity_in_fluid", False) and any(g):
        return "p - p0 (Pa): gauge pressure, hydrostatic part included"
    return "p - p0 (Pa): dynamic (gauge) pressure"


def plot_snapshot(run, out):
    snaps = run.snapshots
    if len(snaps) == 0 or not os.path.exists(snaps.files[-1]):
        return
    snap = snaps[-1]
    x, y = snap.points[:, 0], snap.points[:, 1]
    p0 = run.case.get("fluid", {}).get("p0", 0.0)
    fields = [("pressure", snap["pressure"] - p0, pressure_label(run.case)),
              ("vx", snap["velocity"][:, 0], "vx (m/s)"), ("vy", snap["velocity"][:, 1], "vy (m/s)")]
    width, height = float(np.ptp(x)), float(np.ptp(y))
    aspect = height / width if width > 0 else 1
    fig, axes = plt.subplots(1, 3, figsize=(14, max(3.0, min(9.0, 4.2 * aspect)) + 1.2))
    size = max(0.5, min(20.0, 20000.0 / max(1, len(x))))
    for ax, (name, vals, label) in zip(axes, fields):
        # colour range from the 1st to the 99th percentile, so that a few outliers (a particle
        # squeezed against a wall, a failing run's last state) do not wash out the field
        lo, hi = np.percentile(vals, [1, 99])
        if name != "pressure":
            hi = max(abs(lo), abs(hi))
            lo = -hi
        sc = ax.scatter(x, y, c=vals, s=size, cmap="coolwarm" if name != "pressure" else "viridis", linewidths=0,
                        vmin=lo, vmax=hi if hi > lo else lo + 1e-30)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title("%s at t = %.4g s" % (name, snap.time), fontsize=10)
        fig.colorbar(sc, ax=ax, label=label, shrink=0.8)
    fig.suptitle(title(run, "particles"), fontsize=11)
    fig.tight_layout()
    save(fig, out, "snapshot_fields")


def main(argv):
    args = argv[1:]
    if len(args) == 3 and args[1] == "--format":
        OUTPUT["format"] = args[2]
        args = args[:1]
    if len(args) != 1:
        sys.stderr.write("usage: plot_run.py RUN_DIR [--format %s]\n" % "|".join(FORMATS))
        return 2
    if OUTPUT["format"] not in FORMATS:
        sys.stderr.write("plot_run.py: --format '%s': plots are drawn as %s; nothing drawn\n"
                         % (OUTPUT["format"], ", ".join(FORMATS)))
        return 2
    path = args[0]
    if not os.path.isdir(path):
        sys.stderr.write("plot_run.py: '%s' is not a run directory\n" % path)
        return 2
    run = reader.read_run(path)
    out = os.path.join(path, "plots")
    os.makedirs(out, exist_ok=True)
    for name in sorted(run.probes):
        if run.probes[name].rows == 0:
            continue
        if probe_spec(run.case, name).get("kind", "line") == "points":
            plot_point_probe(run, name, out)
        else:
            plot_line_probe(run, name, out)
    plot_flows(run, out)
    plot_bodies(run, out)
    plot_coefficients(run, out)
    plot_snapshot(run, out)
    print("plots written to %s" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
