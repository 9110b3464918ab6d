// Each body's rigid group in the scene: its surface particles (a fixed body's placed against the
// walls it stands on or crosses) and its dummies.
#include "scene_bodies.hpp"

#include <cmath>

#include "particula/bodies/rigid_motion.hpp"
#include "scene_walls.hpp"

namespace particula::scene_detail {

namespace {

/// A fixed body's surface sample as placed in the particle arrays (world-frame normal).
struct PlacedSample {
  bool keep = true;
  bool junction = false;  // normal and volume factor changed for a body-wall junction
  Vec2 normal;
  real volume_factor = 1;
};

/// A fixed body standing on a wall (the half-disc obstacle of paper 7.5, a block on the floor)
/// shares a side with the wall. The samples of that side lie on the wall line and face into the
/// wall: no fluid reaches them, and left in they would be a second, inward-facing surface right
/// behind the junction, seen by the fluid there through the kernel (it made the fluid particle
/// in the junction of 7.5 lose its density). They are left out, as the wall particles under the
/// body are. A corner sample where the body's free side meets the wall is a concave corner of
/// the fluid, like a box corner: its normal becomes the bisector of the free side's normal and
/// the wall's, and its volume gets the box corner's factor (corner_volume_factor).
PlacedSample place_on_walls(const SurfaceSample& smp, Vec2 x, real cth, real sth, const Case& c) {
  PlacedSample out{true, false, rotate(smp.normal, cth, sth), 1};
  constexpr real antiparallel = -0.999;
  for (const auto& ws : c.walls) {
    const WallNearest near = ws.piece().nearest(x);
    if (near.distance >= 0.5 * c.d0) continue;
    const Vec2 nw = near.normal;
    if (!smp.corner) {
      if (dot(out.normal, nw) < antiparallel) out.keep = false;
      continue;
    }
    const Vec2 s0 = rotate(smp.sides[0], cth, sth), s1 = rotate(smp.sides[1], cth, sth);
    const bool f0 = dot(s0, nw) < antiparallel, f1 = dot(s1, nw) < antiparallel;
    if (f0 && f1) {
      out.keep = false;
    } else if (f0 || f1) {
      const Vec2 free_side = f0 ? s1 : s0, bisector = free_side + nw;
      if (norm(bisector) < 1e-12) continue;
      out.junction = true;
      out.normal = bisector / norm(bisector);
      out.volume_factor = corner_volume_factor(nw, free_side);
    }
  }
  return out;
}

/// Whether the surface sample x of a fixed body is hidden from the fluid by the walls: beyond a
/// wall (outside the region the walls enclose) or beyond the domain's edge along a non-periodic
/// axis, or within d0/2 of a point where the body crosses a wall (the junction particle there
/// stands for it).
bool hidden_by_walls(Vec2 x, const std::vector<WallPiece>& walls, const Domain& dom,
                     const std::vector<Crossing>& crossings, real d0) {
  if (beyond_walls(x, walls, dom)) return true;
  for (const auto& cr : crossings)
    if (norm(x - cr.x) < 0.5 * d0) return true;
  return false;
}

/// Body k's rigid group at t = 0 before its particles are added: its motion, pose, velocities
/// (a prescribed body's at t = 0) and mass properties.
RigidGroup body_group_state(const BodySpec& bs, const BodyParams& bp, std::size_t k, Vec2 pos) {
  RigidGroup g;
  g.name = bs.name;
  g.is_wall = false;
  g.body = static_cast<int>(k);
  g.motion = bs.motion == BodyMotion::Free    ? Motion::Free
             : bs.motion == BodyMotion::Fixed ? Motion::Fixed
                                              : Motion::Prescribed;
  g.pos = g.pos0 = pos;
  g.angle = g.angle0 = bs.angle;
  if (g.motion == Motion::Free) {
    g.vel = bs.velocity;
    g.omega = bs.omega;
  } else if (g.motion == Motion::Prescribed) {
    const auto st = prescribed_state(bs.schedule, bs.velocity, bs.omega, 0.0);
    g.vel = st.vel;
    g.omega = st.omega;
    g.acc = st.acc;
    g.alpha = st.alpha;
  }
  g.area = bp.shape.area();
  g.mass = bs.density * g.area;
  g.inertia = bs.density * bp.shape.polar_moment();
  return g;
}

/// Where the body's particles go: its group, its pose (cos and sin of its angle) and the spacing.
struct BodyPlacement {
  std::int32_t group;
  Vec2 pos;
  real cth, sth, d0;

  /// A surface particle at x (local and normal_local in the body frame) standing for ds of surface.
  void add_surface(BoundaryArrays& b, Vec2 x, Vec2 local, Vec2 normal_local, real ds,
                   real volume_factor, real wedge = 0) const {
    b.add(x, local, normal_local, ds, ds * d0 * volume_factor, Kind::Boundary, -1, group, wedge);
  }
};

/// A fixed body crossing a wall: the points where its surface meets the walls (junctions).
std::vector<Crossing> wall_crossings(const BodyParams& bp, const RigidGroup& g, real angle,
                                     const std::vector<WallPiece>& walls, real d0) {
  std::vector<Crossing> crossings;
  if (g.motion == Motion::Fixed)
    for (const WallPiece& w : walls) {
      const auto found = body_wall_crossings(bp.shape, g.pos, angle, w, d0);
      crossings.insert(crossings.end(), found.begin(), found.end());
    }
  return crossings;
}

/// The surface particles of the body's samples (a fixed body's placed against the walls, those
/// hidden by them left out); returns the indices into bp.samples of the particles made.
std::vector<std::size_t> add_body_surface(const Case& c, const BodyParams& bp,
                                          const std::vector<WallPiece>& walls, const Domain& dom,
                                          const std::vector<Crossing>& crossings, Motion motion,
                                          const BodyPlacement& at, BoundaryArrays& b) {
  std::vector<std::size_t> kept;
  for (std::size_t s = 0; s < bp.samples.size(); ++s) {
    const SurfaceSample& smp = bp.samples[s];
    const Vec2 x = at.pos + rotate(smp.x, at.cth, at.sth);
    Vec2 normal = smp.normal;
    real volume_factor = 1, wedge = smp.wedge;
    if (motion == Motion::Fixed) {
      const PlacedSample ps = place_on_walls(smp, x, at.cth, at.sth, c);
      if (!ps.keep) continue;
      if (ps.junction) {
        normal = rotate(ps.normal, at.cth, -at.sth);  // back to the body frame
        volume_factor = ps.volume_factor;
        wedge = 0;  // a concave corner of the fluid
      } else if (hidden_by_walls(x, walls, dom, crossings, at.d0)) {
        continue;
      }
    }
    kept.push_back(s);
    at.add_surface(b, x, smp.x, normal, smp.ds, volume_factor, wedge);
  }
  return kept;
}

/// Each crossing is a concave corner of the fluid between the body's free side and the wall,
/// like a box corner: a surface particle there with the bisector normal and the corner's
/// volume factor, standing for d0 of surface (half on each side).
void add_junctions(const std::vector<Crossing>& crossings, const BodyPlacement& at, BoundaryArrays& b) {
  for (const auto& cr : crossings) {
    const Vec2 bisector = cr.body_normal + cr.wall_normal;
    if (norm(bisector) < 1e-12) continue;
    const Vec2 n = bisector / norm(bisector);
    at.add_surface(b, cr.x, rotate(cr.x - at.pos, at.cth, -at.sth), rotate(n, at.cth, -at.sth), at.d0,
                   corner_volume_factor(cr.wall_normal, cr.body_normal));
  }
}

/// Dummy particles on a body-frame lattice inside the solid, up to ceil(h/d0) spacings deep, each
/// with the normal of the nearest surface particle made (the first one of the group at `first`).
void add_body_dummies(const BodyParams& bp, const std::vector<WallPiece>& walls, const Domain& dom,
                      const std::vector<Crossing>& crossings, const std::vector<std::size_t>& kept,
                      int dummy_layers, std::size_t first, const BodyPlacement& at, BoundaryArrays& b) {
  const real d0 = at.d0;
  const int m = static_cast<int>(std::ceil(bp.shape.bounding_radius() / d0)) + 1;
  for (int iy = -m; iy <= m; ++iy)
    for (int ix = -m; ix <= m; ++ix) {
      const Vec2 q{ix * d0, iy * d0};
      const real sd = bp.shape.signed_distance(q);
      if (sd > -0.5 * d0 || sd < -(dummy_layers + 0.5) * d0 || kept.empty()) continue;
      // the part of a body beyond a wall has the wall's dummies behind it
      if (!crossings.empty() && hidden_by_walls(at.pos + rotate(q, at.cth, at.sth), walls, dom, {}, d0))
        continue;
      std::size_t nearest = 0;  // among the surface particles made
      for (std::size_t s2 = 1; s2 < kept.size(); ++s2)
        if (norm2(bp.samples[kept[s2]].x - q) < norm2(bp.samples[kept[nearest]].x - q)) nearest = s2;
      const Vec2 nearest_normal = b.normal[first + nearest];
      b.add(at.pos + rotate(q, at.cth, at.sth), q, nearest_normal, 0, d0 * d0, Kind::Dummy,
            static_cast<std::int32_t>(first + nearest), at.group);
    }
}

}  // namespace

RigidGroup add_body_group(const Case& c, const PhysicsParams& prm, const Domain& dom, std::size_t k, Vec2 pos,
                          int dummy_layers, std::int32_t group, BoundaryArrays& b) {
  const BodySpec& bs = c.bodies[k];
  const BodyParams& bp = prm.bodies[k];
  RigidGroup g = body_group_state(bs, bp, k, pos);
  g.first = b.size();
  const BodyPlacement at{group, g.pos, std::cos(bs.angle), std::sin(bs.angle), c.d0};
  const std::vector<Crossing> crossings = wall_crossings(bp, g, bs.angle, prm.walls, c.d0);
  const std::vector<std::size_t> kept = add_body_surface(c, bp, prm.walls, dom, crossings, g.motion, at, b);
  add_junctions(crossings, at, b);
  if (c.boundary == BoundaryModel::Dummy)
    add_body_dummies(bp, prm.walls, dom, crossings, kept, dummy_layers, g.first, at, b);
  g.count = b.size() - g.first;
  return g;
}

}  // namespace particula::scene_detail
