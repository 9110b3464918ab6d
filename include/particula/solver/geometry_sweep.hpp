// The geometry sweep of a step (docs/method.md sections 3-7): everything that depends on the
// positions and the start-of-step volumes alone, once per step, for one particle at a time:
// B, Bhat, the P.18 normal sum, the mean spacing, the shifting direction, the nearest surfaces,
// and the per-pair weights every later sweep of the step multiplies (solver/sweeps.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "particula/boundary/surface_guard.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/solver/sweep_context.hpp"
#include "particula/sph/operators.hpp"
#include "particula/sph/operators3.hpp"

namespace particula {

// ---- geometry (positions and start-of-step volumes only, once per step) --------------------
// Written once for D = 2 and 3 (GeometryAt, geometry_at: the 2D solver's).

/// The moment sums of Bhat's system in D dimensions.
template <int D>
struct LaplacianMomentsOf;
template <>
struct LaplacianMomentsOf<2> {
  using type = LaplacianMoments;
};
template <>
struct LaplacianMomentsOf<3> {
  using type = LaplacianMoments3;
};

/// Position-only quantities of particle i.
template <int D>
struct GeometryAtOf {
  Mat<D> B = unit_matrix<D>(), Bhat = unit_matrix<D>();
  real rbar = 0;                  // mean neighbour distance (P.33)
  Vec<D> normal_sum;              // sum_j w_j gradW_ij, the P.18 normal before normalization
  Vec<D> shift_direction;         // sum_j (rbar^2 / r^2) e_ij of P.33, before the factor beta V_max dt
  Vec<D> lap_esum;                // sum_j (Laplacian weight) e_ij, folded into lap_w
  NearestSurfaces near;           // fluid particles: the nearest surface particles (surface guard)
  real others_fluid_support = 0;  // fluid particles: sum_{j fluid} w_j W_ij over the neighbours (isolated)
  bool B_ok = true;
  bool sparse = false;  // fluid particle whose moment matrix was bounded below (bound_sparse_moment)
  bool Bhat_ok = true;  // false only for a fluid particle's singular system: at boundary particles
                        // Bhat = k I is the designed guard (docs/method.md, "The Bhat
                        // guard"), not an event
};
using GeometryAt = GeometryAtOf<2>;

/// A dummy particle's pairs (baseline): the plain SPH gradient weights w_j gradW_ij, no Laplacian.
template <int D>
PARTICULA_HD void dummy_pair_weights(const SweepContextOf<D>& c, std::size_t i, Vec<D>* grad_w, real* lap_w) {
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  const Vec<D> xi = c.x[i];
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    const PairGeometryOf<D> g = pair_geometry(c.domain, c.kernel, xi, c.x[j]);
    grad_w[k] = (c.vol[j] * g.F) * g.rij;
    lap_w[k] = 0;
  }
}

/// The sums over particle i's pairs that B, Bhat and the consistent gradient need (the first pass
/// of geometry_at).
template <int D>
struct PairMoments {
  Mat<D> S;                                  // -sum_j w_j r_ij (x) gradW_ij, B's inverse (P.6)
  typename LaplacianMomentsOf<D>::type mom;  // the moments of Bhat's system (P.11)
  real rsum = 0;                             // sum_j r_ij
  real support = 0;                          // sum_j w_j W_ij (j != i)
  Vec<D> support_r;                          // sum_j w_j W_ij r_ij
};

/// First pass of geometry_at: the moment sums, and into `out` the P.18 normal sum, the nearest
/// surfaces and the fluid's support. The pair vector and distance are parked in the pair's output
/// slots (grad_w[k], lap_w[k]) so the later passes read them from cache instead of recomputing the
/// minimum image and the square root.
template <int D>
PARTICULA_HD PairMoments<D> pair_moments(const SweepContextOf<D>& c, std::size_t i, GeometryAtOf<D>& out,
                                         Vec<D>* grad_w, real* lap_w) {
  PairMoments<D> m;
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  const Vec<D> xi = c.x[i];
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    const PairGeometryOf<D> g = pair_geometry(c.domain, c.kernel, xi, c.x[j]);
    const real w = c.vol[j];
    const real inv_r = 1 / g.r;
    m.S += renormalization_pair(w, g.F, g.rij);
    laplacian_moments_pair(m.mom, w, g.r, g.F * g.r, inv_r * g.rij);
    out.normal_sum += (w * g.F) * g.rij;
    m.rsum += g.r;
    if (j < c.nb && i >= c.nb && c.kind[j] == Kind::Boundary)
      offer_surface(out.near, j, c.group[j], g.r * g.r);
    const real wW = w * c.kernel.W(g.r);
    m.support += wW;
    m.support_r += wW * g.rij;
    if (j >= c.nb && i >= c.nb) out.others_fluid_support += wW;
    grad_w[k] = g.rij;
    lap_w[k] = g.r;
  }
  return m;
}

/// Second pass of geometry_at (Fatehi-Manzari): lap_esum = sum_k weight e_ij, which the third
/// pass folds into the Laplacian weights.
template <int D>
PARTICULA_HD Vec<D> laplacian_esum(const SweepContextOf<D>& c, std::size_t i, const Mat<D>& Bhat,
                                   const Vec<D>* grad_w, const real* lap_w) {
  Vec<D> esum;
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const Vec<D> rij = grad_w[k];
    const real r = lap_w[k];
    const real inv_r = 1 / r;
    esum += fm_pair_weight(Bhat, c.vol[c.j[k]], c.kernel.F(r) * r, inv_r * rij) * (inv_r * rij);
  }
  return esum;
}

/// The first-derivative weights of a pair: the consistent ones (matrix Bg and correction gamma of
/// consistent_gradient_correction) or the paper's w_j B_i gradW_ij.
template <int D>
struct GradientWeights {
  bool consistent = false;
  Mat<D> Bg;
  Vec<D> gamma;
};

/// Third pass of geometry_at: the stored weights of every later sweep over the parked pair
/// vectors and distances, and a fluid particle's shifting direction.
template <int D>
PARTICULA_HD void store_pair_weights(const SweepContextOf<D>& c, std::size_t i, const GradientWeights<D>& gw,
                                     GeometryAtOf<D>& out, Vec<D>* grad_w, real* lap_w) {
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  const bool fluid = i >= c.nb;
  const real rbar2 = out.rbar * out.rbar;
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const Vec<D> rij = grad_w[k];
    const real r = lap_w[k];
    const real F = c.kernel.F(r);
    const real w = c.vol[c.j[k]];
    const real inv_r = 1 / r;
    const Vec<D> eij = inv_r * rij;
    const real dW = F * r;
    const Vec<D> paper_w = (w * F) * (out.B * rij);  // w_j B_i gradW_ij (P.7)
    lap_w[k] = c.fatehi_manzari ? fm_pair_weight(out.Bhat, w, dW, eij) * inv_r + dot(out.lap_esum, paper_w)
                                : morris_pair_weight(w, dW) * inv_r;
    grad_w[k] = gw.consistent ? gw.Bg * (w * (F * rij - c.kernel.W(r) * gw.gamma)) : paper_w;
    if (fluid) out.shift_direction += shifting_pair(rbar2, inv_r, eij);
  }
}

/// The geometry sweep for particle i: B_i (P.6), Bhat_i (P.11, with the soundness guard for
/// boundary particles), rbar_i, the P.18 normal sum, the shifting direction of fluid particles
/// (P.33), and the per-pair weights of every later sweep, written to grad_w[k], lap_w[k] for
/// the pairs k of i:
///   grad_w = w_j B_i gradW_ij, so <grad u>_i = sum_k grad_w (u_j - u_i)            (P.7)
///     and at fluid particles with numerics.gradient = "consistent" w_j B~_i (gradW_ij -
///     gamma_i W_ij) instead, whose weights sum to zero (consistent_gradient_correction);
///   Laplacian pair term = weight [ (u_i - u_j)/r - e . <grad u>_i ]                 (P.10)
///     with weight = 2 w_j W' (e . Bhat_i . e) (Fatehi-Manzari) or 2 w_j W' and no
///     gradient term (Morris, P.8), and <grad u>_i the P.7 gradient, with which the Laplacian is
///     exact for quadratic fields. Since that gradient is itself a pair sum, the Laplacian is one
///     pair sum <lap u>_i = sum_k lap_w (u_i - u_j) with
///       lap_w = weight / r + lap_esum . (w_j B_i gradW_ij),   lap_esum = sum_k weight e_ij,
///     so it needs no P.7 gradient of its own when grad_w holds the consistent one.
/// Dummy particles (baseline) get B = Bhat = I: their pressure gradient, which the Rhie-Chow
/// term of their fluid neighbours reads, is the plain SPH gradient; no Laplacian weights.
/// `d0` is rbar for a particle alone.
template <int D>
PARTICULA_HD GeometryAtOf<D> geometry_at(const SweepContextOf<D>& c, std::size_t i, real d0, Vec<D>* grad_w,
                                         real* lap_w) {
  GeometryAtOf<D> out;
  if (c.kind[i] == Kind::Dummy) {
    dummy_pair_weights(c, i, grad_w, lap_w);
    return out;
  }
  const std::uint32_t np = c.pair_count(i);
  const PairMoments<D> m = pair_moments(c, i, out, grad_w, lap_w);
  // A fluid particle's moment matrix is bounded below (bound_sparse_moment: a sparse support at
  // the edge of a void); boundary particles keep theirs, which P.20 solves through.
  Mat<D> S_fluid = m.S;
  if (i >= c.nb) out.sparse = bound_sparse_moment(S_fluid);
  out.B_ok = renormalization_tensor(S_fluid, out.B);
  // Every particle's Bhat must be usable: sound (positive definite, bounded) at a boundary
  // particle; bounded and diffusive on average at a fluid particle, where an anti-diffusive Bhat
  // beside a void in the particle distribution (seen under two bodies resting on a floor) made
  // the viscous term amplify the particle's own velocity by 10 % per step until it left the
  // domain (operators.hpp, laplacian_correction_is_bounded_diffusive).
  const bool boundary = i < c.nb;
  out.Bhat_ok = laplacian_correction_tensor(m.mom, out.B, out.Bhat,
                                            boundary ? BhatCheck::Sound : BhatCheck::BoundedDiffusive) ||
                boundary;
  out.rbar = np > 0 ? m.rsum / static_cast<real>(np) : d0;
  // The first-derivative weights of a fluid particle: with numerics.gradient = "consistent" the
  // kernel gradient corrected to zeroth order before the renormalization, so that the weights sum
  // to zero (consistent_gradient_correction); the paper's otherwise, or where that fails.
  GradientWeights<D> gw;
  gw.consistent = !boundary && c.zeroth_order_gradient && out.B_ok &&
                  consistent_gradient_correction(m.S, out.normal_sum, m.support, m.support_r, gw.Bg, gw.gamma,
                                                 out.sparse);
  if (c.fatehi_manzari) out.lap_esum = laplacian_esum(c, i, out.Bhat, grad_w, lap_w);
  store_pair_weights(c, i, gw, out, grad_w, lap_w);
  return out;
}

}  // namespace particula
