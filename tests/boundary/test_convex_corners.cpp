// Convex corners of the solid (boundary/surface_guard.hpp, surface_distance): the inward corner
// of an L- or T-shaped container and a polygon body's vertices, where the fluid wraps round more
// than 180 degrees. The surface guard and the shifting limit see the two sides ending at the
// corner, and a wall's tangent line ends one spacing past its last particle; the scene marks
// those corners (Particles::wedge) and gives an inward wall corner a flat wall's volume.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "case_builders.hpp"
#include "particula/boundary/surface_guard.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

namespace {

const Domain kOpen{{-10, -10}, {10, 10}, false, false};

// The inward corner of an L-shaped container at the origin: the step's underside (normal
// (0, -1), running along +x) and the upper arm's right wall (normal (-1, 0), running along +y);
// the solid is the quadrant x > 0, y > 0 and the fluid wraps round it through 270 degrees.
SurfaceTangent inward_corner() {
  return SurfaceTangent{{0, 0}, Vec2{-1, -1} / std::sqrt(2.0), {}, 0.25 * M_PI, 1.0};
}

NearSurfaces only(const SurfaceTangent& s) {
  NearSurfaces ns;
  ns.s[ns.count++] = s;
  return ns;
}

}  // namespace

TEST(ConvexCorner, DistanceIsTheOneFromTheSolidWedge) {
  const SurfaceTangent s = inward_corner();
  Vec2 away;
  // in the corner's normal cone: the corner point is the nearest point of the solid
  EXPECT_NEAR(surface_distance(kOpen, {-0.5, -0.25}, s, away), std::hypot(0.5, 0.25), 1e-14);
  EXPECT_NEAR(away.x, -0.5 / std::hypot(0.5, 0.25), 1e-14);
  // under the step, level with its underside: the distance from the step, not from the bisector line
  EXPECT_NEAR(surface_distance(kOpen, {0.5, -0.1}, s, away), 0.1, 1e-14);
  EXPECT_NEAR(away.y, -1, 1e-14);
  // left of the upper arm's wall
  EXPECT_NEAR(surface_distance(kOpen, {-0.2, 3.0}, s, away), 0.2, 1e-14);
  EXPECT_NEAR(away.x, -1, 1e-14);
  // inside the solid: minus the depth below the nearer side
  EXPECT_NEAR(surface_distance(kOpen, {0.1, 0.3}, s, away), -0.1, 1e-14);
  EXPECT_NEAR(away.x, -1, 1e-14);
}

TEST(ConvexCorner, GuardPushesAwayFromTheSidesAndTheCornerOnly) {
  const real keep = 0.25;
  const NearSurfaces ns = only(inward_corner());
  // Level with the step's underside, past the corner: in the fluid, 0.45 from the corner. The
  // tangent line across the bisector put it 0.28 inside the solid and threw it 0.53 along the
  // bisector.
  Vec2 x{-0.4, -0.2}, v{};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::None);
  EXPECT_EQ(x.x, -0.4);
  EXPECT_EQ(x.y, -0.2);
  // 0.1 under the step: back to 0.25 under it, straight down, and no velocity into it
  x = {0.5, -0.1};
  v = {0.3, 0.2};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(x.x, 0.5, 1e-14);
  EXPECT_NEAR(x.y, -0.25, 1e-14);
  EXPECT_NEAR(v.x, 0.3, 1e-14);
  EXPECT_NEAR(v.y, 0.0, 1e-14);
  // next to the corner point: out along the radius to `keep` from it
  x = {-0.1, -0.05};
  v = {};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(std::hypot(x.x, x.y), keep, 1e-14);
  EXPECT_NEAR(x.y / x.x, 0.5, 1e-12);
}

TEST(ConvexCorner, AWallsTangentLineEndsOneSpacingPastItsLastParticle) {
  // The step's last particle, one spacing from the corner: its line y = 0 stands for the wall
  // as far as the corner and no farther.
  const SurfaceTangent last{{1, 0}, {0, -1}, {}, 0, 1.0};
  const NearSurfaces ns = only(last);
  Vec2 x{-0.5, -0.1}, v{};  // past the corner, 0.1 below the line's extension
  EXPECT_EQ(guard_surfaces(ns, 0.25, kOpen, x, v), GuardOutcome::None);
  EXPECT_EQ(x.y, -0.1);
  Vec2 away;
  EXPECT_NEAR(surface_distance(kOpen, {-0.5, -0.1}, last, away), std::hypot(0.5, 0.1), 1e-14);
  // within its reach the line holds
  x = {0.2, -0.1};
  EXPECT_EQ(guard_surfaces(ns, 0.25, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(x.y, -0.25, 1e-14);
  // an unbounded line (reach 0) is the tangent line everywhere
  const SurfaceTangent unbounded{{1, 0}, {0, -1}, {}, 0, 0};
  EXPECT_NEAR(surface_distance(kOpen, {-0.5, -0.1}, unbounded, away), 0.1, 1e-14);
}

TEST(ConvexCorner, ShiftingSlidesAlongTheSideItIsNear) {
  const NearSurfaces ns = only(inward_corner());
  // 0.3 under the step: a shift up and along is cut to along; in the corner's cone a shift
  // towards the corner keeps only its part across the radius
  Vec2 dr = limit_shift_at_surfaces({0.1, 0.05}, ns, 1.0, kOpen, {0.5, -0.3});
  EXPECT_NEAR(dr.x, 0.1, 1e-14);
  EXPECT_NEAR(dr.y, 0.0, 1e-14);
  dr = limit_shift_at_surfaces({0.1, 0.1}, ns, 1.0, kOpen, {-0.3, -0.3});
  EXPECT_NEAR(dr.x, 0.0, 1e-14);
  EXPECT_NEAR(dr.y, 0.0, 1e-14);
  // far from the corner nothing is cut
  dr = limit_shift_at_surfaces({0.1, 0.1}, ns, 1.0, kOpen, {-2, -2});
  EXPECT_EQ(dr.x, 0.1);
}

TEST(ConvexCorner, SceneMarksInwardWallCornersAndBodyVertices) {
  const real d0 = 2e-4, L = 0.01;
  Case c = cases::walled_polygon({{0, 0}, {L, 0}, {L, L / 2}, {L / 2, L / 2}, {L / 2, L}, {0, L}}, d0);
  BodySpec tri;
  tri.name = "triangle";
  tri.shape = BodyShape::Polygon;
  tri.vertices = {{0.001, 0.001}, {0.004, 0.001}, {0.001, 0.004}};  // right angle, two 45-degree vertices
  tri.density = 2000;
  tri.motion = BodyMotion::Free;
  c.bodies.push_back(tri);
  BodySpec ring;  // a square with a square hole: the hole's corners are concave for the solid
  ring.name = "frame";
  ring.shape = BodyShape::Polygon;
  ring.vertices = {{0.0055, 0.0005}, {0.0095, 0.0005}, {0.0095, 0.0045}, {0.0055, 0.0045}};
  ring.holes = {{{0.0065, 0.0015}, {0.0085, 0.0015}, {0.0085, 0.0035}, {0.0065, 0.0035}}};
  ring.density = 2000;
  ring.motion = BodyMotion::Fixed;
  c.bodies.push_back(ring);
  const Scene sc = build_scene(c);
  const Particles& P = sc.particles;
  int inward = 0, box = 0, vertices = 0, hole_corners = 0;
  auto near = [&](std::size_t i, Vec2 p) { return norm(P.x[i] - p) < 1e-9; };
  for (std::size_t i = 0; i < P.n_boundary; ++i) {
    if (P.kind[i] != Kind::Boundary) continue;
    if (near(i, {L / 2, L / 2})) {  // the inward corner: a flat wall particle's volume
      ++inward;
      EXPECT_NEAR(P.wedge[i], 0.25 * M_PI, 1e-12);
      EXPECT_NEAR(P.m[i], c.rho0 * P.ds[i] * d0, 1e-12 * P.m[i]);
    } else if (near(i, {0, 0}) || near(i, {L, 0}) || near(i, {0, L}) || near(i, {L / 2, L})) {
      ++box;  // concave for the solid: the tangent line, twice the volume
      EXPECT_EQ(P.wedge[i], 0);
      EXPECT_NEAR(P.m[i], 2 * c.rho0 * P.ds[i] * d0, 1e-12 * P.m[i]);
    } else if (near(i, {0.001, 0.001})) {
      ++vertices;
      EXPECT_NEAR(P.wedge[i], 0.25 * M_PI, 1e-12);
    } else if (near(i, {0.004, 0.001}) || near(i, {0.001, 0.004})) {
      ++vertices;
      EXPECT_NEAR(P.wedge[i], 0.5 * (M_PI - 0.25 * M_PI), 1e-12);
    } else if (near(i, {0.0065, 0.0015}) || near(i, {0.0085, 0.0015}) || near(i, {0.0085, 0.0035}) ||
               near(i, {0.0065, 0.0035})) {
      ++hole_corners;
      EXPECT_EQ(P.wedge[i], 0);
    } else if (near(i, {0.0055, 0.0005}) || near(i, {0.0095, 0.0005}) || near(i, {0.0095, 0.0045}) ||
               near(i, {0.0055, 0.0045})) {
      ++vertices;
      EXPECT_NEAR(P.wedge[i], 0.25 * M_PI, 1e-12);
    } else {
      EXPECT_EQ(P.wedge[i], 0) << "at " << P.x[i].x << ", " << P.x[i].y;
    }
  }
  EXPECT_EQ(inward, 1);
  EXPECT_EQ(box, 4);
  EXPECT_EQ(vertices, 7);
  EXPECT_EQ(hole_corners, 4);
}

// Fluid at rest under gravity in L- and T-shaped containers keeps its time step: the tangent line
// of the inward corner (and of the last particles before it) pushed the fluid next to the corner
// onto its neighbours, and the step fell to 1e-2 of the case's within 20 steps and to 1e-4 (exit
// 3) further on.
TEST(ConvexCorner, FluidAtRestInLAndTShapedContainersKeepsItsTimeStep) {
  const real d0 = 2.5e-4, L = 0.01;
  const std::vector<std::vector<Vec2>> containers = {
      {{0, 0}, {L, 0}, {L, L / 2}, {L / 2, L / 2}, {L / 2, L}, {0, L}},  // L
      {{0.3 * L, 0}, {0.7 * L, 0}, {0.7 * L, 0.6 * L}, {L, 0.6 * L}, {L, L}, {0, L}, {0, 0.6 * L}, {0.3 * L, 0.6 * L}},  // T
  };
  for (const auto& corners : containers) {
    SCOPED_TRACE(corners.size());
    const Case c = cases::walled_polygon(corners, d0);
    const Scene sc = build_scene(c);
    Solver s(sc.params, sc.domain, sc.particles, sc.groups);
    const real dt_case = s.case_dt();
    real dt_min = 1e300;
    for (int k = 0; k < 150; ++k) {
      ASSERT_FALSE(s.step().has_value()) << "step " << k;
      dt_min = std::min(dt_min, s.last_dt());
    }
    EXPECT_GT(dt_min, 0.5 * dt_case);
    const Particles& P = s.particles();
    real vmax = 0;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) vmax = std::max(vmax, norm(P.v[i]));
    EXPECT_LT(vmax, 0.01 * c.c) << "the fluid stays at rest";
  }
}
