// The checks of `particula validate` for the open-boundary cases (src/validation/validate_open.cpp) on
// fabricated run directories: the DFG 2D-2 check finds the shedding frequency and the maxima of a
// noisy periodic C_D and C_L, the 2D-1 check averages over the last third, and the mass balance
// catches a fluid mass that does not follow the fluxes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_process.hpp"
#include "fabricated_runs.hpp"
#include "particula/case/load.hpp"
#include "particula/io/csv.hpp"
#include "particula/scene/scene.hpp"
#include "particula/validation/validate.hpp"

namespace fs = std::filesystem;
using namespace particula;

namespace {

const fs::path kCases = fs::path(PARTICULA_SOURCE_DIR) / "cases";

/// open_boundaries.csv of one inlet and one outlet: a steady flux `rate` (kg/(m s)) in and out
/// from t = 0, and a fluid mass that drifts by `leak` kg/m per second besides.
void write_open_boundaries(const fs::path& dir, double t_end, double rate, double leak) {
  io::CsvWriter csv(dir / "open_boundaries.csv", {"time", "boundary", "mass", "backflow_mass", "created", "deleted",
                                                   "buffer_particles", "fluid_mass"});
  for (int k = 0; k <= 100; ++k) {
    const double t = t_end * k / 100, m = 1.0 + leak * t;
    csv.row({t, 0, rate * t, 0, 0, 0, 40, m});
    csv.row({t, 1, rate * t, 0, 0, 0, 40, m});
  }
}

/// coefficients.csv of one body: C_D = cd0 + a_d cos(4 pi f t), C_L = a_l sin(2 pi f t), plus a
/// seeded noise of amplitude `noise`, every 0.01 s to t_end.
void write_coefficients(const fs::path& dir, double t_end, double f, double cd0, double a_d, double a_l, double noise) {
  io::CsvWriter csv(dir / "coefficients.csv", {"time", "body", "re", "re_body", "cd", "cl", "cm"});
  SplitMix64 rng(7);
  const int n = static_cast<int>(std::lround(t_end / 0.01));
  for (int k = 0; k <= n; ++k) {
    const double t = 0.01 * k;
    const double cd = cd0 + a_d * std::cos(4 * M_PI * f * t) + noise * rng.symmetric();
    const double cl = a_l * std::sin(2 * M_PI * f * t) + noise * rng.symmetric();
    csv.row({t, 0, 100, 0, cd, cl, 0});
  }
}

/// bodies.csv of the fixed cylinder every 0.01 s to t_end: drag fx = 1 N/m with the damping's
/// sink fdx = 0.02 N/m, and before t = t_end / 4 (outside every check's window) 10 and 5.
void write_cylinder(const fs::path& dir, double t_end) {
  io::CsvWriter csv(dir / "bodies.csv", {"time", "body", "x", "y", "fx", "fy", "fdx", "fdy"});
  const int n = static_cast<int>(std::lround(t_end / 0.01));
  for (int k = 0; k <= n; ++k) {
    const double t = 0.01 * k;
    const bool early = t < t_end / 4;
    csv.row({t, 0, 0.2, 0.2, early ? 10.0 : 1.0, 0, early ? 5.0 : 0.02, 0});
  }
}

}  // namespace

TEST(ValidateOpen, Dfg2d2FindsTheSheddingFrequencyAndTheMaximaThroughTheNoise) {
  const fs::path dir = cli_test::fresh_dir("validate_dfg2d2");
  const Case c = load_case(kCases / "dfg_2d2.toml", {"resolution.d0=0.01"});
  // St = 0.3 at U = 1, D = 0.1: f = 3 Hz; largest C_D 3.23, largest C_L 1.0
  write_coefficients(dir, 10, 3.0, 3.18, 0.05, 1.0, 0.05);
  write_open_boundaries(dir, 10, 0.4, 0);
  write_cylinder(dir, 10);
  const auto checks = check_dfg_2d2(dir, c);
  const auto& st = fabricated::find(checks, "Strouhal number");
  EXPECT_NEAR(st.value, 0.3, 0.003);
  EXPECT_TRUE(st.pass);
  EXPECT_NEAR(fabricated::find(checks, "largest C_D").value, 3.23, 0.01) << "the noise does not inflate the maximum";
  EXPECT_NEAR(fabricated::find(checks, "largest C_L").value, 1.0, 0.01);
  EXPECT_TRUE(fabricated::find(checks, "fluid mass against the fluxes").pass);
  EXPECT_NEAR(fabricated::find(checks, "odd-even damping at the cylinder").value, 0.02, 1e-12);
  EXPECT_TRUE(fabricated::find(checks, "odd-even damping at the cylinder").report_only);
  // a shedding at 2.5 Hz (St 0.25) fails
  write_coefficients(dir, 10, 2.5, 3.18, 0.05, 1.0, 0.05);
  EXPECT_FALSE(fabricated::find(check_dfg_2d2(dir, c), "Strouhal number").pass);
  // no shedding at all: one failing check says so
  write_coefficients(dir, 10, 3.0, 3.18, 0.0, 0.0, 0.0);
  const auto none = check_dfg_2d2(dir, c);
  ASSERT_EQ(none.size(), 1u);
  EXPECT_FALSE(none[0].pass);
}

TEST(ValidateOpen, Dfg2d1AveragesTheLastThirdAndTheMassBalanceCatchesALeak) {
  const fs::path dir = cli_test::fresh_dir("validate_dfg2d1");
  const Case c = load_case(kCases / "dfg_2d1.toml", {"resolution.d0=0.01"});
  // C_D 9 during the start, 5.6 with noise after t = 6 s
  io::CsvWriter k(dir / "coefficients.csv", {"time", "body", "re", "re_body", "cd", "cl", "cm"});
  SplitMix64 rng(3);
  for (int i = 0; i <= 1200; ++i) {
    const double t = 0.01 * i;
    k.row({t, 0, 20, 0, (t < 6 ? 9.0 : 5.6) + 0.05 * rng.symmetric(), 0.01, 0});
  }
  io::CsvWriter p(dir / "probe_pressure_difference.csv", {"time", "x", "y", "vx", "vy", "p"});
  for (int i = 0; i <= 240; ++i) {
    const double t = 0.05 * i;
    p.row({t, 0.15, 0.2, 0, 0, 0.2});
    p.row({t, 0.25, 0.2, 0, 0, 0.2 - 0.1174});
  }
  write_open_boundaries(dir, 12, 0.08, 0);
  write_cylinder(dir, 12);
  const auto checks = check_dfg_2d1(dir, c);
  EXPECT_NEAR(fabricated::find(checks, "drag coefficient").value, 5.6, 0.01);
  EXPECT_TRUE(fabricated::find(checks, "drag coefficient").pass);
  EXPECT_NEAR(fabricated::find(checks, "pressure difference").value, 0.1174, 1e-12);
  EXPECT_TRUE(fabricated::find(checks, "fluid mass against the fluxes").pass);
  EXPECT_NEAR(fabricated::find(checks, "odd-even damping at the cylinder").value, 0.02, 1e-12);
  write_open_boundaries(dir, 12, 0.08, 1e-9);  // a leak of 1e-9 kg/m per second
  EXPECT_FALSE(fabricated::find(check_dfg_2d1(dir, c), "fluid mass against the fluxes").pass);
}
