// The per-particle work of one time step (docs/method.md sections 3-10), written once as
// PARTICULA_HD functions of plain pointers: the OpenMP loops of cpu_backend.cpp and the CUDA
// kernels of src/cuda/ call exactly these functions, so no formula exists twice.
//
// Every neighbour sum is a gather over particle i's own CSR neighbour list, in list order, so
// the result of a sweep does not depend on the number of threads (or on the GPU's scheduling).
//
// Positions are frozen during the two stages of a step, so everything that depends on them
// alone is computed once per step by the geometry sweep and stored per pair (28 bytes with the
// neighbour index): the gradient weight w_j B_i gradW_ij and the Laplacian weight. Every later
// sweep is then a few multiply-adds per pair on stored weights and gathered fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "particula/boundary/surface_guard.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/core/types.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/sph/kernel.hpp"
#include "particula/solver/geometry_sweep.hpp"
#include "particula/solver/sweep_context.hpp"
#include "particula/sph/operators.hpp"

namespace particula {

// ---- derivative sweeps (stored weights times gathered fields) -------------------------------

/// Velocity gradient L_i = <grad V>_i (L_ab = d_a V_b; renormalized, P.7, and at fluid particles
/// also corrected to zeroth order with numerics.gradient = "consistent") and the viscous
/// Laplacian <lap V>_i (P.10 or P.8, one pair sum: geometry_at). Zero for dummies. At a surface
/// particle the Laplacian, which P.20 turns into the wall's normal pressure gradient, leaves out
/// isolated fluid particles (surface_guard.hpp, `isolated`), as P.20's pressure sums do: a lone
/// particle 0.4 d0 off the surface moving 1 cm/s against it gave nu lap V of ~50 m/s^2 there, a
/// surface pressure of -2.9 Pa (a thousand times the flow's viscous stress), whose gradient drove
/// the particle faster still (docs/method.md, "Isolated particles").
template <int D>
PARTICULA_HD void velocity_derivatives_at(const SweepContextOf<D>& c, std::size_t i, const Vec<D>* v, Mat<D>& L, Vec<D>& lap) {
  L = Mat<D>{};
  lap = Vec<D>{};
  if (c.kind[i] == Kind::Dummy) return;
  const Vec<D> vi = v[i];
  const bool surface = i < c.nb && c.isolated;
  Vec<D> a;
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    const Vec<D> dv = v[j] - vi;  // V_j - V_i
    L += vector_gradient_pair(c.grad_w[k], dv);
    if (surface && j >= c.nb && c.isolated[j]) continue;
    a -= c.lap_w[k] * dv;  // lap_w (V_i - V_j)
  }
  lap = a;
}

/// <grad P>_i / rho_i with the renormalized gradient (P.7; at fluid particles with
/// numerics.gradient = "consistent" also corrected to zeroth order, geometry_at).
template <int D>
PARTICULA_HD Vec<D> pressure_gradient_at(const SweepContextOf<D>& c, std::size_t i, const real* p, const real* rho) {
  Vec<D> g;
  const real pi = p[i];
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) g += gradient_pair(c.grad_w[k], p[c.j[k]] - pi);
  return g / rho[i];
}

/// The Rhie-Chow bracket of the modified continuity equation (P.13-P.16):
///   <div <grad P/rho>>_i - <div (grad P/rho)>_i,
/// the first-derivative scheme applied twice minus the second-derivative scheme applied once
/// (to P with the pair-averaged density). `G` holds <grad P>/rho of every particle. Zero for dummies.
template <int D>
PARTICULA_HD real rhie_chow_at(const SweepContextOf<D>& c, std::size_t i, const real* p, const real* rho, const Vec<D>* G) {
  if (c.kind[i] == Kind::Dummy) return 0;
  const Vec<D> Gi = G[i];
  const real pi = p[i], rhoi = rho[i];
  real div_g = 0, lap_p = 0;
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    div_g += dot(c.grad_w[k], G[j] - Gi);
    lap_p += c.lap_w[k] * ((pi - p[j]) / (0.5 * (rhoi + rho[j])));
  }
  return div_g - lap_p;
}

/// Whether neighbour j of surface particle i is the surface of another solid facing it across a
/// gap (another rigid group, normals more than 120 degrees apart). P.20 leaves such neighbours
/// out: the wall pressure is a condition on the fluid beside the surface, and two surfaces that
/// read each other's P.20 pressures across a gap narrower than the kernel support form a loop
/// that the conditioning guard allows to amplify (weights up to 2 in magnitude), which ran away
/// in a body resting against a wall (docs/method.md, "Sharp corners"). Box corners
/// (normals at 90 degrees) and a body's own surface keep the paper's treatment.
template <int D>
PARTICULA_HD bool surface_across_a_gap(const SweepContextOf<D>& c, std::size_t i, std::uint32_t j) {
  return j < c.nb && c.group != nullptr && c.normal != nullptr && c.kind[j] == Kind::Boundary &&
         c.group[j] != c.group[i] && dot(c.normal[i], c.normal[j]) < -0.5;
}

/// P.20 for boundary particle i: the pressure that makes the normal momentum balance hold at
/// the wall, from the neighbours' pressures, the surface acceleration `a`, nu <lap V>_i and the
/// body force `f` kept in the fluid. Where P.20 is ill-conditioned (sharp convex corners, see
/// kWallPressureMinConditioning), or its fluid neighbours are too far from the surface to carry
/// the normal derivative (den below min_den = 1 / (rho0 h), see wall_pressure_well_conditioned),
/// the pressure is extrapolated from the fluid neighbours with the
/// same momentum balance. With no fluid within void_distance (kVoidDistance d0; 0: no void
/// test), the surface faces a void and takes its pressure, p0, where no fluid in its support is
/// in tension (void_pressure_applies). Kept: p_out untouched (no fluid neighbour at all).
template <int D>
PARTICULA_HD WallPressureOutcome wall_pressure_at(const SweepContextOf<D>& c, std::size_t i, const real* p, const real* rho,
                                                  Vec<D> n, Vec<D> a, Vec<D> nu_lap_v, Vec<D> f, real min_den,
                                                  real void_distance, real p0, real& p_out) {
  WallPressureSums s;
  const real rhoi = rho[i];
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  // "none yet" (1e300, as surface_guard.hpp: std::numeric_limits is host-only under nvcc)
  constexpr real inf = 1e300;
  real nearest_fluid2 = inf, nearest_solid2 = inf, p_min_fluid = inf;
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    const real r2 = norm2(c.domain.separation(c.x[j], c.x[i]));
    if (j < c.nb && c.kind[j] == Kind::Boundary && c.group && c.group[j] != c.group[i])
      nearest_solid2 = r2 < nearest_solid2 ? r2 : nearest_solid2;
    if (surface_across_a_gap(c, i, j)) continue;
    if (c.isolated && j >= c.nb && c.isolated[j]) continue;  // an isolated particle (surface_guard.hpp)
    wall_pressure_pair(s, c.grad_w[k], n, p[j], 0.5 * (rhoi + rho[j]), j >= c.nb);
    if (j < c.nb) continue;
    nearest_fluid2 = r2 < nearest_fluid2 ? r2 : nearest_fluid2;
    p_min_fluid = p[j] < p_min_fluid ? p[j] : p_min_fluid;
  }
  // room for a row of fluid in front of the surface (no other solid within void_distance + d0:
  // not the film or wedge of a contact, where no particle fits) and none there
  const real room = void_distance * (1 + 1 / kVoidDistance);
  if (void_distance > 0 && s.fluid_neighbors > 0 && nearest_fluid2 > void_distance * void_distance &&
      nearest_solid2 > room * room && void_pressure_applies(p0, p_min_fluid)) {
    p_out = p0;
    return WallPressureOutcome::Void;
  }
  const bool conditioned = wall_pressure_well_conditioned(s);
  if (conditioned && s.den >= min_den && wall_pressure(s, a, nu_lap_v, f, n, p_out)) return WallPressureOutcome::Solved;
  WallExtrapolationSums e;
  const Vec<D> xi = c.x[i], balance = f + nu_lap_v - a;
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    if (j < c.nb) continue;
    if (c.isolated && c.isolated[j]) continue;  // takes its pressure from the surfaces instead
    const Vec<D> x_ji = c.domain.separation(c.x[j], xi);
    wall_extrapolation_pair(e, c.kernel.W(norm(x_ji)), p[j], rho[j], x_ji, balance);
  }
  if (!wall_extrapolation(e, p_out)) return WallPressureOutcome::Kept;
  return conditioned && s.den < min_den ? WallPressureOutcome::ExtrapolatedFar : WallPressureOutcome::Extrapolated;
}

/// The Shepard mean sum_j w_j W_ij P_j / sum_j w_j W_ij of the pressures of particle i's surface
/// neighbours (`surfaces`) or of its fluid neighbours (not `surfaces`; isolated ones left out).
/// Returns false (p_out untouched) with no such neighbour in the support.
template <int D>
PARTICULA_HD bool shepard_pressure_at(const SweepContextOf<D>& c, std::size_t i, const real* p, bool surfaces,
                                      real& p_out) {
  real sw = 0, swp = 0;
  const Vec<D> xi = c.x[i];
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) {
    const std::uint32_t j = c.j[k];
    const bool surface = j < c.nb && c.kind[j] == Kind::Boundary;
    if (surface != surfaces || (j < c.nb && !surface) || (!surfaces && c.isolated && c.isolated[j])) continue;
    const real w = c.vol[j] * c.kernel.W(norm(c.domain.separation(c.x[j], xi)));
    sw += w;
    swp += w * p[j];
  }
  if (!(sw > 0)) return false;
  p_out = swp / sw;
  return true;
}

/// Pressure of an isolated fluid particle (surface_guard.hpp, `isolated`; docs/method.md,
/// "Isolated particles"): the Shepard mean sum_j w_j W_ij P_j / sum_j w_j W_ij over the surface
/// particles in its support, whose P.20 pressures come from the resolved fluid around them (an
/// isolated particle is left out of P.20). The continuity equation of a particle with no fluid
/// around it measures nothing but the motion of the surfaces that hold it: integrated, it
/// compressed a lone particle in a closing gap to 1.3-2 rho0 while the fluid around the gap stayed
/// at its hydrostatic density, and the burst ended the run (`settling_pile`, `mixed_shapes`). With
/// its pressure taken from the surfaces, the particle is carried by the local pressure field and
/// offers no spurious cushion. Returns false (p_out untouched) with no surface particle in support.
template <int D>
PARTICULA_HD bool isolated_pressure_at(const SweepContextOf<D>& c, std::size_t i, const real* p, real& p_out) {
  return shepard_pressure_at(c, i, p, true, p_out);
}

// ---- pointwise updates of one particle ------------------------------------------------------

/// Which stage-start buffers a stage reads: the predictor starts from the step-start values
/// (V^n, rho^n), the corrector from the predicted ones (V*, rho*).
enum class StageStart { StepStart, Predicted };

/// Constants of the pointwise updates (a plain struct for host and device), in D dimensions
/// (`StageParams` the 2D solver's).
template <int D>
struct StageParamsOf {
  real dt = 0;
  real g_dt = 0;       // Rhie-Chow factor G times dt (P.16)
  real nu = 0;
  Vec<D> f;            // body force, plus gravity when it is kept in the fluid
  real rho0 = 1000, c = 0, p0 = 0;
  real kappa = 0;      // coefficient of the velocity odd-even damping (m^2/s), see odd_even_velocity_at
  real void_distance = 0;  // kVoidDistance d0: a surface particle with no fluid this near faces a void (0: none)
  bool single_layer = true;
};
using StageParams = StageParamsOf<2>;

/// Explicit momentum stage of a fluid particle: V = V_start + dt (-<grad P>/rho + nu <lap V> + f).
template <int D>
PARTICULA_HD Vec<D> momentum_stage(Vec<D> v_start, Vec<D> grad_p_over_rho, Vec<D> lap_v, const StageParamsOf<D>& s) {
  return v_start + s.dt * momentum_rate(grad_p_over_rho, lap_v, s.nu, s.f);
}

/// Whether particle i's density evolves by the continuity equation: fluid particles, and in the
/// dummy baseline also the surface particles (the single-layer wall gets P from P.20 instead).
PARTICULA_HD bool evolves_density(std::size_t i, std::size_t nb, Kind kind, bool single_layer) {
  return (i >= nb || !single_layer) && kind != Kind::Dummy && !is_buffer(kind);
}

/// Modified continuity stage (P.13-P.16) and the equation of state: rho = rho_start + dt D, P(rho).
template <int D>
PARTICULA_HD void continuity_stage(real rho_start, real div_v, real rhie_chow, const StageParamsOf<D>& s, real& rho,
                                   real& p) {
  rho = rho_start + s.dt * continuity_rate(rho_start, div_v, s.g_dt, rhie_chow);
  p = equation_of_state(rho, s.rho0, s.c, s.p0);
}

/// End of step (P.28): fluid velocity and density the mean of the step-start and corrected
/// values, position advanced with the new velocity. Returns |V|^2 for the shifting scale.
/// Buffer particles of open boundaries keep the fields the boundary set and are moved by it.
template <int D>
PARTICULA_HD real end_of_step_update(std::size_t i, std::size_t nb, Kind kind, const DomainOf<D>& domain, real dt,
                                     bool single_layer, Vec<D> v_n, real rho_n, real p_n, Vec<D>& x, Vec<D>& v, real& rho,
                                     real& p) {
  if (is_buffer(kind)) return norm2(v);
  if (i >= nb) {
    v = 0.5 * (v + v_n);
    x = domain.wrap(x + dt * v);
  }
  if (i >= nb || single_layer || kind != Kind::Dummy) {
    rho = 0.5 * (rho + rho_n);
    p = 0.5 * (p + p_n);
  }
  return norm2(v);
}

/// Particle shifting of a fluid particle (P.33-P.36): displacement dr = beta V_max dt times the
/// direction of the geometry sweep, with the first-order Taylor corrections of V, P and rho
/// (using the step's mean velocity gradient and the new <grad P>/rho). The shift has no
/// component towards a surface closer than `surface_range` (surface guard).
template <int D>
PARTICULA_HD void shift_particle(Vec<D> direction, real scale, const Mat<D>& grad_v, Vec<D> grad_p_over_rho,
                                 const NearSurfacesOf<D>& surfaces, real surface_range, const DomainOf<D>& domain, real c,
                                 Vec<D>& x, Vec<D>& v, real& p, real& rho) {
  const Vec<D> dr = limit_shift_at_surfaces(scale * direction, surfaces, surface_range, domain, x);  // P.33
  x = domain.wrap(x + dr);
  v += dr * grad_v;                              // P.34
  const real dp = rho * dot(dr, grad_p_over_rho);  // P.35: rho dr . <grad P / rho>
  p += dp;
  rho += dp / (c * c);                           // P.36
}

/// The surface guard of fluid particle i (boundary/surface_guard.hpp) against its nearest
/// surface particles near_a[i], near_b[i] of this step's geometry sweep, whose positions,
/// normals and velocities (`surfaces`, over the same arrays as x and v) are those of the end of
/// the step. Race-free in one loop: it reads
/// boundary particles and writes only fluid particle i.
template <int D>
PARTICULA_HD GuardOutcome surface_guard_at(std::size_t i, const std::uint32_t* near_a, const std::uint32_t* near_b,
                                           const SurfaceArraysOf<D>& surfaces, Vec<D>* x, Vec<D>* v, real keep,
                                           const DomainOf<D>& domain) {
  const NearSurfacesOf<D> ns = gather_surfaces(near_a[i], near_b[i], surfaces);
  return guard_surfaces(ns, keep, domain, x[i], v[i]);
}

/// Limits of a healthy state (exit 3 otherwise).
template <int D>
struct HealthLimitsOf {
  real rho_lo = 0, rho_hi = 0, h = 0;
  DomainOf<D> domain;
};
using HealthLimits = HealthLimitsOf<2>;

/// Whether particle i is unhealthy: a non-finite value, or for a fluid particle (`fluid`: kind
/// Fluid) a density outside the limits or a position outside a closed domain (by more than h).
template <int D>
PARTICULA_HD bool particle_unhealthy(bool fluid, Vec<D> x, Vec<D> v, real rho, real p, const HealthLimitsOf<D>& l) {
  const bool finite = all_finite(x) && all_finite(v) && std::isfinite(rho) && std::isfinite(p);
  if (!finite) return true;
  if (!fluid) return false;
  if (rho < l.rho_lo || rho > l.rho_hi) return true;
  return l.domain.outside_closed(x, l.h);
}

// ---- one particle's share of a fused pass (the loop body of the CPU loop and the GPU kernel) --

/// Velocity derivatives of `v` at particle i, stored: grad V, lap V and div V = tr(grad V).
template <int D>
PARTICULA_HD void store_velocity_derivatives(const SweepContextOf<D>& c, std::size_t i, const Vec<D>* v, Mat<D>* grad_v,
                                             Vec<D>* lap_v, real* div_v) {
  Mat<D> L;
  Vec<D> lap;
  velocity_derivatives_at(c, i, v, L, lap);
  grad_v[i] = L;
  lap_v[i] = lap;
  div_v[i] = trace(L);
}

/// The velocity counterpart of the Rhie-Chow bracket: <lap V>_i (compact, P.10) minus
/// <div <grad V>>_i (the first-derivative scheme applied twice, a wide stencil). Both are
/// consistent Laplacians: the difference is exactly zero for linear fields and of the order of
/// the gradient's truncation error on smooth ones, but the compact Laplacian sees an odd-even
/// (checkerboard) velocity mode that the wide one does not. kappa times this damps exactly that
/// mode, which nothing else controls at high cell Reynolds numbers c d0 / nu
/// (docs/method.md, "Odd-even velocity damping").
template <int D>
PARTICULA_HD Vec<D> odd_even_velocity_at(const SweepContextOf<D>& c, std::size_t i, const Mat<D>* grad_v, Vec<D> lap_v) {
  const Mat<D> Li = grad_v[i];
  Vec<D> wide;
  const std::size_t b = c.first_pair(i), st = c.stride;
  const std::uint32_t np = c.pair_count(i);
  for (std::size_t q = 0, k = b; q < np; ++q, k += st) wide += c.grad_w[k] * (grad_v[c.j[k]] - Li);
  return lap_v - wide;
}

/// The bracket that makes a particle in an unresolved film relax its density to that of the
/// Shepard mean p_fluid of its fluid neighbours' pressures over the time tau = h / c that sound
/// takes to cross the kernel support (at least one step):
///   -rho_i G dt bracket = (rho(p_fluid) - rho_i) / tau.
/// The paper's bracket at a film particle also reads the surfaces' P.20 pressures, which are read
/// from that very particle with weights that may be negative near a corner: the loop drained a
/// resting film between two polygons to 0.5 rho0 (mixed_shapes at d0 = 5e-5; docs/method.md,
/// "Unresolved films"). The relaxation has positive weights and a rate of at most 1 per step, so
/// it cannot amplify.
template <int D>
PARTICULA_HD real film_relaxation_bracket(real rho_i, real p_fluid, const StageParamsOf<D>& s, real h) {
  const real tau = s.c > 0 && h / s.c > s.dt ? h / s.c : s.dt;
  const real rho_target = density_from_pressure(p_fluid, s.rho0, s.c, s.p0);
  return -(rho_target - rho_i) / (tau * rho_i * s.g_dt);
}

/// Rhie-Chow bracket of the current P at particle i (in an unresolved film blended with the
/// relaxation to its fluid neighbours, film_relaxation_bracket), then (fluid) the momentum stage
/// from v_start, and (odd_even not null) the odd-even damping's acceleration
/// kappa (<lap V> - <div <grad V>>) of fluid particle i, which the band sums report apart from the
/// loads (solver/momentum_loads.hpp, band_share_damping). Race-free in one loop: it reads P, rho,
/// G, grad V of the neighbours and writes only particle i's entries. (`odd_even` may be nullptr:
/// a parameter D is not deduced from.)
template <int D>
PARTICULA_HD void rhie_chow_and_momentum_at(const SweepContextOf<D>& c, std::size_t i, const real* p,
                                            const real* rho, const Vec<D>* G, const Mat<D>* grad_v,
                                            const Vec<D>* lap_v, const Vec<D>* v_start, const StageParamsOf<D>& s,
                                            real* rc, Vec<D>* v, std::type_identity_t<Vec<D>>* odd_even) {
  rc[i] = rhie_chow_at(c, i, p, rho, G);
  const real film = c.film != nullptr ? c.film[i] : real(0);
  real p_fluid = 0;
  if (film > 0 && s.g_dt > 0 && shepard_pressure_at(c, i, p, false, p_fluid))
    rc[i] = (1 - film) * rc[i] + film * film_relaxation_bracket(rho[i], p_fluid, s, c.kernel.h);
  if (c.kind[i] != Kind::Fluid) return;  // surfaces move with their solid; buffers are set by their boundary
  v[i] = momentum_stage(v_start[i], G[i], lap_v[i], s);
  if (s.kappa > 0) {
    const Vec<D> oe = odd_even_velocity_at(c, i, grad_v, lap_v[i]);
    v[i] += (s.dt * s.kappa) * oe;
    if (odd_even != nullptr) odd_even[i] = s.kappa * oe;
  }
}

/// The unresolved-film fraction of fluid particle i (boundary/surface_guard.hpp, film_fraction)
/// from its nearest surfaces of this step's geometry sweep; 0 for boundary particles. Computed
/// once per step into SweepContext::film, after the geometry sweep (which writes the normals).
template <int D>
PARTICULA_HD real film_fraction_at(const SweepContextOf<D>& c, std::size_t i, real film_gap) {
  if (i < c.nb || !(film_gap > 0) || c.near_a == nullptr) return 0;
  return film_fraction(gather_surfaces(c.near_a[i], c.near_b[i], SurfaceArraysOf<D>{c.x, c.normal, c.wedge, c.ds, nullptr}), film_gap, c.domain, c.x[i]);
}

/// Velocity derivatives of the new V at particle i, then its continuity stage from rho_start.
/// In an unresolved film the volume change -rho div V is left out in proportion to the film
/// fraction c.film[i] (the Rhie-Chow term stays, blended with a relaxation to the fluid
/// neighbours' pressure: rhie_chow_and_momentum_at). The fraction is read from an array: looked
/// up here, per stage, it cost 12 % of the step (docs/performance.md).
/// Race-free in one loop: the derivatives read V and the frozen volumes, never rho or P.
template <int D>
PARTICULA_HD void derivatives_and_continuity_at(const SweepContextOf<D>& c, std::size_t i, const Vec<D>* v,
                                                const real* rho_start, const real* rc, const StageParamsOf<D>& s,
                                                Mat<D>* grad_v, Vec<D>* lap_v, real* div_v, real* rho, real* p) {
  store_velocity_derivatives(c, i, v, grad_v, lap_v, div_v);
  if (!evolves_density(i, c.nb, c.kind[i], s.single_layer)) return;
  const real resolved = c.film ? 1 - c.film[i] : real(1);
  continuity_stage(rho_start[i], resolved * div_v[i], rc[i], s, rho[i], p[i]);
}

// ---- rigid surfaces ------------------------------------------------------------------------

/// Pose and motion of a rigid group as the per-particle functions need them (a plain struct
/// that can be copied to the device).
struct GroupMotion {
  Vec2 pos, vel, acc;
  real cos_angle = 1, sin_angle = 0, omega = 0, alpha = 0;
};

/// Surface particle position from the group's pose (exact rigid placement, never x += dt u).
PARTICULA_HD Vec2 surface_position(const Domain& domain, const GroupMotion& g, Vec2 local) {
  return domain.wrap(g.pos + rotate(local, g.cos_angle, g.sin_angle));
}

/// Velocity V + Omega x R and acceleration a + alpha x R - Omega^2 R of a surface point at
/// body-frame offset `local` (R = rotated offset); the acceleration feeds P.20.
PARTICULA_HD void surface_kinematics(const GroupMotion& g, Vec2 local, Vec2& v, Vec2& a) {
  const Vec2 R = rotate(local, g.cos_angle, g.sin_angle);
  v = g.vel + cross(g.omega, R);
  a = g.acc + cross(g.alpha, R) - (g.omega * g.omega) * R;
}

/// Surface traction of boundary particle i times its length dS (P.26-P.27), split into the
/// pressure part -P n dS and the viscous part n . tau dS with tau = mu (L + L^T).
PARTICULA_HD void surface_traction(real p, real ds, Vec2 n, const Mat2& L, real mu, Vec2& tp, Vec2& tv) {
  const Mat2 tau = mu * (L + transpose(L));
  tp = (-p * ds) * n;
  tv = ds * (n * tau);
}

}  // namespace particula
