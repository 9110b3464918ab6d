// The subcommands added to the command line: --help of each (with examples), --version, `plot`,
// `validate`, `schema`, `info --no-timing` and the guard against absurd particle counts.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_process.hpp"
#include "particula/case/schema.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/run/version.hpp"
#include "particula/validation/validate.hpp"

namespace fs = std::filesystem;
using cli_test::fresh_dir;
using cli_test::cli;
using cli_test::read_text;

namespace {
const fs::path kCases = fs::path(PARTICULA_SOURCE_DIR) / "cases";

bool has_matplotlib() {
  const char* python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  return cli_test::Child(python, {"-c", "import matplotlib"}).wait().code == 0;
}
}  // namespace

TEST(CliCommands, EverySubcommandHasHelp) {
  for (const char* sub : {"run", "resume", "info", "validate", "generate", "plot", "schema"}) {
    const auto r = cli({sub, "--help"});
    EXPECT_EQ(r.code, 0) << sub << ": " << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub << ": " << r.output;
    // an example of the command itself, and where case files are documented
    EXPECT_NE(r.output.find("Examples:\n  particula " + std::string(sub)), std::string::npos) << sub << ": " << r.output;
    EXPECT_NE(r.output.find("docs/case-files.md"), std::string::npos) << sub << ": " << r.output;
  }
  const auto r = cli({"--help"});
  EXPECT_EQ(r.code, 0);
  for (const char* sub : {"run", "resume", "info", "validate", "generate", "plot", "schema"})
    EXPECT_NE(r.output.find(sub), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("docs/case-files.md"), std::string::npos) << r.output;
  EXPECT_EQ(cli({"frobnicate"}).code, 2);
}

TEST(CliCommands, VersionNamesTheVersionAndCommit) {
  const auto r = cli({"--version"});
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, particula::version_line() + "\n");
  EXPECT_EQ(r.output.rfind("particula " + particula::version() + " (commit ", 0), 0u) << r.output;
  EXPECT_FALSE(particula::git_commit().empty());
}

TEST(CliCommands, SchemaPrintsTheReferenceOrTheJsonSchema) {
  const auto md = cli({"schema"});
  EXPECT_EQ(md.code, 0);
  EXPECT_EQ(md.output, particula::case_reference_markdown());
  const auto json = cli({"schema", "--json"});
  EXPECT_EQ(json.code, 0);
  EXPECT_EQ(json.output, particula::case_json_schema());
}

TEST(CliCommands, UnknownValidationCaseListsTheNamesAndCreatesNothing) {
  const fs::path dir = fresh_dir("validate_unknown");
  const auto bad = cli({"validate", "--case", "couete", "--out", (dir / "out").string()});
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--case couete: no validation case of that name"), std::string::npos) << bad.output;
  for (const auto& e : particula::validation_entries()) EXPECT_NE(bad.output.find(e.name), std::string::npos) << e.name;
  EXPECT_NE(bad.output.find("analytic: couette"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing created";
}

TEST(CliCommands, AbsurdResolutionIsRefusedBeforeAnyAllocation) {
  const fs::path dir = fresh_dir("absurd");
  const auto run = cli({"run", (kCases / "couette.toml").string(), "--out", (dir / "run").string(), "--set",
                              "resolution.d0=1e-10"});
  EXPECT_EQ(run.code, 2) << run.output;
  EXPECT_NE(run.output.find("resolution.d0"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "run")) << "nothing is written";
  // The load checks speak first here: steps of d0^2 / nu, far too many of them.
  EXPECT_NE(run.output.find("steps"), std::string::npos) << run.output;
  const auto r = cli({"info", (kCases / "hydrostatic.toml").string(), "--set", "resolution.d0=1e-6"});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("resolution.d0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1e+10 particles"), std::string::npos) << r.output;
  // A big domain at a fine but individually valid d0.
  const auto big = cli({"info", (kCases / "hydrostatic.toml").string(), "--set", "domain.max=[1e6, 1e6]",
                              "--no-timing"});
  EXPECT_EQ(big.code, 2) << big.output;
}

TEST(CliCommands, InfoWithoutTiming) {
  const auto r = cli({"info", (kCases / "hydrostatic.toml").string(), "--no-timing"});
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1600 fluid"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("wall time"), std::string::npos) << r.output;
}

TEST(CliCommands, PlotNeedsARunDirectory) {
  const fs::path dir = fresh_dir("plot");
  auto r = cli({"plot", (dir / "missing").string()});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("not a run directory"), std::string::npos) << r.output;
  r = cli({"plot", dir.string()});
  EXPECT_EQ(r.code, 2) << r.output;

  const auto run = cli({"run", (kCases / "couette.toml").string(), "--out", (dir / "run").string(), "--quiet",
                              "--no-plots", "--set", "time.end=0.05"});
  ASSERT_EQ(run.code, 0) << run.output;
  EXPECT_FALSE(fs::exists(dir / "run" / "plots"));
  r = cli({"plot", (dir / "run").string()});
  if (has_matplotlib()) {
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "run" / "plots" / "probe_profile_profiles.png")) << r.output;
  } else {
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("matplotlib"), std::string::npos) << r.output;
  }
}

TEST(CliCommands, ValidateOneQuickCaseWritesTheReport) {
  const fs::path dir = fresh_dir("validate");
  const auto r = cli({"validate", "--quick", "--case", "couette", "--out", dir.string(), "--threads", "1"});
  EXPECT_EQ(r.code, 0) << r.output;
  const std::string report = read_text(dir / "report.md");
  EXPECT_NE(report.find("| case | quantity | value | reference | tolerance | result |"), std::string::npos) << report;
  EXPECT_NE(report.find("[couette](couette/)"), std::string::npos) << report;
  EXPECT_NE(report.find("| pass |"), std::string::npos) << report;
  EXPECT_EQ(report.find("FAIL"), std::string::npos) << report;
  EXPECT_TRUE(fs::exists(dir / "couette" / "summary.json"));
  const auto bad = cli({"validate", "--case", "nonsense", "--out", dir.string()});
  EXPECT_EQ(bad.code, 2) << bad.output;
}

TEST(CliCommands, ValidateGroupIsChecked) {
  const fs::path dir = fresh_dir("validate_group");
  const auto bad = cli({"validate", "--group", "nonsense", "--out", dir.string()});
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(cli({"validate", "--help"}).output.find("robustness"), std::string::npos);
}

TEST(CliCommands, GenerateWritesALoadableCase) {
  const fs::path dir = fresh_dir("generate");
  const auto r = cli({"generate", "--seed", "7", "--out", (dir / "seven.toml").string()});
  ASSERT_EQ(r.code, 0) << r.output;
  const auto out = cli({"generate", "--seed", "7"});
  EXPECT_EQ(out.code, 0);
  EXPECT_EQ(out.output, read_text(dir / "seven.toml")) << "stdout and --out give the same text";
  const auto info = cli({"info", (dir / "seven.toml").string(), "--no-timing"});
  EXPECT_TRUE(info.code == 0 || info.code == 2) << info.output;  // a refusal at load is allowed
  EXPECT_EQ(cli({"generate"}).code, 2) << "--seed is required";
}

// The checks themselves, on fabricated run directories.
TEST(ValidationChecks, ProfileErrorPassesBelowItsLimitOnly) {
  const fs::path dir = fresh_dir("validate_checks");
  particula::io::write_file_atomic(dir / "summary.json", R"({"profile_error": 0.004})");
  auto c = particula::check_profile_error(dir, 0.01);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].pass);
  EXPECT_EQ(c[0].shown, "0.4 %");
  particula::io::write_file_atomic(dir / "summary.json", R"({"profile_error": 0.02})");
  EXPECT_FALSE(particula::check_profile_error(dir, 0.01)[0].pass);
  particula::io::write_file_atomic(dir / "summary.json", R"({"profile_error": null})");
  EXPECT_FALSE(particula::check_profile_error(dir, 0.01)[0].pass) << "NaN never passes";
  particula::io::write_file_atomic(dir / "summary.json", R"({"status": "failed"})");
  EXPECT_THROW(particula::check_profile_error(dir, 0.01), particula::io::IoError);
}

TEST(ValidationChecks, SuiteListsTheAnalyticCases) {
  const auto entries = particula::validation_entries();
  ASSERT_GE(entries.size(), 4u);
  for (const auto& e : entries) {
    EXPECT_TRUE(fs::exists(fs::path(PARTICULA_SOURCE_DIR) / e.case_file)) << e.case_file;
    EXPECT_TRUE(static_cast<bool>(e.evaluate)) << e.name;
  }
}
