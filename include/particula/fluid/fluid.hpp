// Fluid physics per particle and per pair (docs/method.md sections 1, 5, 10).
#pragma once

#include "particula/core/types3.hpp"

namespace particula {

/// Equation of state (P.3/P.12): P = P0 + c^2 (rho - rho0).
PARTICULA_HD real equation_of_state(real rho, real rho0, real c, real p0) {
  return p0 + c * c * (rho - rho0);
}
/// Its inverse, used for boundary particles whose pressure comes from P.20.
PARTICULA_HD real density_from_pressure(real p, real rho0, real c, real p0) {
  return rho0 + (p - p0) / (c * c);
}

/// Momentum rate of a fluid particle (P.2 discretized):
///   dV/dt = -<grad P>_i / rho_i + nu <lap V>_i + f,   f = body force (+ g when kept in the fluid).
template <int D>
PARTICULA_HD Vec<D> momentum_rate(Vec<D> grad_p_over_rho, Vec<D> lap_v, real nu, Vec<D> f) {
  return -grad_p_over_rho + nu * lap_v + f;
}

/// Modified continuity rate (P.13-P.16):
///   d rho/dt = -rho [ <div V> + G dt ( <div <grad P/rho>> - <div (grad P/rho)> ) ]
/// `rhie_chow` is the bracket (first minus second derivative scheme), `g_dt` the generalization
/// factor times the time step.
PARTICULA_HD real continuity_rate(real rho, real div_v, real g_dt, real rhie_chow) {
  return -rho * (div_v + g_dt * rhie_chow);
}

/// Shifting displacement contribution of neighbour j (P.33): (rbar_i^2 / r_ij^2) e_ij, from
/// 1/r_ij and e_ij; the sum is multiplied by beta V_max dt.
template <int D>
PARTICULA_HD Vec<D> shifting_pair(real rbar2, real inv_r, Vec<D> e) {
  return (rbar2 * inv_r * inv_r) * e;
}

}  // namespace particula
