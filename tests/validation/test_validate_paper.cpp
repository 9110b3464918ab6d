// The checks of the paper's body cases in `particula validate`, on fabricated run directories
// (bodies.csv written here from closed-form trajectories), and the suite's paper entries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include "cli_process.hpp"
#include "fabricated_runs.hpp"
#include "particula/case/load.hpp"
#include "particula/io/csv.hpp"
#include "particula/validation/validate.hpp"

namespace fs = std::filesystem;
using namespace particula;
using cli_test::fresh_dir;
using fabricated::find;
using fabricated::Row;
using fabricated::write_bodies;

namespace {

const fs::path kCases = fs::path(PARTICULA_SOURCE_DIR) / "cases";

}  // namespace

TEST(ValidationPaperChecks, SettlingCylinderAgainstGlowinski) {
  const fs::path dir = fresh_dir("validate_settling");
  const Case c = load_case(kCases / "falling_cylinder.toml");
  // vy = -U (1 - exp(-t/tau)): 95 % of U at 3 tau = 0.231 s
  auto settle = [](double U, double tau) {
    return [U, tau](double t, int) {
      Row r;
      r.x = 0.01;
      r.vy = -U * (1 - std::exp(-t / tau));
      r.y = 0.04 - U * (t - tau * (1 - std::exp(-t / tau)));
      return r;
    };
  };
  write_bodies(dir, 1, 0.005, 0.6, settle(0.0554, 0.077));
  auto good = check_settling_cylinder(dir, c);
  for (const auto& k : good) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(find(good, "time to 95").value, 0.23, 0.005);
  EXPECT_NE(find(good, "peak settling speed").shown.find("at t = 0.600 s"), std::string::npos);
  // 20 % too fast and too early: speed and time fail
  write_bodies(dir, 1, 0.005, 0.6, settle(0.0665, 0.03));
  auto bad = check_settling_cylinder(dir, c);
  EXPECT_FALSE(find(bad, "peak settling speed").pass);
  EXPECT_FALSE(find(bad, "time to 95").pass);
  // the coarse level is allowed 10 %, the paper's level 5 %
  write_bodies(dir, 1, 0.005, 0.6, settle(0.0554 * 1.07, 0.077));
  EXPECT_FALSE(find(check_settling_cylinder(dir, c), "peak settling speed").pass);
  const Case coarse = load_case(kCases / "falling_cylinder.toml", {"resolution.d0=2.5e-4"});
  EXPECT_TRUE(find(check_settling_cylinder(dir, coarse), "peak settling speed").pass);
  EXPECT_THROW(check_settling_cylinder(fresh_dir("validate_empty"), c), io::IoError);
}

TEST(ValidationPaperChecks, ShearMigrationAgainstFeng) {
  const fs::path dir = fresh_dir("validate_migration");
  const Case c = load_case(kCases / "shear_migration.toml");
  // Feng's curve, shifted by `dy`, or no migration at all
  const auto feng = io::read_csv(fs::path(PARTICULA_SOURCE_DIR) / "reference" / "feng2002_migration_y.csv");
  const auto ft = feng.column("t"), fy = feng.column("y");
  auto migrate = [&](double dy, double omega, bool moves) {
    return [&, dy, omega, moves](double t, int) {
      Row r;
      r.x = 0.025;
      r.y = 0.0075 + dy;
      for (std::size_t i = 0; moves && i + 1 < ft.size(); ++i)
        if (t >= ft[i] && t <= ft[i + 1]) r.y = fy[i] + (fy[i + 1] - fy[i]) * (t - ft[i]) / (ft[i + 1] - ft[i]) + dy;
      r.omega = omega;
      return r;
    };
  };
  write_bodies(dir, 1, 0.1, 20, migrate(1.5e-4, -0.95, true));  // the shipped case at an earlier end
  auto good = check_shear_migration(dir, c);
  for (const auto& k : good) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown << " vs " << k.reference;
  EXPECT_NEAR(find(good, "|y - H/2|").value, 0.708e-3 + 1.5e-4, 1e-6);  // Feng: 0.708e-3 at 20 s
  write_bodies(dir, 1, 0.1, 20, migrate(3.5e-4, -0.95, true));  // 0.35 mm above the curve
  EXPECT_FALSE(find(check_shear_migration(dir, c), "y - Feng").pass);
  // no migration at all, and a cylinder that does not turn
  write_bodies(dir, 1, 0.1, 20, migrate(0, -0.2, false));
  auto bad = check_shear_migration(dir, c);
  EXPECT_FALSE(find(bad, "|y - H/2|").pass);
  EXPECT_FALSE(find(bad, "y - Feng").pass);
  EXPECT_FALSE(find(bad, "omega").pass);
}

TEST(ValidationPaperChecks, TwoCylindersAgainstThePaper) {
  const fs::path dir = fresh_dir("validate_two");
  const Case c = load_case(kCases / "two_cylinders_shear.toml");
  // vx dips to -1.1e-3 at 6 s and recovers; the free cylinder stays near the centreline
  auto dip = [](double depth, double t_min, double dy) {
    return [=](double t, int body) {
      Row r;
      r.x = body == 0 ? 0.02125 : 0.02875;
      r.y = 0.005 + (body == 0 ? dy * std::sin(t) : 0);
      if (body == 0) r.vx = -depth * (t / t_min) * std::exp(1 - t / t_min);
      return r;
    };
  };
  write_bodies(dir, 2, 0.1, 12, dip(1.1e-3, 6, 1e-5));
  for (const auto& k : check_two_cylinders(dir, c)) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  write_bodies(dir, 2, 0.1, 12, dip(0.5e-3, 6, 1e-3));  // too weak, and leaves the centreline
  for (const auto& k : check_two_cylinders(dir, c)) EXPECT_FALSE(k.pass) << k.quantity << ": " << k.shown;
  write_bodies(dir, 2, 0.1, 4, dip(1.1e-3, 6, 1e-5));  // ends before the minimum
  EXPECT_FALSE(find(check_two_cylinders(dir, c), "most negative vx").pass);
}

TEST(ValidationPaperChecks, DktTumblesInThePapersWindow) {
  const fs::path dir = fresh_dir("validate_dkt");
  const Case c = load_case(kCases / "dkt.toml");
  // the upper cylinder (body 1) catches up by 0.5 s, then the two swap over 0.5 ... 1.0 s
  auto dkt = [](double t_level) {
    return [t_level](double t, int body) {
      Row r;
      const double lower_y = 0.05 - 0.045 * t;
      const double gap = 3e-3 - std::min(t, 0.5) / 0.5 * (3e-3 - 2.05e-3);
      const double phase = std::clamp((t - (t_level - 0.25)) / 0.5, 0.0, 1.0) * M_PI;
      r.x = 0.01 + (body == 1 ? gap * std::sin(phase) : 0);
      r.y = lower_y + (body == 1 ? gap * std::cos(phase) : 0);
      r.vy = body == 1 && t < 0.5 ? -0.047 : -0.045;
      return r;
    };
  };
  write_bodies(dir, 2, 0.005, 1.2, dkt(0.85));
  auto good = check_dkt(dir, c);
  for (const auto& k : good) EXPECT_TRUE(k.pass) << k.quantity << ": " << k.shown;
  EXPECT_NEAR(find(good, "tumbling").value, 0.85, 0.01);
  EXPECT_NEAR(find(good, "kissing").value, 0.40, 0.006);  // gap < eps = 3 d0 = 2.4e-4 m
  EXPECT_TRUE(find(good, "drafting").report_only);
  write_bodies(dir, 2, 0.005, 1.2, dkt(1.5));  // no tumbling before the end
  EXPECT_FALSE(find(check_dkt(dir, c), "tumbling").pass);
}

TEST(ValidationPaperChecks, EllipseObstacleOnlyReports) {
  const fs::path dir = fresh_dir("validate_ellipse");
  const Case c = load_case(kCases / "ellipse_obstacle.toml");
  write_bodies(dir, 2, 0.01, 3, [](double t, int body) {
    Row r;
    if (body == 0) return Row{0, 0.04, 0, 0, 0, 0};
    r.x = 0.01 + 2e-3 * std::sin(M_PI * t / 3);
    r.y = 0.054 - 0.015 * t;
    r.angle = -0.4 * std::sin(M_PI * t / 2.5);
    r.vy = -0.015;
    return r;
  });
  const auto checks = check_ellipse_obstacle(dir, c);
  ASSERT_FALSE(checks.empty());
  for (const auto& k : checks) EXPECT_TRUE(k.report_only && k.pass) << k.quantity;
  EXPECT_NEAR(find(checks, "largest tilt").value, -0.4, 1e-3);
  EXPECT_NEAR(find(checks, "largest drift").value, 2e-3, 1e-5);
  EXPECT_NEAR(find(checks, "peak Re").value, 0.015 * 4e-3 / 1e-5, 1);
}

TEST(ValidationPaperChecks, SuiteHasThePaperCasesWithCoarseQuickLevels) {
  std::vector<std::string> names;
  for (const auto& e : validation_entries()) {
    if (!e.paper) continue;
    if (e.group == ValidationGroup::Paper) names.push_back(e.name);
    // the quick level loads (passes the case checks, e.g. 10 particles across every body) and
    // is coarser than the shipped (paper) level
    const Case shipped = load_case(fs::path(PARTICULA_SOURCE_DIR) / e.case_file);
    const Case quick = load_case(fs::path(PARTICULA_SOURCE_DIR) / e.case_file, e.quick_overrides);
    EXPECT_GT(quick.d0, shipped.d0) << e.name;
    EXPECT_LE(quick.t_end, shipped.t_end) << e.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"shear_migration", "falling_cylinder", "two_cylinders_shear", "dkt",
                                             "ellipse_obstacle"}));
}

TEST(ValidationPaperChecks, TheBenchmarkGroupHasTheDfgCaseWithACoarseQuickLevel) {
  std::vector<std::string> names;
  for (const auto& e : validation_entries())
    if (e.group == ValidationGroup::Benchmark) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"dfg_2d1", "dfg_2d2"}));
  ValidateOptions plain;
  for (const auto& e : validation_entries()) {
    if (e.group == ValidationGroup::Benchmark) {
      EXPECT_TRUE(entry_selected(e, plain)) << "run by a plain validate";
    }
  }
}
