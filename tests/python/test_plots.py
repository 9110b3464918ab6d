"""tools/plot_run.py: plots for a run with derived outputs, and for a run that
failed (exit 3): drawn, each title naming the case and its resolution."""
import os
import subprocess
import sys

import pytest

from conftest import ROOT

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")
PLOT = os.path.join(ROOT, "tools", "plot_run.py")

pytest.importorskip("matplotlib")


def settling_with(tmp_path, extra):
    case_file = tmp_path / "case.toml"
    with open(SETTLING) as f:
        case_file.write_text(f.read() + extra)
    return case_file


def test_plots_of_a_run_with_derived_outputs(particula, tmp_path):
    case_file = settling_with(tmp_path, """
[analysis]
reference_velocity = [0.0, 0.01]
reference_length = 2.5e-3

[[probe]]
name = "spots"
kind = "points"
at = [[0.005, 0.004], [0.005, 0.0]]
interval = 0.005
""")
    out = tmp_path / "run"
    assert particula.run_case(case_file, out, plots=False).exit_code == 0
    subprocess.run([sys.executable, PLOT, str(out)], check=True, capture_output=True)
    assert sorted(os.listdir(out / "plots")) == [
        "bodies.png", "coefficients.png", "flow_rates.png", "probe_midline_profiles.png", "probe_spots_points.png",
        "snapshot_fields.png"]
    # the titles (matplotlib text) name the case and the resolution
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    import plot_run
    run = plot_run.reader.read_run(out)
    t = plot_run.title(run, "bodies")
    assert "case 'settling'" in t and "d0 = 0.00025 m, 10 particles across cylinder" in t


def test_a_failed_run_is_plotted(particula, tmp_path):
    # a density bound the first step exceeds: the run fails (exit 3) at once
    out = tmp_path / "failed"
    result = particula.run_case(SETTLING, out, {"guard.rho_max_ratio": 1.0000000001}, check=False)
    assert result.exit_code == 3
    assert {"bodies.png", "snapshot_fields.png"} <= set(os.listdir(out / "plots"))
    sys.path.insert(0, os.path.join(ROOT, "tools"))
    import plot_run
    assert "FAILED at t = " in plot_run.title(plot_run.reader.read_run(out), "bodies")
