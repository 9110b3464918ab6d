// Solver behaviour: thread-count independence, the dummy-particle baseline, the blow-up
// guard, and the neighbour list against a brute-force search.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

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

/// Hydrostatic box with a perturbed lattice: exercises walls, corners, gravity and shifting.
Case busy_box() {
  Case c = cases::closed_box(0.02, 0.02, 0.001);
  c.gravity = {0, -9.81};
  c.gravity_in_fluid = true;
  c.hydrostatic = true;
  c.c = 5;
  c.nu = 1e-4;
  c.shifting_beta = 0.02;
  c.perturbation = 0.1;
  return c;
}

std::vector<Vec2> run_with_threads(int threads, int steps) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Solver s = make_solver(busy_box());
  for (int k = 0; k < steps; ++k) EXPECT_FALSE(s.step().has_value());
  omp_set_num_threads(before);
  // Order by particle id: the fluid block is reordered by cell.
  std::vector<Vec2> out(s.particles().size());
  for (std::size_t i = 0; i < out.size(); ++i) out[s.particles().id[i]] = s.particles().v[i];
  return out;
}

}  // namespace

TEST(Solver, OneAndTwoThreadsAgreeBitwise) {
  const auto a = run_with_threads(1, 120);
  const auto b = run_with_threads(2, 120);
  ASSERT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(Vec2)) != 0) ++differ;
  EXPECT_EQ(differ, 0u) << "particles whose velocity differs between 1 and 2 threads";
  real vmax = 0;
  for (const auto& v : a) vmax = std::max(vmax, norm(v));
  EXPECT_GT(vmax, 0.0) << "the comparison must see a moving fluid";
}

TEST(Solver, NeighbourListMatchesBruteForce) {
  Case c = cases::startup_channel(20, 0, 0);
  c.perturbation = 0.3;
  Solver s = make_solver(c);
  const auto& P = s.particles();
  const auto& nl = s.host().neighbors();
  const real h = s.params().h;
  real closest = std::numeric_limits<real>::infinity();
  for (std::size_t i = 0; i < P.size(); ++i) {
    std::vector<std::uint32_t> brute;
    for (std::size_t j = 0; j < P.size(); ++j) {
      const real r = norm(s.domain().separation(P.x[i], P.x[j]));
      if (j != i && r < h) {
        brute.push_back(static_cast<std::uint32_t>(j));
        closest = std::min(closest, r);
      }
    }
    std::vector<std::uint32_t> listed(nl.j.begin() + nl.start[i], nl.j.begin() + nl.start[i + 1]);
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, brute) << "particle " << i;
  }
  // d_min of the time-step control (P.29-P.31), reduced over the kept candidates only.
  EXPECT_DOUBLE_EQ(nl.min_distance, closest);
  EXPECT_GT(closest, 0.0);
}

TEST(Solver, DummyParticleBaselineRunsCouette) {
  const real V0 = 1.25e-5, L = 1e-3, nu = 1e-6;
  Case c = cases::startup_channel(20, V0, 0);
  c.boundary = BoundaryModel::Dummy;
  Scene sc = build_scene(c);
  std::size_t dummies = 0;
  for (auto k : sc.particles.kind) dummies += k == Kind::Dummy;
  EXPECT_EQ(dummies, 2u * 8u * 3u);  // two walls x 8 surface particles x 3 layers
  Solver s(sc.params, sc.domain, sc.particles, sc.groups);
  while (s.time() < 0.5) ASSERT_FALSE(s.step().has_value());
  real err2 = 0;
  std::size_t n = 0;
  for (std::size_t i = s.particles().n_boundary; i < s.particles().size(); ++i) {
    const real e =
        s.particles().v[i].x - analytic::couette_startup(s.particles().x[i].y, s.time(), L, V0, nu);
    err2 += e * e;
    ++n;
  }
  const real err = std::sqrt(err2 / n) / V0;
  std::printf("Couette 20 with dummy particles: error %.3f %% at t = %.3f s\n", 100 * err, s.time());
  EXPECT_LT(err, 0.05);
}

TEST(Solver, CollapsedTimeStepStopsTheRunAndNamesTheClosestPair) {
  // Two fluid particles 1e-6 d0 apart: the Courant limit at their distance is 1e6 times below
  // the case's own step, far past kTimeStepCollapse; the run must stop instead of crawling.
  const Case c = busy_box();
  Scene scene = build_scene(c);
  Particles& P = scene.particles;
  // a: the lowest fluid particle (next to the bottom wall); b moved onto it
  std::size_t a = P.n_boundary;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i)
    if (P.x[i].y < P.x[a].y) a = i;
  const std::size_t b = a + 1 < P.size() ? a + 1 : a - 1;
  ASSERT_GT(b, P.n_boundary);
  P.x[b] = P.x[a] + Vec2{1e-6 * c.d0, 0};
  Solver s(scene.params, scene.domain, P, scene.groups);
  const std::optional<Failure> f = s.step();
  ASSERT_TRUE(f.has_value());
  EXPECT_NE(f->what.find("time step collapsed"), std::string::npos) << f->what;
  EXPECT_NE(f->what.find("particles collapsing"), std::string::npos) << f->what;
  EXPECT_EQ(s.step_count(), 0);
  // where: the pair's first particle (not the origin), both particles and their nearest surfaces
  EXPECT_EQ(f->particle_id, P.id[a]);
  EXPECT_EQ(f->position.x, P.x[a].x);
  EXPECT_EQ(f->position.y, P.x[a].y);
  EXPECT_NE(f->what.find(fmt::format("fluid particle {} at", P.id[a])), std::string::npos) << f->what;
  EXPECT_NE(f->what.find(fmt::format("fluid particle {} at", P.id[b])), std::string::npos) << f->what;
  EXPECT_NE(f->what.find("d0 from wall '"), std::string::npos) << f->what;
  // The same box without the pair steps normally: the guard does not fire on a healthy case.
  Solver healthy = make_solver(c);
  for (int k = 0; k < 20; ++k) ASSERT_FALSE(healthy.step().has_value());
}

TEST(Solver, StrongBodyForceLimitsTheTimeStep) {
  // A body force of 100 m/s^2 along a channel of fluid at rest: the Courant and viscous limits
  // of the first step (0.09 s and 1e-3 s here) know nothing of it, the force condition
  // 0.25 sqrt(h / |f|) = 2.85e-4 s does. Without it a strong body force moved particles by more
  // than h in a step. (From the second step on the flow's speed, far above this channel's sound
  // speed, sets the Courant condition below it.)
  const Case c = cases::startup_channel(20, 0, 100);
  Solver s = make_solver(c);
  const real limit = 0.25 * std::sqrt(s.params().h / 100);
  EXPECT_NEAR(s.body_force_dt(), limit, 1e-12 * limit);
  ASSERT_FALSE(s.step().has_value());
  EXPECT_EQ(s.last_dt(), limit);
  EXPECT_EQ(s.last_step_limit(), StepLimit::BodyForce);
}

TEST(Solver, EachStepNamesTheLimitThatSetIt) {
  // The box as it is: the Courant condition (P.30). 1e4 times the viscosity: viscous
  // diffusion (P.31). A dt_max below both: dt_max. A step shortened to land on a time: Landing.
  Case c = busy_box();
  Solver acoustic = make_solver(c);
  ASSERT_FALSE(acoustic.step().has_value());
  EXPECT_EQ(acoustic.last_step_limit(), StepLimit::Acoustic);
  const real dt = acoustic.last_dt();
  ASSERT_FALSE(acoustic.step_to(acoustic.time() + 0.5 * dt).has_value());
  EXPECT_EQ(acoustic.last_step_limit(), StepLimit::Landing);
  Case viscous = c;
  viscous.nu *= 1e4;
  Solver v = make_solver(viscous);
  ASSERT_FALSE(v.step().has_value());
  EXPECT_EQ(v.last_step_limit(), StepLimit::Viscous);
  Case capped = c;
  capped.dt_max = 0.5 * dt;
  Solver m = make_solver(capped);
  ASSERT_FALSE(m.step().has_value());
  EXPECT_EQ(m.last_step_limit(), StepLimit::DtMax);
  EXPECT_STREQ(step_limit_name(StepLimit::Viscous), "viscous");
}

TEST(Solver, BlowUpIsDetectedWithParticleAndReason) {
  // A sound speed far below sqrt(g H): the density leaves [0.5, 2] rho0 within a few steps.
  Case c = busy_box();
  c.c = 0.05;
  Solver s = make_solver(c);
  std::optional<Failure> f;
  for (int k = 0; k < 2000 && !f; ++k) f = s.step();
  ASSERT_TRUE(f.has_value());
  EXPECT_GE(f->particle_id, 0);
  EXPECT_NE(f->what.find("particle"), std::string::npos) << f->what;
}
