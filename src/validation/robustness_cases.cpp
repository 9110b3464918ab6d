// The case-specific checks of the robustness group (incline, channel, suspensions, squeeze) and
// the group's entries: which case runs with which checks (robustness.hpp). The checks every case
// shares (overlap, containment, energy, touching, rebound) are in robustness.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "particula/io/error.hpp"
#include "particula/io/vtk.hpp"
#include "particula/validation/robustness.hpp"
#include "robustness_support.hpp"

namespace particula {

namespace fs = std::filesystem;
using namespace robustness_support;

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
  const double gap =
      body_gap(c, block, {b.x[last], b.y[last]}, b.angle[last], slope, {s.x[last], s.y[last]}, s.angle[last]);
  const double tol = 0.05 * g_along * (b.t[last] - b.t[0]);
  std::vector<ValidationCheck> out;
  out.push_back(make_check(fmt::format("distance slid down the slope by t = {:.4g} s (m)", b.t[last]), slide,
                           fmt::format("{:.3e}", slide), "slides (friction 0 by default)",
                           fmt::format(">= {:.3g}", min_slide), slide >= min_slide));
  out.push_back(make_check("gap between block and slope at the end (d0)", gap / c.d0,
                           fmt::format("{:.3f}", gap / c.d0), "on the slope", "within [-0.25, 1]",
                           gap >= -0.25 * c.d0 && gap <= c.d0));
  out.push_back(make_check("largest rotation of the block (rad)", tilt, fmt::format("{:.3f}", tilt),
                           "0 (slides flat)", "< 0.35", tilt < 0.35));
  out.push_back(make_check(
      "speed along the slope - frictionless drag-free bound g' sin(theta) t (m/s)", excess,
      fmt::format("{:+.3e} at t = {:.4g} s (g' sin theta = {:.3g} m/s^2)", excess, t_excess, g_along), "<= 0",
      fmt::format("<= 5 % of the bound at the end ({:.2e})", tol), excess <= tol));
  return out;
}

namespace {

/// The mean fluid velocity along x of snapshot `file` (the fluid's momentum per mass).
double mean_fluid_speed_x(const fs::path& run_dir, const std::string& file) {
  const io::VtpData vtp = io::read_vtp(run_dir / file);
  const auto& v = vtp.array("velocity");
  const auto& kind = vtp.int_array("kind");
  double sum = 0;
  std::size_t nf = 0;
  for (std::size_t i = 0; i < vtp.num_points; ++i)
    if (kind.data[i] == static_cast<std::int32_t>(Kind::Fluid)) sum += v.data[3 * i], ++nf;
  return nf ? sum / static_cast<double>(nf) : 0.0;
}

/// The mean of y(t) over [t_a, t_b] (trapezoidal rule over the output rows); mean_from(t, y,
/// from) when the interval is empty.
double mean_between(const std::vector<double>& t, const std::vector<double>& y, double t_a, double t_b,
                    double from) {
  if (!(t_b > t_a)) return mean_from(t, y, from);
  double integral = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double a = std::max(t[i - 1], t_a), b = std::min(t[i], t_b);
    if (b <= a) continue;
    const auto at = [&](double x) { return y[i - 1] + (y[i] - y[i - 1]) * (x - t[i - 1]) / (t[i] - t[i - 1]); };
    integral += 0.5 * (at(a) + at(b)) * (b - a);
  }
  return integral / (t_b - t_a);
}

/// The x-momentum budget of the channel between the first snapshot of the window and the last.
struct ChannelBudget {
  double t_a = 0, t_b = 0;    // the snapshots' times
  double U = 0;               // mean fluid speed of the last snapshot
  double drag = 0;            // mean drag on the cylinder
  double damping_at_cylinder = 0, damping = 0;  // the odd-even damping's sink (cylinder; all surfaces)
  double momentum_rate = 0;   // d(rho A U)/dt
  double driving = 0;         // rho f A_fluid
  double balance = 0;         // (drag + wall shear + damping + momentum rate) / driving
};

// The mean drag and wall shear (trapezoidal rule over the output rows), plus the momentum the
// odd-even damping took from the fluid next to the surfaces (the fdx columns: a numerical sink,
// not a load; solver/momentum_loads.hpp, band_share_damping), plus the rate of change of the
// fluid's momentum rho A U equal the driving rho f A. Without the momentum change the check fails a
// flow still developing: 0.938 at Re 100 over 0.42-0.7 s, while the fluid's mean speed goes from
// 0.090 to 0.101 and back to 0.095 m/s. Without the damping's sink it fails the channel at Re 100
// at 10 particles across, where kappa = 1.2 nu: 0.948, the damping 3 % of the driving
// (docs/validation.md, "Robustness cases").
ChannelBudget channel_budget(const fs::path& run_dir, const Case& c, const BodyTrack& cyl,
                             const std::vector<WallTrack>& walls, double from, double area) {
  ChannelBudget b;
  b.driving = c.rho0 * c.body_force.x * area;
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  b.U = mean_fluid_speed_x(run_dir, index.entries().back().file);
  b.t_a = cyl.t.back();
  double u_a = b.U;
  for (const auto& e : index.entries())
    if (e.time >= from - 1e-12) {
      b.t_a = e.time;
      u_a = mean_fluid_speed_x(run_dir, e.file);
      break;
    }
  b.t_b = index.entries().back().time;
  b.damping_at_cylinder = mean_between(cyl.t, cyl.fdx, b.t_a, b.t_b, from);
  double f_walls = 0;
  b.damping = b.damping_at_cylinder;
  for (const auto& w : walls)
    f_walls += mean_between(w.t, w.fx, b.t_a, b.t_b, from), b.damping += mean_between(w.t, w.fdx, b.t_a, b.t_b, from);
  b.drag = mean_between(cyl.t, cyl.fx, b.t_a, b.t_b, from);
  b.momentum_rate = b.t_b > b.t_a ? c.rho0 * area * (b.U - u_a) / (b.t_b - b.t_a) : 0.0;
  b.balance = (b.drag + f_walls + b.damping + b.momentum_rate) / b.driving;
  return b;
}

/// The drag and the lift of the cylinder over the window t >= from: a steady drag (`shedding`
/// false) or a lift that oscillates (true).
void add_drag_lift_checks(std::vector<ValidationCheck>& out, const BodyTrack& cyl, double drag, double from,
                          double D, double U, bool shedding) {
  const double t_end = cyl.t.back();
  const std::string win = fmt::format("t >= {:.3g} s", from);
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
  const double amplitude = 0.5 * (lmax - lmin) / std::fabs(drag);
  if (!shedding) {
    // Steady: the drag's drift over the window (a least-squares line through it: its change from
    // the start to the end of the window) below 2 % of the mean, and its fluctuation about that
    // line (the pressure noise of the weakly compressible fluid, or an oscillation) below 1 %.
    // (max - min) / mean would measure the noise's range instead: 2.3 % at Re 10 with a drift of
    // 0.28 % and a fluctuation of 0.41 %.
    const LineFit fit = fit_line_from(cyl.t, cyl.fx, from);
    const double drift = std::fabs(fit.slope * (t_end - from) / drag), wobble = fit.rms / std::fabs(drag);
    out.push_back(make_check(fmt::format("drag over {}: drift of a fitted line / mean; fluctuation about it / mean", win),
                             drift, fmt::format("{:.3g}; {:.3g} (max - min: {:.3g})", drift, wobble, (fmax - fmin) / std::fabs(drag)),
                             "0 (steady)", "drift < 2 %, fluctuation < 1 %", drift < 0.02 && wobble < 0.01));
    out.push_back(report("lift amplitude / drag", amplitude, fmt::format("{:.3g}", amplitude)));
    return;
  }
  const double periods = 0.5 * (crossings - 1), st = periods > 0 ? periods / (t_last - t_first) * D / U : 0;
  out.push_back(
      make_check(fmt::format("lift oscillation over {}: half the peak-to-peak / drag, periods", win),
                 amplitude, fmt::format("{:.3g}, {:.1f} periods (Strouhal {:.3g})", amplitude, periods, st),
                 "periodic shedding", ">= 0.05 and >= 2 periods", amplitude >= 0.05 && periods >= 2));
}

}  // namespace

std::vector<ValidationCheck> check_channel_cylinder(const fs::path& run_dir, const Case& c, double re_nominal,
                                                    bool shedding, double window) {
  const BodyTrack cyl = tracks_or_throw(run_dir, c).at(0);
  const std::vector<WallTrack> walls = read_wall_tracks(run_dir, c.walls.size());
  const double from = cyl.t.back() * (1 - window);
  const Shape shape = body_shape(c.bodies.at(0));
  const double D = 2 * shape.equivalent_radius();
  const Vec2 span = c.domain_max - c.domain_min;
  const double area = span.x * span.y - shape.area();
  const ChannelBudget b = channel_budget(run_dir, c, cyl, walls, from, area);
  const double U = b.U, drag = b.drag, re = U * D / c.nu;
  std::vector<ValidationCheck> out;
  out.push_back(make_check(
      fmt::format("(cylinder drag + wall shear + odd-even damping at the surfaces + d(rho A U)/dt) / "
                  "(rho f A_fluid), {:.3g} to {:.3g} s",
                  b.t_a, b.t_b),
      b.balance,
      fmt::format("{:.4f} (damping {:+.4f}, momentum change {:+.4f})", b.balance, b.damping / b.driving,
                  b.momentum_rate / b.driving),
      "1 (x momentum balance)", "within 5 %", std::fabs(b.balance - 1) <= 0.05));
  out.push_back(report("odd-even damping at the cylinder / its drag (a numerical sink, not in the drag)",
                       b.damping_at_cylinder / drag, fmt::format("{:.3g}", b.damping_at_cylinder / drag)));
  out.push_back(make_check("Reynolds number U_mean D / nu (last snapshot)", re, fmt::format("{:.3g}", re),
                           fmt::format("{:g} (nominal)", re_nominal), "within a factor 1.5",
                           re >= re_nominal / 1.5 && re <= re_nominal * 1.5));
  out.push_back(report("drag coefficient F / (0.5 rho U^2 D); F / (mu U)", drag,
                       fmt::format("{:.4g}; {:.4g} (F = {:.3e} N/m)", drag / (0.5 * c.rho0 * U * U * D),
                                   drag / (c.mu() * U), drag)));
  add_drag_lift_checks(out, cyl, drag, from, D, U, shedding);
  return out;
}

std::vector<ValidationCheck> check_sheared_suspension(const fs::path& run_dir, const Case& c,
                                                      double min_strain, double lo, double hi,
                                                      const std::string& reference) {
  const std::size_t bottom = wall_at_y(c, c.domain_min.y), top = wall_at_y(c, c.domain_max.y);
  const std::vector<WallTrack> walls = read_wall_tracks(run_dir, c.walls.size());
  const WallTrack &B = walls[bottom], &T = walls[top];
  if (T.t.size() < 2)
    throw io::IoError(fmt::format("'{}': fewer than two rows", (run_dir / "walls.csv").string()));
  const double L = c.domain_max.x - c.domain_min.x, H = c.domain_max.y - c.domain_min.y;
  const double gamma = (c.walls[top].velocity.x - c.walls[bottom].velocity.x) / H;
  const double t_end = T.t.back(), strain = std::fabs(gamma) * t_end, from = 0.5 * t_end;
  const double f_top = mean_from(T.t, T.fx, from), f_bottom = mean_from(B.t, B.fx, from);
  // The fluid drags the faster (top) wall back and the bottom one forward: stress > 0 for gamma > 0.
  const double stress = (f_bottom - f_top) / (2 * L) * (gamma >= 0 ? 1 : -1);
  const double mu_r = stress / (c.mu() * std::fabs(gamma)),
               imbalance = std::fabs(f_top + f_bottom) / std::fabs(f_top);
  std::vector<ValidationCheck> out;
  out.push_back(make_check("strain gamma t reached", strain, fmt::format("{:.3g}", strain), "the case's end",
                           fmt::format(">= {}", min_strain), strain >= min_strain * (1 - 1e-6)));
  out.push_back(make_check(
      fmt::format("relative viscosity: wall shear stress / (mu gamma), mean over t >= {:.3g} s", from), mu_r,
      fmt::format("{:.3g}", mu_r), reference, fmt::format("within [{}, {}]", lo, hi),
      mu_r >= lo && mu_r <= hi));
  out.push_back(make_check("|F_top + F_bottom| / |F_top| (the walls' forces balance)", imbalance,
                           fmt::format("{:.3g}", imbalance), "0", "< 10 %", imbalance < 0.1));
  return out;
}

std::vector<ValidationCheck> check_dilute_viscosity(const fs::path& run_dir, const Case& c,
                                                    double min_strain) {
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
  std::vector<ValidationCheck> out = check_sheared_suspension(
      run_dir, c, min_strain, 1, 1 + 4 * phi, fmt::format("{:.4f} (2D Einstein 1 + 2 phi)", 1 + 2 * phi));
  out.push_back(make_check(
      fmt::format("intrinsic viscosity (mu_r - 1) / phi at phi = {:.4f}, mu_r over t >= {:.3g} s", phi, from),
      intrinsic,
      fmt::format("{:.3g} ± {:.2g} (mu_r = {:.4f} ± {:.4f}, 2D Einstein {:.4f})", intrinsic, intrinsic_err,
                  mean, err, 1 + 2 * phi),
      "2 (2D Einstein, unbounded dilute)", "within [1, 3]",
      blocks.size() > 1 && intrinsic >= 1 && intrinsic <= 3));
  return out;
}

std::vector<ValidationCheck> check_prescribed_squeeze(const fs::path& run_dir, const Case& c,
                                                      double target_gap) {
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
    fn[k] = A.fx[k] * n.x + A.fy[k] * n.y;                               // < 0: pushes A back
    w_max = std::max(w_max, std::fabs(w[k]));
  }
  // The force at constant speed (no added-mass reaction): rows within 1 % of the top speed.
  double f_close = 0, f_part = 0;
  int n_close = 0, n_part = 0;
  for (std::size_t k = 0; k < rows; ++k) {
    if (std::fabs(w[k]) < 0.99 * w_max) continue;
    if (w[k] > 0)
      f_close += fn[k], ++n_close;
    else
      f_part += fn[k], ++n_part;
  }
  f_close /= std::max(n_close, 1), f_part /= std::max(n_part, 1);
  std::vector<ValidationCheck> out;
  out.push_back(make_check("smallest gap between the two bodies (d0)", min_gap / c.d0,
                           fmt::format("{:.3f} at t = {:.4g} s", min_gap / c.d0, t_min),
                           fmt::format("{} (schedule)", target_gap), "± 0.02 d0",
                           std::fabs(min_gap / c.d0 - target_gap) <= 0.02));
  out.push_back(make_check("force on body 0 along the line of centres while closing at full speed (N/m)",
                           f_close, fmt::format("{:+.3e} ({} rows)", f_close, n_close),
                           "< 0 (resists the approach)", "< 0", n_close > 0 && f_close < 0));
  out.push_back(make_check("force on body 0 along the line of centres while parting at full speed (N/m)",
                           f_part, fmt::format("{:+.3e} ({} rows)", f_part, n_part),
                           "> 0 (holds them together)", "> 0", n_part > 0 && f_part > 0));
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
    for (auto&& k : check_time_step_held(d)) out.push_back(std::move(k));
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
  // Within 0.2 mm (a distance: robustness.hpp): 2 d0 at the shipped resolution of both cases, the
  // range below which the contact model's lubrication force carries the film between two
  // surfaces (collision.lubrication_range, and numerics.film_gap for the particles). A body that
  // close is in near contact, sinking through its film at the rate the lubrication force allows.
  // A limit of 0.1 mm makes the check depend on the seed and the instant: mixed_shapes with seeds
  // 1 to 3 reads largest gaps of 0.59, 0.90 and 1.17 d0 at 1 s and 1.14, 0.50 and 0.51 d0 at
  // 1.5 s, the body past 1 d0 each time an ellipse sliding down the pile at 0.5-0.6 mm/s with the
  // lubrication force acting on it (docs/validation.md, "Robustness cases").
  for (auto&& k : check_bodies_touching(d, c, 2e-4)) out.push_back(std::move(k));
  return out;
}

/// The schedule of cylinder `body` of prescribed_squeeze (D = 1 mm, 1 mm apart) that closes the
/// gap to 0.1 d0 and opens it again: each moves half the way at 1 mm/s, with 0.1 s ramps, a
/// 0.1 s hold at the closest gap, then back (as the case file at d0 = 1e-4 m).
std::string squeeze_schedule(int body, double d0) {
  const double V = body == 0 ? 1e-3 : -1e-3, move = 0.5 * (1e-3 - 0.1 * d0),
               hold = move / std::fabs(V) - 0.1;  // hold: time at full speed
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
  v.push_back(entry("mixed_shapes",
                    with_containment([](const fs::path& d, const Case& c) { return settled(d, c, 0.02); })));
  v.push_back(entry("rising_lid",
                    with_containment([](const fs::path& d, const Case& c) { return settled(d, c, 0.02); })));
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
                      return check_sheared_suspension(d, c, 10, 1.2, 6,
                                                      "about 2.5 (2D Krieger-Dougherty at 0.35)");
                    })));
  for (const char* name : {"dilute_shear_phi005", "dilute_shear_phi010"})
    v.push_back(entry(name, with_containment([](const fs::path& d, const Case& c) {
                        return check_dilute_viscosity(d, c, 20);
                      })));
  v.push_back(entry("rotating_drum", with_containment({})));
  v.push_back(entry("l_shaped_settling",
                    with_containment([](const fs::path& d, const Case& c) { return settled(d, c, 0.02); })));
  // The gap of 0.1 d0 is tied to d0: the fine level gets its own schedules.
  v.push_back(entry("prescribed_squeeze", with_containment([](const fs::path& d, const Case& c) {
                      return check_prescribed_squeeze(d, c, 0.1);
                    }),
                    {"resolution.d0=5e-5", squeeze_schedule(0, 5e-5), squeeze_schedule(1, 5e-5)}));
  // Bodies with open boundaries: shipped in cases/, not cases/robustness/.
  ValidationEntry bed = entry("fluidized_bed", with_containment([](const fs::path& d, const Case& c) {
                                return check_fluidized_bed(d, c, 0.1);
                              }));
  bed.case_file = "cases/fluidized_bed.toml";
  v.push_back(std::move(bed));
  ValidationEntry carried = entry("particle_channel", with_containment([](const fs::path& d, const Case& c) {
                                    return check_particle_channel(d, c, 5e-3);
                                  }));
  carried.case_file = "cases/particle_channel.toml";
  v.push_back(std::move(carried));
  return v;
}

}  // namespace particula
