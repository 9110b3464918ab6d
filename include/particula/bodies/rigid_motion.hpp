// Rigid-body motion inside the predictor-corrector (docs/method.md sections 8-9, P.21-P.23, P.32).
#pragma once

#include <vector>

#include "particula/case/case.hpp"
#include "particula/core/types.hpp"
#include "particula/solver/rigid_group.hpp"

namespace particula {

/// Buoyancy-corrected weight (P.23): b_s = (M_s - rho_f A_s) g when gravity is removed from the
/// fluid (P is the dynamic pressure); M_s g when gravity is kept in the fluid (the hydrostatic
/// pressure on the surface then supplies the buoyancy).
PARTICULA_HD Vec2 body_weight(real mass, real area, real rho_fluid, Vec2 g, bool gravity_in_fluid) {
  return (gravity_in_fluid ? mass : mass - rho_fluid * area) * g;
}

/// Added mass that keeps the explicit coupling of a body lighter than the fluid stable
/// (docs/method.md, "Light bodies"): m_s = max(0, rho_f A - M). The fluid's reaction to the
/// body's acceleration (its added mass m_a, rho_f A for a circle in 2D) reaches the body one stage
/// late through P.20, so V = V0 + dt F/M multiplies an acceleration error by about -m_a/M per
/// stage: unstable for a body much lighter than the fluid (circles of rho_s = 50-200 in water
/// blew up within 3-28 steps; 300 ran). With m_s the factor is (m_s - m_a) / (M + m_s), which is
/// -rho_s/rho_f for m_a = rho_f A and below 1 in magnitude for any m_a < 2 rho_f A - M. Zero for
/// bodies at least as dense as the fluid, whose stages stay the paper's.
PARTICULA_HD real stabilizing_added_mass(real rho_fluid, real area, real mass) {
  const real m = rho_fluid * area - mass;
  return m > 0 ? m : real(0);
}

/// One explicit stage of a free body (P.21-P.22): from the stage-start velocities, with the
/// total force F (hydrodynamic + weight + collision) and torque T:
///   a = (F + m_s a_prev) / (M + m_s),  V = V0 + dt a,  Omega = Omega0 + dt T/I,
/// and the accelerations a, (Omega - Omega0)/dt that the wall pressure P.20 of its surface
/// particles needs. a_prev is the body's acceleration of the previous stage (g.acc) and m_s the
/// stabilizing added mass (stabilizing_added_mass; 0: the paper's V = V0 + dt F/M). The two
/// m_s a terms cancel when the acceleration settles, so the stage is consistent; in between the
/// amplification factor of an acceleration error is (m_s - m_a) / (M + m_s).
void free_body_stage(RigidGroup& g, Vec2 v0, real omega0, Vec2 force, real torque, real dt, real added_mass = 0);

/// End of step (P.32 for the velocities): V^{n+1} = (V** + V^n)/2, the same for Omega, and the
/// centre and angle advanced with the mean of the old and new velocities, which is exact for a
/// constant acceleration (P.32's r += dt V^{n+1} is first order for the body centre).
void free_body_update(RigidGroup& g, Vec2 v_n, real omega_n, real dt);

/// Prescribed motion at time t: constant velocity, or piecewise linear in time from the knots
/// (constant before the first and after the last). Sets vel, omega, acc, alpha and the
/// displacement / rotation since t = 0 (exact integral of the piecewise-linear velocity).
struct PrescribedState {
  Vec2 vel, acc, displacement;
  real omega = 0, alpha = 0, rotation = 0;
};
PrescribedState prescribed_state(const std::vector<MotionKnot>& knots, Vec2 vel, real omega, real t);

}  // namespace particula
