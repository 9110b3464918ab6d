// Wendland C2 kernel in D dimensions with h the cut-off radius (docs/method.md section 2, P.37):
// the same function of q = r/h in 2D and 3D, normalized to unit integral over the disc or ball.
#pragma once

#include "particula/core/types.hpp"

namespace particula {

/// The normalization W0 of the Wendland C2 kernel in D dimensions, W0 = 1 / int (1-q)^4 (4q+1):
/// 7 / (pi h^2) in 2D, 21 / (2 pi h^3) in 3D.
template <int D>
real wendland_normalization(real h);
template <>
inline real wendland_normalization<2>(real h) {
  return 7.0 / (M_PI * h * h);
}
template <>
inline real wendland_normalization<3>(real h) {
  return 21.0 / (2 * M_PI * h * h * h);
}

/// The volume d0^D of one lattice cell of spacing d0 (an area in 2D).
template <int D>
PARTICULA_HD real cell_volume(real d0) {
  real v = d0;
  for (int a = 1; a < D; ++a) v *= d0;
  return v;
}

/// W(r,h) = W0 (1-q)^4 (4q+1) for q = r/h < 1, else 0 (W0 = wendland_normalization<D>(h)).
/// h is the CUT-OFF radius (the support ends at r = h), not half of it.
template <int D>
struct Wendland {
  real h = 1;
  real w0 = 0;      // W0
  real inv_h = 1;
  real f0 = 0;      // -20 W0 / h^2, the factor of F (folded once: F is on the hot path of every pair)

  Wendland() = default;
  explicit Wendland(real cutoff)
      : h(cutoff), w0(wendland_normalization<D>(cutoff)), inv_h(1.0 / cutoff), f0(-20 * w0 * inv_h * inv_h) {}

  PARTICULA_HD real W(real r) const {
    const real q = r * inv_h;
    if (q >= 1) return 0;
    const real a = 1 - q;
    const real a2 = a * a;
    return w0 * a2 * a2 * (4 * q + 1);
  }
  /// dW/dr = -20 W0 q (1-q)^3 / h  (negative inside the support).
  PARTICULA_HD real dW(real r) const {
    const real q = r * inv_h;
    if (q >= 1) return 0;
    const real a = 1 - q;
    return -20 * w0 * q * a * a * a * inv_h;
  }
  /// grad_i W_ij = W'(r) e_ij with e_ij = r_ij / r: returns the factor F = W'(r)/r so that
  /// grad_i W_ij = F r_ij. Finite at r -> 0 (F -> -20 W0 / h^2).
  PARTICULA_HD real F(real r) const {
    const real q = r * inv_h;
    if (q >= 1) return 0;
    const real a = 1 - q;
    return f0 * (a * a * a);
  }
};

/// The kernel of the 2D solver.
using WendlandC2 = Wendland<2>;

}  // namespace particula
