// The single-layer no-slip boundary (docs/method.md sections 6-7, P.18-P.20): normals and the pressure
// of a boundary particle from the normal component of the momentum equation.
#pragma once

#include <cmath>

#include "particula/core/types3.hpp"

namespace particula {

/// P.18: n_i = sum_j w_j gradW_ij / |sum_j w_j gradW_ij|, pointing from the solid into the
/// fluid (gradW_ij points from i towards j). Returns false when the sum vanishes. The functions
/// of this file are written once for D = 2 and 3.
template <int D>
PARTICULA_HD bool kernel_normal(Vec<D> sum_w_gradW, Vec<D>& n) {
  const real len = norm(sum_w_gradW);
  if (!(len > 0)) return false;
  n = sum_w_gradW / len;
  return true;
}

/// Running sums of P.20 over the neighbours j of boundary particle i:
///   num = sum_j w_j (P_j / rhobar_ij) (B_i gradW_ij) . n_i
///   den = sum_j w_j (1   / rhobar_ij) (B_i gradW_ij) . n_i
struct WallPressureSums {
  real num = 0, den = 0, scale = 0;
  int fluid_neighbors = 0;
};

template <int D>
PARTICULA_HD void wall_pressure_pair(WallPressureSums& s, Vec<D> wBgW, Vec<D> n, real p_j, real rhobar,
                                     bool j_is_fluid) {
  const real k = dot(wBgW, n) / rhobar;
  s.num += k * p_j;
  s.den += k;
  s.scale += std::fabs(k);
  s.fluid_neighbors += j_is_fluid ? 1 : 0;
}

/// P.20: P_i = [num + a_i.n_i - nu<lap V>_i.n_i - g.n_i] / den, with a_i the boundary
/// particle's acceleration, nu<lap V>_i = (div tau)/rho evaluated at i, and g the gravity kept
/// in the fluid (zero when P is the dynamic pressure). Returns false (P untouched) when the
/// denominator vanishes, e.g. no fluid neighbour: the caller keeps the previous pressure.
template <int D>
PARTICULA_HD bool wall_pressure(const WallPressureSums& s, Vec<D> a, Vec<D> nu_lap_v, Vec<D> g, Vec<D> n,
                                real& p) {
  if (s.fluid_neighbors == 0 || !(s.den > 1e-6 * s.scale)) return false;
  p = (s.num + dot(a - nu_lap_v - g, n)) / s.den;
  return true;
}

/// How a boundary particle's pressure was set in a sweep: P.20 solved; extrapolated because P.20
/// is ill-conditioned (the fluid wraps round the particle: sharp convex corners, and the wedges
/// beside two surfaces in contact); extrapolated because the fluid neighbours are too far from
/// the surface to carry the normal derivative (a gap narrower than the kernel,
/// wall_pressure_min_den); the void's pressure, no fluid within kVoidDistance (void_pressure_applies);
/// previous pressure kept.
enum class WallPressureOutcome { Solved, Extrapolated, ExtrapolatedFar, Void, Kept };

/// A surface particle with no fluid particle within kVoidDistance d0, and no other solid's
/// surface within kVoidDistance + 1 d0 = 2.6 d0 (room for a row of fluid: not the film or the
/// wedge of a contact, where no particle fits), faces a void: fluid the flow has left behind (a
/// pore between bodies whose fluid was squeezed out and that opens again, the wake of a body
/// thrown off a contact). The first row of fluid lies 0.5-0.8 d0 from
/// a surface. Neither the renormalized pressure gradient (exact for the fluid's own linear
/// field, blind to the empty side) nor the continuity equation (which only sees particles in
/// the support) senses a void, and P.20 or the extrapolation gives the surface the pressure of
/// the fluid beyond it, so a void stayed open: a body rose off its neighbours with nothing
/// below it and spun up in the one-sided flow, and bodies closing on each other met the
/// squeezed fluid's resistance but parted with none (docs/method.md, "Surfaces facing a
/// void: the void's pressure").
inline constexpr real kVoidDistance = 1.6;

/// A void takes the equation of state's pressure at rest density, p0, where all the fluid in
/// the support is at p0 or above, so that the fluid round the void is pushed into it. Where
/// some of that fluid is in tension (p < p0: the wake of a body pulling away, the lee of a
/// sharp corner) the surface keeps P.20: a void pressure that followed the fluid's lowest
/// pressure down drew the nearest fluid particle onto the surface and emptied it (mixed_shapes
/// stopped), and one at p0 would push that fluid away from the surface.
PARTICULA_HD bool void_pressure_applies(real p0, real p_min_fluid) { return p_min_fluid >= p0; }

/// P.20 is solved where it is well conditioned: its denominator at least this fraction of the
/// sum of the magnitudes of its terms, den >= 0.5 sum_j |k_j|. Then P_i is a weighted mean of
/// the neighbours' pressures whose weights k_j/den have magnitudes summing to at most 2. On
/// flat walls, box corners, circles and ellipses (>= 10 particles across) the ratio measured
/// is above 0.6. Where a sharp convex corner lets the fluid wrap round the particle, the
/// neighbours behind its normal cancel the denominator: measured 0.075-0.11 at the corners of
/// a square, negative at a 72-degree corner. There P.20 amplifies the neighbours' pressure
/// noise at every sweep (a triangle's corner pressure grew from 4 to 1500 Pa in 30 steps and
/// the run blew up), so the pressure is extrapolated instead (wall_extrapolation).
inline constexpr real kWallPressureMinConditioning = 0.5;

/// P.20 also needs fluid close enough to the surface to carry the normal derivative. The
/// renormalized gradient of the linear field (x - x_i) . n is exact, so on a flat wall
/// sum_j k_j rho_j (x_j - x_i) . n = 1 over the fluid neighbours: den = 1 / (rho L) with L the
/// k-weighted mean distance of the fluid neighbours from the wall, below the support radius h
/// on any flat wall (about 1.2 d0 = 0.45 h on a lattice). P.20 puts the wall pressure
/// 1/den = rho L times the normal momentum balance (surface acceleration, viscous and body
/// forces) away from the neighbours' mean; where the only fluid neighbours are at the edge of
/// the support (a surface facing a lone particle in a gap narrower than the kernel), L grows
/// without bound, and the surface acceleration in P.20 becomes an added mass that feeds back
/// on the body within a step (a polygon at rest against a body reached 500 N/m in one output
/// interval). Below den = 1 / (rho0 h), i.e. L > h, the pressure is extrapolated instead.
PARTICULA_HD real wall_pressure_min_den(real rho0, real h) { return 1 / (rho0 * h); }

PARTICULA_HD bool wall_pressure_well_conditioned(const WallPressureSums& s, real min_den = 0) {
  return s.fluid_neighbors > 0 && s.den >= kWallPressureMinConditioning * s.scale && s.den >= min_den;
}

/// Sums of the corner fallback over the fluid neighbours j of boundary particle i: the
/// extrapolation of Adami, Hu and Adams (2012) with the whole momentum balance at the wall,
/// grad P / rho = g + nu <lap V>_i - a_i =: `balance`, so that
///   P_i = sum_j W_ij [P_j - rho_j (x_j - x_i) . balance] / sum_j W_ij.
/// Its weights are positive, so it cannot amplify; it is first-order accurate (hydrostatic
/// pressure exact).
struct WallExtrapolationSums {
  real num = 0, den = 0;
};

template <int D>
PARTICULA_HD void wall_extrapolation_pair(WallExtrapolationSums& s, real W, real p_j, real rho_j, Vec<D> x_ji,
                                          Vec<D> balance) {
  s.num += W * (p_j - rho_j * dot(x_ji, balance));
  s.den += W;
}

/// Returns false (P untouched) without a fluid neighbour inside the kernel support.
PARTICULA_HD bool wall_extrapolation(const WallExtrapolationSums& s, real& p) {
  if (!(s.den > 0)) return false;
  p = s.num / s.den;
  return true;
}

}  // namespace particula
