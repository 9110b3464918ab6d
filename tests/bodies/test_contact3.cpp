// Contacts in 3D (bodies/contact_geometry3.hpp, and the spring-dashpot law of bodies/collision.hpp
// instantiated for D = 3): exact sphere-sphere and sphere-plane geometry and the sampled
// fallback, Reynolds' squeeze film between spheres, a sphere's rebound with the restitution, and
// friction turning a sliding sphere into a rolling one at 5/7 of its speed.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "particula/bodies/contact_geometry3.hpp"

using namespace particula;

namespace {

PlacedBody3 placed(const Shape3& s, const std::vector<SurfaceSample3>& samples, Vec3 pos, Quat q = {}) {
  return {&s, &samples, pos, q};
}

/// A free sphere of mass m and radius R against a fixed plane (z = 0, normal +z), stepped as the
/// solver steps a body in contact: the contact load of the step's start for the whole step (its
/// spring at the mid-step overlap), gravity g along -z, V and Omega advanced by dt, the position by
/// the mean velocity.
struct SphereOnPlane {
  real m = 0.01, R = 0.005, k = 0, dt = 0, g = 0;
  ContactLaw law;
  ContactSide3 s, wall;
  real I = 0;

  void step() {
    ContactOf<3> c;
    c.gap = s.pos.z - R;
    c.normal = {0, 0, 1};
    c.point = s.pos - R * c.normal;
    const ContactLoadOf<3> l = spring_dashpot_load(c, s, wall, c.point - s.pos, c.point, k, law, dt);
    const Vec3 v0 = s.vel;
    s.vel += (dt / m) * (l.force + Vec3{0, 0, -m * g});
    s.omega += (dt / I) * l.torque_a;
    s.pos += (0.5 * dt) * (v0 + s.vel);
  }
};

SphereOnPlane sphere_on_plane(real restitution, real friction, real g) {
  SphereOnPlane p;
  p.g = g;
  p.I = 0.4 * p.m * p.R * p.R;
  p.law.delta_c = 0;
  p.law.zeta = damping_ratio(restitution);
  p.law.friction = friction;
  p.k = derived_stiffness(p.m, 0.1, 1e-4);  // 0.1 m/s stopped within 0.1 mm
  p.dt = contact_duration(p.m, p.k) / kStepsPerContact;
  p.s.mass = p.m;
  p.s.inertia_inv = (1 / p.I) * identity3();
  p.s.radius = p.R;
  return p;
}

}  // namespace

TEST(Contact3, SpheresAndPlanesAreExactOtherShapesSampled) {
  const Shape3 a = Shape3::sphere(0.5), b = Shape3::sphere(0.3);
  const std::vector<SurfaceSample3> sa = a.sample_surface(0.05), sb = b.sample_surface(0.05);
  Domain3 d;
  d.lo = {0, 0, 0};
  d.hi = {4, 4, 4};
  d.periodic_x = true;
  // across the periodic side: centres 0.9 apart through x = 0
  const ContactOf<3> c = body_contact(placed(a, sa, {0.3, 2, 2}), placed(b, sb, {3.4, 2, 2}), d);
  EXPECT_NEAR(c.gap, 0.1, 1e-14);
  EXPECT_NEAR(norm(c.normal - Vec3{1, 0, 0}), 0, 1e-15);  // from b towards a
  EXPECT_NEAR(norm(c.point - Vec3{-0.25, 2, 2}), 0, 1e-14);
  const WallPlane floor{{0, 0, 0}, {0, 0, 1}};
  const ContactOf<3> w = wall_contact(placed(a, sa, {1, 1, 0.52}), floor);
  EXPECT_NEAR(w.gap, 0.02, 1e-15);
  EXPECT_NEAR(norm(w.point - Vec3{1, 1, 0.02}), 0, 1e-15);
  // a cuboid flat on the floor: its bottom face's samples are on it, exact
  const Shape3 box = Shape3::cuboid(0.4, 0.3, 0.2);
  const std::vector<SurfaceSample3> sbox = box.sample_surface(0.05);
  EXPECT_NEAR(wall_contact(placed(box, sbox, {1, 1, 0.13}), floor).gap, 0.03, 1e-15);
  // turned 45 degrees about x it stands on an edge: the samples find the gap from above, within
  // the chord of the sampling
  const real edge = 0.5 * std::hypot(0.3, 0.2) * std::cos(M_PI / 4 - std::atan2(0.2, 0.3));
  const ContactOf<3> e =
      wall_contact(placed(box, sbox, {1, 1, edge + 0.03}, axis_angle({1, 0, 0}, M_PI / 4)), floor);
  EXPECT_GE(e.gap, 0.03 - 1e-15);
  EXPECT_LT(e.gap, 0.03 + 0.05);
  // a cuboid against a sphere: the sampled query against the exact signed distances
  const ContactOf<3> bs =
      body_contact(placed(box, sbox, {2, 2, 2}), placed(a, sa, {2, 2, 2.1 + 0.5 + 0.04}), d);
  EXPECT_GE(bs.gap, 0.04);  // samples on one surface against the other's exact distance: never below
  EXPECT_LT(bs.gap, 0.04 + 0.002);
  EXPECT_LT(norm(bs.normal - Vec3{0, 0, -1}), 0.1);
}

// Reynolds: F = 6 pi mu U R*^2 / g between two spheres; the correction vanishes at the range,
// holds g_min below it, and is clipped as in 2D.
TEST(Contact3, SqueezeFilmBetweenSpheresIsReynolds) {
  const real mu = 1e-3, Ra = 1e-3, Rb = 2e-3, g = 1e-5;
  const real R_star = reduced_radius(Ra, Rb);
  EXPECT_DOUBLE_EQ(squeeze_film_coefficient<3>(mu, R_star, g), 6 * M_PI * mu * R_star * R_star / g);
  const real C = [&](real gap) { return squeeze_film_coefficient<3>(mu, R_star, gap); }(2e-5);
  const real range = 4e-5, gmin = 2e-6, m = 1e-3, dt = 1e-5;
  EXPECT_EQ(lubrication_coefficient<3>(mu, R_star, range, gmin, range, m, dt), 0.0);
  EXPECT_DOUBLE_EQ(lubrication_coefficient<3>(mu, R_star, 2e-5, gmin, range, m, dt),
                   C - squeeze_film_coefficient<3>(mu, R_star, range));
  EXPECT_DOUBLE_EQ(lubrication_coefficient<3>(mu, R_star, 1e-9, gmin, range, m, dt),
                   lubrication_coefficient<3>(mu, R_star, gmin, gmin, range, m, dt));
  EXPECT_DOUBLE_EQ(lubrication_coefficient<3>(mu, R_star, 1e-9, gmin, range, 1e-9, dt), 0.5 * 1e-9 / dt);
  // and the 2D law is the cylinders' one still
  EXPECT_DOUBLE_EQ(squeeze_film_coefficient(mu, R_star, g), squeeze_film_coefficient<2>(mu, R_star, g));
  EXPECT_NE(squeeze_film_coefficient<2>(mu, R_star, g), squeeze_film_coefficient<3>(mu, R_star, g));
}

TEST(Contact3, SphereReboundsWithTheRestitution) {
  for (const real e : {0.95, 0.8}) {  // the restitutions the 2D law is checked at
    SphereOnPlane p = sphere_on_plane(e, 0, 0);
    p.s.pos = {0, 0, p.R + 1e-5};
    p.s.vel = {0, 0, -0.1};
    for (int n = 0; n < 400 && !(p.s.pos.z > p.R + 2e-5); ++n) p.step();
    EXPECT_NEAR(p.s.vel.z / 0.1, e, 0.03 * e) << e;
    EXPECT_NEAR(norm(p.s.omega), 0, 1e-15);  // a central impact turns nothing
  }
}

// A sphere sliding without spin on a floor under gravity: friction brakes the sliding and spins
// it up until it rolls, V = 5/7 V0 and Omega_y = V / R for a solid sphere (I = 2/5 m R^2).
TEST(Contact3, FrictionTurnsSlidingIntoRolling) {
  SphereOnPlane p = sphere_on_plane(0.5, 0.3, 9.81);
  p.s.pos = {0, 0, p.R - p.m * p.g / p.k};  // resting on its spring
  p.s.vel = {0.05, 0, 0};
  const real t_slide = 2.0 / 7 * 0.05 / (0.3 * 9.81);  // when Coulomb friction makes it roll
  const int n = static_cast<int>(3 * t_slide / p.dt);
  for (int k = 0; k < n; ++k) p.step();
  EXPECT_NEAR(p.s.vel.x, 5.0 / 7 * 0.05, 0.01 * 0.05);
  EXPECT_NEAR(p.s.omega.y * p.R, p.s.vel.x, 0.01 * 0.05);
  EXPECT_NEAR(p.s.omega.x, 0, 1e-12);
  EXPECT_NEAR(p.s.omega.z, 0, 1e-12);
  EXPECT_NEAR(p.s.vel.y, 0, 1e-12);
}
