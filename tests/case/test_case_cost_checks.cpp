// Load checks of what a case would cost or compute with (src/case/cost_checks.cpp): the scales
// of its numbers, its probes, its time steps and output counts. Each refusal names
// the file, line and key; the shipped cases pass; `info` counts the probes' memory.
#include <gtest/gtest.h>

#include <filesystem>

#include "case_bodies_fixtures.hpp"
#include "particula/run/limits.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

using namespace particula;
using namespace case_bodies_test;

namespace {

const std::filesystem::path kCases = std::filesystem::path(PARTICULA_SOURCE_DIR) / "cases";

/// kBase with one probe along the middle of the box.
const std::string kProbe = kBase + R"(
[[probe]]
name = "mid"
from = [0.01, 0.0]
to = [0.01, 0.06]
points = 61
interval = 0.05
)";

}  // namespace

// ---- scales ----------------------------------------------------------------------------------

TEST(CaseScales, ACaseScaledBy1e150IsRefused) {
  // Every number of a valid case times 1e150: each number alone passes its key's range.
  const std::string scaled = R"(name = "huge"

[domain]
min = [0.0, 0.0]
max = [2e148, 6e148]

[resolution]
d0 = 1e146

[fluid]
rho0 = 1e153
mu = 1e148
c = 5e149
gravity = [0, -9.81e150]

[time]
end = 1e150

[output]
interval = 1e148
)";
  expect_error(scaled, "fluid.rho0", "rho0 =", "the density rho0 is 1e+153 kg/m^3, outside [1e-150, 1e+150]");
  // One number at a time: the derived scale that leaves double range is named.
  expect_error(with(kBase, "c = 0.5", "c = 1e80"), "fluid.c", "c = 1e80", "the pressure scale rho0 c^2 + p0");
  expect_error(with(kBase, "d0 = 1e-4", "d0 = 1e-60"), "resolution.d0", "d0 = 1e-60", "kernel gradient scale");
  expect_error(with(kBase, "gravity = [0, -9.81]", "gravity = [0, -1e200]"), "fluid.gravity", "gravity =",
               "the gravity |g| is 1e+200 m/s^2, outside [1e-150, 1e+150]");
  expect_error(with(kBase, "mu = 0.01", "mu = 1e160"), "fluid.mu", "mu = 1e160", "the kinematic viscosity nu is 1e+157");
  // A value that only adds may be tiny (a gravity of 1e-300 is no gravity).
  EXPECT_NO_THROW(load(with(kBase, "gravity = [0, -9.81]", "gravity = [0, -1e-300]")));
}

TEST(CaseScales, BodyMassAndSpeed) {
  const std::string disc = one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\ndensity = 1000\n");
  EXPECT_NO_THROW(load(disc));
  expect_error(with(disc, "density = 1000", "density = 1e-200"), "body[0].density", "density =",
               "the body's mass density times area");
  expect_error(with(disc, "density = 1000", "density = 1000\nvelocity = [1e200, 0]"), "body[0].velocity",
               "velocity =", "the body speed is 1e+200 m/s");
}

// ---- speed of sound ------------------------------------------------------------------------

TEST(CaseMach, SpeedsAtOrAboveTheSpeedOfSoundAreRefused) {
  // kBase has c = 0.5 m/s. Each speed the case sets is named in the message; the key is fluid.c.
  const std::string disc = one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\ndensity = 1000\n");
  EXPECT_NO_THROW(load(with(disc, "density = 1000", "density = 1000\nvelocity = [0.3, -0.3]")));  // Mach 0.85
  expect_error(with(disc, "density = 1000", "density = 1000\nvelocity = [0.3, -0.4]"), "fluid.c", "c = 0.5",
               "is not above the speed 0.5 m/s that body[0].velocity sets (Mach 1)");
  expect_error(with(disc, "density = 1000", "density = 1000\nomega = 300"), "fluid.c", "c = 0.5",
               "that body[0].omega sets (Mach 1.2)");
  const std::string moved = one_body("shape = \"circle\"\ncenter = [0.01, 0.03]\nradius = 0.002\nmotion = "
                                     "\"prescribed\"\nschedule = [[0, 0, 0, 0], [0.5, 0, -2, 0]]\n");
  expect_error(moved, "fluid.c", "c = 0.5", "that body[0].schedule sets (Mach 4)");
  // A drum of radius 9 mm turning at 60 rad/s: its wall moves at 0.54 m/s.
  const std::string drum = kBase + R"(
[[wall]]
shape = "arc"
center = [0.01, 0.03]
radius = 0.009
start_angle = 0.0
end_angle = 6.283185307179586
omega = 60.0
pivot = [0.01, 0.03]
)";
  expect_error(drum, "fluid.c", "c = 0.5", "that wall[0].omega sets (Mach 1.1)");
  EXPECT_NO_THROW(load(with(drum, "omega = 60.0", "omega = 50.0")));  // Mach 0.9
}

// ---- probes ----------------------------------------------------------------------------------

TEST(CaseProbes, EndsInsideTheDomain) {
  EXPECT_NO_THROW(load(kProbe));  // both ends on the domain edge
  expect_error(with(kProbe, "from = [0.01, 0.0]", "from = [0.01, -0.5]"), "probe[0].from", "from = [0.01, -0.5]",
               "probe 'mid' from point [0.01, -0.5] lies outside the domain [0.0, 0.0] .. [0.02, 0.06]");
  expect_error(with(kProbe, "to = [0.01, 0.06]", "to = [1e300, 0.06]"), "probe[0].to", "to = [1e300",
               "lies outside the domain");
}

TEST(CaseProbes, PointsNoCloserThanAHundredthOfD0) {
  // 0.06 m / (d0/100) = 60000 spacings: at most 60001 points.
  EXPECT_NO_THROW(load(with(kProbe, "points = 61", "points = 60001")));
  expect_error(with(kProbe, "points = 61", "points = 60002"), "probe[0].points", "points = 60002",
               "use at most 60001 points");
  expect_error(with(kProbe, "points = 61", "points = 1000000"), "probe[0].points", "points = 1000000",
               "probe 'mid' has 1000000 points on a 0.06 m line, 6e-08 m apart: closer than d0/100 = 1e-06 m");
  // A probe of length 0 (a point) may have 2 points there, not more.
  const std::string point = with(kProbe, "to = [0.01, 0.06]", "to = [0.01, 0.0]");
  expect_error(point, "probe[0].points", "points = 61", "use at most 2 points");
  EXPECT_NO_THROW(load(with(point, "points = 61", "points = 2")));
}

TEST(CaseProbes, AllProbesTogetherAtMostAMillionPoints) {
  std::string text = kBase;
  for (int k = 0; k < 20; ++k)
    text += "\n[[probe]]\nname = \"p" + std::to_string(k) +
            "\"\nfrom = [0.0, 0.0]\nto = [0.02, 0.06]\npoints = 60000\ninterval = 0.05\n";
  // 16 probes of 60000 points pass; the 17th passes 1e6.
  const CaseError e = error_of(text);
  EXPECT_EQ(e.key(), "probe[16].points") << e.what();
  EXPECT_NE(e.message().find("have 1020000 points in all, more than the 1e+06"), std::string::npos) << e.what();
  // The size estimate (info, the memory check) counts them.
  const Case c = load(with(kProbe, "points = 61", "points = 60001"));
  const SizeEstimate size = estimate_size(c);
  EXPECT_EQ(size.probe_points, 60001);
  EXPECT_DOUBLE_EQ(size.probe_bytes, 60001 * kBytesPerProbePoint);
  EXPECT_GT(size.bytes, estimate_size(load(kBase)).bytes + size.probe_bytes * 0.999);
}

// ---- time steps and outputs ------------------------------------------------------------------

TEST(CaseTimeSteps, EstimatedStepIsTheSolversWithinAFewPercent) {
  // The estimate is a slight under-estimate of the solver's first step.
  for (const char* name : {"hydrostatic", "falling_cylinder", "couette", "taylor_green"}) {
    const Case c = load_case(kCases / (std::string(name) + ".toml"));
    Scene s = build_scene(c);
    const Solver solver(s.params, s.domain, s.particles, s.groups);
    const real est = estimated_dt(c), dt = solver.stable_dt();
    EXPECT_LE(est, dt * 1.0001) << name;
    EXPECT_GT(est, 0.5 * dt) << name;
  }
}

TEST(CaseTimeSteps, DtMaxFloor) {
  // Stable step about 6.4e-5 s here (c = 0.5 m/s, d0 = 1e-4 m).
  EXPECT_NO_THROW(load(with(kBase, "end = 1.0", "end = 1.0\ndt_max = 1e-6")));
  expect_error(with(kBase, "end = 1.0", "end = 1.0\ndt_max = 5e-324"), "time.dt_max", "dt_max =",
               "time.dt_max = 4.94e-324 s is less than 0.001 of the stable time step (about 6.36e-05 s at the "
               "start, estimated from d0, fluid.c, fluid.nu and the initial speeds): it would take about more than "
               "1e308 steps");
}

TEST(CaseTimeSteps, AtMostABillionSteps) {
  expect_error(with(kBase, "end = 1.0", "end = 1e6"), "time.end", "end = 1e6",
               "the run would take about 1.57e+10 steps of 6.36e-05 s to time.end = 1e+06 s, more than the 1e+09");
  // time.max_steps bounds the run.
  EXPECT_NO_THROW(load(with(kBase, "end = 1.0", "end = 1e6\nmax_steps = 1000\n")));
  // A cap far below the stable step is named.
  expect_error(with(kBase, "end = 1.0", "end = 1e3\ndt_max = 1e-7"), "time.dt_max", "dt_max",
               "or raise time.dt_max");
}

TEST(CaseTimeSteps, OutputIntervalsAtLeastAThousandthOfTheStep) {
  expect_error(with(kBase, "interval = 0.01", "interval = 1e-300"), "output.interval", "interval = 1e-300",
               "output.interval = 1e-300 s is less than 0.001 of the time step (about 6.36e-05 s): every step "
               "would be cut short to end on an output time, one output a step, about 1e+300 to time.end = 1 s");
  expect_error(with(kProbe, "interval = 0.05", "interval = 1e-9"), "probe[0].interval", "interval = 1e-9",
               "less than 0.001 of the time step");
  expect_error(with(kBase, "interval = 0.01", "interval = 0.01\nsnapshot_interval = 1e-9"),
               "output.snapshot_interval", "snapshot_interval", "less than 0.001 of the time step");
  expect_error(with(kBase, "interval = 0.01", "interval = 0.01\ncheckpoint_interval = 1e-9"),
               "output.checkpoint_interval", "checkpoint_interval", "a checkpoint at every step");
  // Shorter than the step but not absurdly: the steps are cut short (20000 of them here).
  EXPECT_NO_THROW(load(with(kBase, "interval = 0.01", "interval = 5e-5")));
  // With snapshots off their interval does not matter.
  EXPECT_NO_THROW(load(with(kBase, "interval = 0.01", "interval = 0.01\nsnapshots = false\nsnapshot_interval = 1e-9")));
  // At most a million outputs per stream.
  expect_error(with(kBase, "end = 1.0", "end = 2e4"), "output.interval", "interval = 0.01",
               "output.interval = 0.01 s makes about 2e+06 outputs to time.end = 20000 s, more than the 1e+06");
  expect_error(with(kBase, "interval = 0.01", "interval = 5e-7"), "output.interval", "interval = 5e-7",
               "makes about 2e+06 outputs");
}

TEST(CaseCostChecks, ShippedCasesPass) {
  for (const auto& dir : {kCases, kCases / "robustness"})
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".toml") {
        EXPECT_NO_THROW(load_case(e.path())) << e.path();
      }
}
