// resolved_case_toml: the fully resolved case reads back as an identical Case.
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
c = 0.12345678901234567
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

[[wall]]
name = "bottom"
from = [0.30000000000000004, 0]
to = [-0.3333333333333333, 0]
velocity = [-1e-3, 0]

[[wall]]
from = [-0.3333333333333333, 1e-3]
to = [0.30000000000000004, 1e-3]

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
[[probe]]
name = "p"
from = [0, 0]
to = [1, 1]
points = 5
interval = 0.1
)";
  const Case a = load_case_text(minimal, kFile);
  const std::string text = resolved_case_toml(a);
  const toml::table doc = toml::parse(text);
  for (const KeySpec& s : case_schema()) {
    if (s.key == "fluid.mu") continue;  // viscosity is written as fluid.nu
    std::string path = s.key;
    if (const auto p = path.find("[]"); p != std::string::npos) path.replace(p, 2, "[0]");
    EXPECT_TRUE(doc.at_path(path)) << s.key << " missing from\n" << text;
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
  for (int i = 0; i < 200; ++i) {
    a.d0 = std::exp(uniform(std::log(1e-7), std::log(1e-3)));
    a.h_over_d0 = uniform(1.5, 4);
    a.rho0 = uniform(1, 2e4);
    a.nu = std::exp(uniform(-20, 0));
    a.c = uniform(1e-3, 1e3);
    a.gravity = {uniform(-10, 10), uniform(-1e-200, 1e200)};
    a.t_end = uniform(1e-9, 1e9);
    a.cfl = uniform(1e-3, 1);
    a.walls[0].velocity = {uniform(-1, 1), 0};
    a.probes[0].interval = uniform(1e-6, 1);
    SCOPED_TRACE(i);
    expect_round_trip(a);
    if (HasFailure()) break;
  }
}
