// The single-layer wall in 3D (boundary/wall_pressure.hpp instantiated for D = 3) on the closed box
// of tests/box3.hpp: the P.18 kernel normal of a face particle points into the fluid, and P.20
// gives every wall particle (faces, edges, corners) the hydrostatic pressure of a fluid at rest
// under gravity, exactly, as the renormalized gradient is exact for the linear field; the
// extrapolation fallback is exact for it too.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "box3.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/sph/kernel.hpp"
#include "particula/sph/operators3.hpp"

using namespace particula;
using namespace box3;

TEST(WallPressure3, HydrostaticPressureIsExactOnEveryWallParticle) {
  const real d0 = 0.1, h = 2.6 * d0, rho = 1000;
  const Wendland<3> W(h);
  const Cloud c = perturbed_box(d0, h);
  const Vec3 g{0.5, -1.0, -9.81};  // gravity kept in the fluid, tilted: every wall sees a gradient
  const auto p_exact = [&](Vec3 x) { return 2000 + rho * dot(g, x); };
  std::vector<real> p(c.x.size());
  for (std::size_t i = 0; i < c.x.size(); ++i) p[i] = p_exact(c.x[i]);
  int walls = 0, well_conditioned = 0, face_normals = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (c.where[i] != Where::Wall) continue;
    const std::vector<std::size_t> nb = neighbours(c, i, h);
    Mat3 S;
    Vec3 sum_w_gradW;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      S += renormalization_pair(c.w[j], W.F(norm(r)), r);
      sum_w_gradW += (c.w[j] * W.F(norm(r))) * r;
    }
    Mat3 B;
    ASSERT_TRUE(renormalization_tensor(S, B));
    // P.18 on a face, away from the edges: the kernel normal points into the fluid
    const Vec3 n = c.normal[i];
    Vec3 kn;
    ASSERT_TRUE(kernel_normal(sum_w_gradW, kn));
    const bool on_face = std::fabs(std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z) - 1) < 1e-12;
    const Vec3 x = c.x[i];
    const real from_edges = std::fmin(  // along the face: the distance to the nearest other face
        std::fmin(n.x != 0 ? 1e300 : std::fmin(x.x, kBoxHi.x - x.x),
                  n.y != 0 ? 1e300 : std::fmin(x.y, kBoxHi.y - x.y)),
        n.z != 0 ? 1e300 : std::fmin(x.z, kBoxHi.z - x.z));
    if (on_face && from_edges > h) {
      EXPECT_GT(dot(kn, n), 0.9) << "particle " << i;
      ++face_normals;
    }
    // P.20 with the wall at rest and no viscous term: the normal momentum balance dP/dn = rho g.n
    WallPressureSums s;
    WallExtrapolationSums e;
    for (const std::size_t j : nb) {
      const Vec3 r = c.x[i] - c.x[j];
      const real F = W.F(norm(r));
      const bool fluid = c.where[j] != Where::Wall;
      wall_pressure_pair(s, c.w[j] * (B * (F * r)), n, p[j], rho, fluid);
      if (fluid) wall_extrapolation_pair(e, W.W(norm(r)), p[j], rho, c.x[j] - c.x[i], g);
    }
    real p_wall = 0, p_extrapolated = 0;
    ASSERT_TRUE(wall_pressure(s, Vec3{}, Vec3{}, g, n, p_wall)) << "particle " << i;
    EXPECT_NEAR(p_wall, p[i], 1e-9 * 2000) << "particle " << i;
    ASSERT_TRUE(wall_extrapolation(e, p_extrapolated));
    EXPECT_NEAR(p_extrapolated, p[i], 1e-9 * 2000) << "particle " << i;
    well_conditioned += wall_pressure_well_conditioned(s, wall_pressure_min_den(rho, h)) ? 1 : 0;
    ++walls;
  }
  EXPECT_GT(walls, 600);
  EXPECT_GT(face_normals, 80);
  // the flat faces are well conditioned (the measured ratio is above 0.6 on flat walls in 2D)
  EXPECT_GT(well_conditioned, 0.8 * walls);
}
