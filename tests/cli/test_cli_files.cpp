// The user's files and runs through the command line: --overwrite replaces only a run
// directory particula made holding only the files its case writes (never '.', '..', a directory
// or file of the user's, a link, a file that merely looks like an output) and keeps the old run
// until the new one has started; a file-system failure is exit code 4, logged, and
// the run resumes from its last checkpoint; temporary files of a killed particula are removed on
// resume; SIGTERM during a long output ends the run within a second with a checkpoint, and the
// resumed run writes what the interrupted one gave up; validate and generate write only into
// what is theirs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_process.hpp"
#include "particula/io/json.hpp"
#include "particula/run/run_dir.hpp"

namespace fs = std::filesystem;
using cli_test::cli;
using cli_test::fresh_dir;
using cli_test::read_text;
using cli_test::write_text;

namespace {

const fs::path kCouette = fs::path(PARTICULA_SOURCE_DIR) / "cases" / "couette.toml";

/// `run` of a short coarse couette into `out`.
std::vector<std::string> couette(const std::string& out, const std::string& t_end, std::vector<std::string> extra = {}) {
  std::vector<std::string> a{"run", kCouette.string(), "--out", out, "--quiet", "--no-plots", "--threads", "1",
                             "--set", "time.end=" + t_end};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

/// Every path under `dir` (links not followed) with its size and content: a before/after picture.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> t;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const auto st = e.symlink_status();
    t[e.path().lexically_relative(dir).string()] =
        fs::is_symlink(st) ? "link:" + fs::read_symlink(e.path()).string()
        : fs::is_regular_file(st) ? read_text(e.path())
                                  : "dir";
  }
  return t;
}

/// Runs particula with a file-size limit (ulimit -f, 512-byte blocks): writes beyond it fail with
/// EFBIG ("File too large"), the same code path as a full disk (SIGXFSZ ignored so that the write
/// returns the error).
cli_test::Ended cli_with_file_limit(int blocks, const std::vector<std::string>& args) {
  std::vector<std::string> sh{"-c", "trap '' XFSZ; ulimit -f " + std::to_string(blocks) + "; exec \"$0\" \"$@\"",
                              PARTICULA_BINARY};
  sh.insert(sh.end(), args.begin(), args.end());
  return cli_test::Child("sh", sh).wait();
}

}  // namespace

TEST(CliFiles, OverwriteRefusesWhatParticulaDidNotWrite) {
  const fs::path dir = fresh_dir("files_refuse");
  const fs::path work = dir / "work";
  ASSERT_EQ(cli(couette((dir / "run").string(), "0.01")).code, 0);
  fs::create_directories(work / "thesis");
  write_text(work / "thesis" / "chapter1.tex", "my thesis\n");
  write_text(work / "notes.txt", "notes\n");
  fs::create_directory_symlink(dir / "run", work / "link_to_run");
  const auto before = tree(dir);
  // Each is refused with exit code 2 and a reason; nothing anywhere under `dir` changes.
  const std::vector<std::pair<std::string, std::string>> refused{
      {".", "working directory"},
      {"..", "working directory"},
      {"thesis", "not a particula run directory"},
      {"notes.txt", "is a file"},
      {"link_to_run", "symbolic link"},
      {(work / "thesis").string(), "not a particula run directory"},
  };
  for (const auto& [out, reason] : refused) {
    // Run from inside `work`, so that '.' and '..' are the working directory and its parent.
    const auto r = cli_test::Child("sh", {"-c", "cd \"$0\" && exec \"$@\"", work.string(), PARTICULA_BINARY, "run",
                                          kCouette.string(), "--out", out, "--overwrite", "--quiet", "--no-plots",
                                          "--set", "time.end=0.01"})
                       .wait();
    EXPECT_EQ(r.code, 2) << out << ": " << r.output;
    EXPECT_NE(r.output.find(reason), std::string::npos) << out << ": " << r.output;
    EXPECT_TRUE(tree(dir) == before) << "--out " << out << " changed something";
  }
  // A run directory holding a file of the user's is not replaced either.
  write_text(dir / "run" / "my_analysis.py", "print(1)\n");
  const auto before_run = tree(dir);
  const auto r = cli(couette((dir / "run").string(), "0.01", {"--overwrite"}));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("my_analysis.py"), std::string::npos) << r.output;
  EXPECT_TRUE(tree(dir) == before_run);
  // Without --overwrite an existing directory is refused, naming why --overwrite would not help.
  const auto plain = cli(couette((work / "thesis").string(), "0.01"));
  EXPECT_EQ(plain.code, 2) << plain.output;
  EXPECT_NE(plain.output.find("not a particula run directory"), std::string::npos) << plain.output;
}

TEST(CliFiles, OverwriteKeepsFilesThatOnlyLookLikeOutputs) {
  // Names of particula's patterns that this case never writes are the user's: the overwrite is
  // refused, naming them, and nothing changes; once they are moved out it goes ahead.
  const fs::path dir = fresh_dir("files_lookalike");
  const fs::path run = dir / "run";
  ASSERT_EQ(cli(couette(run.string(), "0.01")).code, 0);
  fs::create_directories(run / "plots");
  const std::vector<std::string> mine{"plots/figure_for_paper.png", "probe_mine.csv", "flow_mine.csv"};
  for (const auto& f : mine) write_text(run / f, "mine");
  const auto before = tree(dir);
  const auto r = cli(couette(run.string(), "0.02", {"--overwrite"}));
  EXPECT_EQ(r.code, 2) << r.output;
  for (const auto& f : mine) EXPECT_NE(r.output.find(f), std::string::npos) << r.output;
  EXPECT_TRUE(tree(dir) == before) << r.output;
  for (const auto& f : mine) fs::remove(run / f);
  const auto again = cli(couette(run.string(), "0.02", {"--overwrite"}));
  EXPECT_EQ(again.code, 0) << again.output;
}

TEST(CliFiles, OverwriteReplacesARunDirectoryAndLeavesNothingAside) {
  const fs::path dir = fresh_dir("files_replace");
  ASSERT_EQ(cli(couette((dir / "run").string(), "0.01")).code, 0);
  const auto r = cli(couette((dir / "run").string(), "0.02", {"--overwrite"}));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(read_text(dir / "run" / "case.toml").find("end = 0.02"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "run" / particula::kRunMarker));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"run"}) << "the old run moved aside is deleted";
  EXPECT_NE(read_text(dir / "run" / "log.txt").find("replacing the run directory"), std::string::npos);
}

TEST(CliFiles, FailedOverwriteLeavesTheOldRunAsItWas) {
  // The new run cannot write its case.toml (a 1 KiB file-size limit): exit 4, and the old run
  // directory is back, byte for byte, with nothing of the new one left.
  const fs::path dir = fresh_dir("files_failed_replace");
  ASSERT_EQ(cli(couette((dir / "run").string(), "0.01")).code, 0);
  const auto before = tree(dir);
  const auto r = cli_with_file_limit(2, couette((dir / "run").string(), "0.02", {"--overwrite"}));
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("I/O failure"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("File too large"), std::string::npos) << r.output;
  EXPECT_TRUE(tree(dir) == before) << r.output;
}

TEST(CliFiles, WriteFailureIsExitFourLoggedAndTheRunResumes) {
  // walls.csv outgrows a 50 KiB file-size limit mid-run (as on a full disk): exit 4 with the file
  // and the OS reason, in log.txt too; resumed without the limit, the run ends as an
  // uninterrupted one would, bitwise.
  const fs::path dir = fresh_dir("files_write_failure");
  const std::vector<std::string> set{"--set", "output.interval=0.001", "--set", "output.checkpoint_interval=0.01",
                                     "--set", "output.snapshots=false"};
  ASSERT_EQ(cli(couette((dir / "full").string(), "0.25", set)).code, 0);
  const auto r = cli_with_file_limit(100, couette((dir / "cut").string(), "0.25", set));
  ASSERT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("I/O failure: cannot write"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("walls.csv"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particula resume"), std::string::npos) << r.output;
  const std::string log = read_text(dir / "cut" / "log.txt");
  EXPECT_NE(log.find("error: I/O failure: cannot write"), std::string::npos) << log;
  const std::string summary = read_text(dir / "cut" / "summary.json");  // small: within the limit
  EXPECT_NE(summary.find("\"status\": \"io_failure\""), std::string::npos) << summary;
  EXPECT_EQ(particula::io::json_number_field(summary, "exit_code"), 4) << summary;
  EXPECT_NE(summary.find("\"error\": \"I/O failure: cannot write"), std::string::npos) << summary;
  const auto resumed = cli({"resume", (dir / "cut").string(), "--quiet", "--no-plots", "--threads", "1"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"walls.csv", "probe_profile.csv"})
    EXPECT_TRUE(read_text(dir / "full" / f) == read_text(dir / "cut" / f)) << f;
}

TEST(CliFiles, UncreatableRunDirectoryIsAnIoFailure) {
  // A directory where this user may not create anything: /sys for root, a read-only one otherwise.
  fs::path out;
  if (::geteuid() == 0) {
    out = "/sys/particula_cannot_create_this";
  } else {
    const fs::path dir = fresh_dir("files_readonly");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    out = dir / "run";
  }
  std::error_code ec;
  if (fs::create_directory(out, ec) || ec == std::errc::no_such_file_or_directory) {
    fs::remove(out, ec);
    GTEST_SKIP() << "this machine lets " << out << " be created";
  }
  const auto r = cli(couette(out.string(), "0.01"));
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("cannot create run directory"), std::string::npos) << r.output;
}

TEST(CliFiles, ResumeRemovesStaleTemporaryFilesOnly) {
  const fs::path dir = fresh_dir("files_stale_temp");
  const fs::path run = dir / "run";
  ASSERT_EQ(cli(couette(run.string(), "0.01")).code, 0);
  const std::string dead = std::to_string(cli_test::dead_pid()), alive = std::to_string(::getpid());
  const std::vector<fs::path> stale{run / "checkpoint" / ("state.bin.tmp." + dead),
                                    run / "particles" / ("step_00000012.vtp.tmp." + dead),
                                    run / ("summary.json.tmp." + dead), run / ("particles.pvd.tmp." + dead)};
  const std::vector<fs::path> kept{run / "checkpoint" / ("state.bin.tmp." + alive),  // a running process's
                                   run / ("my_data.csv.tmp." + dead),                // not a particula file
                                   run / "checkpoint" / "state.bin.tmp.notapid", run / "notes.tmp"};
  for (const auto& p : stale) write_text(p, "partial");
  for (const auto& p : kept) write_text(p, "keep");
  const auto r = cli({"resume", run.string(), "--quiet", "--no-plots", "--set", "time.end=0.02"});
  ASSERT_EQ(r.code, 0) << r.output;
  for (const auto& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const auto& p : kept) EXPECT_EQ(read_text(p), "keep") << p;
  EXPECT_NE(read_text(run / "log.txt").find("removed 4 temporary file(s)"), std::string::npos);
}

TEST(CliFiles, SigtermDuringALongOutputEndsWithinASecondAndTheResumedRunWritesIt) {
  // A probe of 2000 points with the exact solution (about the most the load check allows for an
  // exact series): its output at t = 0 takes some 0.4 s (the series needs 20000 terms there). SIGTERM during it ends the run within a second, with a checkpoint
  // and no partial probe rows; the resumed run writes that output first and ends bitwise as an
  // uninterrupted run.
  const fs::path dir = fresh_dir("files_sigterm_output");
  const std::vector<std::string> set{"--set", "probe.0.points=2000", "--set", "output.snapshots=false"};
  cli_test::Child child(PARTICULA_BINARY, couette((dir / "cut").string(), "0.001", set));
  const fs::path probe = dir / "cut" / "probe_profile.csv";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(probe) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(fs::exists(probe));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // inside the probe's first output
  const auto t0 = std::chrono::steady_clock::now();
  child.signal(SIGTERM);
  const auto cut = child.wait();
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(cut.code, 130) << cut.output;
  EXPECT_LT(waited, 1.0) << "SIGTERM honoured within a second";
  EXPECT_TRUE(fs::exists(dir / "cut" / "checkpoint" / "state.bin"));
  EXPECT_EQ(read_text(probe),
            "time,x,y,vx,vy,p,vx_exact,vy_exact\n# units: time [s], x [m], y [m], vx [m/s], vy [m/s], p [Pa], vx_exact [m/s], vy_exact [m/s]\n")
      << "no partial rows";
  std::printf("SIGTERM during a long probe output: exit 130 after %.3f s\n", waited);

  const auto resumed = cli({"resume", (dir / "cut").string(), "--quiet", "--no-plots", "--threads", "1"});
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  ASSERT_EQ(cli(couette((dir / "full").string(), "0.001", set)).code, 0);
  EXPECT_TRUE(read_text(dir / "full" / "probe_profile.csv") == read_text(probe));
  EXPECT_TRUE(read_text(dir / "full" / "walls.csv") == read_text(dir / "cut" / "walls.csv"));
}

TEST(CliFiles, ValidateAndGenerateWriteOnlyWhatIsTheirs) {
  const fs::path dir = fresh_dir("files_validate");
  fs::create_directories(dir / "mine");
  write_text(dir / "mine" / "report.md", "my own report\n");
  write_text(dir / "afile", "x");
  for (const auto& out : {dir / "mine", dir / "afile"}) {
    const auto r = cli({"validate", "--out", out.string(), "--case", "couette", "--quick", "--quiet"});
    EXPECT_EQ(r.code, 2) << r.output;
  }
  EXPECT_EQ(read_text(dir / "mine" / "report.md"), "my own report\n");
  EXPECT_EQ(read_text(dir / "afile"), "x");
  // generate --out replaces a case it generated, not a file of the user's.
  const auto mine = cli({"generate", "--seed", "3", "--out", (dir / "afile").string()});
  EXPECT_EQ(mine.code, 2) << mine.output;
  EXPECT_EQ(read_text(dir / "afile"), "x");
  ASSERT_EQ(cli({"generate", "--seed", "3", "--out", (dir / "case.toml").string()}).code, 0);
  const auto again = cli({"generate", "--seed", "4", "--out", (dir / "case.toml").string()});
  EXPECT_EQ(again.code, 0) << again.output;
  EXPECT_NE(read_text(dir / "case.toml").find("seed 4"), std::string::npos);
}

TEST(CliFiles, ARunDirectoryCanBeResumedAsSoonAsItHasStarted) {
  // A checkpoint of the initial state is written before the run takes its first step, so a run
  // stopped by a full disk (or killed) before its first scheduled checkpoint still resumes; a
  // failure before that checkpoint removes the new directory instead.
  const fs::path dir = fresh_dir("cli_resumable_at_start") / "run";
  cli_test::Child child(PARTICULA_BINARY, couette(dir.string(), "1000", {"--set", "output.checkpoint_interval=500"}));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool stepping = false;
  while (!stepping && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::error_code ec;
    if (fs::exists(dir / "log.txt", ec)) stepping = read_text(dir / "log.txt").find("  step ") != std::string::npos;
  }
  child.signal(SIGKILL);
  child.wait();
  ASSERT_TRUE(stepping) << "the run never took a step";
  EXPECT_TRUE(fs::exists(dir / "checkpoint" / "state.bin")) << "no checkpoint before the first scheduled one";
  const auto r = cli({"resume", dir.string(), "--quiet", "--no-plots", "--threads", "1", "--set", "time.end=0.01"});
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(CliFiles, ResumeRefusesAnEditedCaseFileRatherThanDiscardingIt) {
  const fs::path dir = fresh_dir("cli_resume_edited") / "run";
  ASSERT_EQ(cli(couette(dir.string(), "0.01")).code, 0);
  const std::string original = read_text(dir / "case.toml");
  const auto resume = [&] {
    return cli({"resume", dir.string(), "--quiet", "--no-plots", "--threads", "1", "--set", "time.end=0.015"});
  };
  // A changed viscosity: refused, naming the key, nothing written.
  const std::string edited = std::regex_replace(original, std::regex("nu = 1e-06"), "nu = 2e-06");
  ASSERT_NE(edited, original);
  write_text(dir / "case.toml", edited);
  const auto before = tree(dir.parent_path());
  const auto r = resume();
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("case.toml was edited since the run wrote it"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("+ [fluid] nu = 2e-06"), std::string::npos) << r.output;
  EXPECT_TRUE(tree(dir.parent_path()) == before) << "a refused resume changed the run directory";
  // A comment is no edit of the case; a deleted case.toml is written again.
  write_text(dir / "case.toml", "# my note\n" + original);
  EXPECT_EQ(resume().code, 0);
  fs::remove(dir / "case.toml");
  const auto again = cli({"resume", dir.string(), "--quiet", "--no-plots", "--threads", "1", "--set", "time.end=0.02"});
  EXPECT_EQ(again.code, 0) << again.output;
  EXPECT_TRUE(fs::exists(dir / "case.toml"));
}
