"""particula.Simulation: load, build, step, fields as views, body states, checkpoints, errors."""
import math
import os

import numpy as np
import pytest

from conftest import HYDROSTATIC, ROOT, case

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")


@pytest.fixture(scope="module")
def hydro(particula):
    return particula.Simulation(case("hydrostatic"), HYDROSTATIC)


def test_load_and_build(particula, hydro):
    sim = hydro
    assert sim.name == "hydrostatic"
    assert sim.case["resolution"]["d0"] == 5e-3  # the override, in the resolved case
    assert sim.d0 == 5e-3 and sim.h > sim.d0
    assert sim.time == 0 and sim.step_count == 0
    n, nb = sim.n_particles, sim.n_boundary
    assert n - nb == 20 * 20  # fluid particles of the 0.1 m box at d0 = 5 mm
    kind = sim.kind
    assert kind.dtype == np.uint8 and kind.shape == (n,)
    assert np.all(kind[:nb] == particula.KIND_BOUNDARY) and np.all(kind[nb:] == particula.KIND_FLUID)
    x = sim.positions
    assert x.shape == (n, 2) and x.dtype == np.float64
    assert np.all((x >= -1e-12) & (x <= 0.1 + 1e-12))
    assert sim.velocity.shape == (n, 2)
    assert np.allclose(sim.density, 1000, rtol=1e-2)  # hydrostatic initial density
    assert np.all(sim.group[nb:] == -1) and set(np.unique(sim.group[:nb])) == {0, 1, 2, 3}
    assert sorted(sim.id) == list(range(n))
    assert np.array_equal(sim.wall_index, sim.group)  # no bodies: the groups are the walls
    assert np.all(sim.body_index == -1)


def test_fields_are_read_only_views(hydro):
    for name in ("positions", "velocity", "density", "pressure", "mass", "kind", "id", "group", "normals"):
        a = getattr(hydro, name)
        assert not a.flags.owndata and a.base is not None, name
        assert not a.flags.writeable, name
        assert np.shares_memory(a, getattr(hydro, name)), name  # the solver's array, not a copy
        with pytest.raises(ValueError):
            a[0] = 0
    assert hydro.body_index.flags.owndata  # a copy


def test_step_and_run_to(particula):
    sim = particula.Simulation(case("hydrostatic"), HYDROSTATIC)
    dt = sim.step()
    assert dt > 0 and sim.time == dt and sim.step_count == 1 and sim.dt == dt
    assert sim.step(max_dt=dt / 4) == dt / 4
    taken = sim.run_to(0.005)
    assert sim.time == pytest.approx(0.005, rel=1e-12)
    assert sim.step_count == 2 + taken
    # Water at rest stays at rest: the fluid's speed stays far below the sound speed.
    assert np.abs(sim.velocity).max() < 0.01 * sim.case["fluid"]["c"]


def test_views_follow_the_state(particula):
    sim = particula.Simulation(SETTLING)
    x = sim.positions
    before = np.array(x)
    body = sim.body_index == 0
    sim.run_to(0.002)
    # The same view now shows the cylinder's surface particles lower down.
    assert np.all(x[body, 1] < before[body, 1])
    assert np.array_equal(x, sim.positions)


def test_body_states(particula):
    sim = particula.Simulation(SETTLING)
    b = sim.body_states()
    assert b["name"] == ["cylinder"] and b["motion"] == ["free"]
    r = 1.25e-3
    assert b["area"][0] == pytest.approx(math.pi * r * r, rel=1e-12)
    assert b["mass"][0] == pytest.approx(1250 * math.pi * r * r, rel=1e-12)
    assert np.array_equal(b["position"], [[0.005, 0.009]])
    sim.run_to(0.003)
    b = sim.body_states()
    assert b["velocity"][0, 1] < 0 and b["position"][0, 1] < 0.009
    assert np.array_equal(b["force"], b["force_pressure"] + b["force_viscous"])
    # The odd-even damping's momentum sink next to the body: reported apart, small beside the load.
    assert b["force_damping"].shape == (1, 2) and np.all(np.isfinite(b["force_damping"]))
    assert 0 < np.linalg.norm(b["force_damping"][0]) < 0.1 * np.linalg.norm(b["force"][0])
    w = sim.wall_states()
    assert w["name"] == ["bottom", "right", "top", "left"]
    assert w["force"].shape == (4, 2)
    # Surface particles of the body: as many as the group has, all of kind boundary.
    assert np.all(sim.kind[sim.body_index == 0] == particula.KIND_BOUNDARY)
    assert np.count_nonzero(sim.body_index == 0) > 20


def state(sim):
    """Every array of the state, as copies."""
    names = ("positions", "velocity", "density", "pressure", "mass", "kind", "id", "group", "normals")
    out = {n: np.array(getattr(sim, n)) for n in names}
    for k, v in sim.body_states().items():
        out["body." + k] = np.array(v)
    out["time"], out["step"] = sim.time, sim.step_count
    return out


def assert_bitwise_equal(a, b):
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(a[k], b[k]), k
        if isinstance(a[k], np.ndarray) and a[k].dtype.kind == "f":
            assert a[k].tobytes() == b[k].tobytes(), k  # also the signs of zeros


def test_checkpoint_resume_is_bitwise_identical(particula, tmp_path):
    # 30 steps, a checkpoint, 40 more (past the fluid reordering at step 50): the restarted
    # simulation must reach the same state bit for bit.
    sim = particula.Simulation(SETTLING)
    for _ in range(30):
        sim.step()
    file = tmp_path / "ck" / "state.bin"
    sim.write_checkpoint(file)
    at_checkpoint = state(sim)
    for _ in range(40):
        sim.step()
    resumed = particula.Simulation.from_checkpoint(file)
    assert_bitwise_equal(state(resumed), at_checkpoint)
    for _ in range(40):
        resumed.step()
    assert_bitwise_equal(state(resumed), state(sim))
    assert resumed.case_toml == sim.case_toml


def test_checkpoint_errors(particula, tmp_path):
    sim = particula.Simulation(case("hydrostatic"), HYDROSTATIC)
    file = tmp_path / "state.bin"
    sim.write_checkpoint(file)
    with pytest.raises(particula.InputError, match="only time.end and output"):
        particula.Simulation.from_checkpoint(file, {"fluid.nu": 2e-6})
    assert particula.Simulation.from_checkpoint(file, {"time.end": 1.0}).case["time"]["end"] == 1.0
    data = bytearray(file.read_bytes())
    data[len(data) // 2] ^= 0xFF
    damaged = tmp_path / "damaged.bin"
    damaged.write_bytes(bytes(data))
    with pytest.raises(particula.InputError, match="damaged.bin"):
        particula.Simulation.from_checkpoint(damaged)
    with pytest.raises(particula.InputError, match="missing.bin"):
        particula.Simulation.from_checkpoint(tmp_path / "missing.bin")
    with pytest.raises(particula.IoFailure):  # a directory where the file should be
        os.mkdir(tmp_path / "taken")
        sim.write_checkpoint(tmp_path / "taken")


def test_case_errors_carry_file_line_and_key(particula, tmp_path):
    with pytest.raises(particula.CaseError) as e:
        particula.Simulation(case("hydrostatic"), {"fluid.nuu": 1e-6})
    assert isinstance(e.value, ValueError)
    assert (e.value.file, e.value.line, e.value.key) == ("--set", 0, "fluid.nuu")
    assert "unknown key (did you mean 'fluid.nu'?)" in str(e.value)
    text = open(case("hydrostatic")).read().replace("nu = 1.0e-6", "nuu = 1.0e-6")
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    line = text.splitlines().index("nuu = 1.0e-6") + 1
    with pytest.raises(particula.CaseError) as e:
        particula.load_case(bad)
    assert (e.value.file, e.value.line, e.value.key) == (str(bad), line, "fluid.nuu")
    assert str(e.value).startswith("%s:%d: key 'fluid.nuu': unknown key" % (bad, line))
    with pytest.raises(particula.CaseError, match="no_such.toml"):
        particula.Simulation(tmp_path / "no_such.toml")
    with pytest.raises(particula.InputError, match="unknown"):
        particula.Simulation(case("hydrostatic"), HYDROSTATIC, backend="opencl")


def test_numerical_failure(particula):
    # A sound speed far too low for the water column (a valid input) lets it collapse under
    # gravity at once: the health check at the end of the first step stops it.
    sim = particula.Simulation(case("hydrostatic"), dict(HYDROSTATIC, **{"fluid.c": 0.05, "time.dt_max": 1e-3}))
    with pytest.raises(particula.NumericalFailure) as e:
        sim.run_to(0.5)
    f = e.value
    assert isinstance(f, RuntimeError)
    assert f.step == sim.step_count and f.time == sim.time
    assert str(f).startswith("numerical failure at t = ") and f.reason in str(f)
    assert f.particle_id is not None and len(f.position) == 2


def test_overrides_take_python_values(particula):
    c = particula.load_case(case("couette"), {"resolution.d0": 2.5e-5, "domain.periodic": [True, False],
                                              "numerics.laplacian": "morris", "probe.0.points": np.int64(11),
                                              "fluid.c": np.float64(3e-4)})
    assert c["resolution"]["d0"] == 2.5e-5
    assert c["numerics"]["laplacian"] == "morris"
    assert c["probe"][0]["points"] == 11 and c["fluid"]["c"] == 3e-4
    assert particula.load_case(case("couette"), ["resolution.d0=2.5e-5"])["resolution"]["d0"] == 2.5e-5
