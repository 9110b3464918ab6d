// The rigid groups as solids, for the components that look at their geometry (contacts, the load
// band): a wall at a pose, a body's placed shape, the bodies still in the run.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "particula/bodies/collision.hpp"
#include "particula/core/types.hpp"
#include "particula/geometry/wall_piece.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/sweeps.hpp"

namespace particula {

/// Wall group k's geometry with its group at angle `angle` (a turning wall rotated about its
/// pivot; a sliding wall runs along a periodic axis and keeps its line).
inline WallPiece wall_at(const PhysicsParams& prm, const RigidGroup& g, std::size_t k, real angle) {
  if (angle == g.angle0) return prm.walls[k];
  return prm.walls[k].moved(g.pos0, angle - g.angle0, Vec2{});
}

/// Wall group k's geometry now.
inline WallPiece wall_now(const PhysicsParams& prm, const std::vector<RigidGroup>& groups, std::size_t k) {
  return wall_at(prm, groups[k], k, groups[k].angle);
}

/// Group g's pose and motion as the per-particle functions read them.
inline GroupMotion group_motion(const RigidGroup& g) {
  GroupMotion m;
  m.pos = g.pos;
  m.vel = g.vel;
  m.acc = g.acc;
  m.cos_angle = std::cos(g.angle);
  m.sin_angle = std::sin(g.angle);
  m.omega = g.omega;
  m.alpha = g.alpha;
  return m;
}

/// Body group g's shape at its current pose.
inline PlacedBody placed_body(const PhysicsParams& prm, const RigidGroup& g) {
  const BodyParams& b = prm.bodies[static_cast<std::size_t>(g.body)];
  return PlacedBody{&b.shape, &b.samples, g.pos, g.angle};
}

/// Whether open boundary z is an outlet with bodies = "removed" (its screen removes bodies
/// instead of holding them).
inline bool removes_bodies(const PhysicsParams& prm, std::size_t z) {
  return !prm.open[z].inlet && prm.open_specs[z].bodies == OutletBodies::Removed;
}

/// The bodies still in the run, in group order: their groups, positions and bounding radii (the
/// input of contact_candidates).
struct BodyList {
  std::vector<std::size_t> groups;
  std::vector<Vec2> pos;
  std::vector<real> bound;

  void list(const PhysicsParams& prm, const std::vector<RigidGroup>& all) {
    groups.clear();
    pos.clear();
    bound.clear();
    for (std::size_t k = 0; k < all.size(); ++k) {
      if (all[k].is_wall || all[k].removed) continue;
      groups.push_back(k);
      pos.push_back(all[k].pos);
      bound.push_back(prm.bodies[static_cast<std::size_t>(all[k].body)].shape.bounding_radius());
    }
  }
};

}  // namespace particula
