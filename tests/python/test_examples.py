"""The Python examples at their --quick level (examples/python)."""
import csv
import os
import subprocess
import sys

from conftest import ROOT

EXAMPLES = os.path.join(ROOT, "examples", "python")
RUN_HERE = ["run_and_plot_field.py", "sweep_terminal_speed.py"]  # each by a test below


def test_every_example_is_run_here():
    assert sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".py")) == RUN_HERE


def run_example(name, *args):
    proc = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), "--quick", *args], capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout


def test_sweep_terminal_speed(tmp_path):
    run_example("sweep_terminal_speed.py", "--out", str(tmp_path), "--jobs", "2")
    with open(tmp_path / "terminal_speed.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["ratio"]) for r in rows] == [1.25, 2.0]
    assert all(r["exit_code"] == "0" for r in rows)
    light, heavy = (float(r["peak_settling_speed"]) for r in rows)
    assert 0 < light < heavy  # the heavier cylinder accelerates faster
    assert (tmp_path / "terminal_speed.png").stat().st_size > 10000
    for r in ("1.25", "2"):
        assert (tmp_path / ("ratio_" + r) / "summary.json").exists()


def test_run_and_plot_field(tmp_path):
    out = run_example("run_and_plot_field.py", "--out", str(tmp_path))
    assert "2 snapshots of 19783 particles; the last at t = 0.005 s" in out
    for png in ("fields.png", "settling.png"):
        assert (tmp_path / png).stat().st_size > 10000, png
