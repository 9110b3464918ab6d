"""Reading a run directory with NumPy alone (no VTK): particula.read_run(DIR).

    run = particula.read_run("runs/demo")
    run.summary["end_time"]              # summary.json as a dict
    run.case["resolution"]["d0"]         # case.toml as a dict
    run.bodies["vy"]                     # bodies.csv: a Table, one float64 array per column
    run.bodies.units["fx"]               # "N/m", from the file's "# units:" line
    run.body(0)["vy"]                    # the rows of body 0
    run.walls, run.probes["profile"]     # walls.csv, probe_<name>.csv
    run.flows["profile"]["flow_rate"]    # flow_<name>.csv: the flow rate through a line probe
    run.coefficient(0)["cd"]             # coefficients.csv (cases with reference velocity and length)
    run.probe("profile")["vx"]           # a probe as (times, points) arrays
    run.snapshots.times                  # particles.pvd: the snapshot times
    snap = run.snapshots[-1]             # a Snapshot, read when asked for
    snap.points, snap["pressure"], snap["velocity"]

Snapshots are read lazily (one file per access). Point arrays of 3 components (the .vtp form of
2D vectors, z = 0) come back as (n, 2), like the points.
"""
import base64
import json
import os
import tomllib
import xml.etree.ElementTree as ET

import numpy as np

# .vtp DataArray types and their NumPy types (little-endian, as particula writes them).
_VTK_TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "Int16": "<i2", "Int8": "i1",
              "UInt64": "<u8", "UInt32": "<u4", "UInt16": "<u2", "UInt8": "u1"}
_HEADER_TYPES = {"UInt64": "<u8", "UInt32": "<u4"}
# CSV columns that hold indices.
_INDEX_COLUMNS = ("body", "wall")


class Table(dict):
    """The columns of a CSV file: {name: 1-D NumPy array}, in file order; `units` maps a column
    to its unit when the file has a units row or header comment, else it is empty."""

    def __init__(self, columns, units=None, path=None):
        super().__init__(columns)
        self.units = units or {}
        self.path = path

    @property
    def rows(self):
        return len(next(iter(self.values()))) if self else 0

    def __repr__(self):
        return "<particula.Table %s: %d rows, columns %s>" % (self.path, self.rows, ", ".join(self))

    def where(self, mask):
        """The rows where mask (a boolean array) is true, as a Table."""
        return Table({k: v[mask] for k, v in self.items()}, self.units, self.path)

    def to_pandas(self):
        """The table as a pandas.DataFrame (pandas is optional: ImportError saying so when it is
        missing); the units are in its attrs["units"]."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Table.to_pandas needs pandas (pip install pandas, or apt-get install "
                              "python3-pandas); the columns are NumPy arrays without it") from None
        frame = pandas.DataFrame({k: v for k, v in self.items()})
        frame.attrs["units"] = dict(self.units)
        return frame


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _unit(entry, column):
    """The unit of one entry of a units comment: "x [m]" (particula's form, naming the column)
    or a bare "m"."""
    entry = entry.strip()
    if entry.endswith("]") and " [" in entry:
        name, unit = entry[:-1].split(" [", 1)
        return unit if name.strip() == column else None
    return entry


def _comment_units(comments, header):
    """Units from a comment line such as "# units: time [s], x [m], ..." (particula writes it
    after the header) or "# units: s,m,..." (one per column), if any."""
    for c in comments:
        body = c.lstrip("#").strip()
        if body.lower().startswith("units:"):
            entries = body[len("units:"):].split(",")
            if len(entries) == len(header):
                units = [_unit(e, h) for e, h in zip(entries, header)]
                if None not in units:
                    return dict(zip(header, units))
    return {}


def read_csv(path):
    """A particula CSV file (bodies.csv, walls.csv, probe_<name>.csv) as a Table. Lines starting
    with '#' are comments; a row of non-numbers after the header is read as the units row; an
    incomplete last line (a run killed while writing) is left out."""
    with open(path, newline="") as f:
        lines = f.read().split("\n")
    complete = lines[:-1]  # the text after the last newline is an incomplete line, or empty
    comments = [ln for ln in complete if ln.startswith("#")]
    rows = [ln.split(",") for ln in complete if ln.strip() and not ln.startswith("#")]
    if not rows:
        raise ValueError("%s: no header line" % path)
    header = [h.strip() for h in rows[0]]
    units = _comment_units(comments, header)
    body = rows[1:]
    if body and not all(_is_number(v) for v in body[0]):
        units = dict(zip(header, (u.strip() for u in body[0])))
        body = body[1:]
    body = [r for r in body if len(r) == len(header)]
    data = np.array(body, dtype=np.float64).reshape(len(body), len(header))
    columns = {}
    for j, name in enumerate(header):
        col = data[:, j]
        columns[name] = col.astype(np.int64) if name in _INDEX_COLUMNS else col
    return Table(columns, units, path)


def _decode_array(el, num, header_dtype):
    """A binary inline DataArray as a (num,) or (num, components) NumPy array."""
    name = el.get("Name")
    if el.get("format") != "binary":
        raise ValueError("array '%s': format '%s' is not supported (binary only)" % (name, el.get("format")))
    dtype = np.dtype(_VTK_TYPES[el.get("type")])
    raw = base64.b64decode("".join((el.text or "").split()))
    hsize = np.dtype(header_dtype).itemsize
    if len(raw) < hsize:
        raise ValueError("array '%s' has no byte-count header" % name)
    nbytes = int(np.frombuffer(raw[:hsize], dtype=header_dtype)[0])
    if nbytes != len(raw) - hsize:
        raise ValueError("array '%s' declares %d bytes but holds %d" % (name, nbytes, len(raw) - hsize))
    values = np.frombuffer(raw[hsize:], dtype=dtype)
    components = int(el.get("NumberOfComponents", "1"))
    if values.size != num * components:
        raise ValueError("array '%s' has %d values for %d points x %d components" % (name, values.size, num, components))
    values = values.astype(dtype.newbyteorder("="))  # a native, writable copy
    return values.reshape(num, components) if components > 1 else values


class Snapshot(dict):
    """The particles of one .vtp file: points (n, 2) in m and {array name: NumPy array}; a
    3-component array (a 2D vector) is (n, 2). Arrays particula writes: pressure (Pa),
    velocity (m/s), density (kg/m^3), kind (0 fluid, 1 wall or body surface, 2 dummy particle of
    the dummy-particle boundary), body (the body's index in the case, as in bodies.csv; -1 for
    particles of no body), wall (the wall's index in the case, as in walls.csv; -1 otherwise), id
    (a particle's stable identity)."""

    def __init__(self, points, arrays, time=None, path=None):
        super().__init__(arrays)
        self.points = points
        self.time = time
        self.path = path

    @property
    def num_points(self):
        return len(self.points)

    def __repr__(self):
        return "<particula.Snapshot %s: t = %r s, %d points, arrays %s>" % (
            self.path, self.time, self.num_points, ", ".join(self))


def _vector2(a):
    return a[:, :2].copy() if a.ndim == 2 and a.shape[1] == 3 else a


def read_vtp(path, time=None):
    """A .vtp file (VTK XML PolyData, inline binary, as particula writes it) as a Snapshot."""
    root = ET.parse(path).getroot()
    if root.get("type") != "PolyData":
        raise ValueError("%s: not a VTK PolyData file" % path)
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise ValueError("%s: byte order %s is not supported" % (path, root.get("byte_order")))
    if root.get("compressor"):
        raise ValueError("%s: compressed files are not supported" % path)
    header = _HEADER_TYPES[root.get("header_type", "UInt32")]
    pieces = root.findall("PolyData/Piece")
    if len(pieces) != 1:
        raise ValueError("%s: %d pieces (one expected)" % (path, len(pieces)))
    piece = pieces[0]
    n = int(piece.get("NumberOfPoints"))
    try:
        points = _vector2(_decode_array(piece.find("Points/DataArray"), n, header))
        arrays = {el.get("Name"): _vector2(_decode_array(el, n, header))
                  for el in piece.findall("PointData/DataArray")}
    except (ValueError, KeyError) as e:
        raise ValueError("%s: %s" % (path, e)) from None
    return Snapshot(points, arrays, time, path)


def read_pvd(path):
    """The (time, file) entries of a .pvd index, file relative to the index's directory."""
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


class Snapshots:
    """The snapshots of particles.pvd: times (NumPy array), files, and snapshots[i] (negative i
    counts from the end) or at(t) (the nearest) read when asked for."""

    def __init__(self, pvd):
        self.dir = os.path.dirname(pvd)
        entries = read_pvd(pvd) if os.path.exists(pvd) else []
        self.times = np.array([t for t, _ in entries], dtype=np.float64)
        self.files = [os.path.join(self.dir, f) for _, f in entries]

    def __len__(self):
        return len(self.files)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        return read_vtp(self.files[i], float(self.times[i]))

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    def at(self, t):
        """The snapshot nearest to time t."""
        return self[int(np.argmin(np.abs(self.times - t)))]


class Run:
    """A run directory's content (see the module's docstring). Files a run did not write
    (walls.csv of a case without walls, snapshots when output.snapshots is off, summary.json of a
    run still going) are None / empty."""

    def __init__(self, path):
        path = os.fspath(path)
        if not os.path.isdir(path):
            raise FileNotFoundError("run directory '%s' does not exist" % path)
        if not os.path.exists(os.path.join(path, "case.toml")) and \
                not os.path.exists(os.path.join(path, ".particula-run")):
            from .errors import InputError
            raise InputError("'%s' is not a particula run directory (it has no case.toml; run directories are "
                             "made by particula.run_case or `particula run`)" % path)
        self.dir = path
        self.case = self._toml("case.toml")
        self.summary = self._json("summary.json")
        self.bodies = self._csv("bodies.csv")
        self.walls = self._csv("walls.csv")
        self.coefficients = self._csv("coefficients.csv")
        self.probes, self.flows = {}, {}
        for f in sorted(os.listdir(self.dir)):
            for prefix, table in (("probe_", self.probes), ("flow_", self.flows)):
                if f.startswith(prefix) and f.endswith(".csv"):
                    table[f[len(prefix):-len(".csv")]] = read_csv(os.path.join(self.dir, f))
        self.snapshots = Snapshots(os.path.join(self.dir, "particles.pvd"))
        log = os.path.join(self.dir, "log.txt")
        self.log = open(log).read() if os.path.exists(log) else ""

    def _path(self, name):
        p = os.path.join(self.dir, name)
        return p if os.path.exists(p) else None

    def _toml(self, name):
        p = self._path(name)
        if not p:
            return {}
        with open(p, "rb") as f:
            return tomllib.load(f)

    def _json(self, name):
        p = self._path(name)
        if not p:
            return {}
        with open(p) as f:
            return json.load(f)

    def _csv(self, name):
        p = self._path(name)
        return read_csv(p) if p else None

    def _group_index(self, kind, which):
        """The case index of the body or wall `which` (its index or its name); KeyError naming
        the valid ones otherwise."""
        groups = self.case.get(kind, [])
        names = [g.get("name", "") for g in groups]
        if isinstance(which, str):
            if which in names and which:
                return names.index(which)
        elif isinstance(which, (int, np.integer)) and not isinstance(which, bool) and 0 <= which < len(groups):
            return int(which)
        if not groups:
            raise KeyError("%r: the case of %s has no %s" % (which, self.dir, kind))
        named = ", ".join("%d %r" % (i, n) if n else str(i) for i, n in enumerate(names))
        raise KeyError("%r: no %s of that index or name in %s (the %ss are %s)" % (which, kind, self.dir, kind, named))

    def _rows(self, table, file, column, index):
        if table is None:
            raise KeyError("%s has no %s (the run wrote none)" % (self.dir, file))
        return table.where(table[column] == index)

    def body(self, which):
        """The rows of bodies.csv for a body, by case index or name, a Table; KeyError for an
        unknown body."""
        return self._rows(self.bodies, "bodies.csv", "body", self._group_index("body", which))

    def wall(self, which):
        """The rows of walls.csv for a wall, by case index or name, a Table."""
        return self._rows(self.walls, "walls.csv", "wall", self._group_index("wall", which))

    def coefficient(self, which):
        """The rows of coefficients.csv (re, re_body, cd, cl, cm) for a body, by case index or name."""
        return self._rows(self.coefficients, "coefficients.csv", "body", self._group_index("body", which))

    def probe(self, name):
        """A probe as arrays: time (nt,), x and y (np,), and each other column (nt, np)."""
        if name not in self.probes:
            raise KeyError("%r: no probe of that name in %s (the probes are %s)" % (name, self.dir,
                                                                                   ", ".join(self.probes) or "none"))
        t = self.probes[name]
        times = np.unique(t["time"])
        npts = t.rows // max(1, len(times))
        if npts * len(times) != t.rows:
            raise ValueError("probe '%s': %d rows are not %d times x whole profiles" % (name, t.rows, len(times)))
        out = {"time": times, "x": t["x"][:npts], "y": t["y"][:npts]}
        for k, v in t.items():
            if k not in ("time", "x", "y"):
                out[k] = v.reshape(len(times), npts)
        return out

    def __repr__(self):
        return "<particula.Run %s: %d snapshots, %d bodies>" % (
            self.dir, len(self.snapshots), 0 if self.bodies is None else len(np.unique(self.bodies["body"])))


def read_run(path):
    """The content of a run directory as a Run (bodies, walls, probes, summary, case, snapshots)."""
    return Run(path)


__all__ = ["read_run", "read_csv", "read_vtp", "read_pvd", "Run", "Table", "Snapshot", "Snapshots"]
