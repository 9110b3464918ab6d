// Wendland C2 kernel: normalization and derivative.
#include <gtest/gtest.h>

#include <utility>

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

// The 3D kernel is the same function of q, normalized over the ball: 4 pi int_0^h W r^2 dr = 1
// (Simpson's rule on a polynomial of degree 7 per panel: exact to round-off at 2000 panels).
TEST(Kernel, NormalizedOverTheBallIn3D) {
  const real h = 0.7;
  const Wendland<3> k(h);
  const int n = 2000;
  const real dr = h / n;
  real s = 0;
  for (int i = 0; i <= n; ++i) {
    const real r = i * dr, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += w * k.W(r) * r * r;
  }
  EXPECT_NEAR(4 * M_PI * s * dr / 3, 1.0, 1e-12);
  // and the 2D one over the disc, 2 pi int_0^h W r dr = 1, with the 2D constant unchanged
  const WendlandC2 k2(h);
  EXPECT_DOUBLE_EQ(k2.w0, 7.0 / (M_PI * h * h));
  real s2 = 0;
  for (int i = 0; i <= n; ++i) {
    const real r = i * dr, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s2 += w * k2.W(r) * r;
  }
  EXPECT_NEAR(2 * M_PI * s2 * dr / 3, 1.0, 1e-12);
}

TEST(Kernel, LatticeSumsNearOneIn3D) {
  // a fine lattice, and h = 2.6 d0: the discrete sum of the 3D kernel, as in 2D
  const real h = 1.0;
  const Wendland<3> k(h);
  for (const auto& [d0, tol] : {std::pair<real, real>{h / 40, 1e-4}, {h / 2.6, 3e-2}}) {
    const int n = static_cast<int>(h / d0) + 1;
    real sum = 0;
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j)
        for (int l = -n; l <= n; ++l) sum += k.W(d0 * std::sqrt(real(i * i + j * j + l * l))) * d0 * d0 * d0;
    EXPECT_NEAR(sum, 1.0, tol) << "d0 = " << d0;
  }
  // the derivatives are the 2D ones scaled by the constant
  const Wendland<3> k3(0.37);
  for (real r = 0.005; r < 0.37; r += 0.013) {
    const real eps = 1e-7;
    EXPECT_NEAR(k3.dW(r), (k3.W(r + eps) - k3.W(r - eps)) / (2 * eps), 1e-6 * k3.w0 / 0.37);
    EXPECT_NEAR(k3.F(r) * r, k3.dW(r), 1e-12 * k3.w0);
  }
}
