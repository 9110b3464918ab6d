"""particula.Case (a case from Python data: to_toml and back, dotted keys, bodies and walls added
and removed, checked with the CLI's messages), run from Python (Simulation, run_case), progress
callbacks and bars, and the reader's errors and to_pandas."""
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import HYDROSTATIC, ROOT, case


def box(particula, n=0):
    """A closed 1 cm box under gravity at d0 = 2e-4 m with n circles placed in code."""
    c = particula.Case({"name": "box", "domain": {"min": [0, 0], "max": [0.01, 0.01]},
                        "resolution": {"d0": 2e-4}, "fluid": {"rho0": 1000.0, "nu": 1e-5, "c": 0.2, "gravity": [0, -9.81]},
                        "time": {"end": 0.002}, "output": {"interval": 5e-4}})
    for side, (a, b) in {"bottom": ([0, 0], [0.01, 0]), "right": ([0.01, 0], [0.01, 0.01]),
                         "top": ([0.01, 0.01], [0, 0.01]), "left": ([0, 0.01], [0, 0])}.items():
        c.add_wall({"name": side, "from": a, "to": b})
    for i in range(n):
        c.add_body(name="c%d" % i, shape="circle", radius=1e-3, center=[0.0025 + 0.005 * (i % 2), 0.006],
                   density=1200.0)
    return c


def test_round_trip_through_toml(particula):
    shipped = particula.Case.from_file(case("dkt"))
    text = shipped.to_toml()
    again = particula.Case.from_toml(text)
    assert again == shipped
    assert again.to_toml() == text
    # The resolved case of the Case is the shipped file's.
    assert shipped.resolved() == particula.load_case(case("dkt"))
    assert particula.load_case(shipped, {"resolution.d0": 2e-4})["resolution"]["d0"] == 2e-4


def test_dotted_keys_and_bodies(particula):
    c = box(particula, 2)
    assert c["fluid.nu"] == 1e-5
    c["fluid.nu"] = 2e-5
    c["body.1.density"] = 1500
    assert c.bodies[1]["density"] == 1500 and "body.1.density" in c and "body.7.density" not in c
    c["analysis.reference_length"] = 0.002  # a table created on the way
    assert c.data["analysis"] == {"reference_length": 0.002}
    del c["analysis"]
    with pytest.raises(KeyError):
        c["fluid.nope"]
    i = c.add_body({"shape": "circle", "radius": 1e-3, "center": [0.005, 0.003]}, density=1100.0, name="extra")
    assert i == 2 and c.bodies[2]["density"] == 1100.0
    assert c.remove_body("c0")["name"] == "c0" and [b["name"] for b in c.bodies] == ["c1", "extra"]
    assert c.remove_body(-1)["name"] == "extra"
    with pytest.raises(KeyError, match="no body named 'nosuch'"):
        c.remove_body("nosuch")
    with pytest.raises(IndexError):
        c.remove_body(5)
    with pytest.raises(TypeError):
        c.remove_body(1.5)
    with pytest.raises(TypeError, match="fluid.bad"):
        c["fluid.bad"] = object()
    with pytest.raises(TypeError):
        particula.Case([1, 2])
    # NumPy values are written as TOML numbers
    c["body.0.center"] = np.array([0.004, 0.005])
    assert particula.Case.from_toml(c.to_toml()).bodies[0]["center"] == [0.004, 0.005]
    c.check()


def test_mistakes_are_refused_with_the_clis_message(particula):
    c = box(particula, 1)
    c["body.0.densty"] = 1200
    with pytest.raises(particula.CaseError) as e:
        c.check()
    assert e.value.key == "body[0].densty" and "did you mean" in str(e.value) and "density" in str(e.value)
    assert e.value.file == "<particula.Case>"
    c = box(particula, 1)
    c["body.0.radius"] = -1
    with pytest.raises(particula.CaseError, match=r"body\[0\]\.radius"):
        particula.Simulation(c)
    with pytest.raises(particula.CaseError):
        particula.Case.from_toml("name = ")


def test_simulation_and_run_case_take_a_case(particula, tmp_path):
    c = box(particula, 2)
    sim = particula.Simulation(c)
    assert sim.name == "box" and len(sim.body_index[sim.body_index >= 0]) > 0
    sim.run_to(0.0005)
    ran = particula.run_case(c, tmp_path / "box", plots=False)
    run = ran.read()
    assert run.summary["status"] == "completed" and run.case["body"][1]["name"] == "c1"
    assert "<particula.Case>" in run.log
    # bodies by index and by name
    assert run.body("c1")["body"][0] == 1 and len(run.body(0)["time"]) > 0
    with pytest.raises(KeyError, match="no body of that index or name"):
        run.body(7)
    with pytest.raises(KeyError, match="'cylinder'"):
        run.body("cylinder")
    with pytest.raises(KeyError, match="no probe"):
        run.probe("nosuch")


def test_progress_callbacks(particula, tmp_path):
    seen = []
    sim = particula.Simulation(case("hydrostatic"), HYDROSTATIC)
    sim.run_to(0.002, progress=lambda t, end, step: seen.append((t, end, step)))
    assert seen and seen[-1][0] == pytest.approx(0.002) and seen[-1][1] == 0.002
    assert seen[-1][2] == sim.step_count
    # an exception from the callback stops run_to between two steps, and is raised
    def stop(t, end, step):
        raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        sim.run_to(0.004, progress=stop)
    assert 0.002 < sim.time < 0.004
    with pytest.raises(TypeError, match="progress"):
        sim.run_to(0.005, progress="yes")
    # run_case: the callback, and a stop from it ends the run as Ctrl-C does, with a checkpoint
    seen.clear()
    particula.run_case(case("hydrostatic"), tmp_path / "a", dict(HYDROSTATIC, **{"time.end": 0.002}), plots=False,
                       progress=lambda t, end, step: seen.append(t))
    assert seen and seen[-1] == pytest.approx(0.002)
    with pytest.raises(RuntimeError, match="enough"):
        particula.run_case(case("hydrostatic"), tmp_path / "b", dict(HYDROSTATIC, **{"time.end": 1.0}),
                           plots=False, progress=stop)
    assert os.path.exists(tmp_path / "b" / "checkpoint" / "state.bin")
    assert particula.read_run(tmp_path / "b").summary["status"] == "interrupted"
    particula.resume(tmp_path / "b", {"time.end": 0.003}, plots=False)


def test_progress_bar_is_drawn_beside_the_captured_stderr(tmp_path):
    """progress=True draws on the terminal's standard error while the runner's is captured (tqdm
    when installed, else a plain line)."""
    code = ("import particula\n"
            "particula.run_case(%r, %r, {'resolution.d0': 5e-3, 'time.end': 0.002}, plots=False, progress=True)\n"
            % (case("hydrostatic"), str(tmp_path / "bar")))
    env = dict(os.environ)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "hydrostatic" in proc.stderr and ("100%" in proc.stderr or "(100 %)" in proc.stderr), proc.stderr


def test_reader_errors_and_pandas(particula, tmp_path):
    with pytest.raises(particula.InputError, match="not a particula run directory"):
        particula.read_run(tmp_path)
    with pytest.raises(FileNotFoundError):
        particula.read_run(tmp_path / "missing")
    with pytest.raises(FileNotFoundError):
        particula.read_csv(tmp_path / "missing.csv")
    ran = particula.run_case(case("hydrostatic"), tmp_path / "h", dict(HYDROSTATIC, **{"time.end": 0.001}),
                             plots=False)
    run = ran.read()
    with pytest.raises(KeyError, match="has no body"):
        run.body(0)
    try:
        import pandas  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="needs pandas"):
            run.walls.to_pandas()
        return
    frame = run.walls.to_pandas()
    assert list(frame.columns) == list(run.walls) and frame.attrs["units"] == run.walls.units
    assert len(frame) == run.walls.rows
