// Rigid-body motion inside the predictor-corrector (docs/method.md sections 8-9, P.21-P.23, P.32)
// and the stabilization of light bodies ("Light bodies", M.36, M.47, M.48).
#pragma once

#include <vector>

#include "particula/case/case.hpp"
#include "particula/core/types.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/solver/rigid_group.hpp"

namespace particula {

/// Buoyancy-corrected weight (P.23): b_s = (M_s - rho_f A_s) g when gravity is removed from the
/// fluid (P is the dynamic pressure); M_s g when gravity is kept in the fluid (the hydrostatic
/// pressure on the surface then supplies the buoyancy).
PARTICULA_HD Vec2 body_weight(real mass, real area, real rho_fluid, Vec2 g, bool gravity_in_fluid) {
  return (gravity_in_fluid ? mass : mass - rho_fluid * area) * g;
}

/// Moments of a body's surface about its centroid (body frame), the geometry of the fluid's
/// one-stage answer to the body's acceleration (docs/method.md, "Light bodies"): with r the
/// position from the centroid, n the outward normal and the sums over the surface samples,
///   length = sum ds,  normal = largest eigenvalue of sum n n^T ds  (translation),
///   lever = sum (r x n)^2 ds  (0 for a circle),  radius = sum |r|^2 ds  (rotation).
struct SurfaceMoments {
  real length = 0, normal = 0, lever = 0, radius = 0;
};
SurfaceMoments surface_moments(const std::vector<SurfaceSample>& samples);

/// The added mass and moment of inertia with which the fluid next to a surface answers a body's
/// acceleration within one stage (docs/method.md, "Light bodies"): the wall pressure (P.20)
/// rho L a.n over a layer L of about d0 (measured 0.5-0.9 d0), and the viscous stress of a stage,
/// rho nu dt a / L_v, with L_v about d0 / 3 (measured d0 / 2.9 to d0 / 2.0):
///   m_1 = rho_f ( d0 normal + (3 nu dt / d0) length ),
///   I_1 = rho_f ( d0 lever  + (3 nu dt / d0) radius ).
PARTICULA_HD real stage_added_mass(real rho_fluid, real d0, real nu, real dt, SurfaceMoments m) {
  return rho_fluid * (d0 * m.normal + (3 * nu * dt / d0) * m.length);
}
PARTICULA_HD real stage_added_inertia(real rho_fluid, real d0, real nu, real dt, SurfaceMoments m) {
  return rho_fluid * (d0 * m.lever + (3 * nu * dt / d0) * m.radius);
}

/// Added mass that keeps the explicit coupling of a light body stable (docs/method.md, "Light
/// bodies"): m_s = max(0, max(rho_f A, 2 m_1) - M), m_1 = stage_added_mass. The fluid's reaction
/// to the body's acceleration reaches the body one stage late, so V = V0 + dt F/M multiplies an
/// acceleration error by -m_a/M per stage, m_a the reaction's added mass: unstable for a body
/// lighter than it (circles of rho_s = 50-200 in water blew up within 3-28 steps; 300 ran). With
/// m_s the factor is (m_s - m_a) / (M + m_s), below 1 in magnitude for any m_a < 2 m_s + M. rho_f A
/// (a circle's potential-flow added mass) is the larger term for bodies 10 particles across;
/// 2 m_1 covers coarse or slender ones. Zero for a body with M >= max(rho_f A, 2 m_1): the paper's
/// stage.
PARTICULA_HD real stabilizing_added_mass(real rho_fluid, real area, real mass, real stage_mass = 0) {
  const real fluid = rho_fluid * area, m = (fluid > 2 * stage_mass ? fluid : 2 * stage_mass) - mass;
  return m > 0 ? m : real(0);
}

/// Stabilizing added moment of inertia of a free body's rotation, the counterpart of m_s:
/// I_s = max(0, 2 I_1 - I), I_1 = stage_added_inertia (docs/method.md, "Light bodies"). The
/// amplification factor of an angular-acceleration error per stage is (I_s - I_a) / (I + I_s)
/// for a one-stage reaction I_a: below 1 in magnitude for any I_a < 2 I_s + I = 4 I_1 - I (twice
/// the estimate), about 1/2 for I_a = I_1. Zero (the paper's stage) for a body with I >= 2 I_1.
PARTICULA_HD real stabilizing_added_inertia(real stage_inertia, real inertia) {
  const real i = 2 * stage_inertia - inertia;
  return i > 0 ? i : real(0);
}

/// One explicit stage of a free body (P.21-P.22, M.7): from the stage-start velocities, with the
/// total force F (hydrodynamic + weight + collision) and torque T:
///   a = (F + m_s a_prev) / (M + m_s),  V = V0 + dt a,
///   alpha = (T + I_s alpha_prev) / (I + I_s),  Omega = Omega0 + dt alpha,
/// and the accelerations a, alpha that the wall pressure P.20 of its surface particles needs.
/// a_prev, alpha_prev are the body's accelerations of the previous stage (g.acc, g.alpha), m_s
/// and I_s the stabilizing added mass and moment of inertia (stabilizing_added_mass,
/// stabilizing_added_inertia; 0: the paper's V = V0 + dt F/M, Omega = Omega0 + dt T/I). The two
/// m_s a (I_s alpha) terms cancel when the acceleration settles, so the stage is consistent; in
/// between the amplification factor of an acceleration error is (m_s - m_a) / (M + m_s), that of
/// an angular one (I_s - I_a) / (I + I_s).
void free_body_stage(RigidGroup& g, Vec2 v0, real omega0, Vec2 force, real torque, real dt,
                     real added_mass = 0, real added_inertia = 0);

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
