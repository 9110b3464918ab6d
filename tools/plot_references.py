"""The published reference curves of the paper's cases, for tools/plot_run.py, and whether a run
may be compared with them.

A reference belongs to one shipped case (cases/<name>.toml): it is drawn only when the run's
resolved case (its case.toml) has the physics of that case, every key of PHYSICS the same
(the shipped file's value, or the schema's default where the file leaves a key out). Numerics,
resolution, time, outputs, contacts and analysis may differ. Otherwise nothing of the reference
is drawn, and the panel says why ("no reference: the physics is not that of
cases/falling_cylinder.toml (body[0].density = 1500 here, 1250 there)").
"""
import json
import math
import os

try:
    import tomllib
except ImportError:  # pragma: no cover - Python < 3.11
    tomllib = None

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
REFERENCE_DIR = os.path.join(ROOT, "reference")
CASES_DIR = os.path.join(ROOT, "cases")
SCHEMA = os.path.join(ROOT, "docs", "case.schema.json")

# Published reference curves per case name: (file, x column, y column, bodies.csv column, label).
REFERENCES = {
    "falling_cylinder": [("glowinski2001_settling_vy.csv", "t", "vy", "vy", "Glowinski et al. 2001 (FEM)"),
                         ("zhang2019_settling_y.csv", "t", "y", "y", "Zhang et al. 2019 (FPM)")],
    "shear_migration": [("feng2002_migration_y.csv", "t", "y", "y", "Feng & Michaelides 2002 (LBM)")],
    "two_cylinders_shear": [("hashemi2012_two_cylinders_vx.csv", "t", "vx", "vx", "Hashemi et al. 2012")],
    "dkt": [("hashemi2012_dkt_vy.csv", "t", "vy", "vy", "Hashemi et al. 2012")],
}

# The keys that decide a reference curve: every key of these sections and arrays of tables but
# those named (numbers: names, the fluid's artificial sound speed and background pressure, the
# analysis' reference scales, the initial perturbation). fluid.mu is compared as nu = mu / rho0.
PHYSICS = {
    "domain": (),
    "fluid": ("c", "p0", "mu"),
    "initial": ("perturbation", "seed", "hydrostatic"),
    "wall": ("name",),
    "body": ("name", "reference_velocity", "reference_length"),
    "inlet": ("name", "layers"),
    "outlet": ("name", "layers"),
}


def schema_keys(section):
    """{key: default or None} of a section (or of one table of an array of tables) of the schema."""
    with open(SCHEMA) as f:
        node = json.load(f)["properties"].get(section, {})
    props = node.get("items", node).get("properties", {})
    return {k: v.get("default") for k, v in props.items()}


def physics_values(case, schema=None):
    """{"fluid.nu": 1e-05, "body[0].density": 1250.0, "body.count": 1, ...}: the physics keys of a
    case as a TOML dict, the schema's defaults where a key is left out."""
    values = {}
    for section, skipped in PHYSICS.items():
        keys = {k: d for k, d in schema_keys(section).items() if k not in skipped}
        given = case.get(section, [] if section in ("wall", "body", "inlet", "outlet") else {})
        tables = given if isinstance(given, list) else [given]
        if isinstance(given, list):
            values["%s.count" % section] = len(given)
        for i, table in enumerate(tables):
            prefix = "%s[%d]." % (section, i) if isinstance(given, list) else section + "."
            for k, default in keys.items():
                values[prefix + k] = table.get(k, default)
    fluid = case.get("fluid", {})
    if "nu" not in fluid and "mu" in fluid:
        values["fluid.nu"] = fluid["mu"] / fluid.get("rho0", schema_keys("fluid")["rho0"])
    return values


def same(a, b):
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-300)
    return a == b


def shown(v):
    return json.dumps(v) if isinstance(v, str) else "%s" % (v if not isinstance(v, float) else "%.6g" % v)


def physics_differences(case, shipped):
    """['body[0].density = 1500 here, 1250 there', ...]: one text per physics key whose value in
    `case` differs from that in `shipped`; empty when the physics is the same."""
    mine, theirs = physics_values(case), physics_values(shipped)
    return ["%s = %s here, %s there" % (k, shown(mine.get(k)), shown(theirs.get(k)))
            for k in sorted(set(mine) | set(theirs)) if not same(mine.get(k), theirs.get(k))]


def references_for(case):
    """(references, note) for a run's resolved case: the case's reference curves when its physics
    is that of the shipped case they belong to; else no curves and a note saying why (None when
    the case has no references)."""
    name = case.get("name", "")
    refs = REFERENCES.get(name, [])
    if not refs:
        return [], None
    path = os.path.join(CASES_DIR, name + ".toml")
    rel = os.path.relpath(path, ROOT)
    if tomllib is None or not os.path.exists(path):
        return [], "no reference: %s cannot be read to compare the physics with" % rel
    with open(path, "rb") as f:
        shipped = tomllib.load(f)
    diffs = physics_differences(case, shipped)
    if not diffs:
        return refs, None
    more = " (and %d more)" % (len(diffs) - 2) if len(diffs) > 2 else ""
    return [], "no reference: the physics is not that of %s (%s%s)" % (rel, "; ".join(diffs[:2]), more)
