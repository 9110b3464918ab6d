#include "particula/run/observers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "particula/analytic/solutions.hpp"
#include "particula/run/run_dir.hpp"
#include "particula/solver/interpolation.hpp"

namespace particula {

// ---- snapshots ------------------------------------------------------------------------------

SnapshotWriter::SnapshotWriter(std::filesystem::path run_dir, io::StopCheck stop)
    : dir_(std::move(run_dir)), stop_(std::move(stop)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_ / "particles", ec);
  if (ec)
    throw io::WriteError(fmt::format("cannot create '{}': {}", (dir_ / "particles").string(), ec.message()));
}

std::vector<std::int32_t> particle_case_index(const Particles& P, const std::vector<RigidGroup>& groups,
                                              bool walls) {
  std::vector<std::int32_t> of_group(groups.size(), -1);
  std::int32_t wall = 0;  // groups are walls first, then bodies, each in case order (scene.cpp)
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].is_wall && walls) of_group[g] = wall;
    if (!groups[g].is_wall && !walls) of_group[g] = groups[g].body;
    wall += groups[g].is_wall ? 1 : 0;
  }
  std::vector<std::int32_t> index(P.size(), -1);
  for (std::size_t i = 0; i < P.size(); ++i)
    if (P.group[i] >= 0) index[i] = of_group.at(static_cast<std::size_t>(P.group[i]));
  return index;
}

void SnapshotWriter::write(const Solver& s) {
  const Particles& P = s.particles();
  const std::size_t n = P.size();
  io::VtkArray pressure{"pressure", 1, std::vector<double>(P.p.begin(), P.p.end())};
  io::VtkArray density{"density", 1, std::vector<double>(P.rho.begin(), P.rho.end())};
  io::VtkIntArray kind{"kind", 1, std::vector<std::int32_t>(n)}, id{"id", 1, std::vector<std::int32_t>(n)};
  io::VtkIntArray body{"body", 1, particle_case_index(P, s.groups(), false)};
  io::VtkIntArray wall{"wall", 1, particle_case_index(P, s.groups(), true)};
  for (std::size_t i = 0; i < n; ++i) {
    kind.data[i] = static_cast<std::int32_t>(P.kind[i]);
    id.data[i] = static_cast<std::int32_t>(P.id[i]);
  }
  const std::string name = fmt::format("particles/step_{:08d}.vtp", s.step_count());
  io::write_vtp(dir_ / name, P.x, {pressure, io::vector_array("velocity", P.v), density},
                {kind, body, wall, id}, stop_);
  pvd_.add(s.time(), name);
  pvd_.write(dir_ / "particles.pvd");
}

// ---- exact solutions ------------------------------------------------------------------------

namespace {
/// Channel height and moving-wall speed of a start-up channel case (walls along x).
void channel_geometry(const Case& c, double& L, double& V0) {
  L = c.domain_max.y - c.domain_min.y;
  V0 = 0;
  for (const auto& w : c.walls) V0 = std::max(V0, std::fabs(w.velocity.x));
}
}  // namespace

std::optional<Vec2> exact_velocity(const Case& c, Vec2 x, double t) {
  if (c.exact == ExactSolution::SpinUp) {
    const WallSpec& w = c.walls.at(0);  // the container (checked at load)
    const Vec2 r = x - w.center;
    const double rn = norm(r);
    if (rn == 0) return Vec2{};
    const double u = analytic::spin_up_velocity(std::min(rn, w.radius), t, w.radius, w.omega, c.nu);
    return (u / rn) * Vec2{-r.y, r.x};
  }
  double L, V0;
  channel_geometry(c, L, V0);
  const double y = x.y - c.domain_min.y;
  switch (c.exact) {
    case ExactSolution::Couette:
      return Vec2{analytic::couette_startup(y, t, L, V0, c.nu), 0};
    case ExactSolution::Poiseuille:
      return Vec2{analytic::poiseuille_startup(y, t, L, c.body_force.x, c.nu), 0};
    case ExactSolution::SpinUp:
    case ExactSolution::None:
      break;
  }
  return std::nullopt;
}

double exact_error2(const Case& c, Vec2 v, Vec2 exact) {
  const Vec2 e = v - exact;
  return c.exact == ExactSolution::SpinUp ? norm2(e) : e.x * e.x;
}

std::optional<double> particle_profile_error(const Solver& s, const Case& c, const io::StopCheck& stop) {
  if (c.exact == ExactSolution::None) return std::nullopt;
  const Particles& P = s.particles();
  double err2 = 0;
  std::size_t n = 0;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
    if (stop && (i - P.n_boundary) % 256 == 0 && stop()) return std::nullopt;
    if (P.kind[i] != Kind::Fluid) continue;  // buffer particles of open boundaries are set, not solved
    err2 += exact_error2(c, P.v[i], *exact_velocity(c, P.x[i], s.time()));
    ++n;
  }
  return n ? std::optional<double>(std::sqrt(err2 / n) / exact_peak_speed(c)) : std::nullopt;
}

double exact_peak_speed(const Case& c) {
  if (c.exact == ExactSolution::SpinUp) return std::fabs(c.walls.at(0).omega) * c.walls.at(0).radius;
  double L, V0;
  channel_geometry(c, L, V0);
  if (c.exact == ExactSolution::Poiseuille) return std::fabs(c.body_force.x) * L * L / (8 * c.nu);
  return V0;
}

// ---- probes ---------------------------------------------------------------------------------

namespace {
std::vector<std::string> probe_columns(const Case& c) {
  std::vector<std::string> cols{"time", "x", "y", "vx", "vy", "p"};
  if (c.exact != ExactSolution::None) cols.insert(cols.end(), {"vx_exact", "vy_exact"});
  return cols;
}

/// The units of probe_columns(c), in the same order.
std::vector<std::string> probe_units(const Case& c) {
  std::vector<std::string> units{"s", "m", "m", "m/s", "m/s", "Pa"};
  if (c.exact != ExactSolution::None) units.insert(units.end(), {"m/s", "m/s"});
  return units;
}
}  // namespace

const std::vector<std::string> kFlowColumns{"time", "flow_rate"};
const std::vector<std::string> kFlowUnits{"s", "m^2/s"};

ProbeWriter::ProbeWriter(const std::filesystem::path& run_dir, const ProbeSpec& spec, const Case& c,
                         io::StopCheck stop)
    : spec_(spec),
      case_(c),
      points_(probe_points(spec)),
      csv_(run_dir / probe_csv_name(spec.name), probe_columns(c), probe_units(c)),
      stop_(std::move(stop)) {
  if (spec.kind == ProbeKind::Line)
    flow_.emplace(run_dir / flow_csv_name(spec.name), kFlowColumns, kFlowUnits);
}

double flow_rate_of(Vec2 from, Vec2 to, const std::vector<Vec2>& v) {
  const real length = norm(to - from);
  if (v.size() < 2 || !(length > 0)) return 0;
  const Vec2 t = (to - from) / length, n{t.y, -t.x};
  const real ds = length / static_cast<real>(v.size() - 1);
  double q = 0;
  for (std::size_t k = 0; k + 1 < v.size(); ++k) q += 0.5 * (dot(v[k], n) + dot(v[k + 1], n)) * ds;
  return q;
}

namespace {
/// A Failure naming the first non-finite value of `row` (columns `names`), or nullopt.
std::optional<Failure> non_finite(const std::vector<double>& row, const std::vector<std::string>& names,
                                  const std::string& where, Vec2 position) {
  for (std::size_t j = 0; j < row.size(); ++j) {
    if (std::isfinite(row[j])) continue;
    Failure f;
    f.what = fmt::format("non-finite value (NaN or Inf) in {}: {} = {}", where, names.at(j), row[j]);
    f.position = position;
    return f;
  }
  return std::nullopt;
}
}  // namespace

std::optional<Failure> ProbeWriter::write(const Solver& s) {
  const auto poll = [this] {
    if (stop_ && stop_()) throw io::Cancelled();
  };
  const bool exact = case_.exact != ExactSolution::None;
  const std::size_t np = points_.size(), nc = exact ? 8 : 6;
  const std::vector<std::string> names = probe_columns(case_);
  // Interpolated in chunks (each point on its own, so the values do not depend on the chunking),
  // polling the stop check between chunks and, with the exact series (slow at early times), per point.
  // Every value is checked before anything is written: a non-finite one writes nothing and is
  // returned as a failure (the run ends with exit 3).
  constexpr std::size_t kChunk = 16384;
  std::vector<double> values;
  values.reserve(np * nc);
  std::vector<Vec2> chunk, velocities;
  double err2 = 0;
  for (std::size_t k0 = 0; k0 < np; k0 += kChunk) {
    poll();
    const std::size_t k1 = std::min(np, k0 + kChunk);
    chunk.assign(points_.begin() + static_cast<std::ptrdiff_t>(k0),
                 points_.begin() + static_cast<std::ptrdiff_t>(k1));
    const auto samples = interpolate_at(s.particles(), s.domain(), s.kernel(), chunk);
    for (std::size_t k = k0; k < k1; ++k) {
      const PointSample& a = samples[k - k0];
      velocities.push_back(a.v);
      values.insert(values.end(), {s.time(), points_[k].x, points_[k].y, a.v.x, a.v.y, a.p});
      if (exact) {
        poll();
        const Vec2 ex = *exact_velocity(case_, points_[k], s.time());
        values.insert(values.end(), {ex.x, ex.y});
        err2 += exact_error2(case_, a.v, ex);
      }
      const std::vector<double> row(values.end() - static_cast<std::ptrdiff_t>(nc), values.end());
      if (auto f = non_finite(row, names, fmt::format("probe '{}' (point {})", spec_.name, k), points_[k]))
        return f;
    }
  }
  std::vector<double> flow_row;
  if (flow_) {
    flow_row = {s.time(), flow_rate_of(spec_.from, spec_.to, velocities)};
    if (auto f = non_finite(flow_row, kFlowColumns, fmt::format("flow_{}.csv", spec_.name), spec_.from))
      return f;
  }
  csv_.rows(values, stop_);
  if (flow_) flow_->row(flow_row);
  if (exact) last_error_ = std::sqrt(err2 / points_.size()) / exact_peak_speed(case_);
  return std::nullopt;
}

// ---- body history ---------------------------------------------------------------------------

namespace {
// fdx, fdy: the odd-even damping's momentum sink next to the solid (RigidGroup::force_damping),
// reported, not part of fx, fy.
const std::vector<std::string> kBodyColumns{"time",  "body", "x",   "y",      "angle", "vx",  "vy",
                                            "omega", "fx",   "fy",  "torque", "fpx",   "fpy", "fvx",
                                            "fvy",   "fcx",  "fcy", "fdx",    "fdy"};
const std::vector<std::string> kWallColumns{"time", "wall", "fx",     "fy",  "fpx", "fpy",
                                            "fvx",  "fvy",  "torque", "fdx", "fdy"};
// Units of the columns above. In 2D a force is per unit depth (N/m) and a torque N m/m.
const std::vector<std::string> kBodyUnits{"s",     "-",   "m",   "m",     "rad", "m/s", "m/s",
                                          "rad/s", "N/m", "N/m", "N m/m", "N/m", "N/m", "N/m",
                                          "N/m",   "N/m", "N/m", "N/m",   "N/m"};
const std::vector<std::string> kWallUnits{"s",   "-",   "N/m",   "N/m", "N/m", "N/m",
                                          "N/m", "N/m", "N m/m", "N/m", "N/m"};
}  // namespace

const std::vector<std::string> kCoefficientColumns{"time", "body", "re", "re_body", "cd", "cl", "cm"};
const std::vector<std::string> kCoefficientUnits{"s", "-", "-", "-", "-", "-", "-"};

Coefficients body_coefficients(const BodyReference& ref, Vec2 force, double torque, Vec2 body_velocity,
                               double rho0, double nu) {
  const real U = norm(ref.velocity), L = ref.length;
  const Vec2 e = ref.velocity / U, n{-e.y, e.x};
  const real q = 0.5 * rho0 * U * U * L;  // dynamic pressure times length: a force per unit depth
  Coefficients c;
  c.re = U * L / nu;
  c.re_body = norm(body_velocity) * L / nu;
  c.cd = dot(force, e) / q;
  c.cl = dot(force, n) / q;
  c.cm = torque / (q * L);
  return c;
}

bool BodyHistoryWriter::writes_coefficients(const Case& c) {
  for (std::size_t i = 0; i < c.bodies.size(); ++i)
    if (body_reference(c, i).complete()) return true;
  return false;
}

BodyHistoryWriter::BodyHistoryWriter(const std::filesystem::path& run_dir)
    : csv_(run_dir / "bodies.csv", kBodyColumns, kBodyUnits),
      walls_(run_dir / "walls.csv", kWallColumns, kWallUnits) {}

BodyHistoryWriter::BodyHistoryWriter(const std::filesystem::path& run_dir, const Case& c)
    : BodyHistoryWriter(run_dir) {
  if (!writes_coefficients(c)) return;
  coefficients_.emplace(run_dir / "coefficients.csv", kCoefficientColumns, kCoefficientUnits);
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    const BodyReference r = body_reference(c, i);
    references_.push_back(r.complete() ? std::optional<BodyReference>(r) : std::nullopt);
  }
  rho0_ = c.rho0;
  nu_ = c.nu;
}

std::optional<Failure> BodyHistoryWriter::write(const Solver& s) {
  std::vector<std::vector<double>> bodies, walls, coefficients;
  int wall = 0;
  for (const RigidGroup& g : s.groups()) {
    if (g.removed) continue;  // taken out at an outlet: its rows end at its removal
    const Vec2 f = g.force_pressure + g.force_viscous;
    const bool is_wall = g.is_wall;
    auto& rows = is_wall ? walls : bodies;
    if (is_wall)
      rows.push_back({s.time(), static_cast<double>(wall++), f.x, f.y, g.force_pressure.x, g.force_pressure.y,
                      g.force_viscous.x, g.force_viscous.y, g.torque, g.force_damping.x, g.force_damping.y});
    else
      rows.push_back({s.time(), static_cast<double>(g.body), g.pos.x, g.pos.y, g.angle, g.vel.x, g.vel.y,
                      g.omega, f.x, f.y, g.torque, g.force_pressure.x, g.force_pressure.y, g.force_viscous.x,
                      g.force_viscous.y, g.force_collision.x, g.force_collision.y, g.force_damping.x,
                      g.force_damping.y});
    const std::string where =
        fmt::format("{} of {} '{}'", is_wall ? "walls.csv" : "bodies.csv", is_wall ? "wall" : "body", g.name);
    if (auto bad = non_finite(rows.back(), is_wall ? kWallColumns : kBodyColumns, where, g.pos)) return bad;
    const auto b = static_cast<std::size_t>(g.body);
    if (is_wall || !coefficients_ || b >= references_.size() || !references_[b]) continue;
    const Coefficients k = body_coefficients(*references_[b], f, g.torque, g.vel, rho0_, nu_);
    coefficients.push_back({s.time(), static_cast<double>(g.body), k.re, k.re_body, k.cd, k.cl, k.cm});
    if (auto bad = non_finite(coefficients.back(), kCoefficientColumns,
                              fmt::format("coefficients.csv of body '{}'", g.name), g.pos))
      return bad;
  }
  for (const auto& row : bodies) csv_.row(row);
  for (const auto& row : walls) walls_.row(row);
  for (const auto& row : coefficients) coefficients_->row(row);
  return std::nullopt;
}

}  // namespace particula

namespace particula {

// ---- open boundaries --------------------------------------------------------------------------

namespace {
const std::vector<std::string> kOpenColumns{
    "time",    "boundary",         "mass",       "backflow_mass", "created",
    "deleted", "buffer_particles", "fluid_mass", "body_fill_mass"};
const std::vector<std::string> kOpenUnits{"s", "-", "kg/m", "kg/m", "-", "-", "-", "kg/m", "kg/m"};
}  // namespace

real fluid_mass(const Particles& P) {
  real m = 0;  // in index order: the same sum on every run of the same state
  for (std::size_t i = P.n_boundary; i < P.size(); ++i)
    if (P.kind[i] == Kind::Fluid) m += P.m[i];
  return m;
}

std::vector<std::int64_t> buffer_counts(const Solver& s) {
  const Particles& P = s.particles();
  const auto& zones = s.params().open;
  std::vector<std::int64_t> count(zones.size(), 0);
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
    if (!is_buffer(P.kind[i])) continue;
    for (std::size_t z = 0; z < zones.size(); ++z)
      if (zones[z].inlet == (P.kind[i] == Kind::Inlet) && beyond_open_line(zones[z], P.x[i])) {
        ++count[z];
        break;
      }
  }
  return count;
}

std::vector<io::JsonObject> open_boundary_summary(const Solver& s) {
  std::vector<io::JsonObject> open;
  const std::vector<std::int64_t> buffers = buffer_counts(s);
  for (std::size_t z = 0; z < s.open_flux().size(); ++z) {
    const OpenFlux& f = s.open_flux()[z];
    io::JsonObject o;
    o.set("index", z).set("name", s.params().open_specs[z].name);
    o.set("kind", std::string(s.params().open[z].inlet ? "inlet" : "outlet"));
    o.set("mass", f.mass).set("backflow_mass", f.backflow_mass);
    o.set("created", f.created).set("deleted", f.deleted).set("buffer_particles", buffers[z]);
    if (!s.params().open[z].inlet)
      o.set("bodies",
            std::string(s.params().open_specs[z].bodies == OutletBodies::Removed ? "removed" : "held"))
          .set("bodies_removed", f.bodies_removed)
          .set("body_fill_mass", f.body_fill_mass);
    open.push_back(std::move(o));
  }
  return open;
}

std::string open_boundary_log_line(const Solver& s) {
  std::string crossed;
  for (std::size_t z = 0; z < s.open_flux().size(); ++z) {
    const OpenFlux& f = s.open_flux()[z];
    crossed += fmt::format("{}{} '{}' {:.6g} kg/m ({:.6g} kg/m the other way; {} created, {} deleted)",
                           z == 0 ? "" : ", ", s.params().open[z].inlet ? "in through" : "out through",
                           s.params().open_specs[z].name, f.mass, f.backflow_mass, f.created, f.deleted);
    if (f.bodies_removed > 0)
      crossed += fmt::format(" and {} bodies removed ({:.6g} kg/m of fluid in their places)",
                             f.bodies_removed, f.body_fill_mass);
  }
  return fmt::format(
      "open boundaries: {}; fluid mass {:.6g} kg/m; mirrored fits that fell back to the Shepard mean {}",
      crossed, fluid_mass(s.particles()), s.counters().open_fit_fallback);
}

OpenBoundaryWriter::OpenBoundaryWriter(const std::filesystem::path& run_dir)
    : csv_(run_dir / "open_boundaries.csv", kOpenColumns, kOpenUnits) {}

std::optional<Failure> OpenBoundaryWriter::write(const Solver& s) {
  const std::vector<OpenFlux>& flux = s.open_flux();
  const std::vector<std::int64_t> buffers = buffer_counts(s);
  const real mass = fluid_mass(s.particles());
  std::vector<std::vector<double>> rows;
  for (std::size_t z = 0; z < flux.size(); ++z) {
    rows.push_back({s.time(), static_cast<double>(z), flux[z].mass, flux[z].backflow_mass,
                    static_cast<double>(flux[z].created), static_cast<double>(flux[z].deleted),
                    static_cast<double>(buffers[z]), mass, flux[z].body_fill_mass});
    if (auto bad =
            non_finite(rows.back(), kOpenColumns,
                       fmt::format("open_boundaries.csv of '{}'", s.params().open_specs[z].name), Vec2{}))
      return bad;
  }
  for (const auto& row : rows) csv_.row(row);
  return std::nullopt;
}

}  // namespace particula
