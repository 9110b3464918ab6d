"""ParaView opens a run's particles.pvd without warnings and reads every snapshot with the point
count of summary.json at the times of particles.pvd. Runs only where
pvpython is installed (Debian: `apt-get install paraview python3-paraview xvfb`, optional, not in
scripts/install-deps); skipped otherwise, with the reason in pytest's summary."""
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

from conftest import ROOT

SETTLING = os.path.join(ROOT, "tests", "python", "data", "settling.toml")

# Run inside pvpython: every time step of the .pvd, its point count and point arrays, as JSON.
SCRIPT = r"""
import json, sys
from paraview.simple import PVDReader
from paraview import servermanager
reader = PVDReader(FileName=sys.argv[1])
reader.UpdatePipelineInformation()
steps = []
for t in reader.TimestepValues:
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    pd = data.GetPointData()
    steps.append({"time": t, "points": data.GetNumberOfPoints(),
                  "arrays": [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]})
print("PARTICULA_JSON " + json.dumps(steps))
"""

pytestmark = pytest.mark.skipif(shutil.which("pvpython") is None,
                                reason="pvpython not installed (optional: apt-get install paraview python3-paraview xvfb)")


def pvpython_command():
    """pvpython, under xvfb-run where there is no display (pvpython opens an X connection)."""
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
        return ["xvfb-run", "-a", "pvpython"]
    return ["pvpython"]


def test_paraview_reads_every_snapshot_without_warnings(particula, tmp_path):
    out = tmp_path / "settling"
    assert particula.run_case(SETTLING, out, plots=False).exit_code == 0
    run = particula.read_run(out)
    script = tmp_path / "read_pvd.py"
    script.write_text(SCRIPT)
    proc = subprocess.run(pvpython_command() + [str(script), str(out / "particles.pvd")],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    noise = [l for l in (proc.stderr + proc.stdout).splitlines()
             if l.strip() and not l.startswith("PARTICULA_JSON ")]
    assert noise == [], "ParaView printed:\n" + "\n".join(noise)
    steps = json.loads(proc.stdout.split("PARTICULA_JSON ", 1)[1])
    assert len(steps) == len(run.snapshots) == 3
    np.testing.assert_array_equal([s["time"] for s in steps], run.snapshots.times)
    assert steps[-1]["time"] == run.summary["end_time"]
    assert set(s["time"] for s in steps) <= set(run.bodies["time"])
    for s in steps:
        assert s["points"] == run.summary["particles"]
        assert s["arrays"] == ["pressure", "velocity", "density", "kind", "body", "wall", "id"]
