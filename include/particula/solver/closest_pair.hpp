// Where a collapsing time step comes from: the closest pair of particles (the d_min of the
// Courant and viscous conditions, P.30-P.31) and the surfaces nearest to each of the two, found
// on the host for the failure message and the run's report. Not on the step's path: the
// neighbour list keeps only the smallest distance, not where it is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/rigid_group.hpp"

namespace particula {

struct ClosestPair {
  bool found = false;
  std::uint32_t i = 0, j = 0;
  real distance = 0;
};

/// The closest pair within the support radius h, over the pairs min_distance counts (all pairs
/// but those of two buffer particles of an open boundary). With several at the same distance,
/// the one with the lowest indices.
ClosestPair closest_pair(const Particles& P, const Domain& domain, real h);

/// The nearest surface particle (Kind::Boundary with a surface length) to particle i within h,
/// other than i itself; -1 when there is none.
std::int64_t nearest_surface_particle(const Particles& P, const Domain& domain, real h, std::uint32_t i);

/// "fluid particle 1234 at (x, y) m, 0.25 d0 from wall 'step'" for the failure message: the
/// particle's kind, id and position, and its nearest surface (its group's name and distance),
/// or its own wall or body for a surface particle.
std::string describe_particle(const Particles& P, const Domain& domain, const std::vector<RigidGroup>& groups,
                              real h, real d0, std::uint32_t i);

}  // namespace particula
