// Two particula processes that want the same run directory: the second (run, run --overwrite or
// resume) is refused with exit code 2, naming the directory and the pid of the first, and touches
// nothing; the first ends as if it had been alone. The first is stopped (SIGSTOP) while it holds
// the directory, so that the second always meets it at work, however fast or slow the machine.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "cli_process.hpp"
#include "particula/run/run_dir.hpp"

namespace fs = std::filesystem;
using cli_test::Child;
using cli_test::cli;
using cli_test::fresh_dir;
using cli_test::read_text;

namespace {

const fs::path kCouette = fs::path(PARTICULA_SOURCE_DIR) / "cases" / "couette.toml";

/// `run` of a short coarse couette into `out`.
std::vector<std::string> couette(const fs::path& out, const std::string& t_end,
                                 std::vector<std::string> extra = {}) {
  std::vector<std::string> a{"run",        kCouette.string(), "--out", out.string(), "--quiet",
                             "--no-plots", "--threads",       "1",     "--set",      "time.end=" + t_end};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

std::vector<std::string> resume(const fs::path& dir, const std::string& t_end) {
  return {"resume", dir.string(), "--quiet", "--no-plots", "--threads", "1", "--set", "time.end=" + t_end};
}

/// Polls `ready` every millisecond for at most 60 s; whether it became true.
bool wait_until(const std::function<bool()>& ready) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!ready()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

/// Stops `child` and waits until it is stopped; false when it had ended before (then its run was
/// too short for the test: raise kLong).
bool stop(const Child& child) {
  child.signal(SIGSTOP);
  int status = 0;
  while (::waitpid(child.pid(), &status, WUNTRACED) < 0 && errno == EINTR) {
  }
  return WIFSTOPPED(status);
}

/// time.end of the first process: long enough (half a second or so) that it is still at work
/// when the test has seen its files and stops it.
const std::string kLong = "1";

/// The pid written in the lock file of `dir` (0 when none).
long lock_pid(const fs::path& dir) {
  const std::string text = read_text(dir / particula::kRunLock);
  try {
    return text.empty() ? 0 : std::stol(text);
  } catch (const std::exception&) {
    return 0;
  }
}

/// The names in `dir`, sorted.
std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Checks that `second` was refused because `first` (pid) holds `dir`.
void expect_refused_for(const cli_test::Ended& second, const Child& first, const fs::path& dir) {
  EXPECT_EQ(second.code, 2) << second.output;
  EXPECT_NE(second.output.find("pid " + std::to_string(first.pid())), std::string::npos) << second.output;
  EXPECT_NE(second.output.find(dir.string()), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("in use by another particula process"), std::string::npos) << second.output;
}

}  // namespace

TEST(CliConcurrent, ASecondRunIntoARunningRunsDirectoryIsRefused) {
  const fs::path dir = fresh_dir("concurrent_run");
  const fs::path run = dir / "run";
  Child first(PARTICULA_BINARY, couette(run, kLong));
  // The directory appears with its marker and its lock held: no moment where it is unmarked.
  ASSERT_TRUE(wait_until([&] { return fs::exists(run / particula::kRunMarker); }));
  ASSERT_TRUE(stop(first));
  EXPECT_EQ(lock_pid(run), first.pid());
  expect_refused_for(cli(couette(run, "0.02")), first, run);
  expect_refused_for(cli(couette(run, "0.02", {"--overwrite"})), first, run);
  expect_refused_for(cli(resume(run, "0.02")), first, run);
  first.signal(SIGCONT);
  const auto ended = first.wait();
  ASSERT_EQ(ended.code, 0) << ended.output;
  EXPECT_NE(read_text(run / "case.toml").find("end = " + kLong), std::string::npos);
  EXPECT_NE(read_text(run / "summary.json").find("\"status\": \"completed\""), std::string::npos);
  EXPECT_EQ(lock_pid(run), 0) << "the lock file is emptied when the run ends";
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"run"}) << "nothing staged or moved aside is left";
}

TEST(CliConcurrent, AnOverwriteOfADirectoryBeingOverwrittenIsRefused) {
  const fs::path dir = fresh_dir("concurrent_overwrite");
  const fs::path run = dir / "run";
  ASSERT_EQ(cli(couette(run, "0.01")).code, 0);
  Child first(PARTICULA_BINARY, couette(run, kLong, {"--overwrite"}));
  // Its case.toml is in place once it has taken the old run's lock and swapped the new run in.
  ASSERT_TRUE(
      wait_until([&] { return read_text(run / "case.toml").find("end = " + kLong) != std::string::npos; }));
  ASSERT_TRUE(stop(first));
  expect_refused_for(cli(couette(run, "0.03", {"--overwrite"})), first, run);
  first.signal(SIGCONT);
  const auto ended = first.wait();
  ASSERT_EQ(ended.code, 0) << ended.output;
  EXPECT_NE(read_text(run / "case.toml").find("end = " + kLong), std::string::npos);
  EXPECT_NE(read_text(run / "summary.json").find("\"status\": \"completed\""), std::string::npos);
  EXPECT_TRUE(fs::exists(run / "checkpoint" / "state.bin"));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"run"}) << "the old run is deleted, nothing else left";
}

TEST(CliConcurrent, ASecondResumeOfADirectoryIsRefusedAndTheFirstEndsAsAlone) {
  const fs::path dir = fresh_dir("concurrent_resume");
  const fs::path run = dir / "run";
  ASSERT_EQ(cli(couette(run, "0.05")).code, 0);  // ends at an output time: no extra step to land on
  ASSERT_EQ(cli(couette(dir / "straight", kLong)).code, 0);
  Child first(PARTICULA_BINARY, resume(run, kLong));
  ASSERT_TRUE(wait_until([&] { return lock_pid(run) == first.pid(); }));
  ASSERT_TRUE(stop(first));
  expect_refused_for(cli(resume(run, "0.02")), first, run);
  expect_refused_for(cli(couette(run, "0.02", {"--overwrite"})), first, run);
  first.signal(SIGCONT);
  const auto ended = first.wait();
  ASSERT_EQ(ended.code, 0) << ended.output;
  // No duplicated rows: the resumed run's files are those of a run straight to the same time.
  for (const char* f : {"walls.csv", "probe_profile.csv"})
    EXPECT_TRUE(read_text(run / f) == read_text(dir / "straight" / f)) << f;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"run", "straight"}));
}
