// The rotation of a free rigid body in 3D (bodies/rigid_rotation.hpp) and the 3D value types it
// uses (core/types3.hpp): conservation without torque, Euler's precession of a symmetric top,
// second-order accuracy, and the world inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "particula/bodies/rigid_rotation.hpp"

using namespace particula;

namespace {

Vec3 unit(Vec3 v) { return v / norm(v); }

real max_abs_difference(const Mat3& a, const Mat3& b) { return max_abs_entry(a - b); }

/// A body whose principal axes are not its frame's axes (as a mesh read from a file gives):
/// principal moments 1, 2, 3 (kg m^2), axes turned by 0.9 rad about (1, -1, 2).
Mat3 tilted_inertia() {
  const Mat3 R = rotation_matrix(axis_angle(unit({1, -1, 2}), 0.9));
  return R * diagonal({1, 2, 3}) * transpose(R);
}

/// Steps a torque-free body n times with rotation_update, as the solver's step does.
RotationState spin(RotationState s, const Mat3& I_inv, real dt, int n) {
  for (int k = 0; k < n; ++k) s = rotation_update(s.q, s.L, s.L, I_inv, dt);
  return s;
}

}  // namespace

TEST(Types3, QuaternionRotationMatchesItsMatrixAndComposes) {
  const Quat a = axis_angle(unit({0.3, -0.4, 1.2}), 1.1), b = axis_angle(unit({-2, 0.5, 0.1}), -0.7);
  const Mat3 Ra = rotation_matrix(a), Rb = rotation_matrix(b);
  EXPECT_LT(max_abs_difference(Ra * transpose(Ra), identity3()), 1e-15);
  EXPECT_NEAR(det(Ra), 1, 1e-15);
  EXPECT_LT(max_abs_difference(rotation_matrix(a * b), Ra * Rb), 1e-15);  // b first, then a
  // a quarter turn about z takes x to y
  const Vec3 y = rotate(axis_angle({0, 0, 1}, M_PI / 2), {1, 0, 0});
  EXPECT_NEAR(y.x, 0, 1e-15);
  EXPECT_NEAR(y.y, 1, 1e-15);
  const Vec3 v{0.2, -1.5, 0.7};
  const Vec3 back = rotate_back(a, rotate(a, v));
  EXPECT_NEAR(norm(back - v), 0, 1e-15);
  // the Cayley rotation of phi turns about phi by 2 atan(|phi| / 2)
  const Vec3 phi{0.3, 0.1, -0.2};
  const Quat c = cayley_rotation(phi), e = axis_angle(unit(phi), 2 * std::atan(0.5 * norm(phi)));
  EXPECT_LT(max_abs_difference(rotation_matrix(c), rotation_matrix(e)), 1e-15);
  Mat3 inv;
  ASSERT_TRUE(inverse(tilted_inertia(), inv));
  EXPECT_LT(max_abs_difference(inv * tilted_inertia(), identity3()), 1e-14);
  EXPECT_FALSE(inverse(outer(v, v), inv));  // rank one
  EXPECT_NEAR(norm(cross(Vec3{1, 0, 0}, Vec3{0, 1, 0}) - Vec3{0, 0, 1}), 0, 0);
}

TEST(RigidRotation, WorldInertiaTurnsWithTheBody) {
  // a quarter turn about z swaps the x and y moments of a body whose axes are its frame's
  const Mat3 I = world_inertia(axis_angle({0, 0, 1}, M_PI / 2), diagonal({1, 2, 3}));
  EXPECT_LT(max_abs_difference(I, diagonal({2, 1, 3})), 1e-15);
  // and Omega = I_w^-1 L at any orientation
  const Quat q = axis_angle(unit({1, 2, 3}), 0.4);
  Mat3 I_inv;
  ASSERT_TRUE(inverse(tilted_inertia(), I_inv));
  const Vec3 omega{0.3, -1.2, 2.0};
  const Vec3 L = world_inertia(q, tilted_inertia()) * omega;
  EXPECT_LT(norm(angular_velocity(q, I_inv, L) - omega), 1e-14);
}

// A torque-free body with three different principal moments, spinning about a tilted axis, keeps
// its kinetic energy and angular momentum to 1e-10 relative over 1e4 steps while it tumbles.
TEST(RigidRotation, TorqueFreeBodyKeepsEnergyAndAngularMomentum) {
  const Mat3 I_body = tilted_inertia();
  Mat3 I_inv;
  ASSERT_TRUE(inverse(I_body, I_inv));
  RotationState s;
  s.q = axis_angle(unit({1, 2, 3}), 0.7);
  s.omega = {0.3, -1.2, 2.0};  // rad/s, world frame
  s.L = world_inertia(s.q, I_body) * s.omega;
  const real E0 = 0.5 * dot(s.L, s.omega);
  const Vec3 L0 = s.L, omega0 = s.omega;
  const real dt = 1e-3;  // |Omega| dt = 2.4e-3; 1e4 steps are about 4 turns
  const RotationState end = spin(s, I_inv, dt, 10000);
  // measured as a user would, from the orientation and angular velocity the body reports
  const Vec3 L = world_inertia(end.q, I_body) * end.omega;
  const real E = 0.5 * dot(end.omega, world_inertia(end.q, I_body) * end.omega);
  EXPECT_LT(std::fabs(E - E0) / E0, 1e-10);
  EXPECT_LT(norm(L - L0) / norm(L0), 1e-10);
  EXPECT_NEAR(end.q.w * end.q.w + end.q.x * end.q.x + end.q.y * end.q.y + end.q.z * end.q.z, 1, 1e-14);
  // it tumbles: the angular velocity is not a constant of this motion
  EXPECT_GT(norm(end.omega - omega0), 0.1 * norm(omega0));
}

// A symmetric top (I1 = I2 = I, I3) without torque: in the body frame Omega turns about the
// symmetry axis at lambda = (I3 - I) Omega_3 / I; in the world the symmetry axis turns about L at
// |L| / I. The scheme follows both to second order in dt.
TEST(RigidRotation, SymmetricTopPrecessesAsEulerSays) {
  const real I = 2, I3 = 0.5, A = 0.8, W3 = 3;  // kg m^2, rad/s
  const Mat3 I_body = diagonal({I, I, I3}), I_inv = diagonal({1 / I, 1 / I, 1 / I3});
  const real T = 2.0, lambda = (I3 - I) * W3 / I;
  const auto errors = [&](int n) {
    RotationState s;
    s.q = axis_angle(unit({0.2, 1, -0.3}), 0.5);
    s.omega = rotate(s.q, {A, 0, W3});
    s.L = world_inertia(s.q, I_body) * s.omega;
    const Vec3 e3_0 = rotate(s.q, {0, 0, 1});
    const RotationState end = spin(s, I_inv, T / n, n);
    // body frame: Omega_b(T) = (A cos lambda T, A sin lambda T, Omega_3)
    const Vec3 omega_b = rotate_back(end.q, end.omega);
    const real body_err = norm(omega_b - Vec3{A * std::cos(lambda * T), A * std::sin(lambda * T), W3});
    // world frame: the symmetry axis turned about L by |L| T / I
    const Vec3 e3_exact = rotate(axis_angle(unit(s.L), norm(s.L) * T / I), e3_0);
    const real axis_err = norm(rotate(end.q, {0, 0, 1}) - e3_exact);
    return std::pair<real, real>{body_err, axis_err};
  };
  const auto [b1, a1] = errors(400);
  const auto [b2, a2] = errors(800);
  EXPECT_LT(b1, 2e-3 * A);
  EXPECT_LT(a1, 2e-3);
  // the observed order, log2 of the error ratio at dt and dt / 2
  EXPECT_NEAR(std::log2(b1 / b2), 2, 0.1);
  EXPECT_NEAR(std::log2(a1 / a2), 2, 0.1);
}

// A constant torque about a principal axis from rest, through the predictor-corrector's two
// stages and the end of step: L grows exactly as T t, the angle as T t^2 / (2 I) to second order.
TEST(RigidRotation, ConstantTorqueSpinsUpAboutItsAxis) {
  const Mat3 I_inv = diagonal({1, 0.5, 1 / 3.0});
  const Vec3 torque{0, 0, 0.6};  // N m, along the body's third axis (I3 = 3)
  const auto angle_error = [&](int n) {
    const real dt = 1.0 / n;
    RotationState s;
    for (int k = 0; k < n; ++k) {
      const Vec3 L_star = rotation_stage(s.L, torque, dt);     // predictor
      const Vec3 L_corr = rotation_stage(L_star, torque, dt);  // corrector from the predicted state
      s = rotation_update(s.q, s.L, L_corr, I_inv, dt);
    }
    EXPECT_NEAR(norm(s.L - torque), 0, 1e-13);  // L(1) = T
    EXPECT_NEAR(norm(s.omega - torque / 3.0), 0, 1e-13);
    const real angle = 2 * std::atan2(s.q.z, s.q.w);
    EXPECT_NEAR(std::hypot(s.q.x, s.q.y), 0, 1e-15);  // it turns about z only
    return std::fabs(angle - 0.6 / (2 * 3.0));
  };
  const real e1 = angle_error(50), e2 = angle_error(100);
  EXPECT_LT(e1, 1e-5);
  EXPECT_NEAR(std::log2(e1 / e2), 2, 0.1);  // second order
}
