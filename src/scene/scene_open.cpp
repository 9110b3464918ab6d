// Open boundaries in the scene (docs/method.md, "Open boundaries"): the zones' geometry,
// the buffer particles behind each inlet and outlet, and how far a wall that ends on an open
// boundary continues through the buffer.
#include <cmath>

#include "particula/fluid/fluid.hpp"
#include "scene_open.hpp"

namespace particula::scene_detail {

namespace {

bool same_point(Vec2 a, Vec2 b, real tol) { return norm(a - b) <= tol; }

/// The lattice spacing along a direction parallel to x (dx) or to y (dy).
real spacing_along(Vec2 dir, real dx, real dy) { return std::fabs(dir.x) > std::fabs(dir.y) ? dx : dy; }

}  // namespace

std::vector<OpenZone> open_zones(const Case& c, real dx, real dy) {
  std::vector<OpenZone> zones;
  for (const OpenSpec& o : c.open_boundaries()) {
    OpenZone z;
    z.inlet = o.kind == OpenKind::Inlet;
    z.from = o.from;
    z.t = o.tangent();
    z.n = o.inward_normal();
    z.width = o.width();
    z.spacing = spacing_along(z.n, dx, dy);
    z.depth = c.open_layers(o) * z.spacing;
    z.mass = c.rho0 * dx * dy;
    z.pressure = c.p0 + o.pressure;
    zones.push_back(z);
  }
  return zones;
}

std::vector<BufferPoint> buffer_points(const Case& c, const std::vector<OpenZone>& zones, real dx, real dy) {
  std::vector<BufferPoint> out;
  const std::vector<OpenSpec> specs = c.open_boundaries();
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const OpenZone& z = zones[k];
    // The columns continue the fluid lattice (cell centres lo + (i + 1/2) spacing) across the
    // line, so the buffer and the fluid form one regular lattice at t = 0.
    const bool along_x = std::fabs(z.t.x) > std::fabs(z.t.y);
    const real lo = along_x ? c.domain_min.x : c.domain_min.y;
    const real step = along_x ? dx : dy;
    const real a = along_x ? z.from.x : z.from.y, b = along_x ? (z.from + z.width * z.t).x : (z.from + z.width * z.t).y;
    const real first = std::min(a, b), last = std::max(a, b);
    const int i0 = static_cast<int>(std::ceil((first - lo) / step - 0.5 - 1e-9));
    const int i1 = static_cast<int>(std::floor((last - lo) / step - 0.5 + 1e-9));
    const int layers = c.open_layers(specs[k]);
    for (int i = i0; i <= i1; ++i) {
      const real q = lo + (i + 0.5) * step;
      const real s = along_x ? (q - z.from.x) / z.t.x : (q - z.from.y) / z.t.y;
      if (s <= 0 || s >= z.width) continue;
      for (int l = 0; l < layers; ++l) out.push_back({z.from + s * z.t - ((l + 0.5) * z.spacing) * z.n, k});
    }
  }
  return out;
}

int wall_extension_points(const Case& c, const WallSpec& w, bool at_end, real ds) {
  if (w.shape != WallShape::Segment || !(ds > 0)) return 0;
  const Vec2 p = at_end ? w.to : w.from;
  const real tol = 1e-6 * c.d0;
  const Vec2 dir = (w.to - w.from) / norm(w.to - w.from) * (at_end ? 1.0 : -1.0);
  for (const OpenSpec& o : c.open_boundaries()) {
    if (!same_point(p, o.from, tol) && !same_point(p, o.to, tol)) continue;
    // The wall continues out of the domain only when it leaves through the open line.
    if (dot(dir, o.inward_normal()) >= -1e-9) continue;
    const real depth = c.open_layers(o) * c.d0;  // as deep as the buffer
    return static_cast<int>(std::ceil(depth / ds));
  }
  return 0;
}

void append_buffers(const Case& c, Scene& sc) {
  const std::vector<OpenZone>& zones = sc.params.open;
  Particles& P = sc.particles;
  P.next_id = static_cast<std::int64_t>(P.size());
  if (zones.empty()) return;
  const std::vector<BufferPoint> pts = buffer_points(c, zones, sc.dx, sc.dy);
  const std::size_t n0 = P.size();
  P.resize(n0 + pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const std::size_t i = n0 + k;
    const OpenZone& z = zones[pts[k].zone];
    P.x[i] = pts[k].x;
    P.kind[i] = z.inlet ? Kind::Inlet : Kind::Outlet;
    P.group[i] = -1;
    // The fields are set by the solver before the first step; a buffer starts at rest at the
    // fluid's background pressure.
    P.v[i] = Vec2{};
    P.p[i] = c.p0;
    P.rho[i] = density_from_pressure(c.p0, c.rho0, c.c, c.p0);
    P.m[i] = z.mass;
    P.id[i] = static_cast<std::int64_t>(i);
  }
  P.next_id = static_cast<std::int64_t>(P.size());
}

}  // namespace particula::scene_detail
