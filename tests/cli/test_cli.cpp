// The command-line contract (design.md): outputs of `particula run`, exit codes 2 (bad
// input) and 3 (numerical failure), and `particula info`.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "particula/io/csv.hpp"
#include "particula/io/json.hpp"
#include "particula/io/vtk.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = PARTICULA_SOURCE_DIR;

struct Result {
  int code;
  std::string output;
};

Result run(const std::string& args) {
  const fs::path log = fs::temp_directory_path() / ("particula_cli_" + std::to_string(::getpid()) + ".log");
  const std::string cmd = std::string(PARTICULA_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

/// A path for a run directory the test makes (absent; removed when the binary passes).
fs::path fresh_dir(const std::string& name) { return test_scratch::scratch_dir("cli_" + name, false); }

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(Cli, RunWritesTheRunDirectory) {
  const fs::path out = fresh_dir("couette");
  const auto r = run("run " + (kSource / "cases/couette.toml").string() + " --out " + out.string() +
                     " --quiet --set time.end=0.1 --set output.snapshot_interval=0.05");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f :
       {"case.toml", "summary.json", "particles.pvd", "probe_profile.csv", "bodies.csv", "log.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const std::string summary = read(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"completed\""), std::string::npos) << summary;
  EXPECT_NEAR(particula::io::json_number_field(summary, "end_time"), 0.1, 1e-12);
  // Every step is counted under the limit that set it (time_step.limited_by).
  const std::string limited_by = summary.substr(summary.find("\"limited_by\""));
  double limited = 0;
  for (const char* k : {"acoustic", "viscous", "dt_max", "body_force", "contact", "output_time"})
    limited += particula::io::json_number_field(limited_by, k);
  EXPECT_EQ(limited, particula::io::json_number_field(summary, "steps")) << summary;
  EXPECT_GT(particula::io::json_number_field(limited_by, "viscous"), 0)
      << "viscous diffusion sets this case's step";
  EXPECT_GT(particula::io::json_number_field(limited_by, "output_time"), 0) << "it lands on 0.05 and 0.1 s";
  // Snapshots parse back with every particle and the documented arrays.
  const double particles = particula::io::json_number_field(summary, "particles");
  int snapshots = 0;
  for (const auto& e : fs::directory_iterator(out / "particles")) {
    const auto vtp = particula::io::read_vtp(e.path());
    EXPECT_EQ(static_cast<double>(vtp.num_points), particles);
    EXPECT_EQ(vtp.array("pressure").data.size(), vtp.num_points);
    EXPECT_EQ(vtp.array("velocity").components, 3);
    EXPECT_EQ(vtp.array("density").data.size(), vtp.num_points);
    EXPECT_EQ(vtp.int_array("kind").data.size(), vtp.num_points);
    EXPECT_EQ(vtp.int_array("body").data.size(), vtp.num_points);
    ++snapshots;
  }
  EXPECT_EQ(snapshots, 3);  // t = 0, 0.05, 0.1
  const auto probe = particula::io::read_csv(out / "probe_profile.csv");
  EXPECT_EQ(probe.column("vx_exact").size(), probe.size());
  // The run ends exactly on time.end and on every probe interval (0.0225 s).
  const auto t = probe.column("time");
  EXPECT_DOUBLE_EQ(t.back(), 0.1);
  EXPECT_NEAR(t[41], 0.0225, 1e-15);
  // The resolved case loads again and names every default.
  EXPECT_NE(read(out / "case.toml").find("rhie_chow_factor"), std::string::npos);
}

TEST(Cli, ExistingRunDirectoryIsRefusedWithoutOverwrite) {
  const fs::path out = fresh_dir("exists");
  fs::create_directories(out);
  const auto r =
      run("run " + (kSource / "cases/couette.toml").string() + " --out " + out.string() + " --quiet");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--overwrite"), std::string::npos) << r.output;
}

TEST(Cli, UnknownKeyIsExitTwoNamingFileLineAndKey) {
  const fs::path dir = fresh_dir("badcase");
  fs::create_directories(dir);
  std::string text = read(kSource / "cases/couette.toml");
  const auto pos = text.find("nu = 1.0e-6");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 2, "nuu");
  std::ofstream(dir / "bad.toml") << text;
  const auto r = run("run " + (dir / "bad.toml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fluid.nuu"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean 'fluid.nu'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing is written for a bad case";
}

TEST(Cli, BadOverrideIsExitTwo) {
  const auto r = run("run " + (kSource / "cases/couette.toml").string() + " --set time.cfl=3 --out " +
                     fresh_dir("override").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("time.cfl"), std::string::npos) << r.output;
}

TEST(Cli, NumericalFailureIsExitThreeWithFinalSnapshot) {
  const fs::path out = fresh_dir("blowup");
  // A sound speed 400 times too low for the hydrostatic load.
  const auto r = run("run " + (kSource / "cases/hydrostatic.toml").string() + " --out " + out.string() +
                     " --quiet --set fluid.c=0.05 --set resolution.d0=0.005");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("numerical failure at t ="), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle"), std::string::npos) << r.output;
  // the message names the cause with its numbers: g H / c^2 = 9.81 x 0.1 / 0.05^2 = 392
  EXPECT_NE(r.output.find("gravity compresses the fluid by g H / c^2 = 3.9e+02"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("fluid.c of at least 9.9 m/s"), std::string::npos) << r.output;
  const std::string summary = read(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
  int snapshots = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out / "particles")) ++snapshots;
  EXPECT_GE(snapshots, 2) << "initial and final snapshot";
}

TEST(Cli, InfoReportsCountsAndTimeStep) {
  const auto r = run("info " + (kSource / "cases/hydrostatic.toml").string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1600 fluid"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("initial dt"), std::string::npos) << r.output;
}
