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


def case_name(run):
    try:
        import tomllib
        with open(os.path.join(run, "case.toml"), "rb") as f:
            return tomllib.load(f).get("name", "")
    except Exception:  # no case.toml or no tomllib: plots without reference curves
        return ""


def plot_bodies(run, out):
    cols = read_csv(os.path.join(run, "bodies.csv"))
    if not cols["time"]:
        return
    bodies = sorted(set(int(b) for b in cols["body"]))
    refs = REFERENCES.get(case_name(run), [])
    panels = [("x", "y", "position (m)"), ("vx", "vy", "velocity (m/s)"), ("fx", "fy", "hydrodynamic force (N/m)"),
              ("angle", None, "angle (rad)")]
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    for ax, (a, b, title) in zip([axes[0][0], axes[0][1], axes[1][0], axes[1][1]], panels):
        for body in bodies:
            idx = [i for i, bb in enumerate(cols["body"]) if int(bb) == body]
            t = [cols["time"][i] for i in idx]
            ax.plot(t, [cols[a][i] for i in idx], label="body %d %s" % (body, a))
            if b:
                ax.plot(t, [cols[b][i] for i in idx], "--", label="body %d %s" % (body, b))
        for (fname, xc, yc, col, label) in refs:
            if col not in (a, b):
                continue
            path = os.path.join(REFERENCE_DIR, fname)
            if not os.path.exists(path):
                continue
            ref = read_csv(path)
            if "body" in ref:
                for rb in sorted(set(int(v) for v in ref["body"])):
                    ii = [i for i, v in enumerate(ref["body"]) if int(v) == rb]
                    ax.plot([ref[xc][i] for i in ii], [ref[yc][i] for i in ii], "o", ms=4,
                            label="%s, body %d" % (label, rb))
            else:
                ax.plot(ref[xc], ref[yc], "ko", ms=4, label=label)
        ax.set_xlabel("t (s)")
        ax.set_ylabel(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("bodies of '%s'" % (case_name(run) or run))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "bodies.png"), dpi=120)
    plt.close(fig)


def plot_snapshot(run, out):
    pvd = os.path.join(run, "particles.pvd")
    if not os.path.exists(pvd):
        return
    files = [ds.get("file") for ds in ET.parse(pvd).getroot().iter("DataSet")]
    times = [float(ds.get("timestep")) for ds in ET.parse(pvd).getroot().iter("DataSet")]
    if not files:
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
