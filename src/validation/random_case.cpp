#include "particula/validation/random_case.hpp"

#include "particula/run/runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/error.hpp"
#include "particula/scene/scene.hpp"

namespace particula {

namespace {

/// Uniform draws on top of SplitMix64 (the platform-independent generator of the scene).
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(seed ^ 0x5EEDCA5Eull) {}
  double uniform(double a, double b) { return a + (b - a) * 0.5 * (rng_.symmetric() + 1); }
  double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
  int integer(int a, int b) { return a + static_cast<int>(rng_.next() % static_cast<std::uint64_t>(b - a + 1)); }
  bool chance(double p) { return uniform(0, 1) < p; }

 private:
  SplitMix64 rng_;
};

/// A drawn body, in the terms the case file uses, with the circle that holds it (and its
/// prescribed excursion) for the placement test.
struct DrawnBody {
  std::string shape, motion;
  double width = 0;          // smallest dimension (the particles-across check)
  double radius = 0;         // circle, half_disc
  double a = 0, b = 0;       // ellipse semi-axes
  double angle = 0;
  std::vector<Vec2> unit;    // polygon: vertices about the origin, scaled to `width`
  double bound = 0;          // radius of the circle about `center` that holds the body
  Vec2 center;
  double density = 0;        // free bodies
  Vec2 velocity;             // free: initial velocity
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

/// The domain and the forces of a draw.
struct Setting {
  bool channel = false;
  double d0 = 0, W = 0, H = 0;
  double nu = 0, c = 0, g = 0, force = 0, v_bottom = 0, v_top = 0, U = 0, t_end = 0;
};

/// Motion and density (the rotation rate of a prescribed body needs U: drawn at placement).
void draw_motion(Draw& d, DrawnBody& b, double d0, double rho0) {
  const double r = d.uniform(0, 1);
  if (r < 0.6) {
    b.motion = "free";
    b.density = d.chance(0.2) ? rho0 : d.uniform(500, 3000);
  } else if (r < 0.8) {
    b.motion = "fixed";
  } else {
    b.motion = "prescribed";
    b.amplitude = d0 * d.uniform(0.3, 1.0);
  }
}

/// Whether b fits at its centre: clear of the walls (non-periodic edges) and of the placed
/// bodies (periodic images along x in a channel) by `clear` plus the prescribed excursions.
bool fits(const DrawnBody& b, const std::vector<DrawnBody>& placed, const Setting& s, double clear) {
  const double r = b.bound + b.amplitude + clear;
  if (b.center.x < r || b.center.x > s.W - r || b.center.y < r || b.center.y > s.H - r) return false;
  for (const DrawnBody& o : placed) {
    double dx = std::fabs(b.center.x - o.center.x);
    if (s.channel) dx = std::min(dx, s.W - dx);
    if (std::hypot(dx, b.center.y - o.center.y) < r + o.bound + o.amplitude) return false;
  }
  return true;
}

Setting draw_setting(Draw& d, double smallest, double largest_drho, bool any_body) {
  Setting s;
  s.channel = d.chance(0.5);
  const double g = 9.81;
  s.g = !s.channel || d.chance(0.5) ? g : 0;
  // velocity scale: the settling scale of the heaviest (or lightest) free body, or the walls
  const double U_g = s.g > 0 && any_body ? std::sqrt(std::max(largest_drho, 0.05) * s.g * smallest) : 0;
  s.U = s.channel ? std::max(U_g, d.log_uniform(2e-3, 5e-2)) : std::max(U_g, 1e-3);
  const double re = d.log_uniform(0.5, 50);
  s.nu = s.U * smallest / re;
  // Mach number below 0.1 at 1.5 U, and small density changes from viscous pressure at low Re.
  s.c = std::max(15 * s.U, 10 * std::sqrt(s.nu * s.U / smallest));
  if (s.channel) {
    s.v_bottom = -d.uniform(0, 1) * s.U;
    s.v_top = d.uniform(0, 1) * s.U;
  }
  s.t_end = 20 * smallest / s.U;
  return s;
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

std::string walls_toml(const Setting& s) {
  const Vec2 p00{0, 0}, p10{s.W, 0}, p11{s.W, s.H}, p01{0, s.H};
  auto wall = [](const char* name, Vec2 from, Vec2 to, double v) {
    std::string t = fmt::format("\n[[wall]]\nname = \"{}\"\nfrom = {}\nto = {}\n", name, vec(from), vec(to));
    if (v != 0) t += fmt::format("velocity = [{:.9g}, 0.0]\n", v);
    return t;
  };
  if (s.channel) return wall("bottom", p00, p10, s.v_bottom) + wall("top", p11, p01, s.v_top);
  return wall("bottom", p00, p10, 0) + wall("right", p10, p11, 0) + wall("top", p11, p01, 0) + wall("left", p01, p00, 0);
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
  // about 6000 particles at most: a box of 40-90 d0 a side
  const double W = d0 * d.integer(40, 90), H = d0 * std::min(90, std::max(40, static_cast<int>(6000 / (W / d0))));
  double drho = 0;
  for (DrawnBody& b : bodies) {
    draw_motion(d, b, d0, rho0);
    if (b.motion == "free") drho = std::max(drho, std::fabs(b.density / rho0 - 1));
  }
  Setting s = draw_setting(d, smallest, drho, !bodies.empty());
  s.d0 = d0, s.W = W, s.H = H;
  if (s.channel && d.chance(0.7)) s.force = 8 * s.nu * s.U / (H * H) * d.uniform(0.2, 1);  // Poiseuille peak <= U
  std::vector<DrawnBody> placed;
  for (DrawnBody& b : bodies) {
    if (b.motion == "prescribed") b.omega = d.uniform(-1, 1) * 0.5 * s.U / b.bound;  // surface speed up to U/2
    if (b.motion == "free" && d.chance(0.3)) b.velocity = {d.uniform(-0.5, 0.5) * s.U, d.uniform(-0.5, 0.5) * s.U};
    for (int attempt = 0; attempt < 200; ++attempt) {
      b.center = {d.uniform(0, W), d.uniform(0, H)};
      if (fits(b, placed, s, 2 * d0)) {
        placed.push_back(b);
        break;
      }
    }
  }
  std::string t = fmt::format(
      "# Random case of seed {} (particula generate --seed {}): {} of {} drawn bodies placed, {}.\n"
      "# Generated for robustness tests: default numerics and contact model; d0 = {:.4g} m, {:.3g} particles\n"
      "# across the smallest body, velocity scale U = {:.3g} m/s, Re = U s / nu = {:.3g}.\n",
      seed, seed, placed.size(), bodies.size(),
      s.channel ? "periodic channel between sliding walls" : "closed box under gravity", d0, smallest / d0, s.U,
      s.U * smallest / s.nu);
  t += fmt::format("name = \"random_{}\"\n\n[domain]\nmin = [0.0, 0.0]\nmax = {}\nperiodic = [{}, false]\n", seed,
                   vec({W, H}), s.channel ? "true" : "false");
  t += fmt::format("\n[resolution]\nd0 = {:.9g}\n", d0);
  t += fmt::format("\n[fluid]\nrho0 = {:.1f}\nnu = {:.9g}\nc = {:.9g}\ngravity = [0.0, {:.9g}]\n", rho0, s.nu, s.c, s.g > 0 ? -s.g : 0.0);
  if (s.force > 0) t += fmt::format("body_force = [{:.9g}, 0.0]\n", s.force);
  t += fmt::format("\n[initial]\nseed = {}\n", seed % 1000000);
  t += fmt::format("\n[time]\nend = {:.9g}\n\n[output]\ninterval = {:.9g}\nsnapshot_interval = {:.9g}\n", s.t_end,
                   s.t_end / 100, s.t_end / 20);
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
      std::fprintf(stderr,
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
