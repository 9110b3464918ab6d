// The geometry sweep in 3D: geometry_at, the function the 2D solver's backends run, instantiated
// for D = 3 on the closed box of tests/box3.hpp with the 3D pair list (CSR). Its stored weights
// give gradients of linear fields exact at every particle (the zeroth-order corrected weights at
// fluid particles, P.7 at wall particles) and Laplacians of quadratic fields exact at fluid
// particles, as in 2D; the P.18 normal sums of face particles point into the fluid.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "box3_sweep.hpp"

using namespace particula;
using namespace box3;

TEST(GeometrySweep3, StoredWeightsAreExactForLinearGradientsAndQuadraticLaplacians) {
  const BoxSweep box(0.1, 2.6 * 0.1);
  const std::vector<Vec3>&x = box.x, &normal = box.normal, &grad_w = box.grad_w;
  const std::vector<real>& lap_w = box.lap_w;
  const std::vector<Where>& where = box.where;
  const std::vector<GeometryAtOf<3>>& geo = box.geo;
  const NeighborList& list = box.list;
  const std::size_t nb = box.nb;

  const Vec3 g{2.5, -1.75, 0.6};
  const Mat3 H{1.3, 0.4, -0.2, 0.4, -0.7, 0.5, -0.2, 0.5, 2.1};
  const auto u = [&](Vec3 p) { return 0.5 * dot(p, H * p) + dot(Vec3{0.2, -0.5, 0.8}, p) + 0.1; };
  int counted[3] = {0, 0, 0}, normals = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_TRUE(geo[i].B_ok) << i;
    EXPECT_TRUE(geo[i].Bhat_ok) << i;
    EXPECT_FALSE(geo[i].sparse) << i;
    Vec3 grad;
    real lap = 0;
    for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
      const std::uint32_t j = list.j[k];
      grad += gradient_pair(grad_w[k], dot(g, x[j]) - dot(g, x[i]));
      lap += lap_w[k] * (u(x[i]) - u(x[j]));
    }
    EXPECT_LT(norm(grad - g) / norm(g), 1e-10) << "particle " << i;
    if (i >= nb) {
      EXPECT_NEAR(lap, trace(H), 1e-8 * std::fabs(trace(H))) << "particle " << i;
    }
    if (i < nb &&
        std::fabs(std::fabs(normal[i].x) + std::fabs(normal[i].y) + std::fabs(normal[i].z) - 1) < 1e-12) {
      EXPECT_GT(dot(geo[i].normal_sum, normal[i]), 0) << "particle " << i;
      ++normals;
    }
    ++counted[static_cast<int>(where[i])];
  }
  EXPECT_GT(counted[static_cast<int>(Where::Interior)], 30);
  EXPECT_GT(counted[static_cast<int>(Where::NearWall)], 300);
  EXPECT_GT(counted[static_cast<int>(Where::Wall)], 300);
  EXPECT_GT(normals, 300);
}
