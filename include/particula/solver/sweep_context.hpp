// What every sweep of a step reads (solver/sweeps.hpp): the pair geometry and the neighbour list
// with the step's stored per-pair weights, as plain pointers that the CPU loops and the CUDA
// kernels share.
#pragma once

#include <cstddef>
#include <cstdint>

#include "particula/core/types.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

/// Geometry of the pair (i, j): r_ij = r_i - r_j (minimum image), r = |r_ij|, and the kernel
/// factor F = W'(r)/r so that grad_i W_ij = F r_ij.
template <int D>
struct PairGeometryOf {
  Vec<D> rij;
  real r = 0, F = 0;
};
using PairGeometry = PairGeometryOf<2>;

template <int D>
PARTICULA_HD PairGeometryOf<D> pair_geometry(const DomainOf<D>& domain, const Wendland<D>& kernel, Vec<D> xi,
                                             Vec<D> xj) {
  PairGeometryOf<D> g;
  g.rij = domain.separation(xi, xj);
  g.r = std::sqrt(norm2(g.rij));
  g.F = kernel.F(g.r);
  return g;
}

/// What every sweep reads: the neighbour list (CSR), positions, start-of-step volumes w = m/rho,
/// particle kinds, and the per-pair weights of the geometry sweep. Plain pointers, valid on the
/// host (std::vector data) or on the device (cudaMalloc'd arrays). In D dimensions
/// (`SweepContext` the 2D solver's).
template <int D>
struct SweepContextOf {
  DomainOf<D> domain;
  Wendland<D> kernel;
  // The pairs of particle i are k = first_pair(i) + q * stride, q = 0 .. pair_count(i) - 1:
  //   CSR (the CPU): start[i] + q, the pairs of one particle contiguous (stride 1);
  //   ELL (the GPU): i + q * stride with stride = the padded particle count and per-particle
  //   counts, so that the threads of a warp (consecutive i) read consecutive addresses.
  const std::uint32_t* start = nullptr;  // CSR offsets (size n+1), or nullptr for ELL
  const std::uint32_t* count = nullptr;  // ELL pair counts
  std::size_t stride = 1;
  const std::uint32_t* j = nullptr;

  PARTICULA_HD std::size_t first_pair(std::size_t i) const { return start ? start[i] : i; }
  PARTICULA_HD std::uint32_t pair_count(std::size_t i) const {
    return start ? start[i + 1] - start[i] : count[i];
  }
  std::size_t n = 0;   // particles
  std::size_t nb = 0;  // boundary block [0, nb)
  const Vec<D>* x = nullptr;
  const real* vol = nullptr;
  const Kind* kind = nullptr;
  const std::int32_t* group = nullptr;  // rigid group of a boundary particle (nearest surfaces)
  const Vec<D>* normal = nullptr;       // outward normals of the surface particles
  const real* wedge = nullptr;          // their convex corners' half angles (Particles::wedge)
  const real* ds = nullptr;             // their surface spacings (Particles::ds)
  // the nearest surface particles of each fluid particle, from this step's geometry sweep
  const std::uint32_t* near_a = nullptr;
  const std::uint32_t* near_b = nullptr;
  // per particle: the unresolved-film fraction of this step (film_fraction_at; null: none)
  const real* film = nullptr;
  // per particle: 1 for an isolated fluid particle this step, left out of P.20 (surface_guard.hpp; null:
  // none)
  const std::uint8_t* isolated = nullptr;
  bool fatehi_manzari = true;         // false: Morris Laplacian (baseline)
  bool zeroth_order_gradient = true;  // fluid particles: gradient weights with sum_j grad_w = 0 (geometry_at)
  // written by the geometry sweep
  const Vec<D>* grad_w = nullptr;  // per pair: the first-derivative weight (geometry_at)
  const real* lap_w = nullptr;     // per pair: the Laplacian weight (geometry_at)
};
using SweepContext = SweepContextOf<2>;

}  // namespace particula
