// The figures of the validation cases (ValidationEntry::plot): for each case the run's curve
// that best shows its check, with the exact solution or the published points it is checked
// against. docs/validation.md draws them (report.cpp, svg_plot.cpp).
#include "validate_plots.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "particula/analytic/solutions.hpp"
#include "particula/io/csv.hpp"
#include "particula/solver/particles.hpp"
#include "run_data.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

PlotSeries series(std::string label, std::vector<double> x, std::vector<double> y, bool reference = false) {
  return PlotSeries{std::move(label), std::move(x), std::move(y), reference};
}

/// The rows of a probe file at its last output time, as (y, column) pairs.
struct ProbeLine {
  std::vector<double> y, v, exact;
};

ProbeLine last_probe_line(const fs::path& file, const std::string& column, const std::string& exact_column) {
  const io::CsvTable t = io::read_csv(file);
  const std::size_t it = t.column_index("time"), iy = t.column_index("y"), iv = t.column_index(column);
  const std::size_t ie = exact_column.empty() ? 0 : t.column_index(exact_column);
  if (t.rows.empty()) throw io::IoError(fmt::format("'{}': no rows", file.string()));
  const double last = t.rows.back()[it];
  ProbeLine p;
  for (const auto& r : t.rows)
    if (r[it] == last) {
      p.y.push_back(r[iy]);
      p.v.push_back(r[iv]);
      if (!exact_column.empty()) p.exact.push_back(r[ie]);
    }
  return p;
}

}  // namespace

ValidationPlot plot_probe_profile(const fs::path& run_dir, const Case&) {
  const ProbeLine p = last_probe_line(run_dir / "probe_profile.csv", "vx", "vx_exact");
  ValidationPlot out{"Velocity profile at the end", "vx (m/s)", "y (m)", {}};
  out.series.push_back(series("", p.v, p.y));
  out.series.push_back(series("series solution", p.exact, p.y, true));
  return out;
}

ValidationPlot plot_open_profile(const fs::path& run_dir, const Case& c) {
  const ProbeLine p = last_probe_line(run_dir / "probe_profile.csv", "vx", "");
  const OpenSpec& in = c.inlets.at(0);
  const double Um = in.velocity, H = in.width(), y0 = c.domain_min.y;
  std::vector<double> exact;
  for (const double y : p.y) exact.push_back(4 * Um * (y - y0) * (H - (y - y0)) / (H * H));
  ValidationPlot out{"Velocity profile at x = 0.75 L, last output", "vx (m/s)", "y (m)", {}};
  out.series.push_back(series("", p.v, p.y));
  out.series.push_back(series("the inflow's parabola", exact, p.y, true));
  return out;
}

ValidationPlot plot_taylor_green(const fs::path& run_dir, const Case& c) {
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  const double L = c.domain_max.x - c.domain_min.x, decay = 8 * M_PI * M_PI * c.nu / (L * L);
  std::vector<double> t, peak, te, exact;
  for (const auto& e : index.entries()) {
    t.push_back(e.time);
    peak.push_back(peak_fluid_speed(io::read_vtp(run_dir / e.file)) / c.initial_amplitude);
  }
  const double end = t.empty() ? 0 : t.back();
  for (int i = 0; i <= 100; ++i) te.push_back(end * i / 100), exact.push_back(std::exp(-decay * te.back()));
  ValidationPlot out{"Decay of the peak speed", "t (s)", "peak speed / U", {}};
  out.series.push_back(series("", t, peak));
  out.series.push_back(series("exp(-8 pi^2 t / Re)", te, exact, true));
  return out;
}

ValidationPlot plot_hydrostatic(const fs::path& run_dir, const Case& c) {
  double time = 0;
  const io::VtpData vtp = last_snapshot(run_dir, time);
  const auto& p = vtp.array("pressure");
  const auto& kind = vtp.int_array("kind");
  struct Row {
    double y = 0, p = 0;
    int n = 0;
  };
  std::map<long, Row> rows;  // the fluid particles of each lattice row
  for (std::size_t i = 0; i < vtp.num_points; ++i)
    if (kind.data[i] == static_cast<std::int32_t>(Kind::Fluid)) {
      Row& r = rows[std::lround(std::floor((vtp.points[i].y - c.domain_min.y) / c.d0))];
      r.y += vtp.points[i].y, r.p += p.data[i], r.n += 1;
    }
  const double g = norm(c.gravity);
  std::vector<double> y, mean, exact;
  for (const auto& [k, r] : rows) {
    y.push_back(r.y / r.n);
    mean.push_back(r.p / r.n);
    exact.push_back(c.p0 + c.rho0 * g * (c.domain_max.y - y.back()));
  }
  ValidationPlot out{fmt::format("Mean fluid pressure per row at t = {:g} s", time), "p (Pa)", "y (m)", {}};
  out.series.push_back(series("", mean, y));
  out.series.push_back(series("p0 + rho g (H - y)", exact, y, true));
  return out;
}

ValidationPlot plot_spin_up(const fs::path& run_dir, const Case& c) {
  const WallSpec& w = c.walls.at(0);
  const io::CsvTable table = io::read_csv(run_dir / "walls.csv");
  const std::size_t it = table.column_index("time"), iq = table.column_index("torque");
  std::vector<double> t, q, exact;
  for (const auto& r : table.rows)
    if (r[it] > 0) {
      t.push_back(r[it]);
      q.push_back(r[iq]);
      exact.push_back(analytic::spin_up_torque(r[it], w.radius, w.omega, c.mu(), c.nu));
    }
  ValidationPlot out{"Torque of the fluid on the turning container", "t (s)", "torque (N m / m)", {}};
  out.series.push_back(series("", t, q));
  out.series.push_back(series("Bessel series", t, exact, true));
  return out;
}

ValidationPlot plot_body_curve(const fs::path& run_dir, const BodyCurve& spec) {
  ValidationPlot out{spec.title, "t (s)", spec.y_label, {}};
  for (std::size_t k = 0; k < spec.bodies.size(); ++k) {
    const BodyHistory h = body_history(run_dir, spec.bodies[k]);
    const std::vector<double>& v = spec.column == "x"       ? h.x
                                   : spec.column == "y"     ? h.y
                                   : spec.column == "vx"    ? h.vx
                                   : spec.column == "vy"    ? h.vy
                                   : spec.column == "angle" ? h.angle
                                                            : h.omega;
    out.series.push_back(series(spec.bodies.size() > 1 ? fmt::format("body {}", spec.bodies[k]) : "", h.t, v));
  }
  for (const auto& ref : spec.references) {
    const Curve r = reference_curve(ref.file, ref.column, ref.body);
    out.series.push_back(series(ref.label, r.t, r.v, true));
  }
  return out;
}

ValidationPlot plot_force_coefficients(const fs::path& run_dir, const Case&) {
  const io::CsvTable k = io::read_csv(run_dir / "coefficients.csv");
  const std::size_t it = k.column_index("time"), icd = k.column_index("cd"), icl = k.column_index("cl");
  std::vector<double> t, cd, cl;
  for (const auto& r : k.rows) t.push_back(r[it]), cd.push_back(r[icd]), cl.push_back(r[icl]);
  ValidationPlot out{"Drag and lift coefficients of the cylinder", "t (s)", "C_D, C_L", {}};
  out.series.push_back(series("C_D", t, cd));
  out.series.push_back(series("C_L", t, cl));
  return out;
}

}  // namespace particula
