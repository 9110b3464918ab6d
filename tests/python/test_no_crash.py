"""No crash, whatever the caller does: thread counts out of range, one Simulation stepped from two
threads, times that are not times, stepping after a numerical failure. Each call that crashed
once runs in a child process (subprocess_run), so that a crash fails the test."""
import json

from conftest import HYDROSTATIC, case
from subprocess_run import run_cli, run_python

SETUP = """
import json, math, threading
import particula
CASE, SMALL = %r, %r
def outcome(f):
    try:
        f()
        return "ok"
    except Exception as e:
        return "%%s: %%s" %% (type(e).__name__, e)
""" % (case("hydrostatic"), HYDROSTATIC)

RUN_CLI = ["run", case("hydrostatic"), "--set", "resolution.d0=5e-3", "--set", "time.end=0.001", "--quiet",
           "--no-plots", "--overwrite"]


def outcomes(body, env=None):
    """The JSON the child prints last, after SETUP and `body`."""
    proc = run_python(SETUP + body, env)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.splitlines()[-1])


def test_threads_argument_is_checked_before_openmp_sees_it():
    got = outcomes("""
calls = [100000, 10**9, 0, -1, 2.5, True, "4"]
print(json.dumps([outcome(lambda n=n: particula.Simulation(CASE, SMALL, threads=n)) for n in calls]
                 + [outcome(lambda: particula.run_case(CASE, "unused", SMALL, threads=10**9))]))
""")
    for text in got[:4] + got[7:]:
        assert text.startswith("ValueError: threads = ") and "1 .. 4096" in text, text
    for text in got[4:7]:
        assert text.startswith("TypeError: threads: an integer"), text


def test_omp_num_threads_out_of_range_is_refused(tmp_path):
    got = outcomes("""
print(json.dumps([outcome(lambda: particula.Simulation(CASE, SMALL)),
                  outcome(lambda: particula.Simulation(CASE, SMALL, threads=1))]))
""", env={"OMP_NUM_THREADS": "100000"})
    assert got[0].startswith("InputError: OMP_NUM_THREADS=100000: not a thread count"), got[0]
    assert got[1] == "ok"  # threads= overrides the variable
    for value in ("100000", "1000000000", "-3", "0"):
        proc = run_cli(RUN_CLI + ["--out", str(tmp_path / "run")], env={"OMP_NUM_THREADS": value})
        assert proc.returncode == 2 and "error: OMP_NUM_THREADS=%s:" % value in proc.stderr, proc.stderr
    proc = run_cli(RUN_CLI + ["--out", str(tmp_path / "run"), "--threads", "1"], env={"OMP_NUM_THREADS": "100000"})
    assert proc.returncode == 0, proc.stderr
    assert run_cli(RUN_CLI + ["--threads", "100000"]).returncode == 2


def test_one_simulation_stepped_from_two_threads():
    got = outcomes("""
sim = particula.Simulation(CASE, SMALL, threads=1)
done = {"steps": 0, "busy": 0, "other": []}
def worker():
    for _ in range(40):
        try:
            sim.step()
            done["steps"] += 1
        except RuntimeError as e:
            done["busy" if "being stepped by another thread" in str(e) else "other"] += 1
long = threading.Thread(target=lambda: done.__setitem__("run_to", sim.run_to(0.02)))
long.start()
workers = [threading.Thread(target=worker) for _ in range(2)]
[w.start() for w in workers]
[w.join() for w in workers + [long]]
done["step_count"] = sim.step_count
print(json.dumps(done))
""")
    assert got["other"] == [], got
    assert got["busy"] > 0, got  # the two threads met
    assert got["step_count"] == got["steps"] + got["run_to"], got  # no step lost


def test_times_are_checked():
    got = outcomes("""
sim = particula.Simulation(CASE, SMALL, threads=1)
out = [outcome(lambda t=t: sim.run_to(t)) for t in (-1.0, math.nan, math.inf, 10**400, "1", None)]
out += [outcome(lambda d=d: sim.step(d)) for d in (math.nan, -1.0, math.inf, [1e-5])]
sim.run_to(0.001)
out += [outcome(lambda: sim.run_to(0.0005)), outcome(lambda: sim.step(1e-300)), outcome(lambda: sim.run_to(0.001))]
out.append(sim.step_count)
print(json.dumps(out))
""")
    for text, name in zip(got[:4], ("t = -1 s", "t = nan s", "t = inf s", "t = 100000...e400 s")):
        assert text.startswith("ValueError: ") and name in text, (text, name)
    assert got[4].startswith("TypeError: t: a number") and got[5].startswith("TypeError: t: a number")
    for text, name in zip(got[6:9], ("max_dt = nan s", "max_dt = -1 s", "max_dt = inf s")):
        assert text.startswith("ValueError: step: ") and name in text, (text, name)
    assert got[9].startswith("TypeError: max_dt: a number")
    assert got[10].startswith("ValueError: run_to: t = 0.0005 s") and "current t = 0.001 s" in got[10]
    assert got[11].startswith("ValueError: step: max_dt = 1e-300 s is too small")
    assert got[12] == "ok" and got[13] > 0  # run_to the current time: no step


def test_no_step_after_a_numerical_failure():
    got = outcomes("""
sim = particula.Simulation(CASE, dict(SMALL, **{"fluid.c": 0.05, "time.dt_max": 1e-3}), threads=1)
out = []
for call in (lambda: sim.run_to(0.5), lambda: sim.step(), lambda: sim.run_to(0.5)):
    try:
        call()
    except particula.NumericalFailure as e:
        out.append([str(e), e.time, e.step])
out.append(sim.step_count)
print(json.dumps(out))
""")
    first, *again, steps = got
    assert first[0].startswith("numerical failure at t = ") and len(again) == 2
    for text, t, step in again:
        assert text.startswith("this Simulation failed at t = %.9g s, step %d and steps no further" % (t, step))
        assert "from a checkpoint" in text and [t, step] == first[1:]
    assert steps == first[2]  # nothing stepped after the failure
