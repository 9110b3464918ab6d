// The spring-dashpot contact model (bodies/collision.hpp, docs/method.md "Contacts"): the
// force law, dry collisions through the solver (restitution and largest overlap), the
// lubrication force against lubrication theory, torques of off-centre contacts, and the cell
// list of contact candidates against all pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "case_builders.hpp"
#include "particula/bodies/collision.hpp"
#include "particula/bodies/contact_pairs.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;

// ---------------------------------------------------------------------------------------------
// The force law

TEST(ContactLaw, NormalForceIsNeverAttractive) {
  const real k = 1e3, gamma = 5;
  EXPECT_EQ(normal_force(k, gamma, 0.0, 1.0), 0.0) << "no overlap, no force";
  EXPECT_EQ(normal_force(k, gamma, -1e-3, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(normal_force(k, gamma, 1e-3, 0.1), k * 1e-3 + gamma * 0.1) << "spring + dashpot";
  // Separating fast at a small overlap: the dashpot would pull, the force is 0 instead.
  EXPECT_EQ(normal_force(k, gamma, 1e-4, -1.0), 0.0);
  EXPECT_DOUBLE_EQ(normal_force(k, gamma, 1e-3, -0.1), k * 1e-3 - gamma * 0.1);
}

TEST(ContactLaw, DampingRatioGivesTheRestitution) {
  // A linear spring-dashpot rebounds with e = exp(-zeta pi / sqrt(1 - zeta^2)).
  for (real e : {1.0, 0.9, 0.8, 0.5, 0.1}) {
    const real zeta = damping_ratio(e);
    EXPECT_NEAR(std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta)), e, 1e-12) << e;
  }
  EXPECT_EQ(damping_ratio(1.0), 0.0);
  EXPECT_DOUBLE_EQ(dashpot_coefficient(0.3, 2.0, 8.0), 2 * 0.3 * 4.0);
  EXPECT_DOUBLE_EQ(effective_mass(2.0, 6.0), 1.5);
  EXPECT_DOUBLE_EQ(effective_mass(2.0, 0.0), 2.0) << "against a wall";
}

TEST(ContactLaw, DerivedStiffnessStopsTheImpactAtTheLargestOverlap) {
  // An explicit loop of the solver's scheme (force of the mid-step overlap, velocity and centre
  // updated as free_body_stage/free_body_update do) at dt = t_c / 20: a body hitting a wall at U
  // with k derived from U stops within delta_max (exactly delta_max without damping).
  const real m = 0.004, U = 0.05, delta_max = 1e-5;
  for (real e : {1.0, 0.8, 0.5, 0.2}) {
    const real k = derived_stiffness(m, U, delta_max);
    const real gamma = dashpot_coefficient(damping_ratio(e), m, k);
    const real dt = contact_duration(m, k) / kStepsPerContact;
    real overlap = -0.3 * U * dt, rate = U, deepest = 0;
    for (int n = 0; n < 1000 && !(overlap < 0 && rate < 0); ++n) {
      const real F = normal_force(k, gamma, overlap + 0.5 * dt * rate, rate);
      const real rate_new = rate - dt * F / m;
      overlap += 0.5 * dt * (rate + rate_new);
      rate = rate_new;
      deepest = std::max(deepest, overlap);
    }
    std::printf("e = %.1f: largest overlap %.4f delta_max, rebound %.4f U\n", e, deepest / delta_max,
                -rate / U);
    EXPECT_LE(deepest, 1.005 * delta_max) << e;
    EXPECT_GT(deepest, (e == 1.0 ? 0.99 : 0.4) * delta_max) << e;
    if (e >= 0.8) {
      EXPECT_NEAR(-rate / U, e, 0.03 * e) << e;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Dry collisions through the solver: walls and bodies only (no fluid particles, no viscosity).

namespace {

struct DryRun {
  real restitution = 0;       // -(relative normal velocity after) / (before)
  real deepest = 0;           // largest overlap delta_c - gap, as a fraction of delta_max
  real smallest_dt = 1e9;     // while in contact
  real contact_dt_limit = 0;  // t_c / 20 of the derived stiffness at the impact speed
};

/// A closed box with the given bodies, without its fluid and without viscosity: the bodies move
/// only under the contact forces. Runs until the bodies have separated (or 4000 steps).
Case dry_case(std::vector<BodySpec> bodies, real e) {
  Case c = cases::closed_box(0.02, 0.01, 2e-4);
  c.collision_restitution = e;
  c.bodies = std::move(bodies);
  return c;
}

Solver dry_solver(const Case& c) {
  Scene sc = build_scene(c);
  sc.particles.resize(sc.particles.n_boundary);  // no fluid
  sc.params.nu = 0;                              // no viscous load, no lubrication
  return Solver(sc.params, sc.domain, sc.particles, sc.groups);
}

DryRun dry_collision(std::vector<BodySpec> bodies, bool against_wall, real e) {
  const Case c = dry_case(std::move(bodies), e);
  Solver s = dry_solver(c);
  const std::size_t a = c.walls.size();
  const real R = c.bodies[0].radius, delta_c = 0.5 * c.d0, delta_max = 0.1 * c.d0;
  auto gap = [&] {
    const RigidGroup& ga = s.groups()[a];
    return against_wall ? c.domain_max.x - ga.pos.x - R
                        : norm(s.groups()[a + 1].pos - ga.pos) - R - c.bodies[1].radius;
  };
  auto approach = [&] {  // relative normal velocity, > 0 when approaching
    const RigidGroup& ga = s.groups()[a];
    if (against_wall) return ga.vel.x;
    const Vec2 n = (s.groups()[a + 1].pos - ga.pos) / norm(s.groups()[a + 1].pos - ga.pos);
    return dot(ga.vel - s.groups()[a + 1].vel, n);
  };
  const real before = approach();
  const real m_eff = against_wall ? s.groups()[a].mass : 0.5 * s.groups()[a].mass;
  DryRun out;
  out.contact_dt_limit =
      contact_duration(m_eff, derived_stiffness(m_eff, before, delta_max)) / kStepsPerContact;
  bool touched = false;
  for (int n = 0; n < 4000; ++n) {
    const auto f = s.step();
    EXPECT_FALSE(f.has_value()) << f->what;
    if (f) break;
    const real g = gap();
    if (g < delta_c) {
      touched = true;
      out.deepest = std::max(out.deepest, (delta_c - g) / delta_max);
      out.smallest_dt = std::min(out.smallest_dt, s.last_dt());
    }
    if (touched && g > delta_c + c.d0) break;
  }
  EXPECT_TRUE(touched);
  out.restitution = -approach() / before;
  return out;
}

BodySpec disc(Vec2 centre, Vec2 velocity) {
  BodySpec b;
  b.name = "disc";
  b.shape = BodyShape::Circle;
  b.center = centre;
  b.radius = 1e-3;
  b.density = 1200;
  b.velocity = velocity;
  return b;
}

}  // namespace

TEST(DryCollision, BodyAgainstAWallReboundsWithTheRestitution) {
  for (real e : {0.8, 0.95}) {
    const DryRun r = dry_collision({disc({0.0185, 0.005}, {0.05, 0})}, true, e);
    std::printf(
        "disc against a wall, e = %.2f: restitution %.4f, largest overlap %.3f delta_max, dt %.3g s "
        "(t_c/20 at the impact speed %.3g s)\n",
        e, r.restitution, r.deepest, r.smallest_dt, r.contact_dt_limit);
    EXPECT_NEAR(r.restitution, e, 0.03 * e);
    EXPECT_LE(r.deepest, 1.02);
    EXPECT_GT(r.deepest, 0.5);
    EXPECT_LE(r.smallest_dt, r.contact_dt_limit * (1 + 1e-9)) << "the step resolves the contact";
  }
}

TEST(DryCollision, HeadOnCollisionOfTwoBodiesReboundsWithTheRestitution) {
  const real e = 0.8;
  const DryRun r =
      dry_collision({disc({0.0075, 0.005}, {0.05, 0}), disc({0.0105, 0.005}, {-0.05, 0})}, false, e);
  std::printf(
      "two discs head-on, e = %.2f: restitution %.4f, largest overlap %.3f delta_max, dt %.3g s (t_c/20 "
      "%.3g s)\n",
      e, r.restitution, r.deepest, r.smallest_dt, r.contact_dt_limit);
  EXPECT_NEAR(r.restitution, e, 0.03 * e);
  EXPECT_LE(r.deepest, 1.02) << "the stiffness follows the relative impact speed";
  EXPECT_GT(r.deepest, 0.5);
  EXPECT_LE(r.smallest_dt, r.contact_dt_limit * (1 + 1e-9));
}

TEST(DryCollision, TooSoftAContactStopsTheRunNamingTheKey) {
  // Overlap beyond 0.25 d0 is a failure (exit code 3) whose message says what to change.
  const auto failure = [](Case c) -> std::string {
    Solver s = dry_solver(c);
    for (int n = 0; n < 4000; ++n)
      if (const auto f = s.step()) return f->what;
    return "";
  };
  // The disc's surface particles half a spacing off the wall's: the Courant step, which follows the
  // smallest particle distance, then does not vanish as the disc reaches the wall.
  Case soft = dry_case({disc({0.0185, 0.0051}, {0.05, 0})}, 0.95);
  soft.collision_max_overlap = 1.0;  // delta_max = d0 > delta_c + 0.25 d0
  const std::string derived = failure(soft);
  EXPECT_NE(derived.find("body 'disc' overlaps wall 'right' by"), std::string::npos) << derived;
  EXPECT_NE(derived.find("contact too soft for this impact speed: lower collision.max_overlap or set "
                         "collision.stiffness"),
            std::string::npos)
      << derived;
  Case given = dry_case({disc({0.0185, 0.0051}, {0.05, 0})}, 0.95);
  given.collision_stiffness = 10;  // N/m^2: far too soft at 0.05 m/s
  const std::string user = failure(given);
  EXPECT_NE(user.find("raise collision.stiffness, or set it to 0 to derive it"), std::string::npos) << user;
}

// ---------------------------------------------------------------------------------------------
// Lubrication

TEST(Lubrication, SqueezeFilmForceIsLubricationTheory) {
  // Reynolds equation for the film h(x) = g + x^2 / (2 R*) squeezed at speed U: the pressure
  // p(x) = 6 mu U R* / h^2; its integral over x must be (3 pi / 2) mu U (2 R* / g)^(3/2).
  const real mu = 1e-3, U = 0.01;
  for (const real R : {1e-3, 2.5e-3}) {
    for (const real g : {1e-6, 1e-5, 1e-4}) {
      const real L = 2000 * std::sqrt(2 * R * g), n = 400000, dx = 2 * L / n;
      real F = 0;
      for (int i = 0; i < n; ++i) {
        const real x = -L + (i + 0.5) * dx, h = g + x * x / (2 * R);
        F += 6 * mu * U * R / (h * h) * dx;
      }
      EXPECT_NEAR(F / (U * squeeze_film_coefficient(mu, R, g)), 1.0, 2e-3) << R << " " << g;
    }
  }
  EXPECT_DOUBLE_EQ(reduced_radius(1e-3, 1e-3), 0.5e-3);
  EXPECT_DOUBLE_EQ(reduced_radius(1e-3, 0), 1e-3) << "cylinder and plane";
}

TEST(Lubrication, CorrectionVanishesAtTheRangeAndIsClipped) {
  const real mu = 1e-3, R = 1e-3, d0 = 1e-4, g_min = 0.1 * d0, g_range = 2 * d0, m = 1.0, dt = 1e-4;
  const auto C = [&](real g) { return squeeze_film_coefficient(mu, R, g); };
  EXPECT_EQ(lubrication_coefficient(mu, R, g_range, g_min, g_range, m, dt), 0.0) << "continuous at the range";
  EXPECT_EQ(lubrication_coefficient(mu, R, 3 * d0, g_min, g_range, m, dt), 0.0);
  EXPECT_DOUBLE_EQ(lubrication_coefficient(mu, R, d0, g_min, g_range, m, dt), C(d0) - C(g_range));
  EXPECT_DOUBLE_EQ(lubrication_coefficient(mu, R, 0.01 * d0, g_min, g_range, m, dt), C(g_min) - C(g_range))
      << "g_eff = max(g, 0.1 d0)";
  // A light body: the coefficient is clipped to c dt / m_eff = 0.5.
  const real light = 1e-6;
  EXPECT_DOUBLE_EQ(lubrication_coefficient(mu, R, d0, g_min, g_range, light, dt), 0.5 * light / dt);
  // Through the contact load: it opposes the approach, and pulls when the bodies separate.
  ContactLaw law;
  law.delta_c = 0.5 * d0;
  law.lubrication = true;
  law.viscosity = mu;
  law.lub_range = g_range;
  law.lub_min_gap = g_min;
  Contact c;
  c.gap = d0;
  c.normal = {0, 1};
  ContactSide a, wall;
  a.mass = m;
  a.radius = R;
  a.vel = {0, -0.01};  // approaching the wall below
  const ContactLoad in = spring_dashpot_load(c, a, wall, {0, -R}, {}, 1e3, law, dt);
  EXPECT_EQ(in.normal, 0.0) << "outside the contact distance";
  EXPECT_NEAR(in.force.y, (C(d0) - C(g_range)) * 0.01, 1e-12 * in.force.y);
  a.vel = {0, 0.01};
  EXPECT_LT(spring_dashpot_load(c, a, wall, {0, -R}, {}, 1e3, law, dt).force.y, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Torques and friction

TEST(ContactTorque, OffCentreContactTurnsTheBody) {
  // An ellipse lying tilted on a wall touches it with the end of its long axis: the normal
  // force at that point, off the line through the centre, has a torque about the centre.
  const Shape e = Shape::ellipse(2e-3, 1e-3);
  const auto samples = e.sample_surface(5e-5);
  const real angle = 0.3;
  const PlacedBody body{&e, &samples, {0.01, 0}, angle};
  Contact c = wall_contact(body, WallPiece::segment({0, -0.5}, {0.02, -0.5}));
  c.gap = 0;  // place the wall at the lowest point
  const Vec2 r = c.point - body.pos;
  EXPECT_GT(std::fabs(r.x), 0.5e-3) << "the lowest point is off the vertical through the centre";
  ContactLaw law;
  law.delta_c = 5e-5;
  ContactSide a, wall;
  a.pos = body.pos;
  a.mass = 0.01;
  a.inertia = 1e-8;
  const ContactLoad l = spring_dashpot_load(c, a, wall, r, {}, 1e4, law, 1e-5);
  EXPECT_NEAR(l.force.y, 1e4 * 5e-5, 1e-12);
  EXPECT_DOUBLE_EQ(l.torque_a, cross(r, l.force));
  EXPECT_NE(l.torque_a, 0.0);
  // Turned by +0.3 rad, the ellipse's lowest point lies left of the centre (r.x < 0): the
  // upward force there turns it clockwise, back towards lying flat.
  EXPECT_LT(r.x, 0.0);
  EXPECT_LT(l.torque_a, 0.0);
}

TEST(ContactTorque, ADiscOnAWallFeelsNoTorqueFromTheNormalForce) {
  // The sampled wall contact of a disc takes its lowest surface sample, up to half a spacing
  // beside the bottom; the exact one takes the point below the centre, so the normal force of a
  // resting disc has no torque, whatever its angle.
  const real R = 1.25e-3;
  const Shape c = Shape::circle(R);
  const auto samples = c.sample_surface(2e-4);
  for (real angle : {0.0, 0.03, 0.05, 1.0}) {
    const PlacedBody disc{&c, &samples, {0.01, 0.001 + R}, angle};
    const Contact sampled = wall_contact(disc, WallPiece::segment({0, 0.001}, {0.02, 0.001}));
    const Contact exact = wall_contact_exact(disc, WallPiece::segment({0, 0.001}, {0.02, 0.001}));
    EXPECT_NEAR(exact.gap, 0.0, 1e-15);
    EXPECT_GE(sampled.gap, exact.gap - 1e-15);
    EXPECT_DOUBLE_EQ(exact.point.x, 0.01);
    EXPECT_EQ(cross(exact.point - disc.pos, exact.normal), 0.0);
  }
  // Beyond the segment's ends the wall does not act.
  const PlacedBody off{&c, &samples, {0.03, 0.001 + R}, 0};
  EXPECT_GT(wall_contact_exact(off, WallPiece::segment({0, 0.001}, {0.02, 0.001})).gap, 1e299);
}

TEST(ContactTorque, FrictionOfASlidingDiscIsCoulombAndSpinsIt) {
  // A disc sliding to the right on a wall below: friction mu F_n to the left at the contact
  // point, and the torque R mu F_n that starts it rolling (clockwise, negative omega).
  const real R = 1e-3, k = 1e4, mu_f = 0.4, dt = 1e-5;
  ContactLaw law;
  law.delta_c = 5e-5;
  law.friction = mu_f;
  Contact c;
  c.gap = 0;
  c.normal = {0, 1};
  c.point = {0, -R};
  ContactSide a, wall;
  a.mass = 0.003;
  a.inertia = 0.5 * a.mass * R * R;
  a.vel = {0.1, 0};
  const ContactLoad l = spring_dashpot_load(c, a, wall, {0, -R}, {}, k, law, dt);
  EXPECT_DOUBLE_EQ(l.normal, k * law.delta_c);
  EXPECT_NEAR(l.friction.x, -mu_f * l.normal, 1e-15);
  EXPECT_NEAR(l.torque_a, -R * mu_f * l.normal, 1e-18);
  // Slowly sliding: the viscous branch, which removes half the sliding speed in one step.
  a.vel = {1e-6, 0};
  const ContactLoad slow = spring_dashpot_load(c, a, wall, {0, -R}, {}, k, law, dt);
  const real m_t = 1 / (1 / a.mass + R * R / a.inertia);
  EXPECT_NEAR(slow.friction.x, -0.5 * m_t / dt * 1e-6, 1e-15);
  // Rolling without sliding (v = -omega R): no tangential relative velocity, no friction.
  a.vel = {0.1, 0};
  a.omega = -0.1 / R;
  // (up to the round-off of v + omega x r, which differs between builds: 1e-16 under the sanitizers)
  EXPECT_NEAR(spring_dashpot_load(c, a, wall, {0, -R}, {}, k, law, dt).friction.x, 0.0, 1e-9 * mu_f * l.normal);
}

// ---------------------------------------------------------------------------------------------
// Contact candidates: the cell list finds exactly the pairs that testing all pairs finds.

TEST(ContactCandidates, CellListEqualsAllPairs) {
  SplitMix64 rng(20240617);
  auto uniform = [&](real lo, real hi) { return lo + (hi - lo) * 0.5 * (rng.symmetric() + 1); };
  int configurations = 0;
  std::size_t pairs_seen = 0;
  for (int periodic = 0; periodic < 4; ++periodic) {
    for (int trial = 0; trial < 25; ++trial) {
      const Domain dom{
          {-0.01, 0.02}, {uniform(0.0, 0.05), uniform(0.03, 0.07)}, (periodic & 1) != 0, (periodic & 2) != 0};
      const int n = 1 + static_cast<int>(uniform(0, 300));
      const real r_max = uniform(1e-4, 4e-3);
      std::vector<Vec2> pos(n);
      std::vector<real> bound(n);
      for (int i = 0; i < n; ++i) {
        // some bodies beyond the box (not yet wrapped, or outside a closed one)
        pos[i] = {uniform(dom.lo.x - 0.003, dom.hi.x + 0.003), uniform(dom.lo.y - 0.003, dom.hi.y + 0.003)};
        bound[i] = uniform(0.2, 1.0) * r_max;
      }
      const real range = uniform(0, 2e-3);
      std::vector<BodyPair> cells, all;
      contact_candidates(pos, bound, range, dom, cells);
      contact_candidates_all_pairs(pos, bound, range, dom, all);
      ASSERT_EQ(cells, all) << "periodic " << periodic << " trial " << trial << " n " << n;
      pairs_seen += all.size();
      ++configurations;
    }
  }
  EXPECT_GT(pairs_seen, 500u) << "the configurations must contain pairs";
  std::printf("cell list = all pairs on %d configurations (%zu pairs)\n", configurations, pairs_seen);
}
