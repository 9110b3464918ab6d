// 3D shapes (geometry/shape3.hpp): exact areas per sample summing to the surface area, samples on
// the surface with the distance's normal at about d0 apart, the mass properties against the
// polyhedron's (a cuboid's mesh exactly, a faceted cylinder and sphere in the limit), and the
// signed distance of each shape.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "particula/geometry/shape3.hpp"

using namespace particula;

namespace {

real max_abs_difference(const Mat3& a, const Mat3& b) { return max_abs_entry(a - b); }

/// The 12 triangles of the box [lo, hi], counter-clockwise seen from outside.
std::vector<TriangleMesh::Triangle> box_triangles(Vec3 lo, Vec3 hi) {
  const auto v = [&](int i) { return Vec3{i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}; };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<TriangleMesh::Triangle> t;
  for (const auto& q : quads) {
    t.push_back({v(q[0]), v(q[1]), v(q[2])});
    t.push_back({v(q[0]), v(q[2]), v(q[3])});
  }
  return t;
}

/// A cylinder of radius R and length L about z, faceted into n sides, centred at `c`.
std::vector<TriangleMesh::Triangle> faceted_cylinder(real R, real L, int n, Vec3 c) {
  std::vector<TriangleMesh::Triangle> t;
  const Vec3 top = c + Vec3{0, 0, L / 2}, bottom = c - Vec3{0, 0, L / 2};
  for (int k = 0; k < n; ++k) {
    const real f0 = 2 * M_PI * k / n, f1 = 2 * M_PI * ((k + 1) % n) / n;  // the last facet closes exactly
    const Vec3 a{R * std::cos(f0), R * std::sin(f0), 0}, b{R * std::cos(f1), R * std::sin(f1), 0};
    t.push_back({bottom + a, bottom + b, top + b});
    t.push_back({bottom + a, top + b, top + a});
    t.push_back({top, top + a, top + b});
    t.push_back({bottom, bottom + b, bottom + a});
  }
  return t;
}

/// The unit sphere's octahedron, each face cut into 4^levels and pushed out to the sphere.
std::vector<TriangleMesh::Triangle> geodesic_sphere(real R, int levels) {
  std::vector<TriangleMesh::Triangle> t;
  const Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  for (const real sx : {-1.0, 1.0})
    for (const real sy : {-1.0, 1.0})
      for (const real sz : {-1.0, 1.0}) {
        TriangleMesh::Triangle f{sx * x, sy * y, sz * z};
        if (sx * sy * sz < 0) std::swap(f[1], f[2]);
        t.push_back(f);
      }
  for (int l = 0; l < levels; ++l) {
    std::vector<TriangleMesh::Triangle> finer;
    for (const auto& f : t) {
      const Vec3 a = f[0], b = f[1], c = f[2];
      const Vec3 ab = (a + b) / norm(a + b), bc = (b + c) / norm(b + c), ca = (c + a) / norm(c + a);
      finer.push_back({a, ab, ca});
      finer.push_back({ab, b, bc});
      finer.push_back({ca, bc, c});
      finer.push_back({ab, bc, ca});
    }
    t = finer;
  }
  for (auto& f : t)
    for (Vec3& v : f) v = R * v;
  return t;
}

/// Every sample on the surface, its normal the distance's gradient there, dA summing to the
/// area, and the samples about d0 apart (nearest-sample distances and dA / d0^2 near 1).
void expect_sampled_at(const Shape3& s, real d0, real area_tol) {
  const std::vector<SurfaceSample3> samples = s.sample_surface(d0);
  ASSERT_GT(samples.size(), 20U);
  real area = 0, nearest_sum = 0;
  for (const SurfaceSample3& p : samples) {
    real d = 0;
    Vec3 n;
    s.distance_and_gradient(p.x, d, n);
    EXPECT_NEAR(d, 0, 1e-9 * s.bounding_radius());
    EXPECT_GT(dot(n, p.normal), 1 - 1e-9) << p.x.x << " " << p.x.y << " " << p.x.z;
    EXPECT_NEAR(norm(p.normal), 1, 1e-14);
    area += p.dA;
    real nearest = 1e300;
    for (const SurfaceSample3& q : samples)
      if (&q != &p) nearest = std::fmin(nearest, norm(q.x - p.x));
    nearest_sum += nearest;
  }
  EXPECT_NEAR(area, s.surface_area(), area_tol * s.surface_area());
  const real mean_nearest = nearest_sum / samples.size() / d0, mean_dA = area / samples.size() / (d0 * d0);
  EXPECT_GT(mean_nearest, 0.6);
  EXPECT_LT(mean_nearest, 1.3);
  EXPECT_GT(mean_dA, 0.75);
  EXPECT_LT(mean_dA, 1.3);
}

}  // namespace

TEST(Shape3, PrimitivesAreSampledWithTheirExactArea) {
  expect_sampled_at(Shape3::sphere(1.0), 0.1, 1e-13);
  expect_sampled_at(Shape3::cuboid(1.0, 0.6, 0.35), 0.1, 1e-13);
  expect_sampled_at(Shape3::cylinder(0.4, 1.1), 0.1, 1e-13);
  expect_sampled_at(Shape3::ellipsoid(1.0, 0.7, 0.45), 0.1, 1e-12);
  expect_sampled_at(
      Shape3::mesh(TriangleMesh::from_triangles(faceted_cylinder(0.4, 0.9, 24, {0.3, -0.2, 1}), "cyl")), 0.1,
      1e-13);
}

// Spheroids have closed-form areas: the ellipsoid's quadrature against them, at two spacings.
TEST(Shape3, SpheroidAreasMatchTheClosedForm) {
  const real a = 0.6, c = 1.5;
  const real ep = std::sqrt(1 - a * a / (c * c));  // prolate: a = b < c
  const real prolate = 2 * M_PI * a * a * (1 + c / (a * ep) * std::asin(ep));
  const real eo = std::sqrt(1 - a * a / (c * c));  // oblate: a = b = c_big, c_small = a
  const real oblate = 2 * M_PI * c * c * (1 + (1 - eo * eo) / eo * std::atanh(eo));
  for (const real d0 : {0.2, 0.07}) {
    real sp = 0, so = 0;
    for (const auto& p : Shape3::ellipsoid(a, a, c).sample_surface(d0)) sp += p.dA;
    for (const auto& p : Shape3::ellipsoid(c, c, a).sample_surface(d0)) so += p.dA;
    EXPECT_NEAR(sp, prolate, 1e-11 * prolate) << d0;
    EXPECT_NEAR(so, oblate, 1e-11 * oblate) << d0;
  }
  EXPECT_NEAR(Shape3::ellipsoid(a, a, c).surface_area(), prolate, 1e-11 * prolate);
}

TEST(Shape3, MassPropertiesAgreeWithThePolyhedron) {
  // a box's mesh, moved off the origin: the cuboid's volume and inertia exactly, the centroid found
  const TriangleMesh box = TriangleMesh::from_triangles(box_triangles({1, 2, 3}, {2.0, 2.6, 3.35}), "box");
  const Shape3 mesh = Shape3::mesh(box), cuboid = Shape3::cuboid(1.0, 0.6, 0.35);
  EXPECT_NEAR(mesh.volume(), cuboid.volume(), 1e-14);
  EXPECT_LT(max_abs_difference(mesh.inertia_per_density(), cuboid.inertia_per_density()), 1e-15);
  EXPECT_NEAR(norm(mesh.centroid_offset() - Vec3{1.5, 2.3, 3.175}), 0, 1e-14);
  EXPECT_NEAR(mesh.surface_area(), cuboid.surface_area(), 1e-14);
  // a cylinder of 1024 facets: the volume and inertia of the faceted solid converge on the
  // cylinder's as (2 pi / n)^2 / 6 (4e-6 relative)
  const Shape3 cyl = Shape3::cylinder(0.4, 1.1);
  const Shape3 facets =
      Shape3::mesh(TriangleMesh::from_triangles(faceted_cylinder(0.4, 1.1, 1024, {}), "cyl"));
  EXPECT_NEAR(facets.volume(), cyl.volume(), 1e-5 * cyl.volume());
  EXPECT_LT(max_abs_difference(facets.inertia_per_density(), cyl.inertia_per_density()),
            1e-5 * cyl.inertia_per_density().xx);
  // a geodesic sphere of 8 * 4^6 faces against the sphere's 2/5 R^2 V
  const Shape3 ball = Shape3::sphere(0.5);
  const Shape3 geo = Shape3::mesh(TriangleMesh::from_triangles(geodesic_sphere(0.5, 6), "sphere"));
  EXPECT_NEAR(geo.volume(), ball.volume(), 1e-3 * ball.volume());
  EXPECT_LT(max_abs_difference(geo.inertia_per_density(), ball.inertia_per_density()),
            2e-3 * ball.inertia_per_density().xx);
  EXPECT_NEAR(geo.inertia_per_density().xx, geo.inertia_per_density().zz, 1e-12);  // as symmetric
  // an ellipsoid: V/5 (b^2 + c^2) about x
  const Shape3 e = Shape3::ellipsoid(1.0, 0.7, 0.45);
  EXPECT_NEAR(e.inertia_per_density().xx, e.volume() / 5 * (0.49 + 0.2025), 1e-15);
  EXPECT_NEAR(e.equivalent_radius(), std::cbrt(1.0 * 0.7 * 0.45), 1e-15);
}

TEST(Shape3, SignedDistances) {
  const Shape3 e = Shape3::ellipsoid(1.0, 0.7, 0.45);
  EXPECT_NEAR(e.signed_distance({2.0, 0, 0}), 1.0, 1e-15);
  EXPECT_NEAR(e.signed_distance({0, 0, 0}), -0.45, 1e-15);
  // against the nearest of many samples (off by at most the sampling's chord error)
  std::mt19937 rng(3);
  std::uniform_real_distribution<real> u(-1.5, 1.5);
  const std::vector<SurfaceSample3> dense = e.sample_surface(0.01);
  int inside = 0;
  for (int k = 0; k < 60; ++k) {
    const Vec3 p = (k % 2 ? 0.5 : 1.0) * Vec3{u(rng), u(rng), u(rng)};  // every other point near the centre
    real best = 1e300;
    for (const auto& s : dense) best = std::fmin(best, norm(s.x - p));
    const real d = e.signed_distance(p);
    EXPECT_NEAR(std::fabs(d), best, 2e-3) << k;
    EXPECT_EQ(d < 0, (p.x * p.x) + (p.y / 0.7) * (p.y / 0.7) + (p.z / 0.45) * (p.z / 0.45) < 1);
    inside += d < 0;
  }
  EXPECT_GT(inside, 5);
  // a cuboid and its mesh agree everywhere, inside (the mesh's sign by the winding number) and out
  const Shape3 box = Shape3::cuboid(1.0, 0.6, 0.35);
  const Shape3 mesh = Shape3::mesh(
      TriangleMesh::from_triangles(box_triangles({-0.5, -0.3, -0.175}, {0.5, 0.3, 0.175}), "box"));
  for (int k = 0; k < 200; ++k) {
    const Vec3 p{0.8 * u(rng), 0.5 * u(rng), 0.4 * u(rng)};
    real d1, d2;
    Vec3 n1, n2;
    box.distance_and_gradient(p, d1, n1);
    mesh.distance_and_gradient(p, d2, n2);
    EXPECT_NEAR(d1, d2, 1e-14) << k;
    EXPECT_LT(norm(n1 - n2), 1e-12) << k;
  }
  EXPECT_NEAR(box.signed_distance({0.5 + 0.3, 0.3 + 0.4, 0}), 0.5, 1e-15);  // off an edge
  const Shape3 cyl = Shape3::cylinder(0.4, 1.0);
  EXPECT_NEAR(cyl.signed_distance({0.7, 0, 0.9}), 0.5, 1e-15);  // off the rim: (0.3, 0.4)
  EXPECT_NEAR(cyl.signed_distance({0, 0.1, 0}), -0.3, 1e-15);
  EXPECT_NEAR(Shape3::sphere(0.5).signed_distance({0, 0.3, 0.4}), 0, 1e-15);
}
