#include "run_data.hpp"

#include <fmt/format.h>

#include <cmath>

#include "particula/io/csv.hpp"
#include "particula/io/error.hpp"
#include "particula/solver/particles.hpp"
#include "particula/validation/validate.hpp"

namespace particula {

namespace fs = std::filesystem;

/// The last snapshot of a run directory (particles.pvd's last entry).
io::VtpData last_snapshot(const fs::path& run_dir, double& time) {
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  if (index.entries().empty()) throw io::IoError(fmt::format("'{}': no snapshot", (run_dir / "particles.pvd").string()));
  time = index.entries().back().time;
  return io::read_vtp(run_dir / index.entries().back().file);
}

/// Largest speed of the fluid particles of a snapshot.
double peak_fluid_speed(const io::VtpData& vtp) {
  const auto& v = vtp.array("velocity");
  const auto& kind = vtp.int_array("kind");
  double peak = 0;
  for (std::size_t i = 0; i < vtp.num_points; ++i)
    if (kind.data[i] == static_cast<std::int32_t>(Kind::Fluid))
      peak = std::max(peak, std::hypot(v.data[3 * i], v.data[3 * i + 1]));
  return peak;
}

// ---- body histories (bodies.csv) and reference curves -----------------------------------------

BodyHistory body_history(const fs::path& run_dir, int body) {
  const io::CsvTable table = io::read_csv(run_dir / "bodies.csv");
  const std::size_t ib = table.column_index("body"), it = table.column_index("time"), ix = table.column_index("x"),
                    iy = table.column_index("y"), ia = table.column_index("angle"), ivx = table.column_index("vx"),
                    ivy = table.column_index("vy"), iw = table.column_index("omega");
  BodyHistory h;
  for (const auto& r : table.rows) {
    if (static_cast<int>(r[ib]) != body) continue;
    h.t.push_back(r[it]);
    h.x.push_back(r[ix]);
    h.y.push_back(r[iy]);
    h.angle.push_back(r[ia]);
    h.vx.push_back(r[ivx]);
    h.vy.push_back(r[ivy]);
    h.omega.push_back(r[iw]);
  }
  if (h.size() < 2)
    throw io::IoError(fmt::format("'{}': fewer than two rows for body {}", (run_dir / "bodies.csv").string(), body));
  return h;
}

Curve reference_curve(const std::string& file, const std::string& column, int body) {
  const io::CsvTable table = io::read_csv(source_dir() / "reference" / file);
  const std::size_t it = table.column_index("t"), iv = table.column_index(column);
  Curve c;
  for (const auto& r : table.rows) {
    if (body >= 0 && static_cast<int>(r[table.column_index("body")]) != body) continue;
    c.t.push_back(r[it]);
    c.v.push_back(r[iv]);
  }
  return c;
}

}  // namespace particula
