// Sharp corners (docs/method.md, "Sharp corners"): an obstacle standing on a wall, the
// conditioning guard of the wall pressure P.20 and its extrapolation fallback, and sharp
// polygons falling through the fluid without blowing up.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "case_builders.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

TEST(ObstacleOnAWall, SharedSideIsLeftOutAndJunctionsAreConcaveCorners) {
  // A fixed half-disc on each of the four walls of a box. The flat side lies on the wall line,
  // facing into the wall: no surface particle may be left there, and the two ends of the arc
  // become concave corners of the fluid with the bisector normal and the box corner's volume
  // (twice a flat wall particle's, scene.cpp corner_volume_factor).
  const real W = 0.02, H = 0.03, d0 = 2.5e-4, R = 0.004;
  Case c = cases::closed_box(W, H, d0);
  struct Placement {
    Vec2 center;
    real angle;
    Vec2 wall_normal;  // the wall's normal, into the fluid
  };
  const Placement placements[] = {{{0, 0.01}, 0, {1, 0}},
                                  {{0.01, 0}, M_PI / 2, {0, 1}},
                                  {{W, 0.02}, M_PI, {-1, 0}},
                                  {{0.01, H}, -M_PI / 2, {0, -1}}};
  for (const auto& pl : placements) {
    BodySpec b;
    b.name = "obstacle";
    b.shape = BodyShape::HalfDisc;
    b.center = pl.center;
    b.radius = R;
    b.angle = pl.angle;
    b.motion = BodyMotion::Fixed;
    c.bodies.push_back(b);
  }
  const Scene sc = build_scene(c);
  const Particles& P = sc.particles;
  const int arc_intervals = static_cast<int>(std::lround(M_PI * R / d0));
  const real arc_ds = M_PI * R / arc_intervals;
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const RigidGroup& g = sc.groups[4 + k];
    const Placement& pl = placements[k];
    EXPECT_EQ(g.count, static_cast<std::size_t>(arc_intervals + 1)) << "the arc with both ends, nothing of the flat side";
    int junctions = 0;
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      const Vec2 n = rotate(P.normal_local[i], std::cos(pl.angle), std::sin(pl.angle));
      const Vec2 from_centre = P.x[i] - pl.center;
      EXPECT_NEAR(norm(from_centre), R, 1e-12);
      EXPECT_GT(dot(n, pl.wall_normal), -1e-9) << "no surface particle faces into the wall";
      if (std::fabs(dot(from_centre, pl.wall_normal)) > 1e-9) {  // on the arc: the radial normal
        EXPECT_NEAR(dot(n, from_centre / R), 1.0, 1e-12);
        EXPECT_NEAR(P.m[i], c.rho0 * arc_ds * d0, 1e-12 * P.m[i]);
        continue;
      }
      ++junctions;  // on the wall line: the bisector of the arc's normal there and the wall's
      const Vec2 bisector = from_centre / R + pl.wall_normal, expected = bisector / norm(bisector);
      EXPECT_NEAR(n.x, expected.x, 1e-12);
      EXPECT_NEAR(n.y, expected.y, 1e-12);
      EXPECT_NEAR(P.m[i], 2 * c.rho0 * P.ds[i] * d0, 1e-12 * P.m[i]);
    }
    EXPECT_EQ(junctions, 2);
  }
  // The wall particles under the bodies are gone: none lies within d0/2 of a body.
  for (std::size_t w = 0; w < 4; ++w) {
    const RigidGroup& g = sc.groups[w];
    for (std::size_t i = g.first; i < g.first + g.count; ++i)
      for (const auto& pl : placements) EXPECT_FALSE(norm(P.x[i] - pl.center) < R + 0.5 * d0 - 1e-12 &&
                                                     dot(P.x[i] - pl.center, pl.wall_normal) > -1e-12);
  }
}

TEST(WallPressure, ExtrapolationIsExactForAHydrostaticField) {
  // Whatever the (positive) weights and the neighbours' layout, a pressure field whose gradient
  // is exactly rho * balance is extrapolated exactly: P_j = P_i + rho (x_j - x_i) . balance.
  SplitMix64 rng(11);
  const real rho = 1000, p_i = 37.5;
  const Vec2 balance{0.3, -9.81};
  WallExtrapolationSums s;
  for (int j = 0; j < 25; ++j) {
    const Vec2 x_ji{1e-3 * rng.symmetric(), 1e-3 * rng.symmetric()};
    const real W = 1 + rng.symmetric();  // in [0, 2)
    wall_extrapolation_pair(s, W, p_i + rho * dot(x_ji, balance), rho, x_ji, balance);
  }
  real p = -1;
  ASSERT_TRUE(wall_extrapolation(s, p));
  EXPECT_NEAR(p, p_i, 1e-12 * std::fabs(p_i) + 1e-9);
  // No fluid neighbour: undefined, the pressure is left as it was.
  real untouched = 5;
  EXPECT_FALSE(wall_extrapolation(WallExtrapolationSums{}, untouched));
  EXPECT_EQ(untouched, 5);
}

TEST(WallPressure, ConditioningGuardRejectsCancellingDenominators) {
  // A flat wall: every term of the P.20 denominator has the same sign.
  WallPressureSums flat;
  for (real k : {0.4, 0.3, 0.2, 0.05}) wall_pressure_pair(flat, Vec2{0, k}, Vec2{0, 1}, 0, 1, true);
  EXPECT_TRUE(wall_pressure_well_conditioned(flat));
  // Fluid on both sides of the normal: the terms cancel, P_i = num/den would amplify.
  WallPressureSums sharp;
  for (real k : {0.4, -0.3, 0.2, -0.25}) wall_pressure_pair(sharp, Vec2{0, k}, Vec2{0, 1}, 0, 1, true);
  EXPECT_FALSE(wall_pressure_well_conditioned(sharp));
  // Only boundary neighbours: never solved, whatever the sums.
  WallPressureSums walls_only;
  wall_pressure_pair(walls_only, Vec2{0, 1}, Vec2{0, 1}, 0, 1, false);
  EXPECT_FALSE(wall_pressure_well_conditioned(walls_only));
}

namespace {
/// A box 1 cm wide with one heavy polygon released from rest (rho_s = 1250, mu = 0.01 Pa s).
Case sharp_body_case(std::vector<Vec2> vertices) {
  Case c = cases::closed_box(0.01, 0.016, 2e-4);
  c.nu = 1e-5;
  c.c = 1;
  c.shifting_beta = 0.02;
  c.gravity = {0, -9.81};
  BodySpec b;
  b.name = "sharp";
  b.shape = BodyShape::Polygon;
  b.vertices = std::move(vertices);
  b.density = 1250;
  c.bodies.push_back(b);
  return c;
}
}  // namespace

TEST(SharpCorners, AcutePolygonsFallWithoutBlowingUp) {
  // A triangle with a 21-degree tip and one with 72-degree base corners. With P.20 solved at
  // their corners both runs blew up within 50 steps (the corner pressure oscillated with growing
  // amplitude); with the conditioning guard they fall.
  const std::vector<std::vector<Vec2>> shapes = {
      {{0.002, 0.008}, {0.008, 0.0088}, {0.002, 0.0102}},  // needle, tip pointing right
      {{0.003, 0.008}, {0.007, 0.008}, {0.005, 0.014}}};    // 72-degree base corners
  for (const auto& v : shapes) {
    Scene sc = build_scene(sharp_body_case(v));
    Solver s(sc.params, sc.domain, sc.particles, sc.groups);
    for (int k = 0; k < 600; ++k) {
      const auto failure = s.step();
      ASSERT_FALSE(failure.has_value()) << "step " << k << ": " << failure->what;
    }
    const RigidGroup& g = s.groups().back();
    const real t = s.time();
    std::printf("sharp polygon after %.4f s: v = (%.3g, %.3g) m/s, omega = %.3g rad/s, %lld corner extrapolations\n",
                t, g.vel.x, g.vel.y, g.omega, static_cast<long long>(s.counters().wall_pressure_extrapolated));
    EXPECT_GT(s.counters().wall_pressure_extrapolated, 0);
    EXPECT_EQ(s.counters().wall_pressure_extrapolated_far, 0) << "no gap: the corners are ill-conditioned, not far";
    // Sinking, slower than free fall with buoyancy and added mass ((rho_s - rho_f) g t / (rho_s + rho_f)).
    EXPECT_LT(g.vel.y, 0.0);
    EXPECT_GT(g.vel.y, -1.2 * 0.25 * 9.81 * t / 2.25);
    EXPECT_LT(std::fabs(g.vel.x), 0.2 * std::fabs(g.vel.y));
  }
}

// A cylinder held 0.5 d0 above the floor of a box of fluid at rest (its contact distance): the
// surface particles facing the gap have no fluid within P.20's reach, and their extrapolations
// are counted as such (`wall_pressure_extrapolated_far`, "extrapolated in narrow gaps"), apart
// from the ill-conditioned ones of corners and contact wedges; the same cylinder in the middle of
// the box has neither.
TEST(WallPressure, FluidOutOfReachInANarrowGapIsCountedApartFromCorners) {
  auto run = [](real gap_d0) {
    const real d0 = 2e-4, R = 1e-3;
    Case c = cases::closed_box(0.008, 0.006, d0);
    c.bodies.push_back(cases::circle_body("resting", {0.004, R + gap_d0 * d0}, R, BodyMotion::Fixed));
    Scene sc = build_scene(c);
    Solver s(sc.params, sc.domain, sc.particles, sc.groups);
    for (int k = 0; k < 20; ++k) EXPECT_FALSE(s.step().has_value());
    std::printf("cylinder %.2g d0 above the floor: extrapolated ill-conditioned %lld, out of reach %lld\n", gap_d0,
                static_cast<long long>(s.counters().wall_pressure_extrapolated),
                static_cast<long long>(s.counters().wall_pressure_extrapolated_far));
    return s.counters();
  };
  const SolverCounters resting = run(0.5), free = run(10);
  EXPECT_GT(resting.wall_pressure_extrapolated_far, 0);
  EXPECT_EQ(free.wall_pressure_extrapolated_far, 0);
  EXPECT_EQ(free.wall_pressure_extrapolated, 0);
  // neither has a void: the gap under the resting cylinder is a contact's film, not room for fluid
  EXPECT_EQ(resting.wall_pressure_void, 0);
  EXPECT_EQ(free.wall_pressure_void, 0);
}

// A fixed cylinder in a box of fluid at rest under gravity, with the fluid within 2 d0 of its
// surface taken away (a void, as a pore whose fluid was squeezed out leaves when it opens; its
// far side within the support h = 2.6 d0 of the surface particles, where they can see it): its
// surface particles take the void's pressure (guard_events.wall_pressure_void) and the fluid
// around, at its hydrostatic pressure, flows in until every surface particle has fluid within
// kVoidDistance d0 again. With the surface given the pressure of the fluid beyond the void (P.20
// or the extrapolation) the void would stay open.
TEST(WallPressure, ASurfaceFacingAVoidTakesTheVoidsPressureAndTheFluidFillsIt) {
  const real d0 = 2e-4, R = 1e-3;
  const Vec2 centre{0.004, 0.003};
  Case c = cases::closed_box(0.008, 0.006, d0);
  c.gravity = {0, -9.81};
  c.gravity_in_fluid = true;
  c.hydrostatic = true;
  c.bodies.push_back(cases::circle_body("held", centre, R, BodyMotion::Fixed));
  Scene sc = build_scene(c);
  Particles& P = sc.particles;
  std::size_t kept = P.n_boundary;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
    if (norm(P.x[i] - centre) < R + 2 * d0) continue;
    P.x[kept] = P.x[i], P.v[kept] = P.v[i], P.rho[kept] = P.rho[i], P.p[kept] = P.p[i], P.m[kept] = P.m[i];
    P.kind[kept] = P.kind[i], P.group[kept] = P.group[i], P.id[kept] = P.id[i];
    ++kept;
  }
  ASSERT_LT(kept, P.size());
  P.resize(kept);
  Solver s(sc.params, sc.domain, sc.particles, sc.groups);
  // the largest distance from a surface particle of the cylinder to its nearest fluid particle
  auto widest_void = [&] {
    const Particles& Q = s.particles();
    real widest = 0;
    for (std::size_t i = 0; i < Q.n_boundary; ++i) {
      if (Q.kind[i] != Kind::Boundary || norm(Q.x[i] - centre) > 1.01 * R) continue;
      real nearest = std::numeric_limits<real>::infinity();
      for (std::size_t j = Q.n_boundary; j < Q.size(); ++j) nearest = std::min(nearest, norm(Q.x[j] - Q.x[i]));
      widest = std::max(widest, nearest);
    }
    return widest / d0;
  };
  ASSERT_GT(widest_void(), 2.0);
  ASSERT_FALSE(s.step().has_value());
  EXPECT_GT(s.counters().wall_pressure_void, 0);
  while (s.time() < 0.03) ASSERT_FALSE(s.step().has_value());
  const real widest = widest_void();
  std::printf("void round a cylinder: widest %.2f d0 at t = %.3f s, %lld surface particle-sweeps facing it\n", widest,
              s.time(), static_cast<long long>(s.counters().wall_pressure_void));
  EXPECT_LT(widest, kVoidDistance);
}
