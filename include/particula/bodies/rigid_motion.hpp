// Rigid-body motion inside the predictor-corrector (method.md sections 8-9, P.21-P.23, P.32).
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

/// One explicit stage of a free body (P.21-P.22): from the stage-start velocities, with the
/// total force F (hydrodynamic + weight + collision) and torque T:
///   V = V0 + dt F/M,  Omega = Omega0 + dt T/I,  and the accelerations (V - V0)/dt, (Omega - Omega0)/dt
/// that the wall pressure P.20 of its surface particles needs.
void free_body_stage(RigidGroup& g, Vec2 v0, real omega0, Vec2 force, real torque, real dt);

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
