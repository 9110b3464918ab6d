// io: run log and progress line (with an injected clock, so fully deterministic).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <regex>

#include "particula/io/atomic_file.hpp"
#include "particula/io/log.hpp"

namespace fs = std::filesystem;
using namespace particula::io;

namespace {

class LogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("particula_io_log_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    out_ = std::tmpfile();
  }
  void TearDown() override {
    std::fclose(out_);
    fs::remove_all(dir_);
  }

  /// Everything printed to the captured output stream so far.
  std::string printed() {
    std::fflush(out_);
    std::rewind(out_);
    std::string s;
    for (int c; (c = std::fgetc(out_)) != EOF;) s += static_cast<char>(c);
    return s;
  }

  /// Options printing to the captured stream with a manual clock.
  ProgressOptions options(bool terminal) {
    ProgressOptions o;
    o.terminal = terminal;
    o.out = out_;
    o.clock = [this] { return clock_; };
    return o;
  }

  static std::size_t count(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
  }

  fs::path dir_;
  std::FILE* out_ = nullptr;
  double clock_ = 0;
};

}  // namespace

TEST_F(LogTest, LinesAreTimestampedAppendedAndFlushed) {
  const fs::path p = dir_ / "log.txt";
  {
    RunLog log(p);
    log.line("first");
    EXPECT_NE(read_file(p).find("first"), std::string::npos);  // flushed while open
    log.warn("two\nlines");
  }
  RunLog again(p);  // append mode keeps earlier lines
  again.record("third");
  const std::string text = read_file(p);
  const std::regex stamp(R"(^\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3}  )");
  std::size_t lines = 0;
  for (std::size_t start = 0; start < text.size(); ++lines) {
    const std::size_t nl = text.find('\n', start);
    EXPECT_TRUE(std::regex_search(text.substr(start, nl - start), stamp)) << text.substr(start, nl - start);
    start = nl + 1;
  }
  EXPECT_EQ(lines, 4u);
  EXPECT_NE(text.find("warning: two"), std::string::npos);
  EXPECT_THROW(RunLog(dir_ / "missing" / "log.txt"), IoError);
}

TEST_F(LogTest, PlainLinesAreThrottledAndLogged) {
  const fs::path p = dir_ / "log.txt";
  RunLog log(p);
  ProgressOptions o = options(false);
  o.plain_interval_s = 5;
  ProgressLine progress(&log, o);
  for (int i = 0; i <= 120; ++i) {  // 12 s of wall time, one update every 0.1 s
    clock_ = 0.1 * i;
    progress.update(i, 0.01 * i, 2.4, 0.01, 1e6);
  }
  const std::string out = printed();
  EXPECT_EQ(count(out, "\n"), 3u) << out;  // at 0, 5 and 10 s
  EXPECT_EQ(count(out, "\r"), 0u);
  EXPECT_NE(out.find("step 50  t = 0.5 / 2.4 s (20.8%)"), std::string::npos) << out;
  // 0.5 s simulated in 5 s of wall time: 1.9 s left takes 19 s.
  EXPECT_NE(out.find("ETA 19s"), std::string::npos) << out;
  progress.finish();
  progress.finish();  // idempotent
  EXPECT_EQ(count(printed(), "\n"), 4u);
  EXPECT_EQ(count(read_file(p), "step "), 4u);
}

TEST_F(LogTest, TerminalLineIsRewrittenAtMostTenTimesASecond) {
  const fs::path p = dir_ / "log.txt";
  RunLog log(p);
  ProgressLine progress(&log, options(true));
  for (int i = 0; i < 1000; ++i) {  // 10 s of wall time, one update every 10 ms
    clock_ = 0.01 * i;
    progress.update(i, 0.001 * i, 1.0, 0.001, 5e5);
  }
  const std::string live = printed();
  EXPECT_EQ(count(live, "\n"), 0u);
  const std::size_t rewrites = count(live, "\r");
  EXPECT_GE(rewrites, 95u);
  EXPECT_LE(rewrites, 101u);
  EXPECT_EQ(count(read_file(p), "step "), 2u);  // log at the plain rate: 0 and 5 s
  // A warning echoed to stderr first ends the live line, so it is not glued to it.
  log.warn("(expected test warning)");
  EXPECT_EQ(count(printed(), "\n"), 1u);
  EXPECT_EQ(printed().back(), '\n');
  EXPECT_NE(printed().find("ETA 0s"), std::string::npos);
  progress.finish();
  EXPECT_EQ(count(printed(), "\n"), 2u);
  EXPECT_EQ(printed().back(), '\n');
}

TEST_F(LogTest, QuietPrintsNothingButStillLogs) {
  const fs::path p = dir_ / "log.txt";
  RunLog log(p);
  ProgressOptions o = options(false);
  o.quiet = true;
  ProgressLine progress(&log, o);
  for (int i = 0; i <= 100; ++i) {
    clock_ = 0.1 * i;
    progress.update(i, 0.1 * i, 10, 0.1, 1);
  }
  progress.finish();
  EXPECT_EQ(printed(), "");
  EXPECT_EQ(count(read_file(p), "step "), 4u);  // 0, 5, 10 s and the final line
}

TEST(ProgressText, DurationsAndUnknownEta) {
  EXPECT_EQ(format_duration(0), "0s");
  EXPECT_EQ(format_duration(59.4), "59s");
  EXPECT_EQ(format_duration(187), "3m07s");
  EXPECT_EQ(format_duration(7500), "2h05m");
  EXPECT_EQ(format_duration(273600), "3d04h");
  EXPECT_EQ(format_duration(-1), "--");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "--");
  const std::string first = format_progress({0, 0.0, 1.0, 1e-4, 0}, -1);
  EXPECT_NE(first.find("ETA --"), std::string::npos) << first;
}
