"""particula.read_csv / read_vtp on hand-made files: comments, units, incomplete lines, the VTK
binary layout, and damaged files."""
import base64
import struct

import numpy as np
import pytest


def test_csv_columns_units_and_incomplete_last_line(particula, tmp_path):
    f = tmp_path / "bodies.csv"
    f.write_text("# a comment\ntime,body,x\ns,-,m\n0,0,0.5\n0.1,1,0.25\n0.2,0,0.1")  # no final newline
    t = particula.read_csv(f)
    assert list(t) == ["time", "body", "x"]
    assert t.units == {"time": "s", "body": "-", "x": "m"}
    assert np.array_equal(t["time"], [0, 0.1]) and t["body"].dtype == np.int64
    assert t.where(t["body"] == 1)["x"].tolist() == [0.25]
    f.write_text("# units: s,-,m\ntime,body,x\n0,0,0.5\n")
    assert particula.read_csv(f).units == {"time": "s", "body": "-", "x": "m"}
    # particula's own form: the units line after the header, naming each column
    f.write_text("time,body,x\n# units: time [s], body [-], x [m]\n0,0,0.5\n")
    t = particula.read_csv(f)
    assert t.units == {"time": "s", "body": "-", "x": "m"} and t.rows == 1
    f.write_text("time,body,x\n# units: body [-], time [s], x [m]\n0,0,0.5\n")  # not these columns
    assert particula.read_csv(f).units == {}
    f.write_text("time,body,x\n")
    assert particula.read_csv(f).rows == 0


def block(values, fmt):
    raw = struct.pack("<%d%s" % (len(values), fmt), *values)
    return base64.b64encode(struct.pack("<Q", len(raw)) + raw).decode()


def vtp(points, pressure, kind):
    n = len(points) // 3
    return f"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <Piece NumberOfPoints="{n}" NumberOfVerts="0">
      <PointData>
        <DataArray type="Float64" Name="pressure" NumberOfComponents="1" format="binary">{pressure}</DataArray>
        <DataArray type="Int32" Name="kind" NumberOfComponents="1" format="binary">{kind}</DataArray>
      </PointData>
      <Points>
        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="binary">{block(points, "d")}</DataArray>
      </Points>
    </Piece>
  </PolyData>
</VTKFile>
"""


def test_vtp_arrays(particula, tmp_path):
    f = tmp_path / "s.vtp"
    f.write_text(vtp([1.0, 2.0, 0.0, 3.0, 4.0, 0.0], block([5.0, -6.0], "d"), block([0, 1], "i")))
    s = particula.read_vtp(f)
    assert s.num_points == 2
    assert np.array_equal(s.points, [[1, 2], [3, 4]])
    assert np.array_equal(s["pressure"], [5, -6]) and s["kind"].dtype == np.int32
    f.write_text(vtp([1.0, 2.0, 0.0, 3.0, 4.0, 0.0], block([5.0], "d"), block([0, 1], "i")))
    with pytest.raises(ValueError, match="pressure"):
        particula.read_vtp(f)


def test_pvd_times(particula, tmp_path):
    (tmp_path / "p.pvd").write_text('<VTKFile type="Collection"><Collection>'
                                    '<DataSet timestep="0" file="a.vtp"/><DataSet timestep="0.35000000000000003" '
                                    'file="b.vtp"/></Collection></VTKFile>')
    assert particula.read_pvd(tmp_path / "p.pvd") == [(0.0, "a.vtp"), (0.35000000000000003, "b.vtp")]
    with pytest.raises(FileNotFoundError):
        particula.read_run(tmp_path / "nothing")
