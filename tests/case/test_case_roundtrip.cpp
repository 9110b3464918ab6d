// resolved_case_toml: the fully resolved case reads back as an identical Case.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "particula/case/load.hpp"
#include "particula/case/schema.hpp"

using namespace particula;

namespace {

const std::string kFile = "cases/full.toml";

/// Every key set, most to values other than the default, with awkward reals and strings.
const std::string kFull = R"(name = "full_case-1"
description = "a \"quoted\" \\ text\nsecond line, tab\t, caf\u00e9, ctrl \u0001"

[domain]
min = [-0.3333333333333333, 0]
max = [0.30000000000000004, 1e-3]
periodic = [true, false]

[resolution]
d0 = 2.5e-5
h_over_d0 = 3.1

[fluid]
rho0 = 998.2
mu = 1.0016e-3
c = 1.2345678901234567
p0 = 12.5
gravity = [0, -9.81]
gravity_in_fluid = true
body_force = [1e-300, -0.0]

[time]
end = 1.5
cfl = 0.25
dt_max = 1e-6
max_steps = 123456789012

[numerics]
laplacian = "morris"
boundary = "dummy"
normals = "analytic"
rhie_chow_factor = 0.5
shifting_beta = 0.2
wall_pressure_sweeps = 3

[initial]
perturbation = 0.1
seed = 9007199254740993
flow = "taylor_green"
amplitude = 2e-3
hydrostatic = true

[output]
interval = 0.05
snapshots = false
snapshot_interval = 0.1
checkpoint_interval = 0.5

[guard]
rho_min_ratio = 0.9
rho_max_ratio = 1.1

[collision]
stiffness = 1.5e6
range = 7.5e-5

[[wall]]
name = "bottom"
from = [-0.3333333333333333, 0]
to = [0.30000000000000004, 0]
velocity = [-1e-3, 0]

[[wall]]
from = [0.30000000000000004, 1e-3]
to = [-0.3333333333333333, 1e-3]

[[probe]]
name = "mid"
from = [0, 0]
to = [0, 1e-3]
points = 81
interval = 0.01

[[probe]]
name = "top"
from = [-0.1, 9e-4]
to = [0.1, 9e-4]
points = 2
interval = 1

[[body]]
name = "drop"
shape = "ellipse"
center = [-0.1, 5e-4]
semi_axes = [3e-4, 2.6e-4]
angle = 0.3
density = 1234.5
velocity = [1e-4, -2e-5]
omega = -0.5

[[body]]
shape = "polygon"
vertices = [[0.1, 2e-4], [0.1005, 2e-4], [0.1005, 8e-4], [0.1, 8e-4], [0.09975, 5e-4]]
motion = "prescribed"
schedule = [[-1, 0, 0, 0], [0.5, 1e-5, -0.0, 0.1], [1.5, 3.0000000000000004e-05, 0, -0.2]]

[[body]]
name = "bump"
shape = "half_disc"
center = [0.2, 0]
radius = 6e-4
angle = 1.5707963267948966
motion = "fixed"

[[body]]
name = "pusher"
shape = "circle"
center = [0.25, 5e-4]
radius = 3e-4
motion = "prescribed"
velocity = [1e-3, 0]
omega = 0.01
)";

/// Bitwise equality of reals (so that -0.0 and 0.0 differ, as they would after printing).
bool same(real a, real b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(Vec2 a, Vec2 b) { return same(a.x, b.x) && same(a.y, b.y); }

#define EXPECT_SAME(field) EXPECT_TRUE(same(a.field, b.field)) << #field
#define EXPECT_EQUAL(field) EXPECT_EQ(a.field, b.field) << #field

/// Every field of Case, compared exactly (source excepted).
void expect_same(const Case& a, const Case& b) {
  EXPECT_EQUAL(name);
  EXPECT_EQUAL(description);
  EXPECT_SAME(domain_min);
  EXPECT_SAME(domain_max);
  EXPECT_EQUAL(periodic_x);
  EXPECT_EQUAL(periodic_y);
  EXPECT_SAME(d0);
  EXPECT_SAME(h_over_d0);
  EXPECT_SAME(rho0);
  EXPECT_SAME(nu);
  EXPECT_SAME(c);
  EXPECT_SAME(p0);
  EXPECT_SAME(gravity);
  EXPECT_EQUAL(gravity_in_fluid);
  EXPECT_SAME(body_force);
  EXPECT_SAME(t_end);
  EXPECT_SAME(cfl);
  EXPECT_SAME(dt_max);
  EXPECT_EQUAL(max_steps);
  EXPECT_EQUAL(laplacian);
  EXPECT_EQUAL(boundary);
  EXPECT_EQUAL(normals);
  EXPECT_SAME(rhie_chow_factor);
  EXPECT_SAME(shifting_beta);
  EXPECT_EQUAL(wall_pressure_sweeps);
  EXPECT_SAME(perturbation);
  EXPECT_EQUAL(seed);
  EXPECT_EQUAL(initial_flow);
  EXPECT_SAME(initial_amplitude);
  EXPECT_EQUAL(hydrostatic);
  EXPECT_SAME(output_interval);
  EXPECT_EQUAL(snapshots);
  EXPECT_SAME(snapshot_interval);
  EXPECT_SAME(checkpoint_interval);
  EXPECT_SAME(rho_min_ratio);
  EXPECT_SAME(rho_max_ratio);
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_EQUAL(walls[i].name);
    EXPECT_SAME(walls[i].from);
    EXPECT_SAME(walls[i].to);
    EXPECT_SAME(walls[i].velocity);
  }
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (std::size_t i = 0; i < a.probes.size(); ++i) {
    EXPECT_EQUAL(probes[i].name);
    EXPECT_SAME(probes[i].from);
    EXPECT_SAME(probes[i].to);
    EXPECT_EQUAL(probes[i].points);
    EXPECT_SAME(probes[i].interval);
  }
  EXPECT_SAME(collision_stiffness);
  EXPECT_SAME(collision_range);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQUAL(bodies[i].name);
    EXPECT_EQUAL(bodies[i].shape);
    EXPECT_SAME(bodies[i].center);
    EXPECT_SAME(bodies[i].radius);
    EXPECT_SAME(bodies[i].semi_axes);
    ASSERT_EQ(a.bodies[i].vertices.size(), b.bodies[i].vertices.size());
    for (std::size_t k = 0; k < a.bodies[i].vertices.size(); ++k) EXPECT_SAME(bodies[i].vertices[k]);
    ASSERT_EQ(a.bodies[i].holes.size(), b.bodies[i].holes.size());
    for (std::size_t h = 0; h < a.bodies[i].holes.size(); ++h) {
      ASSERT_EQ(a.bodies[i].holes[h].size(), b.bodies[i].holes[h].size());
      for (std::size_t k = 0; k < a.bodies[i].holes[h].size(); ++k) EXPECT_SAME(bodies[i].holes[h][k]);
    }
    EXPECT_SAME(bodies[i].angle);
    EXPECT_SAME(bodies[i].density);
    EXPECT_EQUAL(bodies[i].motion);
    EXPECT_SAME(bodies[i].velocity);
    EXPECT_SAME(bodies[i].omega);
    ASSERT_EQ(a.bodies[i].schedule.size(), b.bodies[i].schedule.size());
    for (std::size_t k = 0; k < a.bodies[i].schedule.size(); ++k) {
      EXPECT_SAME(bodies[i].schedule[k].t);
      EXPECT_SAME(bodies[i].schedule[k].velocity);
      EXPECT_SAME(bodies[i].schedule[k].omega);
    }
  }
}

/// Loads the resolved text of `a` and checks that it gives `a` again, and the same text.
void expect_round_trip(const Case& a) {
  const std::string text = resolved_case_toml(a);
  const Case b = load_case_text(text, "run/case.toml");
  expect_same(a, b);
  EXPECT_EQ(resolved_case_toml(b), text);
}

}  // namespace

TEST(CaseRoundTrip, FullCase) {
  const Case a = load_case_text(kFull, kFile);
  EXPECT_EQ(a.walls[1].name, "wall1");
  EXPECT_EQ(a.seed, 9007199254740993u);  // not representable as a double: stays an integer
  EXPECT_TRUE(std::signbit(a.body_force.y));
  EXPECT_EQ(a.bodies[1].name, "body1");
  EXPECT_TRUE(std::signbit(a.bodies[1].schedule[1].velocity.y));
  expect_round_trip(a);
}

TEST(CaseRoundTrip, MinimalCaseWritesEveryKey) {
  const std::string minimal = R"(name = "m"
domain.min = [0, 0]
domain.max = [1, 1]
resolution.d0 = 0.01
fluid.nu = 1e-6
fluid.c = 1
time.end = 1
output.interval = 0.1
[[wall]]
from = [0, 0]
to = [1, 0]
[[wall]]
from = [0.8, 1]
to = [0.7, 1]
[[wall]]
from = [0.55, 1]
to = [0.4, 1]
[[wall]]
shape = "arc"
center = [0.6, 0.85]
radius = 0.08
start_angle = 0
end_angle = -6.283185307179586
omega = 1
pivot = [0.6, 0.85]
[[inlet]]
from = [1, 1]
to = [0.8, 1]
velocity = 0.01
[[inlet]]
from = [0.7, 1]
to = [0.55, 1]
profile = "table"
table = [[0, 0], [0.15, 0.01]]
[[outlet]]
from = [0.4, 1]
to = [0, 1]
[[probe]]
name = "p"
from = [0, 0]
to = [1, 1]
points = 5
interval = 0.1
[[probe]]
name = "q"
kind = "points"
at = [[0.5, 0.5]]
interval = 0.1
[[body]]
shape = "circle"
center = [0.2, 0.2]
radius = 0.1
density = 1000
[[body]]
shape = "ellipse"
center = [0.7, 0.2]
semi_axes = [0.15, 0.1]
motion = "fixed"
[[body]]
shape = "polygon"
vertices = [[0.05, 0.35], [0.45, 0.35], [0.45, 0.75], [0.05, 0.75]]
holes = [[[0.2, 0.5], [0.3, 0.5], [0.3, 0.6], [0.2, 0.6]]]
motion = "prescribed"
schedule = [[0, 0, 0, 0], [1, 0, 0, 0.1]]
[[body]]
shape = "half_disc"
center = [1, 0.6]
radius = 0.2
angle = 3.141592653589793
motion = "fixed"
)";
  const Case a = load_case_text(minimal, kFile);
  const std::string text = resolved_case_toml(a);
  const toml::table doc = toml::parse(text);
  for (const KeySpec& s : case_schema()) {
    if (s.key == "fluid.mu") continue;  // viscosity is written as fluid.nu
    // Every key is written for some element; members of another shape or motion are not.
    const std::size_t n = s.in_array() ? find_section(s.section())->size(a) : 1;
    int written = 0;
    for (std::size_t i = 0; i < n; ++i) {
      std::string path = s.key;
      if (const auto p = path.find("[]"); p != std::string::npos) path.replace(p, 2, fmt::format("[{}]", i));
      const bool present = static_cast<bool>(doc.at_path(path));
      written += present;
      if (!s.used_for(a, i)) {
        EXPECT_FALSE(present) << path << " written for an element that does not use it";
      }
    }
    EXPECT_GT(written, 0) << s.key << " missing from\n" << text;
  }
  expect_round_trip(a);
}

TEST(CaseRoundTrip, OverridesAreResolved) {
  const Case a = load_case_text(
      kFull, kFile, {"resolution.d0=5e-5", "probe.1.points=7", "numerics.laplacian=fatehi_manzari"});
  const std::string text = resolved_case_toml(a);
  EXPECT_NE(text.find("d0 = 5e-05\n"), std::string::npos) << text;
  EXPECT_NE(text.find("laplacian = \"fatehi_manzari\"\n"), std::string::npos) << text;
  expect_round_trip(a);
  EXPECT_EQ(load_case_text(text, kFile).probes[1].points, 7);
}

TEST(CaseRoundTrip, ThroughAFile) {
  const Case a = load_case_text(kFull, kFile);
  const auto path = std::filesystem::temp_directory_path() /
                    ("particula_test_case_roundtrip_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(path, std::ios::binary) << resolved_case_toml(a);
  const Case b = load_case(path);
  std::filesystem::remove(path);
  expect_same(a, b);
  EXPECT_EQ(b.source, path);
}

TEST(CaseRoundTrip, RandomRealsKeepEveryBit) {
  std::mt19937_64 rng(20240611);
  const auto uniform = [&](real lo, real hi) {
    return lo + (hi - lo) * static_cast<real>(rng() >> 11) * 0x1.0p-53;
  };
  Case a = load_case_text(kFull, kFile);
  a.max_steps = 1000;  // the random speeds make the time step tiny: keep the step count within the load checks
  for (int i = 0; i < 200; ++i) {
    a.d0 = std::exp(uniform(std::log(1e-9), std::log(5e-5)));  // the bodies need 10 d0 across
    a.h_over_d0 = uniform(1.5, 4);
    a.rho0 = uniform(1, 2e4);
    a.nu = std::exp(uniform(-20, 0));
    a.c = uniform(2, 1e3);  // above every speed set below (the load's Mach check)
    a.gravity = {uniform(-10, 10), uniform(-1e-200, 1e140)};  // derived scales stay below 1e150
    a.t_end = uniform(1e-9, 100);  // the pusher stays clear of body1 and the bump up to 100 s
    a.cfl = uniform(1e-3, 1);
    a.walls[0].velocity = {uniform(-1, 1), 0};
    a.probes[0].interval = uniform(1e-6, 1);
    a.bodies[0].angle = uniform(-10, 10);
    a.bodies[0].density = uniform(1, 2e4);
    a.bodies[1].schedule[2].velocity = {uniform(-1e-300, 1e-300), uniform(-1e-300, 1e-300)};  // its path stays clear
    a.bodies[1].vertices[4].x = uniform(0.0997, 0.09999);
    a.collision_stiffness = std::exp(uniform(0, 40));
    SCOPED_TRACE(i);
    expect_round_trip(a);
    if (HasFailure()) break;
  }
}
