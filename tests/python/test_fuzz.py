"""A seeded fuzz test of the Python API: random calls of particula.Simulation's methods and
constructors with random arguments of random types, in batches, each batch in a child process.
It fails on a crash (a signal) and on any exception outside the documented ones: TypeError for a
wrong type, ValueError (InputError, CaseError) for a wrong value, NumericalFailure, IoFailure."""
import json
import os

import pytest

from conftest import HYDROSTATIC, case
from subprocess_run import run_python

SEED = 20240611
# 200 calls in CI; PARTICULA_FUZZ_BATCHES=20 for the 1,000 of a longer check (same seeds first).
BATCHES, CALLS = int(os.environ.get("PARTICULA_FUZZ_BATCHES", "4")), 50

CHILD = r"""
import atexit, json, math, os, random, shutil, tempfile
import numpy as np
import particula

CASE, SMALL, SEED, CALLS = %r, %r, %d, %d
rng = random.Random(SEED)
tmp = tempfile.mkdtemp(prefix="particula-fuzz-")
atexit.register(shutil.rmtree, tmp, ignore_errors=True)
os.chdir(tmp)  # a bare file name the fuzz writes to ends up here, not in the caller's directory
saved = os.path.join(tmp, "state.bin")
not_a_checkpoint = os.path.join(tmp, "case.toml")  # a copy: the fuzz may write over it
with open(CASE) as src, open(not_a_checkpoint, "w") as dst:
    dst.write(src.read())

def junk():
    # A value of a random type: what a caller may pass by mistake.
    return rng.choice([None, True, False, 0, 1, -1, 2**40, 10**400, math.nan, math.inf, -math.inf, 1e-300,
                       -0.0, "", "1", "cpu", b"x", [], [1.0], {}, {"a": 1}, object(), np.float64(math.nan),
                       np.int64(-5), np.float32(1e-4), np.array([1.0, 2.0]), 1j])

def a_time(sim):
    # Near the current time (before or after it), or junk that is not a far future time (run_to
    # steps until it: a long run, not an error).
    t = junk()
    if rng.random() < 0.6 or isinstance(t, (int, float, np.number)) and t == t and 0 < t < math.inf:
        return sim.time + rng.uniform(-1e-3, 2e-3)
    return t

def a_dt():
    return rng.choice([0.0, 1e-5, 1e-4, 1e300, rng.uniform(-1e-4, 1e-4), junk()])

def overrides():
    # Coarse or wrong: never the shipped resolution, whose steps take too long for a test.
    return rng.choice([SMALL, ["resolution.d0=1e-2"], dict(SMALL, **{"resolution.d0": rng.choice([1e-2, 0, -1, math.nan,
                       "x", None, [1]])}), dict(SMALL, **{"no.such": 1}), "resolution.d0=5e-3", [1, 2], 7, 1.5,
                       {"resolution.d0": b"x"}])

def a_path():
    return rng.choice([saved, os.path.join(tmp, "sub", "s.bin"), "", tmp, "/proc/no/such", not_a_checkpoint, 5, None, b"x"])

def construct():
    kwargs = {}
    if rng.random() < 0.5:
        kwargs["threads"] = rng.choice([1, 2, 0, -1, 5000, 10**9, 1.5, junk()])
    if rng.random() < 0.3:
        kwargs["backend"] = rng.choice(["cpu", "cuda", "", "CPU", junk()])
    if rng.random() < 0.2:
        return particula.Simulation.from_checkpoint(a_path(), rng.choice([None, {"time.end": 1}, {"fluid.nu": 1}]),
                                                    **kwargs)
    return particula.Simulation(rng.choice([CASE, CASE, "no_such.toml", tmp, junk()]), overrides(), **kwargs)

READS = ["time", "step_count", "dt", "n_particles", "n_boundary", "positions", "velocity", "density",
         "pressure", "mass", "kind", "id", "group", "normals", "body_index", "wall_index", "guard_events",
         "case", "name", "d0", "h", "backend"]

def call(sim):
    what = rng.choice(["step", "step", "run_to", "run_to", "checkpoint", "read", "states", "new", "repr"])
    if what == "step":
        sim.step(a_dt())
    elif what == "run_to":
        sim.run_to(a_time(sim))
    elif what == "checkpoint":
        sim.write_checkpoint(a_path())
    elif what == "read":
        np.asarray(getattr(sim, rng.choice(READS)))
    elif what == "states":
        sim.body_states(); sim.wall_states()
    elif what == "repr":
        repr(sim)
    else:
        return construct()
    return sim

ALLOWED = (TypeError, ValueError, particula.NumericalFailure, particula.IoFailure)
sim = particula.Simulation(CASE, SMALL, threads=1)
counts, unexpected = {}, []
for i in range(CALLS):
    try:
        sim = call(sim)
        name = "ok"
    except ALLOWED as e:
        name = type(e).__name__
    except Exception as e:
        name = type(e).__name__
        unexpected.append("call %%d: %%s: %%s" %% (i, name, e))
    counts[name] = counts.get(name, 0) + 1
print(json.dumps({"counts": counts, "unexpected": unexpected}))
"""


@pytest.mark.parametrize("batch", range(BATCHES))
def test_random_calls_raise_only_documented_errors(batch):
    proc = run_python(CHILD % (case("hydrostatic"), HYDROSTATIC, SEED + batch, CALLS), timeout=120)
    assert proc.returncode == 0, proc.stderr
    got = json.loads(proc.stdout.splitlines()[-1])
    assert got["unexpected"] == [], got
    assert got["counts"].get("ok", 0) > 0 and sum(got["counts"].values()) == CALLS, got
