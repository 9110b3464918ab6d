// The stage sweeps of solver/sweeps.hpp instantiated for D = 3, the functions the backends run,
// on the closed box of tests/box3.hpp with the geometry sweep's stored weights: velocity
// derivatives, pressure gradient, the Rhie-Chow bracket, P.20, the momentum and continuity
// stages, the odd-even damping, shifting with its Taylor corrections and the health check, each
// against fields whose exact values are known.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "box3_sweep.hpp"
#include "particula/solver/sweeps.hpp"

using namespace particula;
using namespace box3;

namespace {

const Mat3 kA{0.3, -1.1, 0.4, 0.7, 0.2, -0.6, -0.5, 0.9, -0.5};  // grad V of the linear field (trace 0)
const Vec3 kV0{0.1, -0.2, 0.05};

Vec3 linear_velocity(Vec3 x) { return kV0 + x * kA; }  // V_b = V0_b + x_a A_ab, so d_a V_b = A_ab

real max_abs(const Mat3& m) { return max_abs_entry(m); }

}  // namespace

TEST(Sweeps3, VelocityDerivativesAreExactForLinearFieldsAndTheLaplacianForQuadraticOnes) {
  const BoxSweep box(0.1, 0.26);
  const std::size_t n = box.x.size();
  // linear: grad V exact at every particle, lap V = 0 and div V = tr A = 0
  std::vector<Vec3> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = linear_velocity(box.x[i]);
  std::vector<Mat3> L(n);
  std::vector<Vec3> lap(n);
  std::vector<real> div(n);
  for (std::size_t i = 0; i < n; ++i)
    store_velocity_derivatives(box.c, i, v.data(), L.data(), lap.data(), div.data());
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_LT(max_abs(L[i] - kA), 1e-10) << i;
    EXPECT_NEAR(div[i], trace(L[i]), 1e-15) << i;
    if (i >= box.nb) {
      EXPECT_LT(norm(lap[i]), 1e-8) << i;
    }
  }
  // quadratic: V_b = 1/2 x . H_b x per component, lap V_b = tr H_b at every fluid particle
  const Mat3 H[3] = {{1.3, 0.4, -0.2, 0.4, -0.7, 0.5, -0.2, 0.5, 2.1},
                     {0.2, 0.1, 0.3, 0.1, 1.5, -0.4, 0.3, -0.4, -0.6},
                     {-1.0, 0.2, 0.0, 0.2, 0.4, 0.8, 0.0, 0.8, 0.9}};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = box.x[i];
    v[i] = {0.5 * dot(p, H[0] * p), 0.5 * dot(p, H[1] * p), 0.5 * dot(p, H[2] * p)};
  }
  for (std::size_t i = box.nb; i < n; ++i) {
    Mat3 Li;
    Vec3 lapi;
    velocity_derivatives_at(box.c, i, v.data(), Li, lapi);
    EXPECT_NEAR(lapi.x, trace(H[0]), 1e-8) << i;
    EXPECT_NEAR(lapi.y, trace(H[1]), 1e-8) << i;
    EXPECT_NEAR(lapi.z, trace(H[2]), 1e-8) << i;
  }
}

TEST(Sweeps3, HydrostaticBoxIsAtRestAndP20GivesTheWallsTheHydrostaticPressure) {
  // A fluid at rest under a tilted gravity kept in the fluid, P = p0 + rho0 g . x at uniform
  // density: the momentum stage leaves every fluid particle at rest, the Rhie-Chow bracket
  // vanishes (G is uniform, P linear), the continuity stage keeps rho0, and P.20 at every wall
  // particle (faces, edges, corners) returns the hydrostatic pressure it was given.
  const BoxSweep box(0.1, 0.26);
  const std::size_t n = box.x.size();
  const Vec3 g{1.5, -9.81, 2.0};
  StageParamsOf<3> s;
  s.dt = 1e-4;
  s.g_dt = 1.0 * s.dt;
  s.nu = 1e-3;
  s.f = g;
  s.rho0 = 1000;
  s.c = 20;
  s.p0 = 50;
  s.kappa = 0.05 * s.c * box.h;
  std::vector<real> p(n), rho(n, s.rho0), rc(n, 7.0), div(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = s.p0 + s.rho0 * dot(g, box.x[i]);
  std::vector<Vec3> G(n), v(n), v_start(n), lap(n), odd_even(n);
  std::vector<Mat3> L(n);
  for (std::size_t i = 0; i < n; ++i) G[i] = pressure_gradient_at(box.c, i, p.data(), rho.data());
  for (std::size_t i = 0; i < n; ++i) EXPECT_LT(norm(G[i] - g), 1e-10 * norm(g)) << i;
  for (std::size_t i = 0; i < n; ++i)
    store_velocity_derivatives(box.c, i, v.data(), L.data(), lap.data(), div.data());
  for (std::size_t i = 0; i < n; ++i)
    rhie_chow_and_momentum_at(box.c, i, p.data(), rho.data(), G.data(), L.data(), lap.data(), v_start.data(),
                              s, rc.data(), v.data(), odd_even.data());
  // (P.16) the bracket of a linear P is 0 (its scale here |g| / d0 = 100 m/s^2/m)
  for (std::size_t i = box.nb; i < n; ++i) {
    EXPECT_LT(std::fabs(rc[i]), 1e-6) << i;
    EXPECT_LT(norm(v[i]), 1e-12) << i;
  }
  std::vector<real> rho_new(n), p_new(n);
  for (std::size_t i = 0; i < n; ++i)
    derivatives_and_continuity_at(box.c, i, v.data(), rho.data(), rc.data(), s, L.data(), lap.data(),
                                  div.data(), rho_new.data(), p_new.data());
  for (std::size_t i = box.nb; i < n; ++i) EXPECT_NEAR(rho_new[i], s.rho0, 1e-10 * s.rho0) << i;

  // P.20: every wall particle, from the exact pressures around it, with no surface motion
  int solved = 0;
  for (std::size_t i = 0; i < box.nb; ++i) {
    real p_out = std::numeric_limits<real>::quiet_NaN();
    const WallPressureOutcome o =
        wall_pressure_at(box.c, i, p.data(), rho.data(), box.normal[i], Vec3{}, Vec3{}, g,
                         wall_pressure_min_den(s.rho0, box.h), 0, s.p0, p_out);
    EXPECT_NE(o, WallPressureOutcome::Kept) << i;
    solved += o == WallPressureOutcome::Solved;
    EXPECT_NEAR(p_out, p[i], 1e-9 * std::fabs(p[i])) << i;
  }
  EXPECT_GT(solved, static_cast<int>(box.nb) / 2);
}

TEST(Sweeps3, OddEvenDampingVanishesOnLinearFieldsAndOpposesACheckerboard) {
  const BoxSweep box(0.1, 0.26);
  const std::size_t n = box.x.size();
  std::vector<Vec3> v(n), lap(n);
  std::vector<Mat3> L(n);
  std::vector<real> div(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = linear_velocity(box.x[i]);
  for (std::size_t i = 0; i < n; ++i)
    store_velocity_derivatives(box.c, i, v.data(), L.data(), lap.data(), div.data());
  for (std::size_t i = box.nb; i < n; ++i)
    EXPECT_LT(norm(odd_even_velocity_at(box.c, i, L.data(), lap[i])), 1e-8) << i;
  // an odd-even mode of the lattice (x velocity +-1 on alternate cells): the damping pulls each
  // interior particle's velocity towards its neighbours' mean, against its own sign
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 q = box.x[i] / box.d0;
    const long parity =
        std::lround(std::floor(q.x)) + std::lround(std::floor(q.y)) + std::lround(std::floor(q.z));
    v[i] = i < box.nb ? Vec3{} : Vec3{parity % 2 == 0 ? 1.0 : -1.0, 0, 0};
  }
  for (std::size_t i = 0; i < n; ++i)
    store_velocity_derivatives(box.c, i, v.data(), L.data(), lap.data(), div.data());
  int interior = 0;
  for (std::size_t i = box.nb; i < n; ++i) {
    if (box.where[i] != Where::Interior) continue;
    ++interior;
    EXPECT_LT(odd_even_velocity_at(box.c, i, L.data(), lap[i]).x * v[i].x, 0) << i;
  }
  EXPECT_GT(interior, 30);
}

TEST(Sweeps3, ShiftingCarriesLinearFieldsToTheNewPositionExactly) {
  // P.33-P.36: V, P and rho corrected to first order; exact for linear fields (the surface limit
  // does nothing away from surfaces).
  const Domain3 domain{{0, 0, 0}, {1, 1, 1}, false, false, false};
  const Vec3 gp{0.3, -2.0, 0.7};  // grad P / rho
  const real c = 15;
  Vec3 x{0.4, 0.5, 0.6}, v = linear_velocity(x);
  real rho = 1001, p = 42;
  const Vec3 dir{0.2, -0.1, 0.3};
  const real scale = 0.01;
  shift_particle(dir, scale, kA, gp, NearSurfacesOf<3>{}, 0.1, domain, c, x, v, p, rho);
  const Vec3 dr = scale * dir;
  EXPECT_LT(norm(x - (Vec3{0.4, 0.5, 0.6} + dr)), 1e-15);
  EXPECT_LT(norm(v - linear_velocity(x)), 1e-14);
  EXPECT_NEAR(p, 42 + 1001 * dot(dr, gp), 1e-12);
  EXPECT_NEAR(rho, 1001 + 1001 * dot(dr, gp) / (c * c), 1e-12);
}

TEST(Sweeps3, EndOfStepAndHealthCheckInThreeDimensions) {
  const Domain3 domain{{0, 0, 0}, {1, 1, 1}, false, false, true};
  // fluid: mean velocity, position advanced and wrapped along the periodic z axis
  Vec3 x{0.5, 0.5, 0.99}, v{0, 0, 2};
  real rho = 1002, p = 3;
  const real v2 =
      end_of_step_update(5, 1, Kind::Fluid, domain, 0.01, true, Vec3{0, 0, 1}, 1000, 1, x, v, rho, p);
  EXPECT_DOUBLE_EQ(v.z, 1.5);
  EXPECT_NEAR(x.z, 0.005, 1e-12);
  EXPECT_DOUBLE_EQ(rho, 1001);
  EXPECT_DOUBLE_EQ(p, 2);
  EXPECT_DOUBLE_EQ(v2, 2.25);

  HealthLimitsOf<3> lim;
  lim.rho_lo = 900;
  lim.rho_hi = 1100;
  lim.h = 0.05;
  lim.domain = Domain3{{0, 0, 0}, {1, 1, 1}, false, false, false};
  EXPECT_FALSE(particle_unhealthy(true, Vec3{0.5, 0.5, 0.5}, Vec3{}, 1000, 0, lim));
  EXPECT_TRUE(particle_unhealthy(true, Vec3{0.5, 0.5, 1.1}, Vec3{}, 1000, 0, lim));    // beyond z = 1 + h
  EXPECT_FALSE(particle_unhealthy(true, Vec3{0.5, 0.5, 1.04}, Vec3{}, 1000, 0, lim));  // within h
  EXPECT_TRUE(particle_unhealthy(false, Vec3{0.5, 0.5, 0.5}, Vec3{0, 0, std::nan("")}, 1000, 0, lim));
  EXPECT_TRUE(particle_unhealthy(true, Vec3{0.5, 0.5, 0.5}, Vec3{}, 1200, 0, lim));
  lim.domain.periodic_z = true;
  EXPECT_FALSE(particle_unhealthy(true, Vec3{0.5, 0.5, 1.1}, Vec3{}, 1000, 0, lim));
}
