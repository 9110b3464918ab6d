// Probe interpolation (src/solver/interpolation.cpp): moving least squares over fluid and
// surface particles reproduces linear and quadratic fields exactly, so that a probe on a no-slip
// wall reads the wall's velocity; in a start-up Poiseuille run it reads the wall velocity at the
// walls and the series solution inside.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "case_builders.hpp"
#include "particula/analytic/solutions.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/interpolation.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

namespace {

constexpr real kL = 1e-3;

/// Points across the channel at x = 3.3 d0: both walls, next to them, and inside.
std::vector<Vec2> across(real d0) {
  std::vector<Vec2> pts;
  for (real y : {0.0, 0.1 * d0, 0.5 * d0, 1.7 * d0, 0.25 * kL, 0.5 * kL, 0.8 * kL, kL - 0.3 * d0, kL})
    pts.push_back({3.3 * d0, y});
  return pts;
}

/// Sets every particle's velocity and pressure from `u(x)` and `p(x)` (the surface particles lie
/// on the walls, where the fields below equal the walls' velocities).
template <class U, class Pr>
void set_fields(Particles& P, U u, Pr p) {
  for (std::size_t i = 0; i < P.size(); ++i) {
    P.v[i] = u(P.x[i]);
    P.p[i] = p(P.x[i]);
  }
}

WendlandC2 kernel_of(const Case& c) { return WendlandC2(c.h()); }

}  // namespace

TEST(Interpolation, LinearShearIsExactAtBothWalls) {
  const real V0 = 1.25e-5;
  const Case c = cases::startup_channel(20, V0, 0);
  Scene s = build_scene(c);
  auto u = [&](Vec2 x) { return Vec2{V0 * x.y / kL, 0}; };
  set_fields(s.particles, u, [](Vec2 x) { return 3 + 2 * x.x - 5 * x.y; });
  const auto pts = across(c.d0);
  const auto out = interpolate_at(s.particles, s.domain, kernel_of(c), pts);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    EXPECT_EQ(out[k].order, 2) << "y = " << pts[k].y;
    EXPECT_NEAR(out[k].v.x, u(pts[k]).x, 1e-12 * V0) << "y = " << pts[k].y;
    EXPECT_NEAR(out[k].v.y, 0, 1e-12 * V0);
    EXPECT_NEAR(out[k].p, 3 + 2 * pts[k].x - 5 * pts[k].y, 1e-12);
  }
  EXPECT_NEAR(out.front().v.x, 0, 1e-12 * V0);  // the wall at rest
  EXPECT_NEAR(out.back().v.x, V0, 1e-12 * V0);   // the moving wall
}

TEST(Interpolation, QuadraticProfileIsExactWhereShepardIsNot) {
  const real A = 50;  // u = A y (L - y): 1.25e-5 m/s at the centre, zero on both walls
  const Case c = cases::startup_channel(20, 0, 1e-4);
  Scene s = build_scene(c);
  auto u = [&](Vec2 x) { return Vec2{A * x.y * (kL - x.y), 0}; };
  set_fields(s.particles, u, [](Vec2 x) { return 1e6 * x.y * x.y; });
  const auto pts = across(c.d0);
  const auto out = interpolate_at(s.particles, s.domain, kernel_of(c), pts);
  const real peak = A * kL * kL / 4;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    EXPECT_NEAR(out[k].v.x, u(pts[k]).x, 1e-10 * peak) << "y = " << pts[k].y;
    EXPECT_NEAR(out[k].p, 1e6 * pts[k].y * pts[k].y, 1e-10) << "y = " << pts[k].y;
  }
  // The Shepard average over the same particles reads a speed at the wall of several % of the peak.
  const auto& P = s.particles;
  real sw = 0, su = 0;
  const WendlandC2 W = kernel_of(c);
  for (std::size_t j = 0; j < P.size(); ++j) {
    const real r = norm(s.domain.separation(P.x[j], pts.front()));
    if (r < W.h && P.kind[j] != Kind::Dummy) {
      sw += W.W(r) * P.m[j] / P.rho[j];
      su += W.W(r) * P.m[j] / P.rho[j] * P.v[j].x;
    }
  }
  EXPECT_GT(su / sw, 0.02 * peak);
}

TEST(Interpolation, TooFewPointsFallBackToLowerOrders) {
  std::vector<Vec2> dx{{0.1, 0}, {-0.2, 0}, {0.3, 0}};
  std::vector<real> w{1, 1, 1}, f{1, 2, 3};
  real value = 0;
  EXPECT_FALSE(mls_fit(1, dx, w, f, 1, &value));  // collinear points do not determine a plane
  dx = {{0.1, 0}, {-0.2, 0.1}, {0.3, -0.2}};
  ASSERT_TRUE(mls_fit(1, dx, w, f, 1, &value));   // three points: the plane through them
  EXPECT_FALSE(mls_fit(2, dx, w, f, 1, &value));  // but not a quadratic
  // f = 1 + 10 dx - 10 dy through the three points: f(0) = 1
  for (std::size_t j = 0; j < 3; ++j) f[j] = 1 + 10 * dx[j].x - 10 * dx[j].y;
  ASSERT_TRUE(mls_fit(1, dx, w, f, 1, &value));
  EXPECT_NEAR(value, 1, 1e-12);
}

TEST(Interpolation, PoiseuilleRunReadsTheWallsAndTheSeriesSolution) {
  const real F = 1e-4, nu = 1e-6, V0 = F * kL * kL / (8 * nu);
  const Case c = cases::startup_channel(20, 0, F);
  Scene sc = build_scene(c);
  Solver s(sc.params, sc.domain, sc.particles, sc.groups);
  while (s.time() < 0.3) ASSERT_FALSE(s.step().has_value());
  const auto pts = across(c.d0);
  const auto out = interpolate_at(s.particles(), s.domain(), s.kernel(), pts);
  real worst_wall = 0, worst_inside = 0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const real exact = analytic::poiseuille_startup(pts[k].y, s.time(), kL, F, nu);
    const real e = std::fabs(out[k].v.x - exact) / V0;
    const bool wall = pts[k].y == 0 || pts[k].y == kL;
    (wall ? worst_wall : worst_inside) = std::max(wall ? worst_wall : worst_inside, e);
  }
  std::printf("Poiseuille 20 at t = %.3f s: probe error %.2e at the walls, %.2e inside (of the peak speed)\n",
              s.time(), worst_wall, worst_inside);
  EXPECT_LT(worst_wall, 1e-5);
  EXPECT_LT(worst_inside, 5e-3);
}
