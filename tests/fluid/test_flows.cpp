// Validated fluid solver: start-up Couette and Poiseuille flows against their series
// solutions, the Taylor-Green vortex decay, and a fluid at rest under gravity
// (reference/README.md). Coarse but tight enough to catch a wrong term.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "case_builders.hpp"
#include "particula/analytic/solutions.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

namespace {

Solver make_solver(const Case& c) {
  Scene s = build_scene(c);
  return Solver(s.params, s.domain, s.particles, s.groups);
}

void run_to(Solver& s, real t) {
  while (s.time() < t - 1e-12) {
    auto f = s.step();
    ASSERT_FALSE(f.has_value()) << f->what;
  }
}

/// L2 error of u_x over fluid particles against `exact(y, t)`, relative to `peak`.
template <class Exact>
real profile_error(const Solver& s, Exact exact, real peak) {
  const auto& P = s.particles();
  real sum = 0;
  std::size_t n = 0;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
    const real e = P.v[i].x - exact(P.x[i].y, s.time());
    sum += e * e;
    ++n;
  }
  return std::sqrt(sum / n) / peak;
}

/// A closed H x H box of water (nu = 1e-6) 40 particles high, starting from the hydrostatic
/// state with gravity g in the fluid, c = 20 sqrt(g H).
Case hydrostatic_box(real H, real g) {
  Case c = cases::closed_box(H, H, H / 40);
  c.gravity = {0, -g};
  c.gravity_in_fluid = true;
  c.hydrostatic = true;
  c.nu = 1e-6;
  c.c = 20 * std::sqrt(g * H);
  return c;
}

}  // namespace

TEST(Flows, CouetteStartup40) {
  const real V0 = 1.25e-5, L = 1e-3, nu = 1e-6;
  Case c = cases::startup_channel(40, V0, 0);
  Solver s = make_solver(c);
  auto exact = [&](real y, real t) { return analytic::couette_startup(y, t, L, V0, nu); };
  run_to(s, 0.1125);
  const real early = profile_error(s, exact, V0);
  run_to(s, 1.5);
  const real steady = profile_error(s, exact, V0);
  std::printf("Couette 40: error %.4f %% at t = 0.1125 s, %.4f %% at t = 1.5 s (%lld steps)\n", 100 * early,
              100 * steady, static_cast<long long>(s.step_count()));
  EXPECT_LT(early, 0.02);
  EXPECT_LT(steady, 0.01);
}

TEST(Flows, PoiseuilleStartup40) {
  const real F = 1e-4, L = 1e-3, nu = 1e-6, V0 = F * L * L / (8 * nu);
  Case c = cases::startup_channel(40, 0, F);
  Solver s = make_solver(c);
  auto exact = [&](real y, real t) { return analytic::poiseuille_startup(y, t, L, F, nu); };
  run_to(s, 0.1125);
  const real early = profile_error(s, exact, V0);
  run_to(s, 1.5);
  const real steady = profile_error(s, exact, V0);
  std::printf("Poiseuille 40: error %.4f %% at t = 0.1125 s, %.4f %% at t = 1.5 s (%lld steps)\n", 100 * early,
              100 * steady, static_cast<long long>(s.step_count()));
  EXPECT_LT(early, 0.02);
  EXPECT_LT(steady, 0.01);
}

TEST(Flows, TaylorGreenDecay) {
  // Periodic unit square, U = 1, rho = 1, Re = 100, c = 10 U, 50 x 50 particles.
  Case c = default_case();
  c.name = "tg";
  c.domain_min = {0, 0};
  c.domain_max = {1, 1};
  c.periodic_x = c.periodic_y = true;
  c.d0 = 1.0 / 50;
  c.rho0 = 1;
  c.nu = 0.01;
  c.c = 10;
  c.initial_flow = InitialFlow::TaylorGreen;
  c.initial_amplitude = 1;
  c.shifting_beta = 0.02;
  c.t_end = 0.5;
  c.output_interval = 0.1;
  Solver s = make_solver(c);
  auto peak = [&] {
    real m = 0;
    for (const auto& v : s.particles().v) m = std::max(m, norm(v));
    return m;
  };
  const real u0 = peak();
  run_to(s, 0.5);
  const real ratio = peak() / u0;
  const real exact = analytic::taylor_green_decay(s.time(), 100);
  std::printf("Taylor-Green: peak ratio %.5f, exact %.5f, error %.3f %% at t = %.4f s (%lld steps)\n", ratio, exact,
              100 * std::fabs(ratio / exact - 1), s.time(), static_cast<long long>(s.step_count()));
  EXPECT_NEAR(ratio / exact, 1.0, 0.03);
}

TEST(Flows, HydrostaticRest) {
  // Closed 0.1 m box of water at rest with gravity kept in the fluid, 40 particles high,
  // run for 20 sound-crossing times.
  const real H = 0.1, g = 9.81, rho0 = 1000;
  Case c = hydrostatic_box(H, g);
  c.shifting_beta = 0.02;
  Solver s = make_solver(c);
  run_to(s, 20 * H / c.c);
  const auto& P = s.particles();
  real bottom = 0, vmax = 0;
  int nbottom = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (i < P.n_boundary && P.kind[i] == Kind::Boundary && P.x[i].y < 1e-9 && P.x[i].x > 0.2 * H &&
        P.x[i].x < 0.8 * H) {
      bottom += P.p[i];
      ++nbottom;
    }
    if (P.is_fluid(i)) vmax = std::max(vmax, norm(P.v[i]));
  }
  bottom /= nbottom;
  const real exact = rho0 * g * H;
  std::printf("Hydrostatic: bottom pressure %.2f Pa vs rho g H = %.2f Pa (%.3f %%), peak speed %.3g m/s = %.3f %% of "
              "sqrt(gH) after %lld steps\n",
              bottom, exact, 100 * (bottom / exact - 1), vmax, 100 * vmax / std::sqrt(g * H),
              static_cast<long long>(s.step_count()));
  EXPECT_NEAR(bottom / exact, 1.0, 0.01);
  EXPECT_LT(vmax, 0.01 * std::sqrt(g * H));
}

TEST(Flows, HydrostaticRestLong) {
  // The same box with the default numerics (Rhie-Chow factor 1) for 50 sound-crossing times.
  // Without the odd-even velocity damping a checkerboard of vertical velocities grows under the
  // top wall (e-folding about 0.025 s here) and the run stops at t = 0.17 s.
  const real H = 0.1, g = 9.81;
  Case c = hydrostatic_box(H, g);
  Solver s = make_solver(c);
  run_to(s, 50 * H / c.c);
  const auto& P = s.particles();
  real vmax = 0;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) vmax = std::max(vmax, norm(P.v[i]));
  std::printf("Hydrostatic, default numerics: peak speed %.3g m/s = %.2e sqrt(gH) at t = %.3f s; surface guard %lld\n",
              vmax, vmax / std::sqrt(g * H), s.time(), static_cast<long long>(s.counters().surface_pushed));
  EXPECT_LT(vmax, 1e-4 * std::sqrt(g * H));
}
