// `particula validate --check DIR [--case NAME]`: the checks of one validation case on an existing
// run directory (exit 0 when they pass, 1 when one fails, 2 on bad input).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "cli_process.hpp"
#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/validation/validate.hpp"

namespace fs = std::filesystem;
using cli_test::cli;
using cli_test::fresh_dir;
using cli_test::read_text;

namespace {

const fs::path kSource = PARTICULA_SOURCE_DIR;

/// A short Couette run (0.02 s at the shipped resolution: a second) in `dir`/couette.
fs::path couette_run(const fs::path& dir) {
  const fs::path run = dir / "couette";
  const auto r = cli({"run", (kSource / "cases" / "couette.toml").string(), "--out", run.string(), "--quiet",
                      "--no-plots", "--threads", "1", "--set", "time.end=0.02"});
  EXPECT_EQ(r.code, 0) << r.output;
  return run;
}

}  // namespace

TEST(ValidateCheck, EveryEntryIsFoundFromItsRunsCaseName) {
  // Without --case, the entry is the one named as case.toml's `name`.
  const auto entries = particula::validation_entries();
  ASSERT_GE(entries.size(), 20u);
  for (const auto& e : entries) EXPECT_EQ(particula::load_case(kSource / e.case_file).name, e.name) << e.case_file;
}

TEST(ValidateCheck, PassingRunPrintsEachCheckAndExitsZero) {
  const fs::path run = couette_run(fresh_dir("validate_check_pass"));
  const auto r = cli({"validate", "--check", run.string()});
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("the checks of couette (analytic)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("completed after"), std::string::npos) << "how the run ended: " << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(L2 error of vx[^\n]*: [0-9.]+ % \(reference [^\n]*, < 1 %\): pass)")))
      << "value, reference, tolerance and verdict: " << r.output;
  EXPECT_NE(r.output.find("all checks pass"), std::string::npos) << r.output;
  const auto named = cli({"validate", "--check", run.string(), "--case", "couette"});
  EXPECT_EQ(named.code, 0) << named.output;
}

TEST(ValidateCheck, FailingCheckExitsOne) {
  // The run's profile error raised above the case's 1 % in summary.json: the check fails.
  const fs::path run = couette_run(fresh_dir("validate_check_fail"));
  const std::string summary = read_text(run / "summary.json");
  const std::regex error(R"("profile_error": *[0-9.eE+-]+)");
  ASSERT_TRUE(std::regex_search(summary, error)) << summary;
  particula::io::write_file_atomic(run / "summary.json", std::regex_replace(summary, error, "\"profile_error\": 0.05"));
  const auto r = cli({"validate", "--check", run.string()});
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("5 % (reference"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("): FAIL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 1 checks FAIL"), std::string::npos) << r.output;
}

TEST(ValidateCheck, BadInputExitsTwoNamingThePath) {
  const fs::path dir = fresh_dir("validate_check_bad");
  // a directory that is not a run directory, and one that does not exist
  for (const fs::path& p : {dir, dir / "missing"}) {
    const auto r = cli({"validate", "--check", p.string()});
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(p.string() + ": not a run directory"), std::string::npos) << r.output;
  }
  const fs::path run = couette_run(dir);
  // an unknown --case lists the names; a case whose outputs the run lacks cannot be checked
  const auto unknown = cli({"validate", "--check", run.string(), "--case", "couete"});
  EXPECT_EQ(unknown.code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("analytic: couette"), std::string::npos) << unknown.output;
  const auto other = cli({"validate", "--check", run.string(), "--case", "falling_cylinder"});
  EXPECT_EQ(other.code, 2) << other.output;
  EXPECT_NE(other.output.find(run.string() + ": the checks of falling_cylinder cannot read the run"), std::string::npos)
      << other.output;
  // a run of a case that is no validation case needs --case
  particula::io::write_file_atomic(run / "case.toml",
                                   std::regex_replace(read_text(run / "case.toml"), std::regex(R"(name = "couette")"),
                                                      "name = \"my_couette\"", std::regex_constants::format_first_only));
  const auto renamed = cli({"validate", "--check", run.string()});
  EXPECT_EQ(renamed.code, 2) << renamed.output;
  EXPECT_NE(renamed.output.find("'my_couette' is no validation case"), std::string::npos) << renamed.output;
  EXPECT_EQ(cli({"validate", "--check", run.string(), "--case", "couette"}).code, 0);
  // --check runs nothing: the options of a suite run are refused with it
  EXPECT_EQ(cli({"validate", "--check", run.string(), "--quick"}).code, 2);
  EXPECT_EQ(cli({"validate", "--check", run.string(), "--case", "couette", "--case", "poiseuille"}).code, 2);
}
