// The checks of the robustness group of `particula validate` on fabricated run
// directories: overlap, gaps, energy decay, resting bodies, rebound, squeeze, viscosity,
// containment, open-boundary cases and guard counters (tests/validation/test_robustness.cpp runs the group).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "case_builders.hpp"
#include "cli_process.hpp"
#include "fabricated_runs.hpp"
#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/json.hpp"
#include "particula/io/vtk.hpp"
#include "particula/run/runner.hpp"
#include "particula/scene/scene.hpp"
#include "particula/validation/robustness.hpp"
#include "particula/validation/validate.hpp"

namespace fs = std::filesystem;
using namespace particula;
using cli_test::fresh_dir;
using fabricated::find;
using fabricated::Row;
using fabricated::write_bodies;

namespace {

const fs::path kSource = PARTICULA_SOURCE_DIR;

BodySpec circle(Vec2 center, real radius, BodyMotion motion = BodyMotion::Free) {
  return cases::circle_body("c", center, radius, motion);
}

/// A 1 cm box at d0 = 1e-4 with two circles of radius 1 mm.
Case two_circles() {
  Case c = cases::closed_box(0.01, 0.01, 1e-4);
  c.bodies = {circle({0.003, 0.005}, 1e-3), circle({0.007, 0.005}, 1e-3)};
  c.bodies[1].name = "d";
  return c;
}

}  // namespace

TEST(RobustnessChecks, OverlapOfBodiesAndWalls) {
  const fs::path dir = fresh_dir("robust_overlap");
  const Case c = two_circles();
  // the circles approach until their surfaces overlap by `depth` d0, the first one also the floor
  auto approach = [](double depth, double floor_depth) {
    return [=](double t, int b) {
      Row r;
      const double half = 1e-3 - 0.5 * depth * 1e-4 * t;  // half the centre distance at t = 1
      r.x = b == 0 ? 0.005 - half : 0.005 + half;
      r.y = 0.005 - (0.004 + floor_depth * 1e-4) * t;
      return r;
    };
  };
  write_bodies(dir, 2, 0.1, 1, approach(0.2, 0.1));
  auto ok = check_no_overlap(dir, c);
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_TRUE(ok[0].pass) << ok[0].shown;
  EXPECT_NEAR(ok[0].value, 0.2, 1e-6);
  write_bodies(dir, 2, 0.1, 1, approach(0.4, 0.1));
  EXPECT_FALSE(check_no_overlap(dir, c)[0].pass);
  write_bodies(dir, 2, 0.1, 1, approach(0.1, 0.3));  // into the floor
  const auto wall = check_no_overlap(dir, c);
  EXPECT_FALSE(wall[0].pass);
  EXPECT_NE(wall[0].shown.find("wall 'bottom'"), std::string::npos) << wall[0].shown;
  EXPECT_NEAR(wall[0].value, 0.3, 0.01);
}

TEST(RobustnessChecks, GapsOfNonCircularShapes) {
  Case c = cases::closed_box(0.01, 0.01, 1e-4);
  BodySpec square;
  square.name = "square";
  square.shape = BodyShape::Polygon;
  square.vertices = {{0.004, 0.004}, {0.006, 0.004}, {0.006, 0.006}, {0.004, 0.006}};
  square.density = 2000;
  c.bodies = {square, circle({0.0075, 0.005}, 1e-3)};
  // centroid (0.005, 0.005); the circle's surface is 0.5 mm from the square's right side
  EXPECT_NEAR(body_gap(c, 0, {0.005, 0.005}, 0, 1, {0.0075, 0.005}, 0), 5e-4, 1e-6);
  // turned by 45 degrees the square's corner reaches sqrt(2) mm: 0.0075 - 0.005 - 1.414e-3 - 1e-3
  EXPECT_NEAR(body_gap(c, 0, {0.005, 0.005}, M_PI / 4, 1, {0.0075, 0.005}, 0),
              2.5e-3 - std::sqrt(2.0) * 1e-3 - 1e-3, 2e-6);
  EXPECT_NEAR(wall_gap(c, 0, {0.005, 0.0012}, 0, 0), 2e-4, 1e-9);  // 0.2 mm above the floor
  EXPECT_NEAR(wall_gap(c, 0, {0.005, 0.0009}, 0, 0), -1e-4, 1e-9);
}

TEST(RobustnessChecks, KineticEnergyDecayAndRestingBodies) {
  const fs::path dir = fresh_dir("robust_energy");
  const Case c = two_circles();
  // both fall and stop on the floor (1 mm radius: centre at 1 mm + gap)
  auto settle = [](double tau, double rest_gap) {
    return [=](double t, int b) {
      Row r;
      r.x = b == 0 ? 0.003 : 0.007;
      r.vy = -0.01 * (t / 0.1) * std::exp(1 - t / tau);
      r.y = 1e-3 + rest_gap + 3e-3 * std::exp(-t / tau);
      return r;
    };
  };
  write_bodies(dir, 2, 0.01, 1, settle(0.1, 0.5e-4));
  for (const auto& k : check_kinetic_energy_decay(dir, c, 0.02))
    EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  for (const auto& k : check_bodies_touching(dir, c, 1e-4))
    EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  // Low in the last row but not at rest: the mean over the last 0.1 s is what counts.
  write_bodies(dir, 2, 0.01, 1, [&](double t, int b) {
    Row r = settle(0.1, 0.5e-4)(t, b);
    if (t > 0.895 && t < 0.995) r.vx = 0.004;  // 16 % of the peak energy, 0 in the last row
    return r;
  });
  const auto stirred = check_kinetic_energy_decay(dir, c, 0.02);
  EXPECT_FALSE(stirred[0].pass) << stirred[0].shown;
  EXPECT_NEAR(stirred[0].value, 10.0 / 11.0 * 0.16, 0.03) << stirred[0].shown;
  write_bodies(dir, 2, 0.01, 1, settle(0.5, 3e-4));  // still moving, and hovering 3 d0 above the floor
  EXPECT_FALSE(check_kinetic_energy_decay(dir, c, 0.02)[0].pass);
  const auto apart = check_bodies_touching(dir, c, 1e-4);
  EXPECT_FALSE(apart[0].pass) << apart[0].shown;
  EXPECT_EQ(apart[0].value, 0);
  // The threshold is a distance: at half the spacing a body 56 um off the floor (1.12 d0) rests,
  // one 0.15 mm off does not.
  Case fine = c;
  fine.d0 = 5e-5;
  write_bodies(dir, 2, 0.01, 1, settle(0.1, 0.56e-4));
  EXPECT_TRUE(check_bodies_touching(dir, fine, 1e-4)[0].pass);
  write_bodies(dir, 2, 0.01, 1, settle(0.1, 1.5e-4));
  EXPECT_FALSE(check_bodies_touching(dir, fine, 1e-4)[0].pass);
}

TEST(RobustnessChecks, ReboundAgainstTheRestitutionCoefficient) {
  const fs::path dir = fresh_dir("robust_rebound");
  Case c = two_circles();
  c.bodies.resize(1);
  // falls at 0.5 m/s onto the floor, reverses at a constant rate over `t_rev` from t_hit and
  // leaves it at `ratio` x 0.5 m/s (no case.toml: e = 0.8)
  auto bounce = [](double ratio, double t_rev = 1e-3) {
    return [=](double t, int) {
      Row r;
      r.x = 0.005;
      const double t_hit = 4e-3, s = t - t_hit, a = t_rev > 0 ? 0.5 * (1 + ratio) / t_rev : 0;
      if (s < 0) {
        r.y = 1e-3 - 0.5 * s;
        r.vy = -0.5;
      } else if (s < t_rev) {
        r.y = 1e-3 - 0.5 * s + 0.5 * a * s * s;
        r.vy = -0.5 + a * s;
      } else {
        r.y = 1e-3 - 0.5 * t_rev + 0.5 * a * t_rev * t_rev + ratio * 0.5 * (s - t_rev);
        r.vy = ratio * 0.5;
      }
      return r;
    };
  };
  write_bodies(dir, 1, 1e-4, 8e-3, bounce(0.75));
  auto good = check_rebound(dir, c, 0, 0, 0.25);
  EXPECT_TRUE(find(good, "rebound speed").pass) << find(good, "rebound speed").shown;
  EXPECT_NEAR(find(good, "rebound speed").value, 0.75, 1e-9);
  EXPECT_NEAR(find(good, "impact speed").value, 0.5, 1e-9);
  EXPECT_TRUE(find(good, "output rows").pass) << find(good, "output rows").shown;
  EXPECT_EQ(find(good, "output rows").value, 10);
  // a record whose rows straddle the reversal (one row apart) cannot show the peak
  write_bodies(dir, 1, 1e-4, 8e-3, bounce(0.75, 0.0));
  auto straddled = check_rebound(dir, c, 0, 0, 0.25);
  EXPECT_FALSE(find(straddled, "output rows").pass);
  EXPECT_EQ(find(straddled, "output rows").value, 1);
  write_bodies(dir, 1, 1e-4, 8e-3, bounce(0.3));  // a dead bounce
  EXPECT_FALSE(find(check_rebound(dir, c, 0, 0, 0.25), "rebound speed").pass);
  // the coefficient of the resolved case wins over the default
  write_bodies(dir, 1, 1e-4, 8e-3, bounce(0.35));
  EXPECT_FALSE(find(check_rebound(dir, c, 0, 0, 0.25), "rebound speed").pass);
  io::write_file_atomic(dir / "case.toml", "[collision]\nrestitution = 0.4\n");
  EXPECT_TRUE(find(check_rebound(dir, c, 0, 0, 0.25), "rebound speed").pass);
}

TEST(RobustnessChecks, SqueezeForcesAndGap) {
  const fs::path dir = fresh_dir("robust_squeeze");
  Case c = two_circles();
  for (auto& b : c.bodies) b.motion = BodyMotion::Prescribed;
  // closing at 1 mm/s to a gap of 0.1 d0 at t = 1, then opening; the force on body 0 opposes
  // the approach (sign -1) and the parting (sign +1) when `physical`
  auto squeeze = [](double sign) {
    return [=](double t, int b) {
      Row r;
      const double s = t <= 1 ? t : 2 - t, v = t <= 1 ? 1e-3 : -1e-3;
      const double half = 1e-3 + 0.5e-5 + 0.5 * 1e-3 * (1 - s);
      r.x = b == 0 ? 0.005 - half : 0.005 + half;
      r.y = 0.005;
      r.vx = b == 0 ? v : -v;
      r.fx = b == 0 ? sign * -v : 0;
      return r;
    };
  };
  write_bodies(dir, 2, 0.01, 2, squeeze(1));
  for (const auto& k : check_prescribed_squeeze(dir, c, 0.1))
    EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(find(check_prescribed_squeeze(dir, c, 0.1), "smallest gap").value, 0.1, 1e-6);
  write_bodies(dir, 2, 0.01, 2, squeeze(-1));
  const auto bad = check_prescribed_squeeze(dir, c, 0.1);
  EXPECT_FALSE(find(bad, "force on body 0 along the line of centres while closing").pass);
  EXPECT_FALSE(find(bad, "force on body 0 along the line of centres while parting").pass);
  EXPECT_FALSE(find(check_prescribed_squeeze(dir, c, 0.3), "smallest gap").pass);
}

TEST(RobustnessChecks, ShearedSuspensionViscosityFromTheWalls) {
  const fs::path dir = fresh_dir("robust_shear");
  Case c = cases::startup_channel(20, 1e-3, 0);  // L = 1 mm high, 8 d0 long, top wall at 1 mm/s
  c.walls[0].velocity = {-1e-3, 0};              // gamma = 2 1/s
  // walls feel the stress mu_r mu gamma over their length
  auto walls = [&](double mu_r, double imbalance) {
    io::CsvWriter csv(dir / "walls.csv", {"time", "wall", "fx", "fy", "fpx", "fpy", "fvx", "fvy"});
    const double L = c.domain_max.x, tau = mu_r * c.mu() * 2;
    for (int k = 0; k <= 60; ++k) {
      csv.row({k * 0.1, 0, tau * L * (1 + imbalance), 0, 0, 0, 0, 0});
      csv.row({k * 0.1, 1, -tau * L, 0, 0, 0, 0, 0});
    }
  };
  walls(2.5, 0.01);
  for (const auto& k : check_sheared_suspension(dir, c, 10, 1.2, 6))
    EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(find(check_sheared_suspension(dir, c, 10, 1.2, 6), "relative viscosity").value, 2.5 * 1.005,
              1e-6);
  walls(1.0, 0.3);  // no thickening, and unbalanced
  const auto bad = check_sheared_suspension(dir, c, 10, 1.2, 6);
  EXPECT_FALSE(find(bad, "relative viscosity").pass);
  EXPECT_FALSE(find(bad, "|F_top + F_bottom|").pass);
  EXPECT_FALSE(find(check_sheared_suspension(dir, c, 20, 1.2, 6), "strain").pass) << "6 s at 2 1/s is 12";
}

TEST(RobustnessChecks, DiluteViscosityAgainstEinstein) {
  const fs::path dir = fresh_dir("robust_dilute");
  const Case c = load_case(kSource / "cases/robustness/dilute_shear_phi010.toml");  // 12 circles, phi 0.1
  const double L = c.domain_max.x, gamma = 1.0;                                     // walls at -+3 mm/s, 6 mm
  // the walls feel mu_r mu gamma over their length, with a seeded noise of 2 % on every row
  auto walls = [&](double mu_r) {
    io::CsvWriter csv(dir / "walls.csv", {"time", "wall", "fx", "fy", "fpx", "fpy", "fvx", "fvy"});
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0, 0.02);
    for (int k = 0; k <= 400; ++k) {
      const double tau = mu_r * (1 + noise(rng)) * c.mu() * gamma;
      csv.row({k * 0.05, 0, tau * L, 0, 0, 0, 0, 0});
      csv.row({k * 0.05, 1, -tau * L, 0, 0, 0, 0, 0});
    }
  };
  walls(1.2);  // 1 + 2 phi
  const auto good = check_dilute_viscosity(dir, c, 20);
  for (const auto& k : good) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(find(good, "intrinsic viscosity").value, 2.0, 0.1);
  walls(1.05);  // half the Einstein increment
  EXPECT_FALSE(find(check_dilute_viscosity(dir, c, 20), "intrinsic viscosity").pass);
  walls(1.45);  // more than 4 phi above: a dense suspension's viscosity, not a dilute one's
  EXPECT_FALSE(find(check_dilute_viscosity(dir, c, 20), "intrinsic viscosity").pass);
  EXPECT_FALSE(find(check_dilute_viscosity(dir, c, 20), "relative viscosity").pass);
}

TEST(RobustnessChecks, FluidOutsideTheDomainOrInsideABody) {
  const fs::path dir = fresh_dir("robust_fluid");
  const Case c = two_circles();
  write_bodies(dir, 2, 0.1, 1, [](double, int b) { return Row{b == 0 ? 0.003 : 0.007, 0.005}; });
  auto snapshot = [&](std::vector<Vec2> fluid) {
    std::vector<std::int32_t> kind(fluid.size(), static_cast<std::int32_t>(Kind::Fluid));
    io::write_vtp(dir / "s.vtp", fluid, {}, {io::VtkIntArray{"kind", 1, kind}});
    io::PvdIndex pvd;
    pvd.add(1.0, "s.vtp");
    pvd.write(dir / "particles.pvd");
  };
  snapshot({{0.005, 0.005}, {0.003, 0.0059}});  // the second 0.9 mm from a centre: 0.1 mm = 1 d0 inside
  auto bad = check_fluid_contained(dir, c);
  EXPECT_TRUE(find(bad, "fluid particles outside").pass);
  EXPECT_FALSE(find(bad, "fluid particles more than").pass);
  snapshot({{0.005, -1e-5}, {0.003, 0.00597}});  // below the floor; 0.3 d0 inside a body is allowed
  bad = check_fluid_contained(dir, c);
  EXPECT_FALSE(find(bad, "fluid particles outside").pass);
  EXPECT_TRUE(find(bad, "fluid particles more than").pass);
}

TEST(RobustnessChecks, ABodyRemovedAtAnOutletIsLeftOutAfterItsLastRow) {
  // Body 1's rows end at t = 0.5 (an outlet removed it): fluid in its last place later is the
  // fill, not fluid inside a body, and the overlap check goes on over the other bodies' rows.
  const fs::path dir = fresh_dir("robust_removed");
  const Case c = two_circles();
  {
    io::CsvWriter csv(dir / "bodies.csv", {"time", "body", "x", "y", "angle", "vx", "vy", "omega", "fx", "fy",
                                           "torque", "fpx", "fpy", "fvx", "fvy", "fcx", "fcy"});
    for (int k = 0; k <= 10; ++k) {
      const double t = 0.1 * k;
      csv.row({t, 0, 0.003, 0.005 - 0.0045 * t, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
               0});  // into the floor by t = 1
      if (k <= 5) csv.row({t, 1, 0.007, 0.005, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    }
  }
  const auto overlap = check_no_overlap(dir, c);
  EXPECT_FALSE(overlap[0].pass) << "the rows after the removal were not checked: " << overlap[0].shown;
  EXPECT_NE(overlap[0].shown.find("wall 'bottom'"), std::string::npos) << overlap[0].shown;
  auto snapshot = [&](double t) {
    const std::vector<Vec2> fluid{{0.007, 0.005}};  // at body 1's centre
    std::vector<std::int32_t> kind(fluid.size(), static_cast<std::int32_t>(Kind::Fluid));
    io::write_vtp(dir / "s.vtp", fluid, {}, {io::VtkIntArray{"kind", 1, kind}});
    io::PvdIndex pvd;
    pvd.add(t, "s.vtp");
    pvd.write(dir / "particles.pvd");
  };
  snapshot(0.5);  // body 1 still there
  EXPECT_FALSE(find(check_fluid_contained(dir, c), "fluid particles more than").pass);
  snapshot(0.6);  // removed: its place holds fluid
  EXPECT_TRUE(find(check_fluid_contained(dir, c), "fluid particles more than").pass);
}

namespace {

/// open_boundaries.csv of one inlet and one outlet passing the same flux, the fluid mass constant.
/// With `gain` != 1 the fluid mass grows linearly to gain times its start by t_end, the inflow
/// carrying the difference (the balance still holds).
void write_balanced_open_boundaries(const fs::path& dir, double t_end, double gain = 1) {
  io::CsvWriter csv(dir / "open_boundaries.csv", {"time", "boundary", "mass", "backflow_mass", "created",
                                                  "deleted", "buffer_particles", "fluid_mass"});
  for (int k = 0; k <= 10; ++k) {
    const double t = t_end * k / 10, extra = 0.2 * (gain - 1) * t / t_end;
    csv.row({t, 0, 0.01 * t + extra, 0, 0, 0, 400, 0.2 + extra});
    csv.row({t, 1, 0.012 * t, 0.002 * t, 0, 0, 400, 0.2 + extra});
  }
}

}  // namespace

TEST(RobustnessChecks, FluidizedBedHeightScreenAndSteadiness) {
  const fs::path dir = fresh_dir("robust_fluidized_bed");
  const Case c = load_case(kSource / "cases" / "fluidized_bed.toml");
  const double screen = c.open_screen_offset(c.inlets.at(0)), R = 5e-4, d0 = c.d0;
  const int n = static_cast<int>(c.bodies.size());
  const double packed = n * M_PI * R * R / (0.01 * 0.82);
  ASSERT_NEAR(screen, 1.3e-3, 1e-12);
  // bodies spread evenly from the screen up to the bed height H(t); `dip` puts body 0 that far
  // (in d0) below the screen at t = 1 s
  auto bed = [&](double H_end, double growth, double dip) {
    return [=](double t, int b) {
      Row r;
      const double H = H_end * (1 - 0.5 * std::exp(-t / 0.3)) + growth * t;
      r.x = 0.005;
      r.y = screen + R + (H - 2 * R) * b / (n - 1);
      if (b == 0 && std::fabs(t - 1) < 1e-9) r.y -= dip * d0;
      return r;
    };
  };
  write_balanced_open_boundaries(dir, 3);
  write_bodies(dir, n, 0.01, 3, bed(1.6 * packed, 0, 0));
  auto ok = check_fluidized_bed(dir, c, 0.1);
  ASSERT_EQ(ok.size(), 5u);
  for (const auto& k : ok) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(ok[1].value, 1.6, 0.01);                       // the bed's height over the densest packing's
  EXPECT_NEAR(ok[0].value, 0, 1e-6);                         // body 0 resting on the screen
  write_bodies(dir, n, 0.01, 3, bed(1.6 * packed, 0, 0.5));  // a body through the screen
  EXPECT_FALSE(check_fluidized_bed(dir, c, 0.1)[0].pass);
  write_bodies(dir, n, 0.01, 3, bed(1.05 * packed, 0, 0));  // hardly expanded
  EXPECT_FALSE(check_fluidized_bed(dir, c, 0.1)[1].pass);
  write_bodies(dir, n, 0.01, 3,
               bed(1.6 * packed, 0.2 * packed, 0));  // still rising: 8 % over the last second
  EXPECT_FALSE(check_fluidized_bed(dir, c, 0.1)[2].pass);
}

TEST(RobustnessChecks, ParticleChannelCarriesBodiesToTheOutletsScreen) {
  const fs::path dir = fresh_dir("robust_particle_channel");
  const Case c = load_case(kSource / "cases" / "particle_channel.toml");
  const double screen = 0.016 - c.open_screen_offset(c.outlets.at(0)), R = 5e-4, d0 = c.d0;
  const int n = static_cast<int>(c.bodies.size());
  // each body moves at 4 mm/s until it stops `short_of` d0 from the screen (two abreast, body b
  // b / 2 diameters behind the first pair); `stuck` stays put; `through` goes 0.5 d0 past it
  auto carried = [&](double short_of, int stuck, int through) {
    return [=, &c](double t, int b) {
      Row r;
      const Vec2 x0 = c.bodies[static_cast<std::size_t>(b)].center;
      const double stop =
          screen - R - short_of * d0 - (b / 2) * 2.05 * R + (b == through ? 0.5 * d0 + short_of * d0 : 0);
      r.x = b == stuck ? x0.x : std::min(x0.x + 4e-3 * t, stop);
      r.y = x0.y;
      return r;
    };
  };
  write_balanced_open_boundaries(dir, 5);
  write_bodies(dir, n, 0.02, 5, carried(0.4, -1, -1));
  auto ok = check_particle_channel(dir, c, 5e-3);
  ASSERT_EQ(ok.size(), 5u);
  for (const auto& k : ok) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(ok[2].value, 0.4, 1e-6);                 // the leading body's gap to the screen
  write_bodies(dir, n, 0.02, 5, carried(0.4, 3, -1));  // one body never moves
  EXPECT_FALSE(check_particle_channel(dir, c, 5e-3)[0].pass);
  write_bodies(dir, n, 0.02, 5, carried(0.4, -1, 0));  // the leading body crosses the screen
  EXPECT_FALSE(check_particle_channel(dir, c, 5e-3)[1].pass);
  write_bodies(dir, n, 0.02, 5, carried(3, -1, -1));  // they stop 3 d0 short of it
  EXPECT_FALSE(check_particle_channel(dir, c, 5e-3)[2].pass);
  write_bodies(dir, n, 0.02, 5, carried(0.4, -1, -1));
  write_balanced_open_boundaries(dir, 5, 1.02);  // the fluid compressed by 2 %
  EXPECT_FALSE(check_particle_channel(dir, c, 5e-3)[3].pass);
}

TEST(RobustnessChecks, GuardCountersAreReadWhateverTheirNames) {
  const std::string json = R"({"steps": 12, "guard_events": {"singular_B": 3, "surface_guard": 17,
    "nested": {"x": 1}, "note": "a \"string\"", "gap_fluid": null}, "after": 5})";
  const auto g = io::json_object_numbers(json, "guard_events");
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0].first, "singular_B");
  EXPECT_EQ(g[1].first, "surface_guard");
  EXPECT_EQ(g[1].second, 17);
  EXPECT_TRUE(std::isnan(g[2].second));
  EXPECT_THROW(io::json_object_numbers(json, "steps"), std::runtime_error);
  EXPECT_THROW(io::json_object_numbers(json, "absent"), std::runtime_error);
}

// The channel's x-momentum budget counts the odd-even damping's sink next to the surfaces (the
// fdx columns): a run whose drag and wall shear carry 90 % of the driving and whose damping
// carries the other 10 % balances; the same loads without the damping's columns do not.
TEST(RobustnessChecks, ChannelBudgetCountsTheDampingsSinkAtTheSurfaces) {
  const fs::path dir = fresh_dir("robust_channel");
  const Case c = load_case(kSource / "cases/robustness/cylinder_channel_re1.toml");
  const Vec2 span = c.domain_max - c.domain_min;
  const double area = span.x * span.y - body_shape(c.bodies.at(0)).area();
  const double driving = c.rho0 * c.body_force.x * area, U = 1e-3;  // Re = U D / nu = 1
  auto write = [&](bool damping_columns) {
    std::vector<std::string> body_cols{"time", "body", "x", "y", "angle", "vx", "vy", "omega", "fx", "fy"},
        wall_cols{"time", "wall", "fx", "fy"};
    if (damping_columns) {
      for (auto* cols : {&body_cols, &wall_cols}) cols->insert(cols->end(), {"fdx", "fdy"});
    }
    io::CsvWriter bodies(dir / "bodies.csv", body_cols), walls(dir / "walls.csv", wall_cols);
    for (int k = 0; k <= 150; ++k) {
      const double t = 0.1 * k;
      std::vector<double> b{t, 0, 0.0025, 0.0025, 0, 0, 0, 0, 0.5 * driving, 0};
      std::vector<double> w0{t, 0, 0.2 * driving, 0}, w1{t, 1, 0.2 * driving, 0};
      if (damping_columns) {
        b.insert(b.end(), {0.04 * driving, 0});
        w0.insert(w0.end(), {0.03 * driving, 0});
        w1.insert(w1.end(), {0.03 * driving, 0});
      }
      bodies.row(b);
      walls.row(w0);
      walls.row(w1);
    }
  };
  io::PvdIndex pvd;
  for (int k = 0; k <= 15; ++k) {
    const std::vector<Vec2> fluid{{0.001, 0.001}, {0.004, 0.004}};
    const std::vector<double> v{U, 0, 0, U, 0, 0};
    const std::string file = fmt::format("s{}.vtp", k);
    io::write_vtp(
        dir / file, fluid, {io::VtkArray{"velocity", 3, v}},
        {io::VtkIntArray{
            "kind", 1, {static_cast<std::int32_t>(Kind::Fluid), static_cast<std::int32_t>(Kind::Fluid)}}});
    pvd.add(k * 1.0, file);
  }
  pvd.write(dir / "particles.pvd");
  write(true);
  const auto good = check_channel_cylinder(dir, c, 1, false, 0.2);
  EXPECT_NEAR(find(good, "(cylinder drag").value, 1.0, 1e-9);
  EXPECT_TRUE(find(good, "(cylinder drag").pass);
  EXPECT_NEAR(find(good, "odd-even damping at the cylinder").value, 0.08, 1e-9);
  EXPECT_TRUE(find(good, "Reynolds number").pass);
  write(false);  // a run without the damping columns: read as zero
  const auto bad = check_channel_cylinder(dir, c, 1, false, 0.2);
  EXPECT_NEAR(find(bad, "(cylinder drag").value, 0.9, 1e-9);
  EXPECT_FALSE(find(bad, "(cylinder drag").pass);
}
