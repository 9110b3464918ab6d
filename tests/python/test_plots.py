"""tools/plot_run.py: plots for a run with derived outputs, and for a run that
failed (exit 3): drawn, each title naming the case, its resolution and its overrides; the
published references only for a run with the physics of their shipped case; `particula plot
--format`."""
import os
import subprocess
import sys

import pytest

from conftest import ROOT, case
from subprocess_run import run_cli

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")
PLOT = os.path.join(ROOT, "tools", "plot_run.py")

pytest.importorskip("matplotlib")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import plot_references  # noqa: E402
import plot_run  # noqa: E402
from matplotlib.text import Text  # noqa: E402


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
    # the titles (matplotlib text) name the case, the resolution and the overrides (none here)
    run = plot_run.reader.read_run(out)
    t = plot_run.title(run, "bodies")
    assert "case 'settling'" in t and "d0 = 0.00025 m, 10 particles across cylinder" in t
    assert "--set" not in t


def test_a_failed_run_is_plotted(particula, tmp_path):
    # a density bound the first step exceeds: the run fails (exit 3) at once
    out = tmp_path / "failed"
    result = particula.run_case(SETTLING, out, {"guard.rho_max_ratio": 1.0000000001}, check=False)
    assert result.exit_code == 3
    assert {"bodies.png", "snapshot_fields.png"} <= set(os.listdir(out / "plots"))
    t = plot_run.title(plot_run.reader.read_run(out), "bodies")
    assert "FAILED at t = " in t and "--set guard.rho_max_ratio=" in t


@pytest.mark.parametrize("name", sorted(plot_references.REFERENCES))
def test_references_for_the_physics_of_their_case(particula, name):
    # resolution and time (the numerics) may change; the references are those of the case
    resolved = particula.load_case(case(name), {"time.end": 0.1, "numerics.shifting_beta": 0.05})
    assert plot_references.references_for(resolved) == (plot_references.REFERENCES[name], None)


@pytest.mark.parametrize("override, difference", [
    ({"body.0.density": 1500}, "body[0].density = 1500 here, 1250 there"),
    ({"fluid.rho0": 1100}, "fluid.rho0 = 1100 here, 1000 there"),  # and nu = mu / rho0 with it
    ({"fluid.mu": 0.02}, "fluid.nu = 2e-05 here, 1e-05 there"),
    ({"fluid.gravity": [0.0, -5.0]}, "fluid.gravity = [0.0, -5.0] here, [0.0, -9.81] there"),
    ({"domain.max": [0.02, 0.08]}, "domain.max = [0.02, 0.08] here, [0.02, 0.06] there"),
    ({"body.0.radius": 1.5e-3}, "body[0].radius = 0.0015 here, 0.00125 there"),
    ({"body.0.center": [0.01, 0.03]}, "body[0].center = [0.01, 0.03] here, [0.01, 0.04] there"),
])
def test_no_reference_for_other_physics(particula, override, difference):
    resolved = particula.load_case(case("falling_cylinder"), dict(override, **{"resolution.d0": 2.5e-4}))
    refs, note = plot_references.references_for(resolved)
    assert refs == []
    assert note.startswith("no reference: the physics is not that of cases/falling_cylinder.toml (")
    assert difference in note


def test_a_run_with_other_physics_is_plotted_without_its_reference(particula, tmp_path):
    # a lighter fluid under the falling cylinder's box, a few steps: the plots carry no reference
    out = tmp_path / "run"
    sets = {"resolution.d0": 2.5e-4, "time.end": 0.005, "body.0.density": 1500}
    assert particula.run_case(case("falling_cylinder"), out, sets, threads=1, plots=False).exit_code == 0
    drawn, texts = [], []
    real_plot, real_save = plot_run.plot_reference, plot_run.save
    plot_run.plot_reference = lambda ax, col, refs: drawn.extend(refs) or real_plot(ax, col, refs)
    plot_run.save = lambda fig, o, stem: texts.extend(t.get_text() for t in fig.findobj(Text)) or real_save(fig, o, stem)
    try:
        assert plot_run.main(["plot_run.py", str(out), "--format", "svg"]) == 0
    finally:
        plot_run.plot_reference, plot_run.save = real_plot, real_save
        plot_run.OUTPUT["format"] = plot_run.FORMATS[0]
    assert drawn == []
    assert "body[0].density = 1500 here, 1250 there" in " ".join(t.replace("\n", " ") for t in texts)
    assert (out / "plots" / "bodies.svg").exists()
    t = plot_run.title(plot_run.reader.read_run(out), "bodies")
    assert "--set resolution.d0=0.00025 --set time.end=0.005 --set body.0.density=1500" in t


@pytest.mark.parametrize("fmt, magic", [("svg", b"<?xml"), ("pdf", b"%PDF"), ("png", b"\x89PNG")])
def test_plot_format(particula, tmp_path, fmt, magic):
    out = tmp_path / "run"
    particula.run_case(SETTLING, out, {"time.end": 0.005}, threads=1, plots=False)
    proc = run_cli(["plot", str(out), "--format", fmt])
    assert proc.returncode == 0, proc.stderr
    files = sorted(os.listdir(out / "plots"))
    assert files == ["bodies." + fmt, "flow_rates." + fmt, "probe_midline_profiles." + fmt, "snapshot_fields." + fmt]
    for f in files:
        assert open(out / "plots" / f, "rb").read(8).startswith(magic), f


def test_a_bad_plot_format_draws_nothing(particula, tmp_path):
    out = tmp_path / "run"
    particula.run_case(SETTLING, out, {"time.end": 0.005}, threads=1, plots=False)
    proc = run_cli(["plot", str(out), "--format", "jpeg"])
    assert proc.returncode == 2
    assert "--format: jpeg not in {png,svg,pdf}" in proc.stderr
    assert not os.path.exists(out / "plots")
    # the script itself, run by hand, refuses it too
    proc = subprocess.run([sys.executable, PLOT, str(out), "--format", "jpeg"], capture_output=True, text=True)
    assert proc.returncode == 2 and "--format 'jpeg': plots are drawn as png, svg, pdf; nothing drawn" in proc.stderr
    assert not os.path.exists(out / "plots")
