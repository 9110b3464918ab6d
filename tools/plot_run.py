#!/usr/bin/env python3
"""Draws the plots of a particula run directory into DIR/plots/.

  plot_run.py DIR

- probe_<name>.csv: velocity profiles along each line probe at every written time, with the
  exact solution (vx_exact column) where the case declares one, and the profile error in time;
- bodies.csv: position, velocity, angle and force histories of every free or driven body
  (walls only when they move), against reference data named in the case when present;
- particles/*.vtp: the last snapshot's particles coloured by pressure and by each velocity
  component, like the paper's contour figures.
Uses Debian's python3-matplotlib; stdlib otherwise (the .vtp files are decoded here).
"""
import base64
import csv
import math
import os
import struct
import sys
import xml.etree.ElementTree as ET

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # pragma: no cover - reported to the user by the caller
    sys.stderr.write("plot_run.py: matplotlib is not installed (apt-get install python3-matplotlib); no plots\n")
    sys.exit(4)


def read_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, data = rows[0], rows[1:]
    cols = {h: [] for h in header}
    for r in data:
        if len(r) != len(header):
            continue  # a partial last line of an interrupted run
        for h, v in zip(header, r):
            cols[h].append(float(v))
    return cols


def read_vtp(path):
    """Points and point-data arrays of a particula .vtp (inline base64, UInt64 headers)."""
    root = ET.parse(path).getroot()
    piece = root.find("PolyData/Piece")
    def decode(el):
        raw = base64.b64decode(el.text.strip())
        nbytes = struct.unpack("<Q", raw[:8])[0]
        body = raw[8:8 + nbytes]
        fmt = {"Float64": "d", "Int32": "i", "Int64": "q"}[el.get("type")]
        return list(struct.unpack("<%d%s" % (nbytes // struct.calcsize(fmt), fmt), body)), int(el.get("NumberOfComponents", "1"))
    pts, _ = decode(piece.find("Points/DataArray"))
    arrays = {}
    for el in piece.find("PointData").findall("DataArray"):
        vals, nc = decode(el)
        arrays[el.get("Name")] = [vals[i::nc] for i in range(nc)] if nc > 1 else [vals]
    return pts[0::3], pts[1::3], arrays


def plot_probe(run, name, out):
    cols = read_csv(os.path.join(run, "probe_%s.csv" % name))
    all_times = sorted(set(cols["time"]))
    # at most 8 profiles, evenly spread over the run, the last included
    step = max(1, int(math.ceil((len(all_times) - 1) / 7.0)))
    times = all_times[::step]
    if times[-1] != all_times[-1]:
        times.append(all_times[-1])
    has_exact = "vx_exact" in cols
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    cmap = plt.get_cmap("viridis")
    errs = []
    for k, t in enumerate(times):
        idx = [i for i, tt in enumerate(cols["time"]) if tt == t]
        y = [cols["y"][i] for i in idx]
        vx = [cols["vx"][i] for i in idx]
        color = cmap(k / max(1, len(times) - 1))
        ax.plot(vx, y, "o", ms=3, color=color, label="SPH t = %.3g s" % t)
        if has_exact:
            ex = [cols["vx_exact"][i] for i in idx]
            ax.plot(ex, y, "-", lw=1, color=color, label="exact" if k == len(times) - 1 else None)
            peak = max(1e-300, max(abs(v) for v in cols["vx_exact"]))
            errs.append((t, math.sqrt(sum((a - b) ** 2 for a, b in zip(vx, ex)) / len(vx)) / peak))
    ax.set_xlabel("vx (m/s)")
    ax.set_ylabel("y (m)")
    ax.set_title("probe '%s': velocity profiles%s" % (name, " against the exact solution" if has_exact else ""))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "probe_%s_profiles.png" % name), dpi=120)
    plt.close(fig)
    if errs:
        fig, ax = plt.subplots(figsize=(6.4, 3.6))
        ax.semilogy([e[0] for e in errs[1:]], [max(e[1], 1e-12) for e in errs[1:]], "o-")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("L2 error of vx / peak speed")
        ax.set_title("probe '%s': profile error" % name)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "probe_%s_error.png" % name), dpi=120)
        plt.close(fig)


REFERENCE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference")

# Published reference curves per case name: (file, x column, y column, bodies.csv column, label).
REFERENCES = {
    "falling_cylinder": [("glowinski2001_settling_vy.csv", "t", "vy", "vy", "Glowinski et al. 2001 (FEM)"),
                         ("zhang2019_settling_y.csv", "t", "y", "y", "Zhang et al. 2019 (FPM)")],
    "shear_migration": [("feng2002_migration_y.csv", "t", "y", "y", "Feng & Michaelides 2002 (LBM)")],
    "two_cylinders_shear": [("hashemi2012_two_cylinders_vx.csv", "t", "vx", "vx", "Hashemi et al. 2012")],
    "dkt": [("hashemi2012_dkt_vy.csv", "t", "vy", "vy", "Hashemi et al. 2012")],
}


def read_case(run):
    """The resolved case.toml of the run as a dict ({} without it or without tomllib)."""
    try:
        import tomllib
        with open(os.path.join(run, "case.toml"), "rb") as f:
            return tomllib.load(f)
    except Exception:  # no case.toml or no tomllib (Python < 3.11): plots without names and references
        return {}


def case_name(run):
    return read_case(run).get("name", "")


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
        path = os.path.join(REFERENCE_DIR, fname)
        if not os.path.exists(path):
            continue
        ref = read_csv(path)
        if "body" in ref:
            for rb in sorted(set(int(v) for v in ref["body"])):
                ii = [i for i, v in enumerate(ref["body"]) if int(v) == rb]
                ax.plot([ref[xc][i] for i in ii], [ref[yc][i] for i in ii], "o", ms=4, label="%s, body %d" % (label, rb))
        else:
            ax.plot(ref[xc], ref[yc], "ko", ms=4, label=label)


def plot_bodies(run, out):
    cols = read_csv(os.path.join(run, "bodies.csv"))
    if not cols["time"]:
        return
    case = read_case(run)
    specs = case.get("body", [])
    bodies = sorted(set(int(b) for b in cols["body"]))
    names = {b: (specs[b].get("name", "body %d" % b) if b < len(specs) else "body %d" % b) for b in bodies}
    refs = REFERENCES.get(case.get("name", ""), [])
    t_last = max(cols["time"])
    series = {}
    for body in bodies:
        idx = [i for i, bb in enumerate(cols["body"]) if int(bb) == body]
        series[body] = {k: [cols[k][i] for i in idx] for k in cols}
    # one panel per quantity, so that each keeps its own scale (y of a migrating cylinder would
    # be flat next to its x), with the reference curves of that quantity
    panels = [("x", "x (m)"), ("y", "y (m)"), ("angle", "angle (rad), counter-clockwise"),
              ("vx", "vx (m/s)"), ("vy", "vy (m/s)"), ("force", "hydrodynamic force (N/m)")]
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    for ax, (col, title) in zip([a for row in axes for a in row], panels):
        if col == "force":
            weights = {}
            for body in bodies:
                ax.plot(series[body]["time"], series[body]["fx"], label="%s fx" % names[body])
                ax.plot(series[body]["time"], series[body]["fy"], "--", label="%s fy" % names[body])
                w = excess_weight_y(case, specs[body]) if body < len(specs) else None
                if w is not None:
                    weights.setdefault(round(w, 12), []).append(names[body])
            for w, who in weights.items():
                ax.axhline(w, color="0.4", ls=":", lw=1.2,
                           label="weight - buoyancy of %s (fy at terminal speed)" % ", ".join(who))
        else:
            for k, body in enumerate(bodies):
                if body < len(specs) and specs[body].get("motion", "free") == "fixed":
                    continue  # a fixed obstacle only has forces to show
                ax.plot(series[body]["time"], series[body][col], color="C%d" % k, label=names[body])
            plot_reference(ax, col, refs)
        if col == "angle" and any(abs(v) > 0 for body in bodies for v in series[body]["omega"]):
            tw = ax.twinx()
            for k, body in enumerate(bodies):
                if body < len(specs) and specs[body].get("motion", "free") == "fixed":
                    continue
                tw.plot(series[body]["time"], series[body]["omega"], ":", lw=1, color="C%d" % k,
                        label="%s omega" % names[body])
            tw.set_ylabel("omega (rad/s), dotted")
        # the run's time span: reference points after its end would only squeeze the curves
        if t_last > 0:
            ax.set_xlim(0, t_last * 1.02)
        ax.set_xlabel("t (s)")
        ax.set_ylabel(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, framealpha=0.7)
    fig.suptitle("bodies of '%s'" % (case.get("name", "") or run))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bodies.png"), dpi=110)
    plt.close(fig)


def plot_snapshot(run, out):
    pvd = os.path.join(run, "particles.pvd")
    if not os.path.exists(pvd):
        return
    files = [ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
    times = [float(ds.get("timestep")) for ds in ET.parse(pvd).getroot().iter("DataSet")]
    if not files or not os.path.exists(os.path.join(run, files[-1])):
        return
    x, y, arrays = read_vtp(os.path.join(run, files[-1]))
    fields = [("pressure", arrays["pressure"][0], "p (Pa)"), ("vx", arrays["velocity"][0], "vx (m/s)"),
              ("vy", arrays["velocity"][1], "vy (m/s)")]
    width = max(x) - min(x)
    height = max(y) - min(y)
    aspect = height / width if width > 0 else 1
    fig, axes = plt.subplots(1, 3, figsize=(12, max(3.0, min(9.0, 4.0 * aspect)) + 0.8))
    size = max(0.5, min(20.0, 20000.0 / max(1, len(x))))
    for ax, (name, vals, label) in zip(axes, fields):
        # colour range from the 1st to the 99th percentile, so that a few outliers (a particle
        # squeezed against a wall, a failing run's last state) do not wash out the field
        ranked = sorted(vals)
        lo = ranked[int(0.01 * (len(ranked) - 1))]
        hi = ranked[int(0.99 * (len(ranked) - 1))]
        if name != "pressure":
            hi = max(abs(lo), abs(hi))
            lo = -hi
        sc = ax.scatter(x, y, c=vals, s=size, cmap="coolwarm" if name != "pressure" else "viridis", linewidths=0,
                        vmin=lo, vmax=hi if hi > lo else lo + 1e-30)
        ax.set_aspect("equal")
        ax.set_title("%s at t = %.4g s" % (name, times[-1]))
        fig.colorbar(sc, ax=ax, label=label, shrink=0.8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "snapshot_fields.png"), dpi=120)
    plt.close(fig)


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: plot_run.py RUN_DIR\n")
        return 2
    run = argv[1]
    if not os.path.isdir(run):
        sys.stderr.write("plot_run.py: '%s' is not a run directory\n" % run)
        return 2
    out = os.path.join(run, "plots")
    os.makedirs(out, exist_ok=True)
    for f in sorted(os.listdir(run)):
        if f.startswith("probe_") and f.endswith(".csv"):
            plot_probe(run, f[len("probe_"):-len(".csv")], out)
    if os.path.exists(os.path.join(run, "bodies.csv")):
        plot_bodies(run, out)
    plot_snapshot(run, out)
    print("plots written to %s" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
