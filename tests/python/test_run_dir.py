"""particula.run_case / resume (the CLI's runner) and particula.read_run on what they write."""
import os
import re
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import COUETTE, HYDROSTATIC, ROOT, case

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")
BINARY = os.environ.get("PARTICULA_BINARY", os.path.join(ROOT, "build", "release", "particula"))


@pytest.fixture(scope="module")
def settling_run(particula, tmp_path_factory):
    out = tmp_path_factory.mktemp("runs") / "settling"
    result = particula.run_case(SETTLING, out, plots=False)
    assert result.exit_code == 0 and result.run_dir == str(out)
    return particula.read_run(out)


def test_run_directory_is_the_clis(settling_run):
    names = set(os.listdir(settling_run.dir))
    assert {"case.toml", "summary.json", "log.txt", "bodies.csv", "walls.csv", "probe_midline.csv",
            "particles.pvd", "particles", "checkpoint", ".particula-run"} <= names
    assert settling_run.summary["status"] == "completed"
    assert settling_run.case["name"] == "settling"


def test_summary_says_what_made_the_run(settling_run):
    summary = settling_run.summary
    version = subprocess.run([BINARY, "--version"], capture_output=True, text=True).stdout.strip()
    assert version == "particula %s (commit %s)" % (summary["version"], summary["commit"])
    assert version in settling_run.log  # log.txt names the build too
    assert summary["exit_code"] == 0 and "failure" not in summary
    assert summary["d0"] == 2.5e-4 and summary["h"] == pytest.approx(2.6 * 2.5e-4, rel=1e-15)
    assert 0 < summary["dt_min"] <= summary["dt_max"] <= summary["end_time"]
    assert summary["overrides"] == [] and summary["backend"] == "cpu" and summary["threads"] >= 1
    # the legend of the body and wall numbers
    assert summary["bodies"] == [{"index": 0, "name": "cylinder", "shape": "circle", "motion": "free"}]
    assert [w["name"] for w in summary["walls"]] == ["bottom", "right", "top", "left"]
    assert [w["index"] for w in summary["walls"]] == [0, 1, 2, 3]


def test_every_snapshot_matches_summary_and_bodies(settling_run):
    run = settling_run
    summary = run.summary
    snaps = run.snapshots
    # snapshot_interval 0.005 to time.end 0.01: t = 0, 0.005, 0.01
    assert len(snaps) == 3
    assert snaps.times[0] == 0 and snaps.times[-1] == summary["end_time"]
    body_times = set(run.bodies["time"])
    for snap in snaps:
        assert snap.num_points == summary["particles"], snap.path
        assert snap.time in body_times, snap.time  # written at an output time, the same double
        assert np.count_nonzero(snap["kind"] == 0) == summary["fluid_particles"]
        # bodies and walls by their case index, as in bodies.csv and walls.csv
        fluid = snap["kind"] == 0
        assert np.all(snap["body"][fluid] == -1) and np.all(snap["wall"][fluid] == -1)
        assert set(snap["body"][~fluid]) == {-1, 0} and set(snap["wall"][~fluid]) == {-1, 0, 1, 2, 3}
        assert np.all((snap["body"] == -1) | (snap["wall"] == -1))
        assert snap["velocity"].shape == (summary["particles"], 2)
        assert sorted(snap["id"]) == list(range(summary["particles"]))
    # bodies.csv: one row per output time (interval 0.0025), for the one body
    times = np.unique(run.bodies["time"])
    assert np.allclose(times, [0, 0.0025, 0.005, 0.0075, 0.01], rtol=0, atol=1e-15)
    assert np.array_equal(run.bodies["body"], np.zeros(len(times)))
    assert run.walls.rows == 4 * len(times)
    assert np.array_equal(run.wall(2)["time"], times)


def test_csv_units_and_decimal_output_times(particula, tmp_path):
    # every CSV names its units; output times are the decimals they stand for (7 x 0.05 is
    # written 0.35, not 0.35000000000000003)
    out = tmp_path / "hydro"
    particula.run_case(case("hydrostatic"), out, dict(HYDROSTATIC, **{"output.interval": 0.05, "time.end": 0.35}),
                       plots=False)
    run = particula.read_run(out)
    assert run.walls.units == {"time": "s", "wall": "-", "fx": "N/m", "fy": "N/m", "fpx": "N/m", "fpy": "N/m",
                               "fvx": "N/m", "fvy": "N/m", "torque": "N m/m", "fdx": "N/m", "fdy": "N/m"}
    assert list(np.unique(run.walls["time"])) == [0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35]
    assert run.summary["end_time"] == 0.35
    assert "0.35000000000000003" not in (out / "walls.csv").read_text()
    # numpy's own readers skip the units line
    data = np.genfromtxt(out / "walls.csv", delimiter=",", names=True)
    assert data.dtype.names[:2] == ("time", "wall") and len(data) == run.walls.rows
    assert np.loadtxt(out / "walls.csv", delimiter=",", skiprows=1).shape == (run.walls.rows, 11)


def test_body_csv_units(settling_run):
    units = settling_run.bodies.units
    assert units["time"] == "s" and units["x"] == "m" and units["omega"] == "rad/s"
    assert units["fx"] == "N/m" and units["torque"] == "N m/m" and units["fcy"] == "N/m"
    assert set(settling_run.bodies) == set(units)
    assert settling_run.probes["midline"].units["p"] == "Pa"


def test_reader_agrees_with_the_module_bitwise(particula, settling_run):
    # The module stepped to the same output times as the runner lands on gives the same state:
    # the last snapshot and bodies.csv's last row hold exactly its values.
    run = settling_run
    sim = particula.Simulation(SETTLING)
    for k in range(1, 5):
        sim.run_to(k * 0.0025)
    sim.run_to(run.case["time"]["end"])
    last = run.snapshots[-1]
    assert last.time == sim.time
    order = np.argsort(sim.id)
    by_id = np.argsort(last["id"])
    assert np.array_equal(last.points[by_id], sim.positions[order])
    assert np.array_equal(last["velocity"][by_id], sim.velocity[order])
    assert np.array_equal(last["pressure"][by_id], sim.pressure[order])
    assert np.array_equal(last["kind"][by_id], sim.kind[order])
    b = sim.body_states()
    row = run.body(0).where(run.body(0)["time"] == sim.time)
    assert row.rows == 1
    assert (row["x"][0], row["y"][0]) == tuple(b["position"][0])
    assert (row["vx"][0], row["vy"][0]) == tuple(b["velocity"][0])
    assert (row["fx"][0], row["fy"][0]) == tuple(b["force"][0])


def test_probe_as_profiles(settling_run):
    p = settling_run.probe("midline")
    assert len(p["time"]) == 3 and len(p["y"]) == 16
    assert p["vx"].shape == (3, 16) and p["p"].shape == (3, 16)
    assert p["y"][0] == 0 and p["y"][-1] == 0.015


def test_errors_are_the_clis(particula, tmp_path):
    taken = tmp_path / "a_file"
    taken.write_text("mine")
    with pytest.raises(particula.InputError) as e:
        particula.run_case(case("couette"), taken, COUETTE, plots=False)
    assert e.value.exit_code == 2
    cli = subprocess.run([BINARY, "run", case("couette"), "--out", str(taken), "--set", "time.end=0.1",
                          "--no-plots", "--quiet"], capture_output=True, text=True)
    assert cli.returncode == 2
    assert "error: " + str(e.value) == cli.stderr.strip()
    with pytest.raises(particula.CaseError) as e:
        particula.run_case(case("couette"), tmp_path / "x", {"fluid.nuu": 1})
    cli = subprocess.run([BINARY, "run", case("couette"), "--out", str(tmp_path / "x"), "--set", "fluid.nuu=1"],
                         capture_output=True, text=True)
    assert "error: " + str(e.value) == cli.stderr.strip()
    assert not (tmp_path / "x").exists()


def test_overwrite_and_resume(particula, tmp_path):
    out = tmp_path / "couette"
    sets = COUETTE
    particula.run_case(case("couette"), out, sets, plots=False)
    with pytest.raises(particula.InputError, match="overwrite"):
        particula.run_case(case("couette"), out, sets, plots=False)
    particula.run_case(case("couette"), out, sets, plots=False, overwrite=True)
    result = particula.resume(out, {"time.end": 0.2}, plots=False)
    run = result.read()
    assert run.summary["end_time"] == pytest.approx(0.2, rel=1e-12)
    assert run.summary["resumed_from"] == pytest.approx(0.1, rel=1e-12)
    assert run.snapshots.times[-1] == run.summary["end_time"]
    assert np.all(np.diff(run.probes["profile"]["time"]) >= 0)
    with pytest.raises(particula.InputError, match="only time.end and output"):
        particula.resume(out, {"fluid.nu": 1e-5}, plots=False)


def test_numerical_failure_of_a_run(particula, tmp_path):
    # As in test_simulation: water with a far too low sound speed collapses in the first step.
    sets = {"resolution.d0": 5e-3, "fluid.c": 0.05, "time.dt_max": 1e-3}
    out = tmp_path / "failed"
    with pytest.raises(particula.NumericalFailure, match="numerical failure at t = ") as e:
        particula.run_case(case("hydrostatic"), out, sets, plots=False)
    assert e.value.exit_code == 3 and e.value.run_dir == str(out)
    assert (out / "checkpoint" / "failure.bin").exists()
    result = particula.run_case(case("hydrostatic"), out, sets, plots=False, overwrite=True, check=False)
    assert result.exit_code == 3 and "numerical failure" in result.message
    run = result.read()
    assert run.summary["status"] == "failed" and run.summary["exit_code"] == 3
    failure = run.summary["failure"]  # structured: reason, time, step, particle, position
    assert failure["time"] == run.summary["end_time"] and failure["step"] == run.summary["steps"]
    assert isinstance(failure["particle"], int) and len(failure["position"]) == 2
    assert failure["reason"] in result.message
    from particula.overrides import override_list
    assert run.summary["overrides"] == override_list(sets) == ["resolution.d0=0.005", "fluid.c=0.05",
                                                               "time.dt_max=0.001"]
    assert run.snapshots.times[-1] == run.summary["end_time"]  # the final snapshot is written


def test_a_run_directory_in_use_is_refused(particula, tmp_path):
    # A CLI run holds its run directory (stopped while it does): run_case --overwrite and resume
    # from Python are refused with the directory and its pid, and the run then ends as if alone.
    out = tmp_path / "couette"
    first = subprocess.Popen([BINARY, "run", case("couette"), "--out", str(out), "--set", "time.end=0.2",
                              "--no-plots", "--quiet", "--threads", "1"])
    deadline = time.monotonic() + 60
    while not (out / ".particula-run").exists():
        assert time.monotonic() < deadline and first.poll() is None
        time.sleep(0.001)
    os.kill(first.pid, signal.SIGSTOP)
    try:
        _, status = os.waitpid(first.pid, os.WUNTRACED)
        assert os.WIFSTOPPED(status), "the first run ended before it was stopped"
        with pytest.raises(particula.InputError, match="pid %d" % first.pid) as e:
            particula.run_case(case("couette"), out, COUETTE, plots=False, overwrite=True)
        assert str(out) in str(e.value) and e.value.exit_code == 2
        with pytest.raises(particula.InputError, match="pid %d" % first.pid):
            particula.resume(out, {"time.end": 0.3}, plots=False)
    finally:
        os.kill(first.pid, signal.SIGCONT)
    assert first.wait(timeout=300) == 0
    assert particula.read_run(out).summary["status"] == "completed"


def test_write_checkpoint_replaces_only_a_checkpoint(particula, tmp_path):
    sim = particula.Simulation(case("hydrostatic"), HYDROSTATIC)
    target = tmp_path / "state.bin"
    sim.write_checkpoint(target)  # a new file
    sim.step()
    sim.write_checkpoint(target)  # over a checkpoint
    assert particula.Simulation.from_checkpoint(target).step_count == 1
    mine = tmp_path / "mycase.toml"
    mine.write_text('name = "mine"\n')
    link = tmp_path / "link.bin"
    os.symlink(target, link)
    dangling = tmp_path / "dangling.bin"
    os.symlink(tmp_path / "nowhere.bin", dangling)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for path, why in ((mine, "not a particula checkpoint"), (link, "symbolic link"), (dangling, "symbolic link"),
                      (fifo, "not a regular file")):
        with pytest.raises(particula.IoFailure, match=re.escape(str(path)) + ".*" + why):
            sim.write_checkpoint(path)
    assert mine.read_text() == 'name = "mine"\n'
    assert os.readlink(link) == str(target) and particula.Simulation.from_checkpoint(link).step_count == 1
    assert not (tmp_path / "nowhere.bin").exists()
    assert sorted(os.listdir(tmp_path)) == ["dangling.bin", "fifo", "link.bin", "mycase.toml", "state.bin"]
