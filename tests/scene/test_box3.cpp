// The 3D box scene (scene/box3.hpp): the fluid lattice fills the box, the walls lie on its closed
// faces, edges and corners with unit normals into the fluid, the periodic axes have none, and a
// face slides along itself only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "particula/scene/box3.hpp"

using namespace particula;

TEST(Box3, ClosedBoxHasFacesEdgesAndCornersAroundAFullLattice) {
  BoxSpec3 spec;
  spec.lo = {-0.1, 0, 0.2};
  spec.hi = {0.5, 0.4, 0.7};
  spec.d0 = 0.1;
  spec.rho0 = 1000;
  spec.p0 = 3;
  const BoxScene3 s = build_box3(spec);
  const Particles3& P = s.particles;
  const int n[3] = {6, 4, 5};
  const std::size_t faces = 2 * (4 * 5 + 5 * 6 + 6 * 4), edges = 4 * (6 + 4 + 5), corners = 8;
  ASSERT_EQ(P.n_boundary, faces + edges + corners);
  ASSERT_EQ(P.size() - P.n_boundary, static_cast<std::size_t>(n[0] * n[1] * n[2]));
  real fluid_volume = 0;
  std::set<std::int64_t> ids;
  for (std::size_t i = 0; i < P.size(); ++i) {
    ids.insert(P.id[i]);
    EXPECT_EQ(P.rho[i], 1000);
    EXPECT_EQ(P.p[i], 3);
    if (i >= P.n_boundary) {
      EXPECT_EQ(P.kind[i], Kind::Fluid);
      fluid_volume += P.m[i] / P.rho[i];
      continue;
    }
    EXPECT_EQ(P.kind[i], Kind::Boundary);
    EXPECT_NEAR(norm(P.normal[i]), 1, 1e-15) << i;
    // on the box's surface, its normal pointing into the box
    const Vec3 x = P.x[i];
    const real to_surface = std::fmin(
        std::fmin(std::fmin(x.x - spec.lo.x, spec.hi.x - x.x), std::fmin(x.y - spec.lo.y, spec.hi.y - x.y)),
        std::fmin(x.z - spec.lo.z, spec.hi.z - x.z));
    EXPECT_NEAR(to_surface, 0, 1e-15) << i;
    const Vec3 inside = x + 0.01 * P.normal[i];
    EXPECT_TRUE(inside.x > spec.lo.x && inside.x < spec.hi.x && inside.y > spec.lo.y &&
                inside.y < spec.hi.y && inside.z > spec.lo.z && inside.z < spec.hi.z)
        << i;
  }
  EXPECT_EQ(ids.size(), P.size());
  EXPECT_NEAR(fluid_volume, 0.6 * 0.4 * 0.5, 1e-14);
  // the faces' areas cover the box's surface
  real area = 0;
  for (std::size_t i = 0; i < P.n_boundary; ++i) area += P.ds[i];
  EXPECT_NEAR(area, 2 * (0.6 * 0.4 + 0.4 * 0.5 + 0.5 * 0.6), 1e-14);
}

TEST(Box3, PeriodicAxesHaveNoWallsAndMovingFacesSlideAlongThemselves) {
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {0.8, 1.0, 0.6};
  spec.periodic[0] = true;
  spec.periodic[2] = true;
  spec.d0 = 0.1;
  spec.rho0 = 1;
  spec.face_velocity[3] = {0.5, 0, 0.25};  // +y
  const BoxScene3 s = build_box3(spec);
  const Particles3& P = s.particles;
  EXPECT_TRUE(s.domain.periodic_x && s.domain.periodic_z && !s.domain.periodic_y);
  ASSERT_EQ(P.n_boundary, 2u * 8 * 6);  // the two y faces only
  for (std::size_t i = 0; i < P.n_boundary; ++i) {
    const bool top = P.x[i].y > 0.5;
    EXPECT_EQ(P.v[i].x, top ? 0.5 : 0.0);
    EXPECT_EQ(P.v[i].z, top ? 0.25 : 0.0);
    EXPECT_EQ(P.normal[i].y, top ? -1.0 : 1.0);
  }
  spec.face_velocity[3] = {0, 0.1, 0};  // into the fluid: not a sliding face
  EXPECT_THROW(build_box3(spec), std::invalid_argument);
}

TEST(Box3, AFixedSphereIsSampledAndTheFluidKeepsClearOfIt) {
  // a sphere centred near a corner of a periodic box: its surface and the fluid left out wrap round
  BoxSpec3 spec;
  spec.lo = {0, 0, 0};
  spec.hi = {1, 1, 1};
  spec.periodic[0] = spec.periodic[1] = spec.periodic[2] = true;
  spec.d0 = 0.05;
  spec.rho0 = 1000;
  const real a = 0.3;
  const Vec3 centre{0.9, 0.1, 0.5};
  spec.solids.push_back(
      FixedSolid3{Shape3::sphere(a), centre, axis_angle(Vec3{1, 1, 0} / std::sqrt(2.0), 0.7)});
  const BoxScene3 s = build_box3(spec);
  const Particles3& P = s.particles;
  real area = 0;
  for (std::size_t i = 0; i < P.n_boundary; ++i) {
    EXPECT_EQ(P.group[i], 6);
    const Vec3 r = s.domain.separation(P.x[i], centre);
    EXPECT_NEAR(norm(r), a, 1e-12) << i;
    EXPECT_LT(norm(P.normal[i] - r / a), 1e-12) << i;  // outward, into the fluid
    EXPECT_TRUE(P.x[i].x >= 0 && P.x[i].x < 1 && P.x[i].y >= 0 && P.x[i].y < 1) << i;
    area += P.ds[i];
  }
  EXPECT_NEAR(area, 4 * M_PI * a * a, 1e-12);
  std::size_t fluid = 0;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i, ++fluid)
    EXPECT_GE(norm(s.domain.separation(P.x[i], centre)), a + 0.5 * spec.d0 - 1e-12) << i;
  // every lattice point outside the sphere by d0 / 2 is kept
  std::size_t expected = 0;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k)
        if (norm(s.domain.separation(Vec3{(i + 0.5) * 0.05, (j + 0.5) * 0.05, (k + 0.5) * 0.05}, centre)) >=
            a + 0.025)
          ++expected;
  EXPECT_EQ(fluid, expected);
  // the fluid's masses fill the box outside the sphere (to the midpoint rule on the cut cells)
  real volume = 0;
  for (std::size_t i = P.n_boundary; i < P.size(); ++i) volume += P.m[i] / P.rho[i];
  const real exact = 1 - 4 * M_PI * a * a * a / 3;
  EXPECT_NEAR(volume / exact, 1, 1e-3);
  std::printf("fluid volume outside the sphere: %.6f of the exact\n", volume / exact);
}
