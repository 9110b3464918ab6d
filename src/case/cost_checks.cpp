// Cross checks on what a case would cost or compute with, run with the others (checks.cpp):
// the size of its numbers (every derived scale a finite double whose square is finite and
// non-zero), its probes (inside the domain, a sensible number of points), and its time steps
// (time.dt_max and the output intervals against the stable step, a bounded step count).
// Each refuses at load what used to be accepted and then crashed, hung or wrote NaN.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "internal.hpp"
#include "particula/case/load.hpp"

namespace particula {

namespace {

/// A speed the case sets at t = 0, and the key that sets it.
struct SetSpeed {
  real speed;
  std::string key;
};

/// Largest distance from `pivot` of the points of wall w (an arc sampled along its sweep).
real wall_reach(const WallSpec& w, Vec2 pivot) {
  real r = std::max(norm(w.from - pivot), norm(w.to - pivot));
  if (w.shape == WallShape::Arc)
    for (int k = 0; k <= 64; ++k) {
      const real a = w.start_angle + (w.end_angle - w.start_angle) * k / 64.0;
      r = std::max(r, norm(w.center + w.radius * Vec2{std::cos(a), std::sin(a)} - pivot));
    }
  return r;
}

/// A lower bound of a body's largest distance from its centre: its radius or largest semi-axis,
/// or half the larger side of a polygon's bounding box.
real body_reach(const BodySpec& b) {
  real reach = std::max({b.radius, b.semi_axes.x, b.semi_axes.y});
  if (!b.vertices.empty()) {
    Vec2 lo = b.vertices.front(), hi = lo;
    for (const Vec2& p : b.vertices) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    reach = std::max({reach, 0.5 * (hi.x - lo.x), 0.5 * (hi.y - lo.y)});
  }
  return reach;
}

/// The largest speed an inlet sets (its uniform speed or parabola peak, or the largest u of its
/// table), ramp left out.
real inlet_speed(const OpenSpec& o) {
  if (o.profile != InletProfile::Table) return o.velocity;
  real u = 0;
  for (const Vec2& row : o.table) u = std::max(u, row.y);
  return u;
}

/// The speeds a case sets: sliding and turning walls, bodies (translation and rotation,
/// schedules included; each the larger of the two, a lower bound of the body's fastest point),
/// the initial flow, and the inflow of inlets (at full speed, after any ramp).
std::vector<SetSpeed> set_speeds(const Case& c) {
  std::vector<SetSpeed> out;
  for (std::size_t k = 0; k < c.walls.size(); ++k) {
    const WallSpec& w = c.walls[k];
    out.push_back({norm(w.velocity), case_detail::wall_key(k, "velocity")});
    out.push_back({std::fabs(w.omega) * wall_reach(w, w.pivot), case_detail::wall_key(k, "omega")});
  }
  if (c.initial_flow == InitialFlow::TaylorGreen) out.push_back({c.initial_amplitude, "initial.amplitude"});
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    const real reach = body_reach(b);
    const auto add = [&](Vec2 v, real omega, const char* leaf) {
      out.push_back({std::max(norm(v), std::fabs(omega) * reach), fmt::format("body[{}].{}", k, leaf)});
    };
    add(b.velocity, b.omega, norm(b.velocity) >= std::fabs(b.omega) * reach ? "velocity" : "omega");
    for (const MotionKnot& m : b.schedule) add(m.velocity, m.omega, "schedule");
  }
  for (std::size_t k = 0; k < c.inlets.size(); ++k) {
    const bool table = c.inlets[k].profile == InletProfile::Table;
    out.push_back({inlet_speed(c.inlets[k]), fmt::format("inlet[{}].{}", k, table ? "table" : "velocity")});
  }
  return out;
}

/// Largest speed at t = 0 (set_speeds).
real initial_speed(const Case& c) {
  real v = 0;
  for (const SetSpeed& s : set_speeds(c)) v = std::max(v, s.speed);
  return v;
}

}  // namespace

real estimated_dt(const Case& c, bool capped) {
  // The nearest pair of the perturbed lattice: d0/sqrt(2) diagonally, each particle moved by up
  // to perturbation d0 (P.30, P.31 of Solver::stable_dt with the initial speeds).
  const real dmin = c.d0 * M_SQRT1_2 * (1 - 2 * c.perturbation);
  real dt = c.cfl * dmin / (c.c + initial_speed(c));
  if (c.nu > 0) dt = std::min(dt, c.cfl * dmin * dmin / c.nu);
  if (capped && c.dt_max > 0) dt = std::min(dt, c.dt_max);
  // the force condition of Solver::body_force_dt
  Vec2 f = c.body_force;
  if (c.gravity_in_fluid) f += c.gravity;
  if (norm(f) > 0) dt = std::min(dt, 0.25 * std::sqrt(c.h_over_d0 * c.d0 / norm(f)));
  return dt;
}

namespace case_detail {

namespace {

/// A count for messages: "2.5e+03", or "more than 1e308" when it overflowed.
std::string count(double n) { return std::isfinite(n) ? fmt::format("{:.3g}", n) : "more than 1e308"; }

real area(const BodySpec& b) {
  switch (b.shape) {
    case BodyShape::Circle: return M_PI * b.radius * b.radius;
    case BodyShape::Ellipse: return M_PI * b.semi_axes.x * b.semi_axes.y;
    case BodyShape::HalfDisc: return 0.5 * M_PI * b.radius * b.radius;
    case BodyShape::Polygon: {
      real a = 0;
      const std::vector<Vec2>& v = b.vertices;
      for (std::size_t i = 1; i + 1 < v.size(); ++i) a += cross(v[i] - v[0], v[i + 1] - v[0]);
      return 0.5 * std::fabs(a);
    }
  }
  return 0;
}

/// Size of a body: its radius, larger semi-axis, or the largest distance of a vertex from the first.
real body_size(const BodySpec& b) {
  real r = std::max({b.radius, b.semi_axes.x, b.semi_axes.y});
  for (const Vec2& p : b.vertices) r = std::max(r, norm(p - b.vertices.front()));
  return r;
}

/// |v| without overflow in the squares (to report a huge vector's true size).
real length(Vec2 v) { return std::hypot(v.x, v.y); }

/// One derived quantity of a case and the key that sets it.
struct Scale {
  std::string key, what, unit;
  real value;
  bool nonzero;  // must also be at least kTinyScale (it divides, or scales the whole run); else
                 // only bounded above (a tiny value such as a gravity of 1e-300 is harmless)
};

}  // namespace

/// Every derived scale of the computation (lengths, the sound speed, pressures, masses, kernel
/// gradients, the time step, forces, accelerations) must lie in [kTinyScale, kHugeScale] =
/// [1e-150, 1e150], so that its square and its products with the others are finite non-zero
/// doubles. A case outside (e.g. every number of a valid case times 1e150) is refused here
/// instead of writing NaN or inf. Quantities that only add (gravity, speeds, coordinates) are
/// bounded above only.
void check_magnitudes(const Case& c, const LoadContext& ctx) {
  constexpr real kHugeScale = 1e150, kTinyScale = 1e-150;
  const real lx = c.domain_max.x - c.domain_min.x, ly = c.domain_max.y - c.domain_min.y;
  const real L = std::max(lx, ly), h = c.h();
  const real pressure = c.rho0 * c.c * c.c + c.p0, mu = c.mu();
  const std::string visc = ctx.given.contains("fluid.mu") ? "fluid.mu" : "fluid.nu";
  std::vector<Scale> scales{
      {"resolution.d0", "the particle spacing d0", "m", c.d0, true},
      {"domain.max", "the domain size max(max - min)", "m", L, true},
      {"domain.min", "the largest coordinate of domain.min", "m",
       std::max(std::fabs(c.domain_min.x), std::fabs(c.domain_min.y)), false},
      {"domain.max", "the largest coordinate of domain.max", "m",
       std::max(std::fabs(c.domain_max.x), std::fabs(c.domain_max.y)), false},
      {"fluid.rho0", "the density rho0", "kg/m^3", c.rho0, true},
      {"fluid.c", "the sound speed c", "m/s", c.c, true},
      {visc, "the kinematic viscosity nu", "m^2/s", c.nu, false},
      {visc, "the dynamic viscosity mu = rho0 nu", "Pa s", mu, false},
      {"fluid.c", "the pressure scale rho0 c^2 + p0", "Pa", pressure, true},
      {"fluid.p0", "the background pressure p0", "Pa", c.p0, false},
      {"resolution.d0", "the particle mass rho0 d0^2", "kg/m", c.rho0 * c.d0 * c.d0, true},
      {"resolution.d0", "the kernel gradient scale 1/h^3 (h = h_over_d0 d0)", "1/m^3", 1 / (h * h * h), true},
      {"fluid.c", "the acceleration scale c^2 / d0", "m/s^2", c.c * c.c / c.d0, true},
      {"fluid.c", "the force scale on a wall (rho0 c^2 + p0) times the domain size", "N/m", pressure * L, true},
      {visc, "the viscous stress scale mu c / d0", "Pa", mu * c.c / c.d0, false},
      {"fluid.gravity", "the gravity |g|", "m/s^2", length(c.gravity), false},
      {"fluid.gravity", "the hydrostatic pressure scale rho0 |g| times the domain size", "Pa",
       c.rho0 * length(c.gravity) * L, false},
      {"fluid.body_force", "the body force |f|", "m/s^2", length(c.body_force), false},
      {"initial.amplitude", "the initial flow amplitude", "m/s", c.initial_amplitude, false},
      {"time.end", "the end time", "s", c.t_end, true},
      {"collision.stiffness", "the contact stiffness", "N/m^2", c.collision_stiffness, false},
      {"collision.range", "the contact distance", "m", c.collision_range, false},
      {"collision.lubrication_range", "the lubrication range", "m", c.collision_lubrication_range, false},
  };
  for (std::size_t k = 0; k < c.walls.size(); ++k)
    scales.push_back({fmt::format("wall[{}].velocity", k), "the wall speed", "m/s", length(c.walls[k].velocity), false});
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const BodySpec& b = c.bodies[k];
    const std::string key = fmt::format("body[{}].", k);
    const real mass = b.density * area(b), size = body_size(b);
    const bool free = b.motion == BodyMotion::Free && b.density > 0;  // density 0: check_density says so
    scales.push_back({key + "velocity", "the body speed", "m/s", length(b.velocity), false});
    scales.push_back({key + "omega", "the body's rotation speed |omega| times its size", "m/s",
                      std::fabs(b.omega) * size, false});
    for (const MotionKnot& m : b.schedule)
      scales.push_back({key + "schedule", "a scheduled speed (|v| + |omega| times the body's size)", "m/s",
                        length(m.velocity) + std::fabs(m.omega) * size, false});
    scales.push_back({key + "density", "the body's mass density times area", "kg/m", mass, free});
    scales.push_back({key + "density", "the body's moment of inertia (mass times size^2)", "kg m", mass * size * size,
                      free});
    scales.push_back({key + "density", "the body's weight (mass times |g|)", "N/m", mass * length(c.gravity), false});
  }
  for (std::size_t k = 0; k < c.inlets.size(); ++k) {
    const bool table = c.inlets[k].profile == InletProfile::Table;
    scales.push_back({fmt::format("inlet[{}].{}", k, table ? "table" : "velocity"), "the inflow speed", "m/s",
                      inlet_speed(c.inlets[k]), false});
    scales.push_back({fmt::format("inlet[{}].ramp_time", k), "the ramp time", "s", c.inlets[k].ramp_time, false});
  }
  for (std::size_t k = 0; k < c.outlets.size(); ++k)
    scales.push_back({fmt::format("outlet[{}].pressure", k), "the outlet pressure", "Pa", c.outlets[k].pressure,
                      false});
  // Last, as it depends on the speeds above.
  scales.push_back({"fluid.c", "the time step (about cfl d0 / (c + V))", "s", estimated_dt(c, false), true});
  for (const Scale& s : scales) {
    const real v = std::fabs(s.value);
    const bool ok = std::isfinite(v) && v <= kHugeScale && (v >= kTinyScale || !s.nonzero);
    if (ok) continue;
    throw ctx.error(s.key, fmt::format("{} is {:.3g} {}, outside [{:.0e}, {:.0e}], the range in which particula "
                                       "computes safely (squares and products of such numbers must stay finite, "
                                       "non-zero doubles): the case's numbers are too extreme; use SI values of a "
                                       "sensible size",
                                       s.what, s.value, s.unit, kTinyScale, kHugeScale));
  }
}

/// Probes: every point inside the domain (there is no fluid to interpolate from outside), the
/// points of a line no closer than d0/100 (the interpolation, over a kernel of radius h, cannot
/// tell them apart), and at most kMaxProbePoints in all (memory and output size: `info` counts them).
void check_probes(const Case& c, const LoadContext& ctx) {
  const real tol = 1e-6 * c.d0;
  auto inside = [&](Vec2 x) {
    return x.x >= c.domain_min.x - tol && x.x <= c.domain_max.x + tol && x.y >= c.domain_min.y - tol &&
           x.y <= c.domain_max.y + tol;
  };
  auto outside = [&](const ProbeSpec& p, const std::string& key, const std::string& which, Vec2 x) {
    return ctx.error(key, fmt::format("probe '{}' {} {} lies outside the domain {} .. {}: there is no fluid to "
                                      "interpolate from there",
                                      p.name, which, vec(x), vec(c.domain_min), vec(c.domain_max)));
  };
  double total = 0;
  for (std::size_t k = 0; k < c.probes.size(); ++k) {
    const ProbeSpec& p = c.probes[k];
    const std::string key = fmt::format("probe[{}].", k);
    if (p.kind == ProbeKind::Points) {
      for (std::size_t i = 0; i < p.at.size(); ++i)
        if (!inside(p.at[i])) throw outside(p, fmt::format("{}at[{}]", key, i), fmt::format("point {}", i), p.at[i]);
    } else {
      for (const auto& [end, x] : {std::pair{"from", p.from}, std::pair{"to", p.to}})
        if (!inside(x)) throw outside(p, key + end, std::string(end) + " point", x);
      const real length = norm(p.to - p.from);
      const double most = std::max(2.0, std::floor(kProbePointsPerD0 * length / c.d0 * (1 + 1e-9)) + 1);
      if (p.points > most)
        throw ctx.error(key + "points",
                        fmt::format("probe '{}' has {} points on a {:.3g} m line, {:.3g} m apart: closer than d0/{:g} = "
                                    "{:.3g} m, which the interpolation (over a radius h = {:.3g} m) cannot tell apart; "
                                    "use at most {:.0f} points",
                                    p.name, p.points, length, length / (p.points - 1), kProbePointsPerD0,
                                    c.d0 / kProbePointsPerD0, c.h(), most));
    }
    total += static_cast<double>(probe_point_count(p));
    if (total > kMaxProbePoints)
      throw ctx.error(key + (p.kind == ProbeKind::Points ? "at" : "points"),
                      fmt::format("the probes up to probe '{}' have {:.0f} points in all, more than the {:.0e} "
                                  "particula accepts (each point is interpolated and written at every probe output)",
                                  p.name, total, kMaxProbePoints));
  }
}

/// Coefficient references: a body needs both a reference velocity and a length (its own or
/// [analysis]'s) or neither; half a reference is a mistake, not a request for no coefficients.
void check_references(const Case& c, const LoadContext& ctx) {
  const bool any_v = c.reference_velocity.x != 0 || c.reference_velocity.y != 0;
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    const BodyReference r = body_reference(c, i);
    const bool has_v = r.velocity.x != 0 || r.velocity.y != 0, has_l = r.length > 0;
    if (has_v == has_l) continue;
    const BodySpec& b = c.bodies[i];
    const bool own = has_v ? (b.reference_velocity.x != 0 || b.reference_velocity.y != 0) : b.reference_length > 0;
    const std::string given = has_v ? "reference_velocity" : "reference_length";
    const std::string missing = has_v ? "reference_length" : "reference_velocity";
    throw ctx.error(own ? fmt::format("body[{}].{}", i, given) : "analysis." + given,
                    fmt::format("body '{}' has a {} but no {}: the coefficients need both; give body[{}].{} or "
                                "analysis.{}",
                                b.name, given, missing, i, missing, missing));
  }
  if (c.bodies.empty() && (any_v != (c.reference_length > 0)))
    throw ctx.error(any_v ? "analysis.reference_velocity" : "analysis.reference_length",
                    "analysis.reference_velocity and analysis.reference_length go together: give both or neither");
}

/// Time steps: time.dt_max and the output intervals not absurdly below the stable step (each step
/// is cut short to end on an output time, so an interval of 1e-300 s would mean 1e300 steps), a
/// bounded number of steps and of outputs. An interval between 1e-3 of the step and the step
/// only makes the steps shorter (like time.dt_max).
/// No speed the case sets may reach the speed of sound: the weakly compressible fluid cannot
/// carry a flow at Mach 1 (its density would change by order one, and the Courant step shrinks
/// with c + V), so such a case would only end in exit 3 after it started writing.
void check_mach(const Case& c, const LoadContext& ctx) {
  for (const SetSpeed& s : set_speeds(c))
    if (s.speed >= c.c)
      throw ctx.error("fluid.c",
                      fmt::format("fluid.c = {:.3g} m/s is not above the speed {:.3g} m/s that {} sets (Mach {:.2g}): "
                                  "a weakly compressible fluid must stay well below its speed of sound; choose "
                                  "fluid.c at least 10 times the fastest speed of the flow ({:.3g} m/s or more here)",
                                  c.c, s.speed, s.key, s.speed / c.c, 10 * s.speed));
}

void check_time_steps(const Case& c, const LoadContext& ctx) {
  const real stable = estimated_dt(c, false), dt = estimated_dt(c, true);
  const std::string about =
      fmt::format("about {:.3g} s at the start, estimated from d0, fluid.c, fluid.nu and the initial speeds", stable);
  if (c.dt_max > 0 && c.dt_max < kMinStepFraction * stable)
    throw ctx.error("time.dt_max",
                    fmt::format("time.dt_max = {:.3g} s is less than {:g} of the stable time step ({}): it would take "
                                "about {} steps to time.end = {:.6g} s; leave time.dt_max at 0 (no cap) or raise it",
                                c.dt_max, kMinStepFraction, about, count(c.t_end / c.dt_max), c.t_end));
  double steps = c.t_end / dt;
  if (c.max_steps > 0) steps = std::min(steps, static_cast<double>(c.max_steps));
  if (!(steps <= kMaxSteps)) {
    const bool capped = c.dt_max > 0 && c.dt_max < stable;
    throw ctx.error(capped ? "time.dt_max" : "time.end",
                    fmt::format("the run would take about {} steps of {:.3g} s to time.end = {:.6g} s, more than "
                                "the {:.0e} particula accepts (the stable step is {}); shorten time.end, set "
                                "time.max_steps, {}",
                                count(steps), dt, c.t_end, kMaxSteps, about,
                                capped ? "or raise time.dt_max" : "or coarsen resolution.d0"));
  }
  struct Stream {
    std::string key;
    real interval;
    bool cuts_steps;  // each step ends on the stream's output times (outputs, snapshots, probes)
  };
  std::vector<Stream> streams{{"output.interval", c.output_interval, true}};
  if (c.snapshots && c.snapshot_interval > 0) streams.push_back({"output.snapshot_interval", c.snapshot_interval, true});
  if (c.checkpoint_interval > 0) streams.push_back({"output.checkpoint_interval", c.checkpoint_interval, false});
  for (std::size_t k = 0; k < c.probes.size(); ++k)
    streams.push_back({fmt::format("probe[{}].interval", k), c.probes[k].interval, true});
  for (const Stream& s : streams) {
    if (s.interval < kMinStepFraction * dt)
      throw ctx.error(
          s.key, fmt::format("{} = {:.3g} s is less than {:g} of the time step (about {:.3g} s): {}, about {} to "
                             "time.end = {:.6g} s; use a longer interval",
                             s.key, s.interval, kMinStepFraction, dt,
                             s.cuts_steps ? "every step would be cut short to end on an output time, one output a step"
                                          : "there would be a checkpoint at every step",
                             count(s.cuts_steps ? c.t_end / s.interval : steps), c.t_end));
    // A stream that cuts the steps short makes t_end / interval outputs (and steps) even when
    // that is more than the step count; a checkpoint is written at most once a step.
    double outputs = c.t_end / s.interval;
    if (!s.cuts_steps) outputs = std::min(outputs, steps);
    else if (c.max_steps > 0) outputs = std::min(outputs, static_cast<double>(c.max_steps));
    if (!(outputs <= kMaxOutputs))
      throw ctx.error(s.key, fmt::format("{} = {:.3g} s makes about {} outputs to time.end = {:.6g} s, more than "
                                         "the {:.0e} particula writes per stream; use a longer interval",
                                         s.key, s.interval, count(outputs), c.t_end, kMaxOutputs));
  }
}

}  // namespace case_detail
}  // namespace particula
