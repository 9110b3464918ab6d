"""Derived outputs in a run directory: coefficients.csv for a body with a
reference velocity and length, flow_<name>.csv for a line probe, a probe at points, all read
with particula.read_run."""
import os

import numpy as np
import pytest

from conftest import ROOT

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")


@pytest.fixture(scope="module")
def derived_case(tmp_path_factory):
    """The settling case with coefficient references and a probe at two points."""
    tmp = tmp_path_factory.mktemp("cases")
    case_file = tmp / "derived.toml"
    with open(SETTLING) as f:
        text = f.read()
    case_file.write_text(text + """
[analysis]
reference_velocity = [0.0, 0.01]  # the fluid passes the settling cylinder upwards
reference_length = 2.5e-3         # its diameter

[[probe]]
name = "spots"
kind = "points"
at = [[0.005, 0.004], [0.005, 0.0]]  # the second on the bottom wall
interval = 0.005
""")
    return case_file


@pytest.fixture(scope="module")
def derived_run(particula, derived_case, tmp_path_factory):
    out = tmp_path_factory.mktemp("runs") / "derived"
    result = particula.run_case(derived_case, out, plots=False)
    assert result.exit_code == 0
    return particula.read_run(out)


def test_coefficients_follow_the_body_forces(derived_run):
    run = derived_run
    c, b = run.coefficient(0), run.body(0)
    assert list(run.coefficients.keys()) == ["time", "body", "re", "re_body", "cd", "cl", "cm"]
    assert run.coefficients.units["cd"] == "-"
    np.testing.assert_array_equal(c["time"], b["time"])
    rho0, nu, U, L = 1000.0, 1e-5, 0.01, 2.5e-3
    q = 0.5 * rho0 * U * U * L
    np.testing.assert_allclose(c["re"], U * L / nu, rtol=1e-12)
    np.testing.assert_allclose(c["cd"], b["fy"] / q, rtol=1e-9, atol=1e-12)  # drag along U = +y
    np.testing.assert_allclose(c["cl"], -b["fx"] / q, rtol=1e-9, atol=1e-12)  # lift along -x
    np.testing.assert_allclose(c["re_body"], np.hypot(b["vx"], b["vy"]) * L / nu, rtol=1e-9, atol=1e-12)


def test_line_probe_flow_rate_and_point_probe(derived_run):
    run = derived_run
    flow = run.flows["midline"]
    assert run.probes["midline"].units["x"] == "m" and flow.units["flow_rate"] == "m^2/s"
    p = run.probe("midline")
    np.testing.assert_array_equal(flow["time"], p["time"])
    # the same trapezoidal sum of vx (n = +x for a line walked upwards) over the written profile
    dy = 0.015 / 15
    expected = [np.sum(0.5 * (vx[1:] + vx[:-1])) * dy for vx in p["vx"]]
    np.testing.assert_allclose(flow["flow_rate"], expected, rtol=1e-9, atol=1e-15)
    assert "spots" not in run.flows  # points have no flow rate
    spots = run.probe("spots")
    np.testing.assert_array_equal(spots["y"], [0.004, 0.0])
    # on the wall the wall's velocity (0) to a small fraction of the speed a wall spacing above it
    # (the fluid there is not a quadratic field: the settling cylinder stirs it)
    near = np.hypot(spots["vx"][-1, 0], spots["vy"][-1, 0])
    print("point probe: |v| = %.3g m/s at y = 4 mm, %.3g m/s on the wall" % (near, np.abs(spots["vx"][-1, 1])))
    assert near > 0
    assert np.all(np.abs(spots["vx"][:, 1]) <= 1e-3 * near)
    assert np.all(np.abs(spots["vy"][:, 1]) <= 1e-3 * near)


def test_resumed_run_writes_the_same_derived_files(particula, derived_case, derived_run, tmp_path):
    half = tmp_path / "half"
    assert particula.run_case(derived_case, half, {"time.end": 0.005}, plots=False).exit_code == 0
    assert particula.resume(half, {"time.end": 0.01}, plots=False).exit_code == 0
    for name in ("coefficients.csv", "flow_midline.csv", "probe_spots.csv"):
        with open(os.path.join(derived_run.dir, name)) as a, open(half / name) as b:
            assert a.read() == b.read(), name
