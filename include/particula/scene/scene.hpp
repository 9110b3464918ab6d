// Builds the initial particles, rigid groups and physics parameters from a Case.
#pragma once

#include <vector>

#include "particula/case/case.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/solver.hpp"

namespace particula {

struct Scene {
  PhysicsParams params;
  Domain domain;
  Particles particles;
  std::vector<RigidGroup> groups;
  real dx = 0, dy = 0;  // actual fluid lattice spacing (d0 adjusted to fit the box exactly)
};

/// The physics parameters of a case: every member of PhysicsParams set from `c` (the reorder
/// interval from kReorderInterval; `cuda` is left false for the caller), so that their defaults are
/// the case's, that is the schema's.
PhysicsParams physics_params(const Case& c);

/// Whether x lies in the region the walls enclose: on the fluid side (the left) of the nearest
/// wall point, through periodic sides (at an end point shared by two walls, the side of their
/// mean normal there); everywhere without walls. The fluid fill of build_scene and the
/// containment checks of the robustness suite.
bool in_fluid_region(const std::vector<WallPiece>& walls, const Domain& dom, Vec2 x);
/// The distance from x to the nearest wall, positive in the region the walls enclose and
/// negative outside it (+inf without walls).
real signed_wall_distance(const std::vector<WallPiece>& walls, const Domain& dom, Vec2 x);
/// A case's walls at time t (a turning wall turned by omega t about its pivot).
std::vector<WallPiece> walls_at(const Case& c, real t);
Scene build_scene(const Case& c);

/// A body's shape in its body frame (origin at the area centroid).
Shape body_shape(const BodySpec& b);
/// A body's position at t = 0: the area centroid in world coordinates.
Vec2 body_position(const BodySpec& b, const Shape& s);

/// Deterministic, platform-independent random numbers (splitmix64) for the seeded lattice
/// perturbation: the same seed gives the same particles on every compiler and machine.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [-1, 1).
  double symmetric() { return static_cast<double>(next() >> 11) * 0x1.0p-52 - 1.0; }

 private:
  std::uint64_t state_;
};

}  // namespace particula
