// The robustness group's checks that every case shares: no overlap, fluid contained, kinetic
// energy that decays, bodies touching at rest, the rebound; and the helpers of robustness_support.hpp.
#include "particula/validation/robustness.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "particula/geometry/shape.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/error.hpp"
#include "particula/io/vtk.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/solver.hpp"
#include "robustness_support.hpp"
#include "run_outcome.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace robustness_support {

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

double gap_between(const Case& c, const BodyGeometry& g, std::size_t a, Vec2 pa, double aa, std::size_t b,
                   Vec2 pb, double ab) {
  const Shape &A = g.shapes[a], &B = g.shapes[b];
  const double d = norm(separation(c, pa, pb));
  if (A.kind() == ShapeKind::Circle && B.kind() == ShapeKind::Circle)
    return d - A.bounding_radius() - B.bounding_radius();
  // Far apart: the bounding circles' gap is a lower bound, good enough for every use here.
  const double bound_gap = d - A.bounding_radius() - B.bounding_radius();
  if (bound_gap > c.d0) return bound_gap;
  return std::min(one_sided_gap(c, g.samples[a], pa, aa, B, pb, ab),
                  one_sided_gap(c, g.samples[b], pb, ab, A, pa, aa));
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

std::vector<WallTrack> read_wall_tracks(const fs::path& run_dir, std::size_t walls) {
  const io::CsvTable table = io::read_csv(run_dir / "walls.csv");
  const std::size_t iw = table.column_index("wall"), it = table.column_index("time"),
                    ix = table.column_index("fx"), iy = table.column_index("fy");
  std::vector<WallTrack> out(walls);
  for (const auto& r : table.rows) {
    const auto w = static_cast<std::size_t>(r[iw]);
    if (w >= walls) continue;
    out[w].t.push_back(r[it]);
    out[w].fx.push_back(r[ix]);
    out[w].fy.push_back(r[iy]);
    out[w].fdx.push_back(column_or_zero(table, r, "fdx"));
    out[w].fdy.push_back(column_or_zero(table, r, "fdy"));
  }
  return out;
}

double column_or_zero(const io::CsvTable& table, const std::vector<double>& r, std::string_view name) {
  const auto it = std::find(table.header.begin(), table.header.end(), name);
  return it == table.header.end() ? 0.0 : r[static_cast<std::size_t>(it - table.header.begin())];
}

/// Mean of y over the samples with t >= from.
double mean_from(const std::vector<double>& t, const std::vector<double>& y, double from) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from) sum += y[i], ++n;
  return n ? sum / static_cast<double>(n) : std::nan("");
}

LineFit fit_line_from(const std::vector<double>& t, const std::vector<double>& y, double from) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  LineFit f;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= from) st += t[k], sy += y[k], stt += t[k] * t[k], sty += t[k] * y[k], ++f.n;
  const double n = static_cast<double>(f.n);
  if (f.n > 1 && n * stt - st * st > 0) f.slope = (n * sty - st * sy) / (n * stt - st * st);
  f.intercept = f.n > 0 ? (sy - f.slope * st) / n : 0;
  double res2 = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= from) res2 += std::pow(y[k] - (f.intercept + f.slope * t[k]), 2);
  f.rms = f.n > 0 ? std::sqrt(res2 / n) : 0;
  return f;
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

}  // namespace robustness_support

using namespace robustness_support;

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
    t.fdx.push_back(column_or_zero(table, r, "fdx"));
    t.fdy.push_back(column_or_zero(table, r, "fdy"));
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
  // A body removed at an outlet has fewer rows (its track ends at its removal): each row k is
  // checked among the bodies that have it (the rows of one time share their index).
  std::size_t rows = 0;
  for (const BodyTrack& t : tracks) rows = std::max(rows, t.size());
  const std::size_t n = c.bodies.size();
  double worst = kInf, t_worst = 0;
  std::string where = "-";
  auto note = [&](double gap, double t, const std::string& what) {
    if (gap < worst) worst = gap, t_worst = t, where = what;
  };
  for (std::size_t k = 0; k < rows; ++k) {
    for (std::size_t a = 0; a < n; ++a) {
      const BodyTrack& A = tracks[a];
      if (A.size() <= k) continue;
      const Vec2 pa{A.x[k], A.y[k]};
      if (moving(c.bodies[a]))
        for (std::size_t w = 0; w < c.walls.size(); ++w)
          note(gap_to_wall(g, a, pa, A.angle[k], c.walls[w]), A.t[k],
               fmt::format("body '{}' and wall '{}'", c.bodies[a].name, c.walls[w].name));
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!moving(c.bodies[a]) && !moving(c.bodies[b])) continue;
        const BodyTrack& B = tracks[b];
        if (B.size() <= k) continue;
        note(gap_between(c, g, a, pa, A.angle[k], b, {B.x[k], B.y[k]}, B.angle[k]), A.t[k],
             fmt::format("bodies '{}' and '{}'", c.bodies[a].name, c.bodies[b].name));
      }
    }
  }
  const double overlap = std::isfinite(worst) ? -worst / c.d0 : 0;
  const std::string shown = std::isfinite(worst)
                                ? fmt::format("{:+.3f} d0 ({}, t = {:.4g} s)", overlap, where, t_worst)
                                : "no pairs";
  return {make_check("deepest overlap of two solids over all output rows (d0; < 0: smallest gap)", overlap,
                     shown, "0 (solids never overlap)", fmt::format("<= {} d0", max_overlap),
                     overlap <= max_overlap)};
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
      // no row at this time: the body was removed at an outlet before it (fluid fills its place)
      if (tracks[b].size() == 0 || tracks[b].t.back() < t - 1e-9 * std::max(1.0, std::fabs(t))) continue;
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
  const std::vector<BodyTrack> tracks =
      c.bodies.empty() ? std::vector<BodyTrack>{} : read_body_tracks(run_dir, c.bodies.size());
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
  out.push_back(make_check(
      fmt::format(
          "fluid particles outside the domain or the region the walls enclose (worst of {} snapshots)", n),
      static_cast<double>(worst_out), worst_out ? fmt::format("{} at t = {:.4g} s", worst_out, t_out) : "0",
      "0", "0", worst_out == 0));
  if (!c.bodies.empty())
    out.push_back(make_check(
        fmt::format("fluid particles more than {} d0 inside a body (worst of {} snapshots)", depth, n),
        static_cast<double>(worst_in), worst_in ? fmt::format("{} at t = {:.4g} s", worst_in, t_in) : "0",
        "0", "0", worst_in == 0));
  return out;
}

namespace {

/// Kinetic energy of the free bodies at each common row.
std::vector<double> kinetic_energy(const Case& c, const std::vector<BodyTrack>& tracks) {
  const BodyGeometry g(c);
  std::vector<double> ke(common_rows(tracks), 0.0);
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    if (c.bodies[b].motion != BodyMotion::Free) continue;
    const double m = c.bodies[b].density * g.shapes[b].area(),
                 I = c.bodies[b].density * g.shapes[b].polar_moment();
    const BodyTrack& t = tracks[b];
    for (std::size_t k = 0; k < ke.size(); ++k)
      ke[k] += 0.5 * m * (t.vx[k] * t.vx[k] + t.vy[k] * t.vy[k]) + 0.5 * I * t.omega[k] * t.omega[k];
  }
  return ke;
}

}  // namespace

std::vector<ValidationCheck> check_time_step_held(const fs::path& run_dir) {
  const double ratio = read_outcome(run_dir).dt_min_ratio;
  return {make_check("smallest time step / the case's own (cfl d0 / c, cfl d0^2 / nu)", ratio,
                     fmt::format("{:.3g}", ratio), "of order 1", fmt::format(">= {:g}", kTimeStepDrop),
                     ratio >= kTimeStepDrop)};
}

std::vector<ValidationCheck> check_kinetic_energy_decay(const fs::path& run_dir, const Case& c,
                                                        double max_fraction, double window) {
  const std::vector<BodyTrack> tracks = tracks_or_throw(run_dir, c);
  const std::vector<double> ke = kinetic_energy(c, tracks);
  const auto peak = std::max_element(ke.begin(), ke.end());
  const std::vector<double>& t = tracks[0].t;
  const double t_peak = t[static_cast<std::size_t>(peak - ke.begin())], t_end = t[ke.size() - 1];
  double sum = 0, t_from = t_end;
  std::size_t rows = 0;
  for (std::size_t k = ke.size(); k-- > 0 && t[k] >= t_end - window * (1 + 1e-9);) {
    sum += ke[k];
    t_from = t[k];
    ++rows;
  }
  const double frac = *peak > 0 && rows > 0 ? sum / static_cast<double>(rows) / *peak : std::nan("");
  return {make_check(
      fmt::format("mean kinetic energy of the free bodies over t = {:.4g} to {:.4g} s / its peak", t_from, t_end),
      frac,
      fmt::format("{:.3g} ({} rows; at the end {:.3g}; peak {:.3g} J/m at t = {:.4g} s)", frac, rows,
                  *peak > 0 ? ke.back() / *peak : std::nan(""), *peak, t_peak),
      "0 (at rest)", fmt::format("< {}", max_fraction), frac < max_fraction)};
}

std::vector<ValidationCheck> check_bodies_touching(const fs::path& run_dir, const Case& c, double max_gap_m) {
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
    for (const WallSpec& w : c.walls)
      nearest = std::min(nearest, gap_to_wall(g, a, pa, tracks[a].angle[k], w));
    for (std::size_t b = 0; b < n; ++b)
      if (b != a)
        nearest = std::min(nearest, gap_between(c, g, a, pa, tracks[a].angle[k], b,
                                                {tracks[b].x[k], tracks[b].y[k]}, tracks[b].angle[k]));
    widest = std::max(widest, nearest / c.d0);
    if (nearest > max_gap_m) ++apart;
  }
  return {make_check(
      fmt::format("free bodies resting on a wall or another body at t = {:.4g} s", tracks[0].t[k]),
      static_cast<double>(free - apart),
      fmt::format("{} of {} (largest gap to the nearest solid {:.2f} d0 = {:.3g} mm)", free - apart, free, widest,
                  widest * c.d0 * 1e3), "all",
      fmt::format("gap <= {:.3g} mm", max_gap_m * 1e3), apart == 0)};
}

std::vector<ValidationCheck> check_rebound(const fs::path& run_dir, const Case& c, std::size_t body,
                                           std::size_t wall, double rel_tol) {
  const BodyTrack tr = tracks_or_throw(run_dir, c).at(body);
  const BodyGeometry g(c);
  const WallSpec& w = c.walls.at(wall);
  const Vec2 t = (w.to - w.from) / norm(w.to - w.from), n{-t.y, t.x};
  std::vector<double> gap(tr.size()), vn(tr.size());
  for (std::size_t k = 0; k < tr.size(); ++k) {
    gap[k] = gap_to_wall(g, body, {tr.x[k], tr.y[k]}, tr.angle[k], w);
    vn[k] = tr.vx[k] * n.x + tr.vy[k] * n.y;  // > 0: away from the wall
  }
  const std::size_t closest =
      static_cast<std::size_t>(std::min_element(gap.begin(), gap.end()) - gap.begin());
  // impact: the speed towards the wall when the gap first falls below 1 d0 (interpolated)
  double v_impact = std::nan("");
  std::size_t crossing = closest;
  for (std::size_t k = 1; k <= closest; ++k)
    if (gap[k - 1] >= c.d0 && gap[k] < c.d0) {
      const double s = (gap[k - 1] - c.d0) / (gap[k - 1] - gap[k]);
      v_impact = -(vn[k - 1] + s * (vn[k] - vn[k - 1]));
      crossing = k - 1;
      break;
    }
  // rebound: the largest speed away from the wall after the closest approach, until it turns back
  double v_rebound = 0;
  std::size_t peak = closest;
  for (std::size_t k = closest; k < tr.size(); ++k) {
    if (vn[k] < 0 && v_rebound > 0) break;
    if (vn[k] > v_rebound) v_rebound = vn[k], peak = k;
  }
  // The reversal (fastest approach to rebound peak) takes about one contact duration; rows
  // further apart than that miss the peak: at output every 1e-4 s the fine level's 0.1 ms contact
  // read 0.588 where every 1e-5 s read 0.814 (the fluid's suction slows the body at once).
  std::size_t fastest = crossing;  // the fastest approach from the gap of 1 d0 on
  for (std::size_t k = crossing; k <= closest; ++k)
    if (vn[k] <= vn[fastest]) fastest = k;
  const double rows = static_cast<double>(peak - fastest);
  constexpr double kMinReversalRows = 4;
  const double e = restitution(run_dir), ratio = v_rebound / v_impact;
  const double D = 2 * g.shapes[body].equivalent_radius();
  const double st = c.bodies[body].density * v_impact * D / (9 * c.mu());
  std::vector<ValidationCheck> out;
  out.push_back(make_check("output rows from the fastest approach to the rebound peak", rows,
                           fmt::format("{:.0f} (t = {:.5g} to {:.5g} s)", rows, tr.t[fastest], tr.t[peak]),
                           "the reversal resolved", fmt::format(">= {:.0f} (else lower output.interval)", kMinReversalRows),
                           rows >= kMinReversalRows));
  out.push_back(report("impact speed at a gap of 1 d0 (m/s), Stokes number rho_s v D / (9 mu)", v_impact,
                       fmt::format("{:.4g} m/s, St = {:.3g}; closest gap {:+.3f} d0 at t = {:.4g} s",
                                   v_impact, st, gap[closest] / c.d0, tr.t[closest])));
  if (std::isnan(e)) {
    out.push_back(report("rebound / impact speed (no restitution coefficient in this contact model)", ratio,
                         fmt::format("{:.3f}", ratio)));
    return out;
  }
  out.push_back(make_check("rebound speed / impact speed", ratio, fmt::format("{:.3f}", ratio),
                           fmt::format("{} = collision.restitution", e),
                           fmt::format("within {:.0f} %", 100 * rel_tol),
                           std::fabs(ratio / e - 1) <= rel_tol));
  return out;
}

}  // namespace particula
