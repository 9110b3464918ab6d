"""The Python examples at their --quick level (examples/python)."""
import csv
import os
import subprocess
import sys

import pytest

from conftest import ROOT

EXAMPLES = os.path.join(ROOT, "examples", "python")
RUN_HERE = ["run_and_plot_field.py", "settling_circles.py", "sweep_terminal_speed.py"]  # each by a test below


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


def test_settling_circles(tmp_path):
    out = run_example("settling_circles.py", "--out", str(tmp_path), "--jobs", "2")
    with open(tmp_path / "settling.csv") as f:
        rows = list(csv.DictReader(f))
    assert [int(r["circles"]) for r in rows] == [1, 5]
    assert all(r["exit_code"] == "0" for r in rows)
    fractions = [float(r["area_fraction"]) for r in rows]
    assert fractions[1] == pytest.approx(5 * fractions[0]) and fractions[0] > 0
    assert all(float(r["mean_settling_speed"]) > 0 for r in rows), out  # they fall
    assert (tmp_path / "settling.png").stat().st_size > 10000
    assert (tmp_path / "n_5" / "case.toml").read_text().count("[[body]]") == 5
