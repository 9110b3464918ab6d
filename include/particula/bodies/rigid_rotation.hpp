// The rotation of a free rigid body in 3D inside the predictor-corrector (docs/method.md,
// "Rigid bodies in 3D"): the orientation a unit quaternion q, the inertia tensor fixed in the body
// frame, the state advanced through the world-frame angular momentum L, so that Euler's equations
// with their gyroscopic term,
//   I dOmega/dt + Omega x (I Omega) = T   (body frame)   <=>   dL/dt = T   (world frame),
// come out of Omega = I_w^-1 L with the world inertia I_w = R I_b R^T of the current orientation.
// In 2D the same scheme is the one of bodies/rigid_motion.hpp (L = I omega, a rotation about z).
#pragma once

#include "particula/core/types3.hpp"

namespace particula {

/// The world-frame inertia tensor I_w = R I_b R^T of a body at orientation q.
PARTICULA_HD Mat3 world_inertia(const Quat& q, const Mat3& I_body) {
  const Mat3 R = rotation_matrix(q);
  return R * I_body * transpose(R);
}

/// The angular velocity of angular momentum L (world frame) at orientation q:
///   Omega = R I_b^-1 R^T L.
PARTICULA_HD Vec3 angular_velocity(const Quat& q, const Mat3& I_body_inv, Vec3 L) {
  return rotate(q, I_body_inv * rotate_back(q, L));
}

/// The kinetic energy of the rotation, E = L . Omega / 2.
PARTICULA_HD real rotational_energy(const Quat& q, const Mat3& I_body_inv, Vec3 L) {
  return 0.5 * dot(L, angular_velocity(q, I_body_inv, L));
}

/// One explicit stage of a free body's rotation (P.22 in 3D): from the stage-start angular
/// momentum L0 with the torque T about the centre of mass (world frame),
///   L = L0 + dt T,   Omega = I_w^-1 L,
/// at the orientation of the step's start (positions, and so orientations, are frozen during the
/// stages). The gyroscopic term is in the orientation's change, applied at the end of the step.
PARTICULA_HD Vec3 rotation_stage(Vec3 L0, Vec3 T, real dt) { return L0 + dt * T; }

/// The largest number of fixed-point iterations of free_rotation; each multiplies the error by
/// about dt |Omega| I_max / I_min, below 1e-3 at any step the fluid allows.
inline constexpr int kFreeRotationIterations = 50;

/// The torque-free rotation of a body over dt at the constant world angular momentum L: the
/// implicit midpoint rule for Euler's equations in the body frame,
///   L_b' = L_b + dt (L_m x Omega_m),  L_m = (L_b + L_b') / 2,  Omega_m = I_b^-1 L_m,
/// solved by fixed-point iteration to round-off, and the orientation turned by the rotation that
/// takes L_b to L_b', the Cayley rotation of dt Omega_m (q' = q c(dt Omega_m), a body-frame
/// increment). Both quadratic invariants of the motion, |L_b|^2 and the energy L_b . I_b^-1 L_b / 2,
/// are invariants of the midpoint rule, and R' L_b' = R L_b = L: a torque-free body keeps its
/// energy and angular momentum to round-off over any number of steps (the exponential map with
/// the start or mean angular velocity drifts by O(dt^2) per unit time). Second order.
PARTICULA_HD Quat free_rotation(const Quat& q, Vec3 L, const Mat3& I_body_inv, real dt) {
  const Vec3 Lb0 = rotate_back(q, L);
  const real tol = 1e-15 * norm(Lb0);
  Vec3 Lb1 = Lb0;
  for (int it = 0; it < kFreeRotationIterations; ++it) {
    const Vec3 Lm = 0.5 * (Lb0 + Lb1);
    const Vec3 next = Lb0 + dt * cross(Lm, I_body_inv * Lm);
    const real change = norm(next - Lb1);
    Lb1 = next;
    if (!(change > tol)) break;
  }
  const Vec3 omega_m = I_body_inv * (0.5 * (Lb0 + Lb1));
  return normalized(q * cayley_rotation(dt * omega_m));
}

/// The rotational state of a free body in 3D: orientation, world angular momentum and the
/// angular velocity it gives at that orientation.
struct RotationState {
  Quat q;
  Vec3 L, omega;
};

/// End of step for the rotation (P.32 in 3D): from the step's start (q^n, L^n) and the corrector's
/// L** (two stages of torque), L^{n+1} = (L** + L^n) / 2 = L^n + dt (T^n + T*) / 2; the orientation
/// turns by the torque-free rotation at the mean angular momentum (L^n + L^{n+1}) / 2 (a symmetric
/// splitting: half of the step's torque impulse, the free rotation, the other half), and
/// Omega^{n+1} = I_w(q^{n+1})^-1 L^{n+1}. In 2D this is angle += dt (omega^n + omega^{n+1}) / 2.
PARTICULA_HD RotationState rotation_update(const Quat& q_n, Vec3 L_n, Vec3 L_corrected,
                                           const Mat3& I_body_inv, real dt) {
  RotationState s;
  s.L = 0.5 * (L_corrected + L_n);
  s.q = free_rotation(q_n, 0.5 * (L_n + s.L), I_body_inv, dt);
  s.omega = angular_velocity(s.q, I_body_inv, s.L);
  return s;
}

}  // namespace particula
