// The consistent operators in 3D (sph/operators3.hpp with the pair functions of
// sph/operators.hpp and the 3D kernel) on a randomly perturbed lattice in a closed box with a
// single layer of wall particles on its faces: gradients of linear fields exact at interior,
// near-wall and wall particles (P.7, and the zeroth-order corrected gradient at fluid particles),
// Fatehi-Manzari Laplacians of quadratic fields exact at interior and near-wall particles.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "box3.hpp"
#include "particula/sph/kernel.hpp"
#include "particula/sph/operators3.hpp"

using namespace particula;

using namespace box3;

namespace {

real relative_difference(const Mat3& a, const Mat3& b) { return std::sqrt(ddot(a - b, a - b) / ddot(b, b)); }

}  // namespace

TEST(Operators3, SymmetricEigenvalues) {
  const Quat q = axis_angle(Vec3{0.3, 0.9, -0.3} / norm(Vec3{0.3, 0.9, -0.3}), 1.3);
  const Mat3 R = rotation_matrix(q);
  const Vec3 l = symmetric_eigenvalues(R * diagonal({2.5, -0.75, 1.0}) * transpose(R));
  EXPECT_NEAR(l.x, -0.75, 1e-13);
  EXPECT_NEAR(l.y, 1.0, 1e-13);
  EXPECT_NEAR(l.z, 2.5, 1e-13);
  const Vec3 same = symmetric_eigenvalues(2 * identity3());
  EXPECT_EQ(same.x, 2);
  EXPECT_EQ(same.z, 2);
}

TEST(Operators3, GradientOfLinearFieldIsExact) {
  const real d0 = 0.1, h = 2.6 * d0;
  const Wendland<3> W(h);
  const Cloud c = perturbed_box(d0, h);
  const Mat3 A{0.37, -1.21, 0.4, 0.83, 0.52, -0.9, 0.15, 1.1, -0.3};
  const Vec3 b{0.3, -0.7, 0.2}, g{2.5, -1.75, 0.6};
  const Mat3 L_exact = transpose(A);  // L_ab = d_a V_b = A_ba
  int counted[3] = {0, 0, 0};
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const std::vector<std::size_t> nb = neighbours(c, i, h);
    Mat3 S;
    Vec3 normal_sum, support_r;
    real support = 0;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      const real F = W.F(norm(r)), Wij = W.W(norm(r));
      S += renormalization_pair(c.w[j], F, r);
      normal_sum += (c.w[j] * F) * r;
      support += c.w[j] * Wij;
      support_r += (c.w[j] * Wij) * r;
    }
    Mat3 B;
    ASSERT_TRUE(renormalization_tensor(S, B)) << "particle " << i;
    // P.7 everywhere; the zeroth-order corrected gradient at fluid particles
    Mat3 Bz = B;
    Vec3 gamma;
    bool sparse = false;
    const bool fluid = c.where[i] != Where::Wall;
    if (fluid) {
      ASSERT_TRUE(consistent_gradient_correction(S, normal_sum, support, support_r, Bz, gamma, sparse));
    }
    EXPECT_FALSE(sparse) << "particle " << i;
    Vec3 grad_p, grad_pz;
    Mat3 L, Lz;
    const real fi = dot(g, c.x[i]);
    const Vec3 vi = A * c.x[i] + b;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      const real F = W.F(norm(r)), Wij = W.W(norm(r));
      const Vec3 wBgW = c.w[j] * (B * (F * r)), wBgWz = c.w[j] * (Bz * (F * r - Wij * gamma));
      grad_p += gradient_pair(wBgW, dot(g, c.x[j]) - fi);
      grad_pz += gradient_pair(wBgWz, dot(g, c.x[j]) - fi);
      L += vector_gradient_pair(wBgW, A * c.x[j] + b - vi);
      Lz += vector_gradient_pair(wBgWz, A * c.x[j] + b - vi);
    }
    EXPECT_LT(norm(grad_p - g) / norm(g), 1e-10) << "particle " << i;
    EXPECT_LT(relative_difference(L, L_exact), 1e-10) << "particle " << i;
    if (fluid) {
      EXPECT_LT(norm(grad_pz - g) / norm(g), 1e-10) << "particle " << i;
      EXPECT_LT(relative_difference(Lz, L_exact), 1e-10) << "particle " << i;
    }
    ++counted[static_cast<int>(c.where[i])];
  }
  EXPECT_GT(counted[0], 30);
  EXPECT_GT(counted[1], 300);
  EXPECT_GT(counted[2], 300);
}

TEST(Operators3, FatehiManzariLaplacianOfQuadraticIsExact) {
  const real d0 = 0.1, h = 2.6 * d0;
  const Wendland<3> W(h);
  const Cloud c = perturbed_box(d0, h);
  // u = x.H.x / 2 + g.x + 0.1: lap u = tr H
  const Mat3 H{1.3, 0.4, -0.2, 0.4, -0.7, 0.5, -0.2, 0.5, 2.1};
  const Vec3 g{0.2, -0.5, 0.8};
  const auto u = [&](Vec3 x) { return 0.5 * dot(x, H * x) + dot(g, x) + 0.1; };
  int counted[2] = {0, 0};
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (c.where[i] == Where::Wall) continue;
    const std::vector<std::size_t> nb = neighbours(c, i, h);
    Mat3 S;
    LaplacianMoments3 m;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      const real d = norm(r);
      S += renormalization_pair(c.w[j], W.F(d), r);
      laplacian_moments_pair(m, c.w[j], d, W.dW(d), r / d);
    }
    Mat3 B, Bhat;
    ASSERT_TRUE(renormalization_tensor(S, B));
    EXPECT_TRUE(laplacian_correction_tensor(m, B, Bhat, BhatCheck::BoundedDiffusive)) << "particle " << i;
    Vec3 grad;  // P.7, which the moments' T3 B Q3 term corrects for
    for (const std::size_t j : nb)
      grad += gradient_pair(c.w[j] * (B * (W.F(norm(c.x[i] - c.x[j])) * (c.x[i] - c.x[j]))),
                            u(c.x[j]) - u(c.x[i]));
    real lap = 0;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      const real d = norm(r);
      lap += fm_laplacian_pair(fm_pair_weight(Bhat, c.w[j], W.dW(d), r / d), u(c.x[i]) - u(c.x[j]), d, r / d,
                               grad);
    }
    EXPECT_NEAR(lap, trace(H), 1e-8 * std::fabs(trace(H))) << "particle " << i;
    ++counted[static_cast<int>(c.where[i])];
  }
  EXPECT_GT(counted[0], 30);
  EXPECT_GT(counted[1], 300);
}

// A singular moment system falls back to k I, which keeps the operator exact for |x|^2 / 2
// (k = -3 / (I : M : I)): neighbours on one line give a rank-deficient system.
TEST(Operators3, SingularBhatFallsBackToNormalizedIdentity) {
  const Wendland<3> W(1.0);
  LaplacianMoments3 m;
  Mat3 S;
  for (const real s : {-0.6, -0.3, 0.3, 0.6}) {
    const Vec3 r{s, 0, 0};
    laplacian_moments_pair(m, 0.1, std::fabs(s), W.dW(std::fabs(s)), r / std::fabs(s));
    S += renormalization_pair(0.1, W.F(std::fabs(s)), r);
  }
  Mat3 Bhat;
  EXPECT_FALSE(laplacian_correction_tensor(m, identity3(), Bhat));
  EXPECT_EQ(Bhat.xy, 0);
  EXPECT_EQ(Bhat.xx, Bhat.zz);
  EXPECT_GT(Bhat.xx, 0);
  Mat3 B;
  EXPECT_FALSE(renormalization_tensor(S, B));  // rank one
  EXPECT_EQ(B.xx, 1);
}
