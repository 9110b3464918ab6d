#include "particula/validation/random_case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/error.hpp"
#include "particula/run/runner.hpp"
#include "particula/scene/scene.hpp"

namespace particula {

namespace {

/// Uniform draws on top of SplitMix64 (the platform-independent generator of the scene).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed ^ 0x5EEDCA5Eull) {}
  double uniform(double a, double b) { return a + (b - a) * 0.5 * (rng_.symmetric() + 1); }
  double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
  int integer(int a, int b) {
    return a + static_cast<int>(rng_.next() % static_cast<std::uint64_t>(b - a + 1));
  }
  bool chance(double p) { return uniform(0, 1) < p; }

 private:
  SplitMix64 rng_;
};

/// A drawn body, in the terms the case file uses, with the circle that holds it (and its
/// prescribed excursion) for the placement test.
struct DrawnBody {
  std::string shape, motion;
  double width = 0;     // smallest dimension (the particles-across check)
  double radius = 0;    // circle, half_disc
  double a = 0, b = 0;  // ellipse semi-axes
  double angle = 0;
  std::vector<Vec2> unit;  // polygon: vertices about the origin, scaled to `width`
  double bound = 0;  // radius of the circle about `center` that holds the body (at every angle it turns to)
  Vec2 center;
  double density = 0;                           // free bodies
  Vec2 velocity;                                // free: initial velocity
  double amplitude = 0, omega = 0, period = 0;  // prescribed: excursion (m), rotation, schedule period
};

/// Smallest width of a convex polygon (largest vertex distance from an edge line, minimised).
double convex_width(const std::vector<Vec2>& v) {
  double w = 1e300;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 e = v[(i + 1) % v.size()] - v[i];
    double far = 0;
    for (const Vec2& p : v) far = std::max(far, std::fabs(cross(e, p - v[i])) / norm(e));
    w = std::min(w, far);
  }
  return w;
}

/// A convex polygon: 3-6 vertices on a circle at jittered angles (counter-clockwise), scaled so
/// that its smallest width is `width`.
void draw_polygon(Draw& d, DrawnBody& b) {
  const int n = d.integer(3, 6);
  const double phase = d.uniform(0, 2 * M_PI), step = 2 * M_PI / n;
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    const double t = phase + step * (i + d.uniform(-0.2, 0.2));
    v.push_back({std::cos(t), std::sin(t)});
  }
  const double scale = b.width / convex_width(v);
  for (Vec2& p : v) p = scale * p;
  b.unit = v;
  b.bound = scale;
}

void draw_shape(Draw& d, DrawnBody& b) {
  const int kind = d.integer(0, 3);
  b.angle = d.uniform(-M_PI, M_PI);
  if (kind == 0) {
    b.shape = "circle", b.radius = 0.5 * b.width, b.bound = b.radius, b.angle = 0;
  } else if (kind == 1) {
    b.shape = "ellipse", b.b = 0.5 * b.width, b.a = b.b * d.uniform(1.2, 2.5), b.bound = b.a;
  } else if (kind == 2) {
    b.shape = "polygon", b.angle = 0;
    draw_polygon(d, b);
  } else {
    b.shape = "half_disc", b.radius = b.width, b.bound = b.radius;  // its width is its radius
  }
}

/// The containers a case is drawn in.
enum class Container { Box, Channel, LShape, TShape, Hopper, Ngon, UShape, OpenChannel };
constexpr int kContainers = 8;

const char* container_name(Container k) {
  switch (k) {
    case Container::Box:
      return "closed box";
    case Container::Channel:
      return "periodic channel between sliding walls";
    case Container::LShape:
      return "L-shaped container";
    case Container::TShape:
      return "T-shaped container";
    case Container::Hopper:
      return "hopper";
    case Container::Ngon:
      return "polygon container";
    case Container::UShape:
      return "container with an arc bottom";
    case Container::OpenChannel:
      return "channel from an inlet to an outlet";
  }
  return "";
}

/// The domain, the container and the forces of a draw.
struct Setting {
  Container kind = Container::Box;
  double d0 = 0, W = 0, H = 0;
  std::vector<Vec2> outline;  // closed containers: the fluid region, counter-clockwise
  double arc_radius = 0;      // UShape: the bottom's radius (centre (W/2, R))
  double nu = 0, c = 0, g = 0, force = 0, v_bottom = 0, v_top = 0, U = 0, inflow = 0, t_end = 0;
  bool channel() const { return kind == Container::Channel; }
  bool open() const { return kind == Container::OpenChannel; }
};

/// Motion and density (the rotation rate of a prescribed body needs U: drawn at placement).
/// Free bodies from 0.1 to 3 times the fluid's density (log-uniform), one in five neutrally buoyant.
void draw_motion(Draw& d, DrawnBody& b, double d0, double rho0) {
  const double r = d.uniform(0, 1);
  if (r < 0.6) {
    b.motion = "free";
    b.density = d.chance(0.2) ? rho0 : rho0 * d.log_uniform(0.1, 3);
  } else if (r < 0.8) {
    b.motion = "fixed";
  } else {
    b.motion = "prescribed";
    b.amplitude = d0 * d.uniform(0.3, 1.0);
    // it turns about its centroid, xc from the disc's centre: the circle about the disc's centre
    // that holds it at every angle reaches xc plus the centroid's farthest point (a flat side's end)
    if (b.shape == "half_disc") {
      const double xc = norm(Shape::half_disc(b.radius).centroid_offset());
      b.bound = xc + std::hypot(b.radius, xc);
    }
  }
}

/// Distance from p to the segment ab.
double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
  return norm(p - (a + t * e));
}

/// Distance from p to the container's walls, negative outside the fluid region (closed
/// containers: the outline; channels: the two walls, and the open lines of an open channel).
double wall_clearance(Vec2 p, const Setting& s) {
  if (s.outline.empty()) {
    double c = std::min(p.y, s.H - p.y);
    if (s.open()) c = std::min({c, p.x, s.W - p.x});
    return c;
  }
  bool inside = false;
  double dist = 1e300;
  const std::size_t n = s.outline.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = s.outline[j], b = s.outline[i];
    if ((b.y > p.y) != (a.y > p.y) && p.x < (a.x - b.x) * (p.y - b.y) / (a.y - b.y) + b.x) inside = !inside;
    dist = std::min(dist, segment_distance(p, a, b));
  }
  return inside ? dist : -dist;
}

/// Whether b fits at its centre: `clear` inside the container's walls (plus the prescribed
/// excursion) and clear of the placed bodies (periodic images along x in a channel); an open
/// channel also keeps bodies clear of its inlet and outlet buffers.
bool fits(const DrawnBody& b, const std::vector<DrawnBody>& placed, const Setting& s, double clear) {
  const double r = b.bound + b.amplitude;
  if (wall_clearance(b.center, s) < r + clear) return false;
  if (s.open() && (b.center.x < r + std::max(0.2 * s.W, 14 * s.d0) ||
                   b.center.x > std::min(0.7 * s.W, s.W - 14 * s.d0) - r))
    return false;
  for (const DrawnBody& o : placed) {
    double dx = std::fabs(b.center.x - o.center.x);
    if (s.channel()) dx = std::min(dx, s.W - dx);
    if (std::hypot(dx, b.center.y - o.center.y) < r + 2 * s.d0 + o.bound + o.amplitude) return false;
  }
  return true;
}

/// The container's outline in the box [0, W] x [0, H] (counter-clockwise; empty for channels).
std::vector<Vec2> draw_outline(Draw& d, Setting& s) {
  const double W = s.W, H = s.H;
  switch (s.kind) {
    case Container::Box:
      return {{0, 0}, {W, 0}, {W, H}, {0, H}};
    case Container::LShape: {
      const double a = d.uniform(0.4, 0.6) * H, b = d.uniform(0.4, 0.6) * W;
      std::vector<Vec2> v{{0, 0}, {W, 0}, {W, a}, {b, a}, {b, H}, {0, H}};
      if (d.chance(0.5)) {  // mirrored: the upper arm on the right
        for (Vec2& p : v) p.x = W - p.x;
        std::reverse(v.begin(), v.end());
      }
      return v;
    }
    case Container::TShape: {
      const double a = d.uniform(0.4, 0.6) * H, half = d.uniform(0.2, 0.3) * W, xc = d.uniform(0.4, 0.6) * W;
      return {{xc - half, 0}, {xc + half, 0}, {xc + half, a}, {W, a}, {W, H}, {0, H}, {0, a}, {xc - half, a}};
    }
    case Container::Hopper: {
      const double half = d.uniform(0.12, 0.25) * W, slope = std::tan(d.uniform(0.5, 1.1));
      const double x0 = 0.5 * W - half, y1 = std::min(x0 * slope, 0.6 * H);
      return {{x0, 0}, {W - x0, 0}, {W, y1}, {W, H}, {0, H}, {0, y1}};
    }
    case Container::Ngon: {
      const int n = d.integer(5, 8);
      const double phase = d.uniform(0, 2 * M_PI);
      std::vector<Vec2> v;
      for (int i = 0; i < n; ++i) {
        const double t = phase + 2 * M_PI * (i + d.uniform(-0.15, 0.15)) / n;
        v.push_back({0.5 * W * (1 + std::cos(t)), 0.5 * H * (1 + std::sin(t))});
      }
      return v;
    }
    case Container::UShape: {
      s.arc_radius = 0.5 * W;
      const double R = s.arc_radius;
      std::vector<Vec2> v;
      for (int k = 0; k <= 32; ++k) {  // the arc, for the placement test (its chords lie inside)
        const double t = M_PI + M_PI * k / 32;
        v.push_back({0.5 * W + R * std::cos(t), R + R * std::sin(t)});
      }
      v.push_back({W, H});
      v.push_back({0, H});
      return v;
    }
    case Container::Channel:
    case Container::OpenChannel:
      return {};
  }
  return {};
}

Setting draw_setting(Draw& d, double smallest, double largest_drho, bool any_body) {
  Setting s;
  s.kind = static_cast<Container>(d.integer(0, kContainers - 1));
  const double g = 9.81;
  s.g = !s.channel() && !s.open() ? g : (d.chance(0.5) ? g : 0);
  // velocity scale: the settling scale of the heaviest (or lightest) free body, or the walls or
  // the inflow
  const double U_g = s.g > 0 && any_body ? std::sqrt(std::max(largest_drho, 0.05) * s.g * smallest) : 0;
  const bool driven = s.channel() || s.open();
  s.U = driven ? std::max(U_g, d.log_uniform(2e-3, 5e-2)) : std::max(U_g, 1e-3);
  // viscous to inertial: Re = U s / nu from 0.1 to 100
  const double re = d.log_uniform(0.1, 100);
  s.nu = s.U * smallest / re;
  // Mach number below 0.1 at 1.5 U (at 2.5 U in a channel from an inlet, whose flow speeds up
  // past the bodies that block part of it: a fixed body there sped it to 3 U), and small density
  // changes from viscous pressure at low Re.
  s.c = std::max((s.open() ? 25 : 15) * s.U, 10 * std::sqrt(s.nu * s.U / smallest));
  if (s.channel()) {
    s.v_bottom = -d.uniform(0, 1) * s.U;
    s.v_top = d.uniform(0, 1) * s.U;
  }
  if (s.open()) s.inflow = s.U * d.uniform(0.5, 1);
  return s;
}

/// The end time: 20 passages of the smallest body at U, or 2000 steps of the case's own step
/// (cfl d0 / c, cfl d0^2 / nu at cfl 0.25), whichever is shorter (a viscous case at Re 0.1 would
/// take 1e5 steps to move 20 widths).
double end_time(const Setting& s, double smallest) {
  const double dt = 0.25 * std::min(s.d0 / s.c, s.d0 * s.d0 / s.nu);
  return std::min(20 * smallest / s.U, 2000 * dt);
}

std::string vec(Vec2 v) { return fmt::format("[{:.9g}, {:.9g}]", v.x, v.y); }

std::string body_toml(const DrawnBody& b, std::size_t k, const Setting& s) {
  std::string t = fmt::format("\n[[body]]\nname = \"b{}\"\nshape = \"{}\"\n", k, b.shape);
  if (b.shape == "polygon") {
    t += "vertices = [";
    for (std::size_t i = 0; i < b.unit.size(); ++i) t += (i ? ", " : "") + vec(b.center + b.unit[i]);
    t += "]\n";
  } else {
    t += fmt::format("center = {}\n", vec(b.center));
  }
  if (b.shape == "circle" || b.shape == "half_disc") t += fmt::format("radius = {:.9g}\n", b.radius);
  if (b.shape == "ellipse") t += fmt::format("semi_axes = [{:.9g}, {:.9g}]\n", b.a, b.b);
  if (b.angle != 0) t += fmt::format("angle = {:.9g}\n", b.angle);
  t += fmt::format("motion = \"{}\"\n", b.motion);
  if (b.motion == "free") {
    t += fmt::format("density = {:.6g}\n", b.density);
    if (b.velocity.x != 0 || b.velocity.y != 0) t += fmt::format("velocity = {}\n", vec(b.velocity));
  }
  if (b.motion == "prescribed") {
    // out along a random direction and back (net displacement 0), turning at a constant rate
    const double T = s.t_end / 4, v = 2 * b.amplitude / T;
    const Vec2 dir{std::cos(b.angle + 1.0), std::sin(b.angle + 1.0)};
    const double knots[5][2] = {{0, 0}, {T / 4, v}, {T / 2, 0}, {3 * T / 4, -v}, {T, 0}};
    t += "schedule = [\n";
    for (const auto& [tk, vk] : knots)
      t += fmt::format("  [{:.9g}, {:.9g}, {:.9g}, {:.9g}],\n", tk, vk * dir.x, vk * dir.y, b.omega);
    t += "]\n";
  }
  return t;
}

std::string wall_toml(const std::string& name, Vec2 from, Vec2 to, double v) {
  std::string t = fmt::format("\n[[wall]]\nname = \"{}\"\nfrom = {}\nto = {}\n", name, vec(from), vec(to));
  if (v != 0) t += fmt::format("velocity = [{:.9g}, 0.0]\n", v);
  return t;
}

std::string walls_toml(const Setting& s) {
  const Vec2 p00{0, 0}, p10{s.W, 0}, p11{s.W, s.H}, p01{0, s.H};
  if (s.channel()) return wall_toml("bottom", p00, p10, s.v_bottom) + wall_toml("top", p11, p01, s.v_top);
  if (s.open())
    return wall_toml("bottom", p00, p10, 0) + wall_toml("top", p11, p01, 0) +
           fmt::format(
               "\n[[inlet]]\nname = \"in\"\nfrom = {}\nto = {}\nprofile = \"parabolic\"\nvelocity = {:.9g}\n"
               "ramp_time = {:.9g}\n",
               vec(p01), vec(p00), s.inflow, 0.1 * s.t_end) +
           fmt::format("\n[[outlet]]\nname = \"out\"\nfrom = {}\nto = {}\n", vec(p10), vec(p11));
  if (s.kind == Container::UShape) {
    const double R = s.arc_radius;
    return fmt::format(
               "\n[[wall]]\nname = \"bottom\"\nshape = \"arc\"\ncenter = {}\nradius = {:.9g}\n"
               "start_angle = {:.17g}\nend_angle = {:.17g}\n",
               vec({0.5 * s.W, R}), R, M_PI, 2 * M_PI) +
           wall_toml("right", {s.W, R}, p11, 0) + wall_toml("top", p11, p01, 0) +
           wall_toml("left", p01, {0, R}, 0);
  }
  std::string t;
  for (std::size_t k = 0; k < s.outline.size(); ++k)
    t += wall_toml(fmt::format("side{}", k), s.outline[k], s.outline[(k + 1) % s.outline.size()], 0);
  return t;
}

/// Where a body goes: fixed and prescribed bodies half of the time close to a wall (1-3 d0
/// clear of it), everything else anywhere at least 2 d0 clear.
bool place(Draw& d, DrawnBody& b, std::vector<DrawnBody>& placed, const Setting& s) {
  const bool near_wall = b.motion != "free" && d.chance(0.5);
  for (int attempt = 0; attempt < 400; ++attempt) {
    b.center = {d.uniform(0, s.W), d.uniform(0, s.H)};
    const double clear = near_wall ? s.d0 * d.uniform(1, 3) : 2 * s.d0;
    if (!fits(b, placed, s, clear)) continue;
    if (near_wall && attempt < 300 && wall_clearance(b.center, s) > b.bound + b.amplitude + 3 * s.d0)
      continue;
    placed.push_back(b);
    return true;
  }
  return false;
}

}  // namespace

std::string random_case_toml(std::uint64_t seed) {
  Draw d(seed);
  const double rho0 = 1000;
  const int n_bodies = d.integer(0, 12);
  const double d0 = d.log_uniform(5e-5, 2e-4), smallest = d0 * d.uniform(10.05, 20);
  // body sizes and densities first: they set the velocity scale
  std::vector<DrawnBody> bodies(static_cast<std::size_t>(n_bodies));
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    bodies[k].width = k == 0 ? smallest : smallest * d.uniform(1, 1.6);
    draw_shape(d, bodies[k]);
  }
  // about 5000 particles at most: a box of 40-80 d0 a side
  const double W = d0 * d.integer(40, 80),
               H = d0 * std::min(80, std::max(40, static_cast<int>(5000 / (W / d0))));
  double drho = 0;
  for (DrawnBody& b : bodies) {
    draw_motion(d, b, d0, rho0);
    if (b.motion == "free") drho = std::max(drho, std::fabs(b.density / rho0 - 1));
  }
  Setting s = draw_setting(d, smallest, drho, !bodies.empty());
  s.d0 = d0, s.W = W, s.H = H;
  s.outline = draw_outline(d, s);
  s.t_end = end_time(s, smallest);
  if (s.channel() && d.chance(0.7))
    s.force = 8 * s.nu * s.U / (H * H) * d.uniform(0.2, 1);  // Poiseuille peak <= U
  std::vector<DrawnBody> placed;
  for (DrawnBody& b : bodies) {
    if (b.motion == "prescribed")
      b.omega = d.uniform(-1, 1) * 0.5 * s.U / b.bound;  // surface speed up to U/2
    if (b.motion == "free" && d.chance(0.3))
      b.velocity = {d.uniform(-0.5, 0.5) * s.U, d.uniform(-0.5, 0.5) * s.U};
    place(d, b, placed, s);
  }
  std::string t = fmt::format(
      "# Random case of seed {} (particula generate --seed {}): {} of {} drawn bodies placed, {}.\n"
      "# Generated for robustness tests: default numerics and contact model; d0 = {:.4g} m, {:.3g} "
      "particles\n"
      "# across the smallest body, velocity scale U = {:.3g} m/s, Re = U s / nu = {:.3g}, c d0 / nu = "
      "{:.3g}.\n",
      seed, seed, placed.size(), bodies.size(), container_name(s.kind), d0, smallest / d0, s.U,
      s.U * smallest / s.nu, s.c * d0 / s.nu);
  t += fmt::format("name = \"random_{}\"\n\n[domain]\nmin = [0.0, 0.0]\nmax = {}\nperiodic = [{}, false]\n",
                   seed, vec({W, H}), s.channel() ? "true" : "false");
  t += fmt::format("\n[resolution]\nd0 = {:.9g}\n", d0);
  t += fmt::format("\n[fluid]\nrho0 = {:.1f}\nnu = {:.9g}\nc = {:.9g}\ngravity = [0.0, {:.9g}]\n", rho0, s.nu,
                   s.c, s.g > 0 ? -s.g : 0.0);
  if (s.force > 0) t += fmt::format("body_force = [{:.9g}, 0.0]\n", s.force);
  t += fmt::format("\n[initial]\nseed = {}\n", seed % 1000000);
  t += fmt::format("\n[time]\nend = {:.9g}\n\n[output]\ninterval = {:.9g}\nsnapshot_interval = {:.9g}\n",
                   s.t_end, s.t_end / 100, s.t_end / 20);
  t += walls_toml(s);
  for (std::size_t k = 0; k < placed.size(); ++k) t += body_toml(placed[k], k, s);
  return t;
}

int generate_command(std::uint64_t seed, const std::filesystem::path& out) {
  const std::string text = random_case_toml(seed);
  if (out.empty()) {
    std::fputs(text.c_str(), stdout);
    return 0;
  }
  // An existing file is replaced only when particula generated it (its first line says so).
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(out, ec))) {
    std::string first;
    if (std::filesystem::is_regular_file(std::filesystem::symlink_status(out, ec))) {
      try {
        first = io::read_file(out).substr(0, 64);
      } catch (const io::IoError&) {
      }
    }
    if (first.rfind("# Random case of seed ", 0) != 0) {
      std::fprintf(
          stderr,
          "error: --out '%s' already exists and is not a case particula generated: it is not replaced "
          "(choose another name)\n",
          out.string().c_str());
      return 2;
    }
  }
  try {
    io::write_file_atomic(out, text);
  } catch (const io::WriteError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return kExitIoFailure;
  }
  std::fprintf(stderr, "wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace particula
