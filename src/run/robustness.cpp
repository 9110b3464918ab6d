#include "particula/run/robustness.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <toml++/toml.h>

#include "particula/geometry/shape.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/error.hpp"
#include "particula/io/vtk.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/particles.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

ValidationCheck make_check(std::string quantity, double value, std::string shown, std::string reference,
                           std::string tolerance, bool pass) {
  ValidationCheck c;
  c.quantity = std::move(quantity);
  c.value = value;
  c.shown = std::move(shown);
  c.reference = std::move(reference);
  c.tolerance = std::move(tolerance);
  c.pass = pass;
  return c;
}

ValidationCheck report(std::string quantity, double value, std::string shown) {
  ValidationCheck c = make_check(std::move(quantity), value, std::move(shown), "", "", true);
  c.report_only = true;
  return c;
}

/// a - b, through the nearest periodic image along periodic axes.
Vec2 separation(const Case& c, Vec2 a, Vec2 b) { return periodic_separation(c, a, b); }

/// The shapes of a case's bodies and their surface samples, built once per check (samples at
/// d0/4, fine enough to see an overlap of a tenth of d0 between two flat sides).
struct BodyGeometry {
  std::vector<Shape> shapes;
  std::vector<std::vector<SurfaceSample>> samples;
  explicit BodyGeometry(const Case& c) {
    for (const BodySpec& b : c.bodies) {
      shapes.push_back(body_shape(b));
      samples.push_back(shapes.back().sample_surface(c.d0 / 4));
    }
  }
};

/// Signed distance of world point p to body k placed at (pos, angle).
double distance_to_body(const Case& c, const Shape& s, Vec2 pos, double angle, Vec2 p) {
  const Vec2 local = rotate(separation(c, p, pos), std::cos(angle), -std::sin(angle));
  return s.signed_distance(local);
}

/// Smallest signed distance of a's surface samples to the solid b.
double one_sided_gap(const Case& c, const std::vector<SurfaceSample>& a_samples, Vec2 pos_a, double angle_a,
                     const Shape& b, Vec2 pos_b, double angle_b) {
  double best = kInf;
  const double ca = std::cos(angle_a), sa = std::sin(angle_a);
  for (const auto& s : a_samples)
    best = std::min(best, distance_to_body(c, b, pos_b, angle_b, pos_a + rotate(s.x, ca, sa)));
  return best;
}

double gap_between(const Case& c, const BodyGeometry& g, std::size_t a, Vec2 pa, double aa, std::size_t b, Vec2 pb,
                   double ab) {
  const Shape &A = g.shapes[a], &B = g.shapes[b];
  const double d = norm(separation(c, pa, pb));
  if (A.kind() == ShapeKind::Circle && B.kind() == ShapeKind::Circle)
    return d - A.bounding_radius() - B.bounding_radius();
  // Far apart: the bounding circles' gap is a lower bound, good enough for every use here.
  const double bound_gap = d - A.bounding_radius() - B.bounding_radius();
  if (bound_gap > c.d0) return bound_gap;
  return std::min(one_sided_gap(c, g.samples[a], pa, aa, B, pb, ab), one_sided_gap(c, g.samples[b], pb, ab, A, pa, aa));
}

double gap_to_wall(const BodyGeometry& g, std::size_t a, Vec2 pa, double aa, const WallSpec& w) {
  const Vec2 t = w.to - w.from;
  const double L2 = norm2(t);
  const Vec2 n = Vec2{-t.y, t.x} / std::sqrt(L2);  // the fluid's side
  const double ca = std::cos(aa), sa = std::sin(aa);
  double best = kInf;
  for (const auto& s : g.samples[a]) {
    const Vec2 p = pa + rotate(s.x, ca, sa);
    const double u = dot(p - w.from, t) / L2;
    if (u < 0 || u > 1) continue;  // beyond the segment's ends another wall acts
    best = std::min(best, dot(p - w.from, n));
  }
  return best;
}

/// Index of the row of `tr` at time t (the nearest row; the checks read rows written together).
std::size_t row_at(const BodyTrack& tr, double t) {
  const auto it = std::lower_bound(tr.t.begin(), tr.t.end(), t);
  if (it == tr.t.end()) return tr.size() - 1;
  const std::size_t k = static_cast<std::size_t>(it - tr.t.begin());
  return k > 0 && t - tr.t[k - 1] < tr.t[k] - t ? k - 1 : k;
}

bool moving(const BodySpec& b) { return b.motion != BodyMotion::Fixed; }

/// Rows common to every body (bodies.csv writes all bodies at each output time).
std::size_t common_rows(const std::vector<BodyTrack>& tracks) {
  std::size_t n = std::numeric_limits<std::size_t>::max();
  for (const auto& t : tracks) n = std::min(n, t.size());
  return tracks.empty() ? 0 : n;
}

std::vector<BodyTrack> tracks_or_throw(const fs::path& run_dir, const Case& c) {
  std::vector<BodyTrack> tracks = read_body_tracks(run_dir, c.bodies.size());
  if (common_rows(tracks) < 2)
    throw io::IoError(fmt::format("'{}': fewer than two rows per body", (run_dir / "bodies.csv").string()));
  return tracks;
}

/// Rows of walls.csv: per wall, time and force.
struct WallTrack {
  std::vector<double> t, fx, fy;
};

std::vector<WallTrack> read_wall_tracks(const fs::path& run_dir, std::size_t walls) {
  const io::CsvTable table = io::read_csv(run_dir / "walls.csv");
  const std::size_t iw = table.column_index("wall"), it = table.column_index("time"), ix = table.column_index("fx"),
                    iy = table.column_index("fy");
  std::vector<WallTrack> out(walls);
  for (const auto& r : table.rows) {
    const auto w = static_cast<std::size_t>(r[iw]);
    if (w >= walls) continue;
    out[w].t.push_back(r[it]);
    out[w].fx.push_back(r[ix]);
    out[w].fy.push_back(r[iy]);
  }
  return out;
}

/// Mean of y over the samples with t >= from.
double mean_from(const std::vector<double>& t, const std::vector<double>& y, double from) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from) sum += y[i], ++n;
  return n ? sum / static_cast<double>(n) : std::nan("");
}

/// The restitution coefficient of the resolved case (collision.restitution), 0.8 when the key
/// does not exist (the documented default of the spring-dashpot model); NaN for the P.38 model,
/// which has none.
double restitution(const fs::path& run_dir) {
  try {
    const toml::table t = toml::parse_file((run_dir / "case.toml").string());
    if (t["collision"]["model"].value_or(std::string("spring_dashpot")) == "paper") return std::nan("");
    return t["collision"]["restitution"].value_or(0.8);
  } catch (const std::exception&) {
    return 0.8;
  }
}

/// The wall at y = `y` spanning the domain (the channel and Couette cases).
std::size_t wall_at_y(const Case& c, double y) {
  for (std::size_t w = 0; w < c.walls.size(); ++w)
    if (std::fabs(c.walls[w].from.y - y) < 1e-9 && std::fabs(c.walls[w].to.y - y) < 1e-9) return w;
  throw io::IoError(fmt::format("case '{}': no wall along y = {} m", c.name, y));
}

}  // namespace

std::vector<BodyTrack> read_body_tracks(const fs::path& run_dir, std::size_t bodies) {
  const io::CsvTable table = io::read_csv(run_dir / "bodies.csv");
  const char* names[] = {"time", "x", "y", "angle", "vx", "vy", "omega", "fx", "fy"};
  std::size_t col[9];
  for (int k = 0; k < 9; ++k) col[k] = table.column_index(names[k]);
  const std::size_t ib = table.column_index("body");
  std::vector<BodyTrack> out(bodies);
  for (const auto& r : table.rows) {
    const auto b = static_cast<std::size_t>(r[ib]);
    if (b >= bodies) continue;
    BodyTrack& t = out[b];
    std::vector<double>* dst[] = {&t.t, &t.x, &t.y, &t.angle, &t.vx, &t.vy, &t.omega, &t.fx, &t.fy};
    for (int k = 0; k < 9; ++k) dst[k]->push_back(r[col[k]]);
  }
  return out;
}

double body_gap(const Case& c, std::size_t a, Vec2 pa, double aa, std::size_t b, Vec2 pb, double ab) {
  const BodyGeometry g(c);
  return gap_between(c, g, a, pa, aa, b, pb, ab);
}

double wall_gap(const Case& c, std::size_t a, Vec2 pa, double aa, std::size_t w) {
  const BodyGeometry g(c);
  return gap_to_wall(g, a, pa, aa, c.walls.at(w));
}

std::vector<ValidationCheck> check_no_overlap(const fs::path& run_dir, const Case& c, double max_overlap) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const BodyGeometry g(c);
  const std::size_t rows = common_rows(tracks), n = c.bodies.size();
  double worst = kInf, t_worst = 0;
  std::string where = "-";
  auto note = [&](double gap, double t, const std::string& what) {
    if (gap < worst) worst = gap, t_worst = t, where = what;
  };
  for (std::size_t k = 0; k < rows; ++k) {
    for (std::size_t a = 0; a < n; ++a) {
      const BodyTrack& A = tracks[a];
      const Vec2 pa{A.x[k], A.y[k]};
      if (moving(c.bodies[a]))
        for (std::size_t w = 0; w < c.walls.size(); ++w)
          note(gap_to_wall(g, a, pa, A.angle[k], c.walls[w]), A.t[k],
               fmt::format("body '{}' and wall '{}'", c.bodies[a].name, c.walls[w].name));
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!moving(c.bodies[a]) && !moving(c.bodies[b])) continue;
        const BodyTrack& B = tracks[b];
        note(gap_between(c, g, a, pa, A.angle[k], b, {B.x[k], B.y[k]}, B.angle[k]), A.t[k],
             fmt::format("bodies '{}' and '{}'", c.bodies[a].name, c.bodies[b].name));
      }
    }
  }
  const double overlap = std::isfinite(worst) ? -worst / c.d0 : 0;
  const std::string shown =
      std::isfinite(worst) ? fmt::format("{:+.3f} d0 ({}, t = {:.4g} s)", overlap, where, t_worst) : "no pairs";
  return {make_check("deepest overlap of two solids over all output rows (d0; < 0: smallest gap)", overlap, shown,
                     "0 (solids never overlap)", fmt::format("<= {} d0", max_overlap), overlap <= max_overlap)};
}

namespace {

/// Counts of one snapshot: fluid particles outside the domain and deep inside a body.
struct Escapes {
  std::size_t outside = 0, inside = 0;
};

Escapes count_escapes(const io::VtpData& vtp, const Case& c, const BodyGeometry& g,
                      const std::vector<BodyTrack>& tracks, double t, double depth) {
  Escapes e;
  const auto& kind = vtp.int_array("kind");
  const double tol = 1e-9 * c.d0;
  const std::vector<WallPiece> walls = walls_at(c, t);
  const Domain dom{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  for (std::size_t i = 0; i < vtp.num_points; ++i) {
    if (kind.data[i] != static_cast<std::int32_t>(Kind::Fluid)) continue;
    const Vec2 x = vtp.points[i];
    const bool out_x = !c.periodic_x && (x.x < c.domain_min.x - tol || x.x > c.domain_max.x + tol);
    const bool out_y = !c.periodic_y && (x.y < c.domain_min.y - tol || x.y > c.domain_max.y + tol);
    if (out_x || out_y || !in_fluid_region(walls, dom, x)) ++e.outside;
    for (std::size_t b = 0; b < c.bodies.size(); ++b) {
      if (tracks[b].size() == 0) continue;
      const std::size_t k = row_at(tracks[b], t);
      const Vec2 pos{tracks[b].x[k], tracks[b].y[k]};
      if (norm(separation(c, x, pos)) > g.shapes[b].bounding_radius()) continue;
      if (distance_to_body(c, g.shapes[b], pos, tracks[b].angle[k], x) < -depth * c.d0) {
        ++e.inside;
        break;
      }
    }
  }
  return e;
}

}  // namespace

std::vector<ValidationCheck> check_fluid_contained(const fs::path& run_dir, const Case& c, double depth) {
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  if (index.entries().empty()) throw io::IoError(fmt::format("'{}': no snapshot", run_dir.string()));
  const std::vector<BodyTrack> tracks = c.bodies.empty() ? std::vector<BodyTrack>{}
                                                         : read_body_tracks(run_dir, c.bodies.size());
  const BodyGeometry g(c);
  std::size_t worst_out = 0, worst_in = 0;
  double t_out = 0, t_in = 0;
  for (const auto& entry : index.entries()) {
    const io::VtpData vtp = io::read_vtp(run_dir / entry.file);
    const Escapes e = count_escapes(vtp, c, g, tracks, entry.time, depth);
    if (e.outside > worst_out) worst_out = e.outside, t_out = entry.time;
    if (e.inside > worst_in) worst_in = e.inside, t_in = entry.time;
  }
  const auto n = index.entries().size();
  std::vector<ValidationCheck> out;
  out.push_back(make_check(fmt::format("fluid particles outside the domain or the region the walls enclose (worst of {} snapshots)", n),
                           static_cast<double>(worst_out),
                           worst_out ? fmt::format("{} at t = {:.4g} s", worst_out, t_out) : "0", "0", "0",
                           worst_out == 0));
  if (!c.bodies.empty())
    out.push_back(make_check(
        fmt::format("fluid particles more than {} d0 inside a body (worst of {} snapshots)", depth, n),
        static_cast<double>(worst_in), worst_in ? fmt::format("{} at t = {:.4g} s", worst_in, t_in) : "0", "0",
        "0", worst_in == 0));
  return out;
}

namespace {

/// Kinetic energy of the free bodies at each common row.
std::vector<double> kinetic_energy(const Case& c, const std::vector<BodyTrack>& tracks) {
  const BodyGeometry g(c);
  std::vector<double> ke(common_rows(tracks), 0.0);
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    if (c.bodies[b].motion != BodyMotion::Free) continue;
    const double m = c.bodies[b].density * g.shapes[b].area(), I = c.bodies[b].density * g.shapes[b].polar_moment();
    const BodyTrack& t = tracks[b];
    for (std::size_t k = 0; k < ke.size(); ++k)
      ke[k] += 0.5 * m * (t.vx[k] * t.vx[k] + t.vy[k] * t.vy[k]) + 0.5 * I * t.omega[k] * t.omega[k];
  }
  return ke;
}

}  // namespace

std::vector<ValidationCheck> check_kinetic_energy_decay(const fs::path& run_dir, const Case& c, double max_fraction) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const std::vector<double> ke = kinetic_energy(c, tracks);
  const auto peak = std::max_element(ke.begin(), ke.end());
  const double t_peak = tracks[0].t[static_cast<std::size_t>(peak - ke.begin())], t_end = tracks[0].t[ke.size() - 1];
  const double frac = *peak > 0 ? ke.back() / *peak : std::nan("");
  return {make_check(fmt::format("kinetic energy of the free bodies at t = {:.4g} s / its peak", t_end), frac,
                     fmt::format("{:.3g} (peak {:.3g} J/m at t = {:.4g} s)", frac, *peak, t_peak),
                     "0 (at rest)", fmt::format("< {}", max_fraction), frac < max_fraction)};
}

std::vector<ValidationCheck> check_bodies_touching(const fs::path& run_dir, const Case& c, double max_gap) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const BodyGeometry g(c);
  const std::size_t k = common_rows(tracks) - 1, n = c.bodies.size();
  std::size_t free = 0, apart = 0;
  double widest = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (c.bodies[a].motion != BodyMotion::Free) continue;
    ++free;
    const Vec2 pa{tracks[a].x[k], tracks[a].y[k]};
    double nearest = kInf;
    for (const WallSpec& w : c.walls) nearest = std::min(nearest, gap_to_wall(g, a, pa, tracks[a].angle[k], w));
    for (std::size_t b = 0; b < n; ++b)
      if (b != a)
        nearest = std::min(nearest, gap_between(c, g, a, pa, tracks[a].angle[k], b, {tracks[b].x[k], tracks[b].y[k]},
                                                tracks[b].angle[k]));
    widest = std::max(widest, nearest / c.d0);
    if (nearest > max_gap * c.d0) ++apart;
  }
  return {make_check(fmt::format("free bodies resting on a wall or another body at t = {:.4g} s", tracks[0].t[k]),
                     static_cast<double>(free - apart),
                     fmt::format("{} of {} (largest gap to the nearest solid {:.2f} d0)", free - apart, free, widest),
                     "all", fmt::format("gap <= {} d0", max_gap), apart == 0)};
}

std::vector<ValidationCheck> check_rebound(const fs::path& run_dir, const Case& c, std::size_t body, std::size_t wall,
                                           double rel_tol) {
  const BodyTrack tr = tracks_or_throw(run_dir, c).at(body);
  const BodyGeometry g(c);
  const WallSpec& w = c.walls.at(wall);
  const Vec2 t = (w.to - w.from) / norm(w.to - w.from), n{-t.y, t.x};
  std::vector<double> gap(tr.size()), vn(tr.size());
  for (std::size_t k = 0; k < tr.size(); ++k) {
    gap[k] = gap_to_wall(g, body, {tr.x[k], tr.y[k]}, tr.angle[k], w);
    vn[k] = tr.vx[k] * n.x + tr.vy[k] * n.y;  // > 0: away from the wall
  }
  const std::size_t closest = static_cast<std::size_t>(std::min_element(gap.begin(), gap.end()) - gap.begin());
  // impact: the speed towards the wall when the gap first falls below 1 d0 (interpolated)
  double v_impact = std::nan("");
  for (std::size_t k = 1; k <= closest; ++k)
    if (gap[k - 1] >= c.d0 && gap[k] < c.d0) {
      const double s = (gap[k - 1] - c.d0) / (gap[k - 1] - gap[k]);
      v_impact = -(vn[k - 1] + s * (vn[k] - vn[k - 1]));
      break;
    }
  // rebound: the largest speed away from the wall after the closest approach, until it turns back
  double v_rebound = 0;
  for (std::size_t k = closest; k < tr.size(); ++k) {
    if (vn[k] < 0 && v_rebound > 0) break;
    v_rebound = std::max(v_rebound, vn[k]);
  }
  const double e = restitution(run_dir), ratio = v_rebound / v_impact;
  const double D = 2 * g.shapes[body].equivalent_radius();
  const double st = c.bodies[body].density * v_impact * D / (9 * c.mu());
  std::vector<ValidationCheck> out;
  out.push_back(report("impact speed at a gap of 1 d0 (m/s), Stokes number rho_s v D / (9 mu)", v_impact,
                       fmt::format("{:.4g} m/s, St = {:.3g}; closest gap {:+.3f} d0 at t = {:.4g} s", v_impact, st,
                                   gap[closest] / c.d0, tr.t[closest])));
  if (std::isnan(e)) {
    out.push_back(report("rebound / impact speed (no restitution coefficient in this contact model)", ratio,
                         fmt::format("{:.3f}", ratio)));
    return out;
  }
  out.push_back(make_check("rebound speed / impact speed", ratio, fmt::format("{:.3f}", ratio),
                           fmt::format("{} = collision.restitution", e), fmt::format("within {:.0f} %", 100 * rel_tol),
                           std::fabs(ratio / e - 1) <= rel_tol));
  return out;
}

namespace {

/// The slope of a fixed polygon: its longest edge, as a unit vector pointing downhill.
Vec2 downhill(const BodySpec& slope) {
  const auto& v = slope.vertices;
  std::size_t best = 0;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (norm(v[(i + 1) % v.size()] - v[i]) > norm(v[(best + 1) % v.size()] - v[best])) best = i;
  Vec2 d = v[(best + 1) % v.size()] - v[best];
  d = d / norm(d);
  return d.y > 0 ? -1.0 * d : d;
}

}  // namespace

std::vector<ValidationCheck> check_incline_slide(const fs::path& run_dir, const Case& c, std::size_t block,
                                                 std::size_t slope, double min_slide) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const BodyTrack& b = tracks.at(block);
  const Vec2 down = downhill(c.bodies.at(slope));
  const double g = norm(c.gravity), sin_theta = -down.y;
  const double g_along = g * sin_theta * (1 - c.rho0 / c.bodies.at(block).density);  // buoyancy-corrected
  const std::size_t last = b.size() - 1;
  const double slide = (b.x[last] - b.x[0]) * down.x + (b.y[last] - b.y[0]) * down.y;
  double excess = -kInf, t_excess = 0, tilt = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const double v_along = b.vx[k] * down.x + b.vy[k] * down.y, bound = g_along * (b.t[k] - b.t[0]);
    if (v_along - bound > excess) excess = v_along - bound, t_excess = b.t[k];
    tilt = std::max(tilt, std::fabs(b.angle[k] - b.angle[0]));
  }
  const BodyTrack& s = tracks.at(slope);
  const double gap = body_gap(c, block, {b.x[last], b.y[last]}, b.angle[last], slope, {s.x[last], s.y[last]},
                              s.angle[last]);
  const double tol = 0.05 * g_along * (b.t[last] - b.t[0]);
  std::vector<ValidationCheck> out;
  out.push_back(make_check(fmt::format("distance slid down the slope by t = {:.4g} s (m)", b.t[last]), slide,
                           fmt::format("{:.3e}", slide), "slides (friction 0 by default)",
                           fmt::format(">= {:.3g}", min_slide), slide >= min_slide));
  out.push_back(make_check("gap between block and slope at the end (d0)", gap / c.d0, fmt::format("{:.3f}", gap / c.d0),
                           "on the slope", "within [-0.25, 1]", gap >= -0.25 * c.d0 && gap <= c.d0));
  out.push_back(make_check("largest rotation of the block (rad)", tilt, fmt::format("{:.3f}", tilt), "0 (slides flat)",
                           "< 0.35", tilt < 0.35));
  out.push_back(make_check("speed along the slope - frictionless drag-free bound g' sin(theta) t (m/s)", excess,
                           fmt::format("{:+.3e} at t = {:.4g} s (g' sin theta = {:.3g} m/s^2)", excess, t_excess, g_along),
                           "<= 0", fmt::format("<= 5 % of the bound at the end ({:.2e})", tol), excess <= tol));
  return out;
}

std::vector<ValidationCheck> check_channel_cylinder(const fs::path& run_dir, const Case& c, double re_nominal,
                                                    bool shedding, double window) {
  const BodyTrack cyl = tracks_or_throw(run_dir, c).at(0);
  const std::vector<WallTrack> walls = read_wall_tracks(run_dir, c.walls.size());
  const double t_end = cyl.t.back(), from = t_end * (1 - window);
  const Shape shape = body_shape(c.bodies.at(0));
  const double D = 2 * shape.equivalent_radius();
  const Vec2 span = c.domain_max - c.domain_min;
  const double driving = c.rho0 * c.body_force.x * (span.x * span.y - shape.area());
  double f_walls = 0;
  for (const auto& w : walls) f_walls += mean_from(w.t, w.fx, from);
  const double drag = mean_from(cyl.t, cyl.fx, from), balance = (drag + f_walls) / driving;
  // mean fluid speed from the last snapshot
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  const io::VtpData vtp = io::read_vtp(run_dir / index.entries().back().file);
  const auto& v = vtp.array("velocity");
  const auto& kind = vtp.int_array("kind");
  double sum = 0;
  std::size_t nf = 0;
  for (std::size_t i = 0; i < vtp.num_points; ++i)
    if (kind.data[i] == static_cast<std::int32_t>(Kind::Fluid)) sum += v.data[3 * i], ++nf;
  const double U = nf ? sum / static_cast<double>(nf) : 0, re = U * D / c.nu;
  std::vector<ValidationCheck> out;
  const std::string win = fmt::format("t >= {:.3g} s", from);
  out.push_back(make_check(fmt::format("(cylinder drag + wall shear) / (rho f A_fluid), mean over {}", win), balance,
                           fmt::format("{:.4f}", balance), "1 (x momentum balance)", "within 5 %",
                           std::fabs(balance - 1) <= 0.05));
  out.push_back(make_check("Reynolds number U_mean D / nu (last snapshot)", re, fmt::format("{:.3g}", re),
                           fmt::format("{:g} (nominal)", re_nominal), "within a factor 1.5",
                           re >= re_nominal / 1.5 && re <= re_nominal * 1.5));
  out.push_back(report("drag coefficient F / (0.5 rho U^2 D); F / (mu U)", drag,
                       fmt::format("{:.4g}; {:.4g} (F = {:.3e} N/m)", drag / (0.5 * c.rho0 * U * U * D), drag / (c.mu() * U),
                                   drag)));
  double fmin = kInf, fmax = -kInf, lift_mean = mean_from(cyl.t, cyl.fy, from);
  double lmin = kInf, lmax = -kInf, t_first = 0, t_last = 0;
  int crossings = 0;
  for (std::size_t k = 0; k < cyl.size(); ++k) {
    if (cyl.t[k] < from) continue;
    fmin = std::min(fmin, cyl.fx[k]), fmax = std::max(fmax, cyl.fx[k]);
    lmin = std::min(lmin, cyl.fy[k]), lmax = std::max(lmax, cyl.fy[k]);
    if (k > 0 && cyl.t[k - 1] >= from && (cyl.fy[k - 1] - lift_mean) * (cyl.fy[k] - lift_mean) < 0) {
      if (crossings++ == 0) t_first = cyl.t[k];
      t_last = cyl.t[k];
    }
  }
  const double drift = (fmax - fmin) / std::fabs(drag), amplitude = 0.5 * (lmax - lmin) / std::fabs(drag);
  if (!shedding) {
    out.push_back(make_check(fmt::format("drag: (max - min) / mean over {}", win), drift, fmt::format("{:.3g}", drift),
                             "0 (steady)", "< 2 %", drift < 0.02));
    out.push_back(report("lift amplitude / drag", amplitude, fmt::format("{:.3g}", amplitude)));
    return out;
  }
  const double periods = 0.5 * (crossings - 1), st = periods > 0 ? periods / (t_last - t_first) * D / U : 0;
  out.push_back(make_check(fmt::format("lift oscillation over {}: half the peak-to-peak / drag, periods", win),
                           amplitude, fmt::format("{:.3g}, {:.1f} periods (Strouhal {:.3g})", amplitude, periods, st),
                           "periodic shedding", ">= 0.05 and >= 2 periods", amplitude >= 0.05 && periods >= 2));
  return out;
}

std::vector<ValidationCheck> check_sheared_suspension(const fs::path& run_dir, const Case& c, double min_strain,
                                                      double lo, double hi, const std::string& reference) {
  const std::size_t bottom = wall_at_y(c, c.domain_min.y), top = wall_at_y(c, c.domain_max.y);
  const std::vector<WallTrack> walls = read_wall_tracks(run_dir, c.walls.size());
  const WallTrack &B = walls[bottom], &T = walls[top];
  if (T.t.size() < 2) throw io::IoError(fmt::format("'{}': fewer than two rows", (run_dir / "walls.csv").string()));
  const double L = c.domain_max.x - c.domain_min.x, H = c.domain_max.y - c.domain_min.y;
  const double gamma = (c.walls[top].velocity.x - c.walls[bottom].velocity.x) / H;
  const double t_end = T.t.back(), strain = std::fabs(gamma) * t_end, from = 0.5 * t_end;
  const double f_top = mean_from(T.t, T.fx, from), f_bottom = mean_from(B.t, B.fx, from);
  // The fluid drags the faster (top) wall back and the bottom one forward: stress > 0 for gamma > 0.
  const double stress = (f_bottom - f_top) / (2 * L) * (gamma >= 0 ? 1 : -1);
  const double mu_r = stress / (c.mu() * std::fabs(gamma)), imbalance = std::fabs(f_top + f_bottom) / std::fabs(f_top);
  std::vector<ValidationCheck> out;
  out.push_back(make_check("strain gamma t reached", strain, fmt::format("{:.3g}", strain), "the case's end",
                           fmt::format(">= {}", min_strain), strain >= min_strain * (1 - 1e-6)));
  out.push_back(make_check(fmt::format("relative viscosity: wall shear stress / (mu gamma), mean over t >= {:.3g} s", from),
                           mu_r, fmt::format("{:.3g}", mu_r), reference,
                           fmt::format("within [{}, {}]", lo, hi), mu_r >= lo && mu_r <= hi));
  out.push_back(make_check("|F_top + F_bottom| / |F_top| (the walls' forces balance)", imbalance,
                           fmt::format("{:.3g}", imbalance), "0", "< 10 %", imbalance < 0.1));
  return out;
}

std::vector<ValidationCheck> check_dilute_viscosity(const fs::path& run_dir, const Case& c, double min_strain) {
  const std::size_t bottom = wall_at_y(c, c.domain_min.y), top = wall_at_y(c, c.domain_max.y);
  const std::vector<WallTrack> walls = read_wall_tracks(run_dir, c.walls.size());
  const WallTrack &B = walls[bottom], &T = walls[top];
  if (T.t.size() < 2 || B.t.size() != T.t.size())
    throw io::IoError(fmt::format("'{}': fewer than two rows", (run_dir / "walls.csv").string()));
  const double L = c.domain_max.x - c.domain_min.x, H = c.domain_max.y - c.domain_min.y;
  const double gamma = (c.walls[top].velocity.x - c.walls[bottom].velocity.x) / H;
  double solid = 0;
  for (const BodySpec& b : c.bodies) solid += M_PI * b.radius * b.radius;
  const double phi = solid / (L * H), from = 0.5 * T.t.back();
  // The relative viscosity of every row of the second half, then its mean and the standard error
  // from 10 block means (the rows are correlated over a few strain units; blocks of one strain
  // unit or more are nearly independent).
  std::vector<double> mu_r;
  for (std::size_t k = 0; k < T.t.size(); ++k)
    if (T.t[k] >= from)
      mu_r.push_back((B.fx[k] - T.fx[k]) / (2 * L) * (gamma >= 0 ? 1 : -1) / (c.mu() * std::fabs(gamma)));
  constexpr std::size_t kBlocks = 10;
  double mean = 0, block_var = 0;
  const std::size_t per = mu_r.size() / kBlocks;
  std::vector<double> blocks;
  for (std::size_t b = 0; per > 0 && b < kBlocks; ++b) {
    double s = 0;
    for (std::size_t k = b * per; k < (b + 1) * per; ++k) s += mu_r[k];
    blocks.push_back(s / static_cast<double>(per));
  }
  for (double v : blocks) mean += v / static_cast<double>(blocks.size());
  for (double v : blocks) block_var += (v - mean) * (v - mean) / static_cast<double>(blocks.size() - 1);
  const double err = blocks.size() > 1 ? std::sqrt(block_var / static_cast<double>(blocks.size())) : kInf;
  const double intrinsic = (mean - 1) / phi, intrinsic_err = err / phi;
  std::vector<ValidationCheck> out = check_sheared_suspension(run_dir, c, min_strain, 1, 1 + 4 * phi,
                                                              fmt::format("{:.4f} (2D Einstein 1 + 2 phi)", 1 + 2 * phi));
  out.push_back(make_check(fmt::format("intrinsic viscosity (mu_r - 1) / phi at phi = {:.4f}, mu_r over t >= {:.3g} s", phi, from),
                           intrinsic,
                           fmt::format("{:.3g} ± {:.2g} (mu_r = {:.4f} ± {:.4f}, 2D Einstein {:.4f})", intrinsic,
                                       intrinsic_err, mean, err, 1 + 2 * phi),
                           "2 (2D Einstein, unbounded dilute)", "within [1, 3]",
                           blocks.size() > 1 && intrinsic >= 1 && intrinsic <= 3));
  return out;
}

std::vector<ValidationCheck> check_prescribed_squeeze(const fs::path& run_dir, const Case& c, double target_gap) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const BodyTrack &A = tracks.at(0), &B = tracks.at(1);
  const BodyGeometry g(c);
  const std::size_t rows = common_rows(tracks);
  double min_gap = kInf, t_min = 0, w_max = 0;
  std::vector<double> w(rows), fn(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    const Vec2 pa{A.x[k], A.y[k]}, pb{B.x[k], B.y[k]};
    const double gap = gap_between(c, g, 0, pa, A.angle[k], 1, pb, B.angle[k]);
    if (gap < min_gap) min_gap = gap, t_min = A.t[k];
    const Vec2 n = separation(c, pb, pa) / norm(separation(c, pb, pa));  // from A to B
    w[k] = (A.vx[k] - B.vx[k]) * n.x + (A.vy[k] - B.vy[k]) * n.y;        // > 0: closing
    fn[k] = A.fx[k] * n.x + A.fy[k] * n.y;                                 // < 0: pushes A back
    w_max = std::max(w_max, std::fabs(w[k]));
  }
  // The force at constant speed (no added-mass reaction): rows within 1 % of the top speed.
  double f_close = 0, f_part = 0;
  int n_close = 0, n_part = 0;
  for (std::size_t k = 0; k < rows; ++k) {
    if (std::fabs(w[k]) < 0.99 * w_max) continue;
    if (w[k] > 0) f_close += fn[k], ++n_close;
    else f_part += fn[k], ++n_part;
  }
  f_close /= std::max(n_close, 1), f_part /= std::max(n_part, 1);
  std::vector<ValidationCheck> out;
  out.push_back(make_check("smallest gap between the two bodies (d0)", min_gap / c.d0,
                           fmt::format("{:.3f} at t = {:.4g} s", min_gap / c.d0, t_min), fmt::format("{} (schedule)", target_gap),
                           "± 0.02 d0", std::fabs(min_gap / c.d0 - target_gap) <= 0.02));
  out.push_back(make_check("force on body 0 along the line of centres while closing at full speed (N/m)", f_close,
                           fmt::format("{:+.3e} ({} rows)", f_close, n_close), "< 0 (resists the approach)", "< 0",
                           n_close > 0 && f_close < 0));
  out.push_back(make_check("force on body 0 along the line of centres while parting at full speed (N/m)", f_part,
                           fmt::format("{:+.3e} ({} rows)", f_part, n_part), "> 0 (holds them together)", "> 0",
                           n_part > 0 && f_part > 0));
  return out;
}

// ---- the entries --------------------------------------------------------------------------------

namespace {

using Check = std::function<std::vector<ValidationCheck>(const fs::path&, const Case&)>;

/// The checks every case with bodies gets: no overlap, no fluid escaping.
Check with_containment(Check specific) {
  return [specific](const fs::path& d, const Case& c) {
    std::vector<ValidationCheck> out = specific ? specific(d, c) : std::vector<ValidationCheck>{};
    for (auto&& k : check_no_overlap(d, c)) out.push_back(std::move(k));
    for (auto&& k : check_fluid_contained(d, c)) out.push_back(std::move(k));
    return out;
  };
}

ValidationEntry entry(std::string name, Check check, std::vector<std::string> fine = {}) {
  ValidationEntry e;
  e.name = name;
  e.group = ValidationGroup::Robustness;
  e.case_file = "cases/robustness/" + name + ".toml";
  e.evaluate = std::move(check);
  e.fine_overrides = std::move(fine);
  return e;
}

std::vector<ValidationCheck> settled(const fs::path& d, const Case& c, double ke_fraction) {
  std::vector<ValidationCheck> out = check_kinetic_energy_decay(d, c, ke_fraction);
  for (auto&& k : check_bodies_touching(d, c, 1.0)) out.push_back(std::move(k));
  return out;
}

/// The schedule of cylinder `body` of prescribed_squeeze (D = 1 mm, 1 mm apart) that closes the
/// gap to 0.1 d0 and opens it again: each moves half the way at 1 mm/s, with 0.1 s ramps, a
/// 0.1 s hold at the closest gap, then back (as the case file at d0 = 1e-4 m).
std::string squeeze_schedule(int body, double d0) {
  const double V = body == 0 ? 1e-3 : -1e-3, move = 0.5 * (1e-3 - 0.1 * d0), hold = move / std::fabs(V) - 0.1;  // hold: time at full speed
  const double t[] = {0, 0.1, 0.1 + hold, 0.2 + hold, 0.3 + hold, 0.4 + hold, 0.4 + 2 * hold, 0.5 + 2 * hold};
  const double v[] = {0, V, V, 0, 0, -V, -V, 0};
  std::string rows;
  for (int k = 0; k < 8; ++k) rows += fmt::format("{}[{:.9g},{:.9g},0,0]", k ? "," : "", t[k], v[k]);
  return fmt::format("body.{}.schedule=[{}]", body, rows);
}

Check channel(double re, bool shedding) {
  return [re, shedding](const fs::path& d, const Case& c) {
    return check_channel_cylinder(d, c, re, shedding, shedding ? 0.4 : 0.2);
  };
}

}  // namespace

std::vector<ValidationEntry> robustness_entries() {
  std::vector<ValidationEntry> v;
  v.push_back(entry("settling_pile", with_containment([](const fs::path& d, const Case& c) {
                      return check_kinetic_energy_decay(d, c, 0.02);
                    })));
  v.push_back(entry("mixed_shapes", with_containment([](const fs::path& d, const Case& c) {
                      return settled(d, c, 0.02);
                    })));
  v.push_back(entry("rising_lid", with_containment([](const fs::path& d, const Case& c) {
                      return settled(d, c, 0.02);
                    })));
  v.push_back(entry("drop_rebound", with_containment([](const fs::path& d, const Case& c) {
                      return check_rebound(d, c, 0, 0, 0.25);
                    })));
  v.push_back(entry("incline_slide", with_containment([](const fs::path& d, const Case& c) {
                      return check_incline_slide(d, c, 1, 0, 2e-3);
                    })));
  v.push_back(entry("cylinder_channel_re0p1", with_containment(channel(0.1, false))));
  v.push_back(entry("cylinder_channel_re1", with_containment(channel(1, false))));
  v.push_back(entry("cylinder_channel_re10", with_containment(channel(10, false))));
  v.push_back(entry("cylinder_channel_re100", with_containment(channel(100, true))));
  v.push_back(entry("sheared_suspension", with_containment([](const fs::path& d, const Case& c) {
                      return check_sheared_suspension(d, c, 10, 1.2, 6, "about 2.5 (2D Krieger-Dougherty at 0.35)");
                    })));
  for (const char* name : {"dilute_shear_phi005", "dilute_shear_phi010"})
    v.push_back(entry(name, with_containment([](const fs::path& d, const Case& c) {
                        return check_dilute_viscosity(d, c, 20);
                      })));
  v.push_back(entry("rotating_drum", with_containment({})));
  // The gap of 0.1 d0 is tied to d0: the fine level gets its own schedules.
  v.push_back(entry("prescribed_squeeze",
                    with_containment([](const fs::path& d, const Case& c) { return check_prescribed_squeeze(d, c, 0.1); }),
                    {"resolution.d0=5e-5", squeeze_schedule(0, 5e-5), squeeze_schedule(1, 5e-5)}));
  return v;
}

}  // namespace particula
