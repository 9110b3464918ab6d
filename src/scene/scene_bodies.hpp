// Bodies in the scene (internal to src/scene): the boundary block's particle arrays as the scene
// builds them, and each body's rigid group (its surface particles and dummies).
#pragma once

#include <cstdint>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/solver.hpp"

namespace particula::scene_detail {

/// The boundary block as the scene fills it, one particle after another: the walls' groups,
/// then the bodies'. A group's particles are its surface particles, then its dummies.
struct BoundaryArrays {
  std::vector<Vec2> x, local, normal;  // position, position in the group's frame, normal (group frame)
  std::vector<real> ds, volume;        // surface length (0 for a dummy), volume
  std::vector<real> wedge;             // a convex corner's half angle (Particles::wedge)
  std::vector<Kind> kind;
  std::vector<std::int32_t> source, group;  // a dummy's surface particle (-1 for a surface one), its group

  std::size_t size() const { return x.size(); }
  void add(Vec2 at, Vec2 at_local, Vec2 n, real ds_, real volume_, Kind k, std::int32_t src,
           std::int32_t grp, real wedge_ = 0) {
    wedge.push_back(wedge_);
    x.push_back(at);
    local.push_back(at_local);
    normal.push_back(n);
    ds.push_back(ds_);
    volume.push_back(volume_);
    kind.push_back(k);
    source.push_back(src);
    group.push_back(grp);
  }
};

/// Body k's rigid group at t = 0, centroid at pos: its surface particles (body frame; a fixed
/// body's samples hidden by the walls left out and junction particles added where it crosses a
/// wall), then with the dummy boundary its dummies. They are appended to b as group `group`.
RigidGroup add_body_group(const Case& c, const PhysicsParams& prm, const Domain& dom, std::size_t k, Vec2 pos,
                          int dummy_layers, std::int32_t group, BoundaryArrays& b);

}  // namespace particula::scene_detail
