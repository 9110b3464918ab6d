// The surface guard in 3D (boundary/surface_guard.hpp, the same functions as in 2D with the 3D
// surface distance): a tangent plane reaching a disc of one spacing, the cone at a convex edge or
// vertex, the guard putting a particle back in front of a plane and stopping it moving in, a
// closing gap carrying its particle, the film fraction between two facing planes, and shifting
// kept from moving a particle into a close surface.
#include <gtest/gtest.h>

#include <cmath>

#include "particula/boundary/surface_guard.hpp"

using namespace particula;

namespace {

const Domain3 kOpen{{-1, -1, -1}, {1, 1, 1}, false, false, false};

NearSurfacesOf<3> one_plane(Vec3 x, Vec3 n, Vec3 v = {}, real reach = 0, real wedge = 0) {
  NearSurfacesOf<3> ns;
  ns.s[ns.count++] = SurfaceTangentOf<3>{x, n, v, wedge, reach};
  return ns;
}

}  // namespace

TEST(SurfaceGuard3, PlaneDistanceWithinItsDiscAndFromTheRimBeyond) {
  const Vec3 n = Vec3{1, 2, 2} / 3;  // a tilted plane through the origin
  const SurfaceTangentOf<3> s{{0, 0, 0}, n, {}, 0, 0.1};
  const Vec3 t = any_perpendicular(n);
  EXPECT_NEAR(dot(t, n), 0, 1e-15);
  EXPECT_NEAR(norm(t), 1, 1e-15);
  Vec3 away;
  // the foot within the disc: the distance along n, away = n
  EXPECT_NEAR(surface_distance(kOpen, 0.05 * t + 0.2 * n, s, away), 0.2, 1e-15);
  EXPECT_LT(norm(away - n), 1e-15);
  EXPECT_NEAR(surface_distance(kOpen, 0.05 * t - 0.2 * n, s, away), -0.2, 1e-15);
  // the foot beyond the disc: the distance from its rim, away from the rim point
  const Vec3 x = 0.4 * t + 0.4 * n;
  EXPECT_NEAR(surface_distance(kOpen, x, s, away), 0.5, 1e-14);  // (0.3, 0.4) from the rim
  EXPECT_LT(norm(away - (x - 0.1 * t) / 0.5), 1e-14);
}

TEST(SurfaceGuard3, ConvexEdgeIsACone) {
  // A right-angled edge seen from its bisector n = (0, 0, 1): wedge 45 degrees.
  const real w = 0.25 * M_PI;
  const SurfaceTangentOf<3> s{{0, 0, 0}, {0, 0, 1}, {}, w, 0};
  Vec3 away;
  // in the normal cone: the distance from the apex
  EXPECT_NEAR(surface_distance(kOpen, Vec3{0.1, 0.1, 0.3}, s, away), std::sqrt(0.11), 1e-14);
  // beside the cone, level with the apex: the side through the apex on that side, r . n1
  const real d = surface_distance(kOpen, Vec3{0.3, 0, 0}, s, away);
  EXPECT_NEAR(d, 0.3 * std::sin(w), 1e-14);
  EXPECT_LT(norm(away - Vec3{std::sin(w), 0, std::cos(w)}), 1e-14);
  // inside the solid below the apex: negative
  EXPECT_LT(surface_distance(kOpen, Vec3{0.01, 0.02, -0.3}, s, away), 0);
  // straight below (no tangential part): still a unit direction and the cone's distance
  EXPECT_NEAR(surface_distance(kOpen, Vec3{0, 0, -0.3}, s, away), -0.3 * std::cos(w), 1e-14);
  EXPECT_NEAR(norm(away), 1, 1e-14);
}

TEST(SurfaceGuard3, ParticleBehindAPlaneIsPutBackAndStopsMovingIn) {
  const real keep = 0.25;
  // Floor z = 0 moving along y at 1; the particle has crossed it and moves down.
  const NearSurfacesOf<3> ns = one_plane({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
  Vec3 x{0.3, -0.2, -0.1}, v{2, 0.5, -3};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Pushed);
  EXPECT_NEAR(x.z, keep, 1e-15);
  EXPECT_NEAR(x.x, 0.3, 1e-15);
  EXPECT_NEAR(x.y, -0.2, 1e-15);
  EXPECT_NEAR(v.z, 0, 1e-15);
  EXPECT_NEAR(v.x, 2, 1e-15);  // tangential motion untouched
  // already far enough and moving away: nothing
  Vec3 y{0, 0, 0.5}, u{0, 0, 1};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, y, u), GuardOutcome::None);
  EXPECT_NEAR(y.z, 0.5, 1e-15);
}

TEST(SurfaceGuard3, ClosingGapCarriesItsParticleAndIsAFilm) {
  const real keep = 0.25;
  NearSurfacesOf<3> ns = one_plane({0, 0, 0}, {0, 0, 1}, {0, 0, 1});
  ns.s[ns.count++] = SurfaceTangentOf<3>{{0.1, 0.2, 0.3}, {0, 0, -1}, {0, 0, -1}, 0, 0};
  Vec3 x{0.05, 0.05, 0.1}, v{0.3, 0, 5};
  EXPECT_EQ(guard_surfaces(ns, keep, kOpen, x, v), GuardOutcome::Gap);
  EXPECT_NEAR(x.z, 0.15, 1e-15);  // midway
  EXPECT_NEAR(v.z, 0, 1e-15);     // the mean of the two surfaces' normal velocities
  EXPECT_NEAR(v.x, 0.3, 1e-15);
  // film fraction: gap 0.3 against film_gap 0.4 -> (0.4 - 0.3) / 0.2 = 0.5
  EXPECT_NEAR(film_fraction(ns, 0.4, kOpen, {0, 0, 0.1}), 0.5, 1e-12);
  EXPECT_EQ(film_fraction(ns, 0.25, kOpen, {0, 0, 0.1}), 0);
}

TEST(SurfaceGuard3, ShiftingIsKeptFromMovingIntoACloseSurface) {
  const NearSurfacesOf<3> ns = one_plane({0, 0, 0}, {0, 0, 1});
  const Vec3 dr{0.01, -0.02, -0.03};
  const Vec3 near = limit_shift_at_surfaces(dr, ns, 0.1, kOpen, Vec3{0, 0, 0.05});
  EXPECT_NEAR(near.z, 0, 1e-17);
  EXPECT_NEAR(near.x, 0.01, 1e-17);
  EXPECT_NEAR(near.y, -0.02, 1e-17);
  const Vec3 far = limit_shift_at_surfaces(dr, ns, 0.1, kOpen, Vec3{0, 0, 0.5});
  EXPECT_NEAR(far.z, -0.03, 1e-17);
}
