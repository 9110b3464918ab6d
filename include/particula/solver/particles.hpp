// Particle state as a structure of arrays. Boundary particles (wall and body surfaces, and
// dummy particles of the baseline) occupy the fixed block [0, n_boundary) so that rigid
// groups can address them by index; fluid particles follow and are periodically reordered
// by cell for locality. In D dimensions (`Particles` the 2D solver's); nothing global: a store
// is one solver's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/core/types3.hpp"

namespace particula {

/// Fluid: integrated fluid particles. Boundary: wall and body surface particles. Dummy: the
/// baseline's dummy particles. Inlet, Outlet: buffer particles behind an open boundary (in the
/// fluid block, not integrated: boundary/open_boundary.hpp).
enum class Kind : std::uint8_t { Fluid = 0, Boundary = 1, Dummy = 2, Inlet = 3, Outlet = 4 };

/// Whether a particle of this kind is a buffer particle of an open boundary.
PARTICULA_HD bool is_buffer(Kind k) { return k == Kind::Inlet || k == Kind::Outlet; }

template <int D>
struct ParticlesOf {
  std::size_t n_boundary = 0;
  std::int64_t next_id = 0;  // the id of the next particle created (open boundaries); ids are never reused

  // every particle
  std::vector<Vec<D>> x, v;
  std::vector<real> rho, p, m;
  std::vector<Kind> kind;
  std::vector<std::int32_t> group;  // rigid group (wall or body) of a boundary particle, -1 for fluid
  std::vector<std::int64_t> id;     // stable identity across reordering

  // boundary block only (size n_boundary)
  std::vector<Vec<D>> local;        // position in the group's body frame
  std::vector<Vec<D>> normal_local; // analytic outward normal in the body frame
  std::vector<real> ds;             // surface length (2D) or area (3D) represented (0 for dummy particles)
  std::vector<Vec<D>> acc;          // acceleration of the surface point
  std::vector<Vec<D>> normal;       // current normal (P.18 or analytic)
  std::vector<real> wedge;          // at a convex corner of the solid: half the angle between the
                                    // two sides' normals (boundary/surface_guard.hpp); 0 elsewhere
  std::vector<std::int32_t> source; // dummy particles: the surface particle they copy P, rho from

  std::size_t size() const { return x.size(); }
  bool is_fluid(std::size_t i) const { return i >= n_boundary; }

  void resize(std::size_t n);
  void resize_boundary(std::size_t nb);
};
using Particles = ParticlesOf<2>;
using Particles3 = ParticlesOf<3>;

}  // namespace particula
