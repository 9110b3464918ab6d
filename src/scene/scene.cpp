#include "particula/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "particula/fluid/fluid.hpp"
#include "particula/neighbors/body_cells.hpp"
#include "scene_bodies.hpp"
#include "scene_open.hpp"
#include "scene_walls.hpp"

namespace particula {

using scene_detail::corner_volume_factor;
using scene_detail::SurfacePoint;

Shape body_shape(const BodySpec& b);
Vec2 body_position(const BodySpec& b, const Shape& s);

namespace {

/// The stretches of the walls that fixed body bp (at pos, turned by angle) covers: where the
/// wall runs inside the body or along its surface (a flat side standing on it), found d0/16
/// apart and refined by bisection; and, when part of the body lies beyond the walls or the
/// domain's edge, the area and centroid of its part in the fluid region (midpoint rule on a
/// d0/16 grid).
void find_covers(BodyParams& bp, Vec2 pos, real angle, const std::vector<WallPiece>& walls, const Domain& dom,
                 real d0) {
  const real cs = std::cos(angle), sn = std::sin(angle), eps = 1e-6 * d0;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const WallPiece& w = walls[k];
    if (w.nearest(pos).distance > bp.shape.bounding_radius() + eps) continue;
    const auto covered = [&](real s) {
      return bp.shape.signed_distance(rotate(w.point_at(s) - pos, cs, -sn)) <= eps;
    };
    for (const auto& [s0, s1] : scene_detail::wall_stretches(w, covered, d0))
      bp.covers.push_back({k, s0, s1});
  }
  bp.area_in = bp.shape.area();
  bp.centroid_in = pos;
  const auto beyond = [&](Vec2 x) { return scene_detail::beyond_walls(x, walls, dom); };
  bool cut = false;
  for (const SurfaceSample& s : bp.samples) cut = cut || beyond(pos + rotate(s.x, cs, sn));
  if (!cut) return;
  // The grid covers the body's box (world frame) clipped to the domain along bounded axes: a
  // body reaching far past an edge (a mutated case put a vertex 1 m below a 2 cm domain) costs
  // no more than the part inside, instead of (2 R / step)^2 points (2.6e10 there: `info` hung).
  const real step = d0 / 16;
  Vec2 lo = pos, hi = pos;
  for (const SurfaceSample& s : bp.samples) {
    const Vec2 x = pos + rotate(s.x, cs, sn);
    lo = {std::min(lo.x, x.x), std::min(lo.y, x.y)};
    hi = {std::max(hi.x, x.x), std::max(hi.y, x.y)};
  }
  lo -= Vec2{d0, d0};  // the samples are d0 apart: a curved side may bulge between two of them
  hi += Vec2{d0, d0};
  if (!dom.periodic_x) lo.x = std::max(lo.x, dom.lo.x), hi.x = std::min(hi.x, dom.hi.x);
  if (!dom.periodic_y) lo.y = std::max(lo.y, dom.lo.y), hi.y = std::min(hi.y, dom.hi.y);
  const long nx = std::max(0L, static_cast<long>(std::ceil((hi.x - lo.x) / step))),
             ny = std::max(0L, static_cast<long>(std::ceil((hi.y - lo.y) / step)));
  real area = 0;
  Vec2 moment;
  for (long iy = 0; iy < ny; ++iy)
    for (long ix = 0; ix < nx; ++ix) {
      const Vec2 x{lo.x + (ix + 0.5) * step, lo.y + (iy + 0.5) * step};
      if (bp.shape.signed_distance(rotate(x - pos, cs, -sn)) >= 0) continue;
      if (beyond(x)) continue;
      area += step * step;
      moment += (step * step) * x;
    }
  bp.area_in = area;
  bp.centroid_in = area > 0 ? moment / area : pos;
}

}  // namespace

PhysicsParams physics_params(const Case& c) {
  PhysicsParams p;
  p.d0 = c.d0;
  p.h = c.h();
  p.rho0 = c.rho0;
  p.nu = c.nu;
  p.c = c.c;
  p.p0 = c.p0;
  p.gravity = c.gravity;
  p.gravity_in_fluid = c.gravity_in_fluid;
  p.body_force = c.body_force;
  p.cfl = c.cfl;
  p.dt_max = c.dt_max;
  p.fatehi_manzari = c.laplacian == LaplacianScheme::FatehiManzari;
  p.zeroth_order_gradient = c.gradient == GradientScheme::Consistent;
  p.single_layer = c.boundary == BoundaryModel::SingleLayer;
  p.kernel_normals = c.normals == NormalModel::Kernel;
  p.momentum_force = c.force == ForceModel::Momentum;
  p.rhie_chow_factor = c.rhie_chow_factor;
  p.shifting_beta = c.shifting_beta;
  p.odd_even_damping = c.odd_even_damping;
  p.film_gap = c.film_gap;
  p.load_band_motion = c.load_band_motion * c.d0;
  p.surface_guard = c.surface_guard;
  p.wall_pressure_sweeps = c.wall_pressure_sweeps;
  p.rho_min_ratio = c.rho_min_ratio;
  p.rho_max_ratio = c.rho_max_ratio;
  p.reorder_interval = kReorderInterval;
  p.collision_model = c.collision_model;
  p.collision_stiffness = c.collision_stiffness;
  p.collision_range = c.collision_range;
  p.collision_restitution = c.collision_restitution;
  p.collision_friction = c.collision_friction;
  p.collision_max_overlap = c.collision_max_overlap;
  p.collision_lubrication = c.collision_lubrication;
  p.collision_lubrication_range = c.collision_lubrication_range;
  for (const auto& w : c.walls) p.walls.push_back(w.piece());
  // the open boundaries on the fluid lattice (spacing as build_scene's)
  const Vec2 L = c.domain_max - c.domain_min;
  const real dx = L.x / std::max(1, static_cast<int>(std::lround(L.x / c.d0)));
  const real dy = L.y / std::max(1, static_cast<int>(std::lround(L.y / c.d0)));
  p.open = scene_detail::open_zones(c, dx, dy);
  for (const OpenSpec& o : c.open_boundaries()) {
    const Vec2 in = c.open_screen_offset(o) * o.inward_normal();
    p.open_screens.push_back(WallPiece::segment(o.from + in, o.to + in));
  }
  p.open_specs = c.open_boundaries();
  const Domain dom{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  for (const auto& b : c.bodies) {
    BodyParams bp{b.name, body_shape(b), {}, b.motion, b.velocity, b.omega, b.schedule, {}, 0, {}};
    bp.samples = bp.shape.sample_surface(c.d0);
    bp.area_in = bp.shape.area();
    bp.centroid_in = body_position(b, bp.shape);
    if (b.motion == BodyMotion::Fixed)
      find_covers(bp, body_position(b, bp.shape), b.angle, p.walls, dom, c.d0);
    p.bodies.push_back(std::move(bp));
  }
  return p;
}

Shape body_shape(const BodySpec& b) {
  switch (b.shape) {
    case BodyShape::Circle:
      return Shape::circle(b.radius);
    case BodyShape::Ellipse:
      return Shape::ellipse(b.semi_axes.x, b.semi_axes.y);
    case BodyShape::Polygon:
      return Shape::polygon(b.vertices, b.holes);
    case BodyShape::HalfDisc:
      return Shape::half_disc(b.radius);
  }
  return Shape::circle(b.radius);
}

Vec2 body_position(const BodySpec& b, const Shape& s) {
  switch (b.shape) {
    case BodyShape::Polygon:
      return s.centroid_offset();
    case BodyShape::HalfDisc:
      return b.center + rotate(s.centroid_offset(), std::cos(b.angle), std::sin(b.angle));
    default:
      return b.center;
  }
}

namespace {
/// Signed distance from x to the nearest body (world frame) where it matters to the fill: the
/// bodies are binned into a uniform grid of cells at least (largest bounding radius + reach)
/// wide, and a query takes the bodies of the 3 x 3 cells round x. Every body whose surface
/// comes within reach of x is among them, so wherever the distance is below reach it is exactly
/// the minimum over all bodies; elsewhere it is some value >= reach (+inf without a body near).
/// The fill asks it at every lattice point and at 256 sample points of each cell beside a
/// surface: asking every body each time made a case with 1000 bodies take over a minute to set up.
class BodyDistance {
 public:
  BodyDistance(const PhysicsParams& prm, const std::vector<Vec2>& pos, const std::vector<real>& angle,
               const Domain& dom, real reach)
      : prm_(prm), pos_(pos), dom_(dom) {
    real bound = 0;
    std::vector<BodyCells::Item> items;
    for (std::size_t k = 0; k < pos.size(); ++k) {
      bound = std::max(bound, prm.bodies[k].shape.bounding_radius());
      turn_.push_back({std::cos(angle[k]), std::sin(angle[k])});
      items.push_back({static_cast<std::uint32_t>(k), pos[k]});
    }
    cells_.build(dom, bound + reach, items);
  }

  real operator()(Vec2 x) const {
    real d = std::numeric_limits<real>::infinity();
    if (cells_.empty()) return d;
    cells_.visit(x, [&](std::uint32_t k) {
      const Vec2 rel = dom_.separation(x, pos_[k]);
      if (norm(rel) > prm_.bodies[k].shape.bounding_radius() + d) return true;
      const Vec2 local = rotate(rel, turn_[k].x, -turn_[k].y);
      d = std::min(d, prm_.bodies[k].shape.signed_distance(local));
      return true;
    });
    return d;
  }

 private:
  const PhysicsParams& prm_;
  const std::vector<Vec2>& pos_;
  const Domain& dom_;
  std::vector<Vec2> turn_;  // cos, sin of each body's angle
  BodyCells cells_;
};

/// A lattice point removed within d0/2 of a body whose cell still holds fluid.
struct BandCell {
  int ix = 0, iy = 0;
  real fraction = 0;  // of the cell outside every body
};

/// Fraction of the lattice cell of size dx x dy centred at x that lies outside every body,
/// from the signed distance `gap` (negative inside a body): 1 or 0 for cells clear of every
/// surface, else the fraction of 16 x 16 sample points outside (error below 1 % of a cell).
template <class Gap>
real cell_fluid_fraction(Vec2 x, real dx, real dy, const Gap& gap) {
  const real reach = 0.5 * std::sqrt(dx * dx + dy * dy);
  const real g = gap(x);
  if (g >= reach) return 1;
  if (g <= -reach) return 0;
  constexpr int n = 16;
  int outside = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const Vec2 s{x.x + ((a + 0.5) / n - 0.5) * dx, x.y + ((b + 0.5) / n - 0.5) * dy};
      if (gap(s) > 0) ++outside;
    }
  return static_cast<real>(outside) / (n * n);
}

/// The kept lattice points nearest to lattice point (ix, iy) within two cells (all of those at
/// the smallest distance; across periodic sides); empty when there is none.
std::vector<std::int64_t> nearest_kept(const std::vector<std::int64_t>& kept, int nx, int ny,
                                       const Domain& dom, int ix, int iy) {
  std::vector<std::int64_t> best;
  int best_d2 = 1 << 30;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      int jx = ix + dx, jy = iy + dy;
      if (dom.periodic_x) jx = (jx + nx) % nx;
      if (dom.periodic_y) jy = (jy + ny) % ny;
      if (jx < 0 || jx >= nx || jy < 0 || jy >= ny) continue;
      const std::int64_t k = kept[static_cast<std::size_t>(jy) * nx + jx];
      const int d2 = dx * dx + dy * dy;
      if (k < 0 || d2 > best_d2) continue;
      if (d2 < best_d2) best.clear();
      best_d2 = d2;
      best.push_back(k);
    }
  return best;
}

/// Whether x lies within d0/2 of a body (the lattice points removed there).
bool near_body(const BodyDistance& body_distance, Vec2 x, real d0) {
  return body_distance(x) < 0.5 * d0 * (1 - 1e-9);
}

/// The fluid particles of the scene before their fields are set.
struct FluidFill {
  std::vector<Vec2> x;
  std::vector<real> area;  // fluid area each fluid particle stands for (its mass / rho)
};

/// The fluid lattice at cell centres, its spacing (sc.dx, sc.dy) adjusted so the box holds a whole
/// number of cells, perturbed by the case's seed; with the momentum loads the areas fill the
/// region outside the bodies and inside the walls exactly.
FluidFill fill_fluid(const Case& c, Scene& sc, const BodyDistance& body_distance) {
  const Domain& dom = sc.domain;
  const real d0 = c.d0;
  const Vec2 L = dom.size();
  const int nx = std::max(1, static_cast<int>(std::lround(L.x / d0)));
  const int ny = std::max(1, static_cast<int>(std::lround(L.y / d0)));
  sc.dx = L.x / nx;
  sc.dy = L.y / ny;
  SplitMix64 rng(c.seed);
  FluidFill fill;
  std::vector<Vec2>& fx = fill.x;
  std::vector<real>& farea = fill.area;
  std::vector<std::int64_t> kept(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), -1);
  std::vector<BandCell> band;  // lattice points removed near a body whose cell holds fluid
  const bool exact_fill = c.force == ForceModel::Momentum && (!c.bodies.empty() || !c.walls.empty());
  // Signed distance to the solids (negative inside a body or outside the region the walls enclose).
  const real diagonal = std::sqrt(sc.dx * sc.dx + sc.dy * sc.dy);
  auto solid_gap = [&](Vec2 x) {
    real g = body_distance(x);
    return std::min(g, signed_wall_distance(sc.params.walls, dom, x));
  };
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix) {
      const Vec2 x{dom.lo.x + (ix + 0.5) * sc.dx, dom.lo.y + (iy + 0.5) * sc.dy};
      // Fluid fills the region on the left of the walls, and not within d0/2 of a solid surface
      // (a lattice point exactly d0/2 from a wall lying on the box edge stays).
      const real wall_gap = signed_wall_distance(sc.params.walls, dom, x);
      const bool keep = wall_gap >= 0.5 * d0 * (1 - 1e-9);
      // A cell whose centre lies farther from the walls than its half-diagonal has every sample
      // on the walls' fluid side (a distance changes no faster than the point moves), so the
      // bodies alone decide its samples: the same fraction without the walls' distance at each of
      // them (with 10 000 bodies, most of the set-up time went there).
      const real fraction = !exact_fill                  ? real(1)
                            : wall_gap >= 0.5 * diagonal ? cell_fluid_fraction(x, sc.dx, sc.dy, body_distance)
                                                         : cell_fluid_fraction(x, sc.dx, sc.dy, solid_gap);
      if (!keep || near_body(body_distance, x, d0)) {
        if (exact_fill && fraction > 0) band.push_back({ix, iy, fraction});
        continue;
      }
      kept[static_cast<std::size_t>(iy) * nx + ix] = static_cast<std::int64_t>(fx.size());
      farea.push_back(fraction * sc.dx * sc.dy);
      const real px = rng.symmetric(), py = rng.symmetric();
      fx.push_back(dom.wrap(x + (c.perturbation * d0) * Vec2{px, py}));
    }
  // The fluid in the cells of lattice points removed beside a solid is shared equally by the
  // nearest kept points, and a kept point's cell counts only its part in the fluid region, so
  // that the fluid masses fill the region outside the bodies and inside the walls exactly (the
  // lattice alone leaves a band of mean width d0/2 along a curved or inclined surface without
  // fluid: 1.4-2.9 % of the fluid mass of a cylinder array at 10-20 particles across, and as much
  // momentum input; walls along the lattice lines, as a box's, are filled exactly by the lattice
  // already). Shared, because beside an inclined wall a removed point often has two kept points at
  // the same distance: giving it all to the first in lattice order piled the fluid onto the
  // downslope side of every lattice step, and a block sliding down such a wall then failed
  // (cases/incline_wall.toml, exit 3 at 0.547 s; docs/method.md, "The fill next to walls").
  for (const BandCell& bc : band) {
    const std::vector<std::int64_t> to = nearest_kept(kept, nx, ny, dom, bc.ix, bc.iy);
    for (const std::int64_t k : to)
      farea[static_cast<std::size_t>(k)] += bc.fraction * sc.dx * sc.dy / static_cast<real>(to.size());
  }
  return fill;
}

/// The fluid particles' fields at t = 0 (particles nb on): the hydrostatic pressure, the
/// case's initial flow, the density from the pressure and the mass from the area.
void set_initial_fluid(const Case& c, const Domain& dom, const FluidFill& fill, std::size_t nb,
                       Particles& P) {
  const Vec2 L = dom.size();
  const real d0 = c.d0;
  // Hydrostatic start: P = rho0 g.(x - x_top), x_top the domain corner highest against g.
  Vec2 x_top = dom.lo;
  for (Vec2 corner : {dom.lo, dom.hi, Vec2{dom.lo.x, dom.hi.y}, Vec2{dom.hi.x, dom.lo.y}})
    if (dot(c.gravity, corner) < dot(c.gravity, x_top)) x_top = corner;
  const bool hydrostatic = c.hydrostatic && c.gravity_in_fluid;
  // Velocities of the walls lying along the domain's lower and upper edges (for initial.flow = couette).
  Vec2 v_lower, v_upper;
  for (const auto& w : c.walls) {
    const real tol = 1e-6 * d0;
    if (std::fabs(w.from.y - dom.lo.y) < tol && std::fabs(w.to.y - dom.lo.y) < tol) v_lower = w.velocity;
    if (std::fabs(w.from.y - dom.hi.y) < tol && std::fabs(w.to.y - dom.hi.y) < tol) v_upper = w.velocity;
  }
  const real U = c.initial_amplitude;
  for (std::size_t k = 0; k < fill.x.size(); ++k) {
    const std::size_t i = nb + k;
    const Vec2 x = fill.x[k];
    P.x[i] = x;
    P.kind[i] = Kind::Fluid;
    P.group[i] = -1;
    real p = c.p0;
    if (hydrostatic) p += c.rho0 * dot(c.gravity, x - x_top);
    if (c.initial_flow == InitialFlow::Couette) {
      // developed Couette flow: linear in y between the velocities of the lower and upper walls
      const real s = (x.y - dom.lo.y) / L.y;
      P.v[i] = (1 - s) * v_lower + s * v_upper;
    }
    if (c.initial_flow == InitialFlow::TaylorGreen) {
      // u = -U cos(2 pi x) sin(2 pi y), v = U sin(2 pi x) cos(2 pi y) on the unit-scaled box,
      // p = -rho U^2 (cos 4 pi x + cos 4 pi y) / 4.
      const real sx = 2 * M_PI * (x.x - dom.lo.x) / L.x, sy = 2 * M_PI * (x.y - dom.lo.y) / L.y;
      P.v[i] = {-U * std::cos(sx) * std::sin(sy), U * std::sin(sx) * std::cos(sy)};
      p += -c.rho0 * U * U * (std::cos(2 * sx) + std::cos(2 * sy)) / 4;
    }
    P.p[i] = p;
    P.rho[i] = density_from_pressure(p, c.rho0, c.c, c.p0);
    P.m[i] = P.rho[i] * fill.area[k];
  }
}

}  // namespace

Scene build_scene(const Case& c) {
  Scene sc;
  sc.params = physics_params(c);
  sc.domain = Domain{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  const Domain& dom = sc.domain;
  Particles& P = sc.particles;
  const real d0 = c.d0;
  const int dummy_layers = static_cast<int>(std::ceil(c.h_over_d0 - 1e-9));
  std::vector<Vec2> body_pos;
  std::vector<real> body_angle;
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    body_pos.push_back(body_position(c.bodies[k], sc.params.bodies[k].shape));
    body_angle.push_back(c.bodies[k].angle);
  }
  // Exact below 3 d0: above every threshold it is compared with (d0 / 2 here, half a lattice
  // cell's diagonal in the fill's fractions).
  const BodyDistance body_distance(sc.params, body_pos, body_angle, dom, 3 * d0);

  // ---- boundary block: one rigid group per wall, surface particles then its dummies
  scene_detail::BoundaryArrays b;
  for (std::size_t w = 0; w < c.walls.size(); ++w) {
    const WallSpec& ws = c.walls[w];
    RigidGroup g;
    g.name = ws.name;
    g.is_wall = true;
    g.motion = norm(ws.velocity) > 0 || ws.omega != 0 ? Motion::Prescribed : Motion::Fixed;
    g.vel = ws.velocity;
    g.omega = ws.omega;
    // A turning wall's frame is centred on its pivot; other walls' frame is the world frame.
    if (ws.omega != 0) g.pos = g.pos0 = ws.pivot;
    g.first = b.size();
    auto surf = scene_detail::sample_wall(c, dom, w);
    // Wall stretches covered by a body (an obstacle sitting on the wall) are not wall surface.
    std::erase_if(surf, [&](const SurfacePoint& sp) { return near_body(body_distance, sp.x, d0); });
    const std::size_t first_surface = b.size();
    for (const auto& sp : surf) {
      b.add(sp.x, sp.x - g.pos0, sp.normal, sp.ds,
            sp.ds * d0 *
                (sp.corner ? corner_volume_factor(sp.wall_normal, sp.corner_normal2, sp.wedge > 0) : 1.0),
            Kind::Boundary, -1, static_cast<std::int32_t>(w), sp.wedge);
    }
    if (c.boundary == BoundaryModel::Dummy) {
      for (const auto& [x, s] : scene_detail::dummy_points(surf, d0, dummy_layers)) {
        b.add(x, x - g.pos0, surf[s].normal, 0, d0 * d0, Kind::Dummy,
              static_cast<std::int32_t>(first_surface + s), static_cast<std::int32_t>(w));
      }
    }
    g.count = b.size() - g.first;
    sc.groups.push_back(g);
  }

  // ---- bodies: one rigid group each, surface particles (body frame) then dummies
  for (std::size_t k = 0; k < c.bodies.size(); ++k)
    sc.groups.push_back(scene_detail::add_body_group(c, sc.params, dom, k, body_pos[k], dummy_layers,
                                                     static_cast<std::int32_t>(sc.groups.size()), b));

  const FluidFill fill = fill_fluid(c, sc, body_distance);

  const std::size_t nb = b.size(), n = nb + fill.x.size();
  P.resize(n);
  P.resize_boundary(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    P.x[i] = b.x[i];
    P.local[i] = b.local[i];
    P.normal_local[i] = b.normal[i];
    P.normal[i] = b.normal[i];
    P.wedge[i] = b.wedge[i];
    P.ds[i] = b.ds[i];
    P.kind[i] = b.kind[i];
    P.source[i] = b.source[i];
    P.group[i] = b.group[i];
    P.rho[i] = c.rho0;
    P.p[i] = c.p0;
    P.m[i] = c.rho0 * b.volume[i];
  }

  set_initial_fluid(c, dom, fill, nb, P);
  for (std::size_t i = 0; i < n; ++i) P.id[i] = static_cast<std::int64_t>(i);
  scene_detail::append_buffers(c, sc);
  return sc;
}

}  // namespace particula
