// Wendland C2 kernel: normalization and derivative.
#include <gtest/gtest.h>

#include "particula/sph/kernel.hpp"

using namespace particula;

TEST(Kernel, NormalizedOnFineLattice) {
  const real h = 1.0;
  const WendlandC2 k(h);
  const real dx = h / 200;  // fine lattice
  real sum = 0;
  const int n = 210;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) sum += k.W(std::hypot(i * dx, j * dx)) * dx * dx;
  EXPECT_NEAR(sum, 1.0, 1e-3);
}

TEST(Kernel, NormalizedAtSolverResolution) {
  // h = 2.6 d0 as in the paper: the discrete sum is still close to one.
  const real d0 = 1.0, h = 2.6 * d0;
  const WendlandC2 k(h);
  real sum = 0;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) sum += k.W(std::hypot(i * d0, j * d0)) * d0 * d0;
  EXPECT_NEAR(sum, 1.0, 2e-2);
}

TEST(Kernel, DerivativeMatchesFiniteDifference) {
  const WendlandC2 k(0.37);
  for (real r = 0.005; r < 0.37; r += 0.013) {
    const real eps = 1e-7;
    const real fd = (k.W(r + eps) - k.W(r - eps)) / (2 * eps);
    EXPECT_NEAR(k.dW(r), fd, 1e-6 * std::fabs(k.w0) / 0.37) << "r = " << r;
    EXPECT_NEAR(k.F(r) * r, k.dW(r), 1e-12 * std::fabs(k.w0));
  }
  EXPECT_EQ(k.W(0.37), 0.0);
  EXPECT_EQ(k.dW(0.5), 0.0);
  EXPECT_LT(k.dW(0.1), 0.0);
}
