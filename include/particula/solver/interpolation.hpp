// Interpolation of particle fields at arbitrary points (probes), by moving least squares (MLS):
// at a point x the field is fitted by the polynomial a . p(x_j - x) that minimizes
//   sum_j w_j (f_j - a . p(x_j - x))^2,   w_j = W(|x - x_j|) m_j / rho_j,
// over the fluid particles and the wall and body surface particles (which carry the velocity of
// their wall or body and their solved pressure), and f(x) = a_0. With the quadratic basis
// p = (1, dx, dy, dx^2, dx dy, dy^2) the interpolation is exact for quadratic fields, so a point on
// a no-slip wall reads the wall's velocity (the surface particles are data points there) and a
// Poiseuille profile is reproduced across the channel. Where the particles around x cannot
// determine a quadratic (a corner, a sparse region) the linear basis (1, dx, dy) is used, and
// where even that fails, the Shepard average f = sum_j w_j f_j / sum_j w_j.
#pragma once

#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

struct PointSample {
  Vec2 v;
  real p = 0;
  real shepard = 0;  // sum_j W w_j (about 1 inside the fluid, 0 where no particle is near)
  int order = -1;    // consistency order used: 2 quadratic, 1 linear, 0 Shepard, -1 no particle near
};

std::vector<PointSample> interpolate_at(const Particles& P, const Domain& domain, const WendlandC2& kernel,
                                        const std::vector<Vec2>& points);

/// The MLS value a_0 at the origin from data points `dx` (offsets x_j - x, in units of the
/// kernel radius), weights `w` and `nrhs` right-hand sides f (row-major, nrhs values per point),
/// with a basis of `order` 2 (6 monomials) or 1 (3 monomials). False when the moment matrix
/// M = sum_j w_j p_j p_j^T is singular or ill-conditioned (a Cholesky pivot below 1e-6 of its
/// diagonal entry): the points do not determine a polynomial of that order.
bool mls_fit(int order, const std::vector<Vec2>& dx, const std::vector<real>& w, const std::vector<real>& f,
             int nrhs, real* value);

}  // namespace particula
