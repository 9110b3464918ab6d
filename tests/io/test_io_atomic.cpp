// io: atomic whole-file writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "particula/io/atomic_file.hpp"

namespace fs = std::filesystem;
using namespace particula::io;

namespace {

/// A fresh directory per test, removed afterwards.
class AtomicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("particula_io_atomic_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Names of every entry of the directory.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(AtomicTest, WritesContentAndLeavesNoTempFile) {
  const fs::path p = dir_ / "a.txt";
  write_file_atomic(p, "hello\nworld\n");
  EXPECT_EQ(read_file(p), "hello\nworld\n");
  EXPECT_EQ(listing(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicTest, ReplacesExistingFileAndKeepsBinaryBytes) {
  const fs::path p = dir_ / "b.bin";
  write_file_atomic(p, "old content that is longer");
  const std::string bytes("\0\x01\xff\n\r", 5);
  write_file_atomic(p, bytes);
  EXPECT_EQ(read_file(p), bytes);
  EXPECT_EQ(listing(), std::vector<std::string>{"b.bin"});
}

TEST_F(AtomicTest, MissingDirectoryRaisesIoErrorNamingThePath) {
  const fs::path p = dir_ / "no_such_dir" / "c.txt";
  try {
    write_file_atomic(p, "x");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
  EXPECT_EQ(listing(), std::vector<std::string>{});
}

TEST_F(AtomicTest, ParentThatIsAFileRaisesIoError) {
  // Works even as root, where permission bits do not stop writes.
  write_file_atomic(dir_ / "plain", "x");
  const fs::path p = dir_ / "plain" / "d.txt";
  try {
    write_file_atomic(p, "x");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(listing(), std::vector<std::string>{"plain"});
}

TEST_F(AtomicTest, TargetThatIsADirectoryRaisesIoErrorAndRemovesTemp) {
  // The temp file is written fine but the rename fails: the temp must be cleaned up.
  fs::create_directories(dir_ / "target" / "inside");
  EXPECT_THROW(write_file_atomic(dir_ / "target", "x"), IoError);
  EXPECT_EQ(listing(), std::vector<std::string>{"target"});
}

TEST_F(AtomicTest, AtomicFileCommitsOnlyOnCommit) {
  const fs::path p = dir_ / "e.txt";
  {
    AtomicFile f(p);
    f.stream() << "abandoned " << 42;
  }
  EXPECT_FALSE(fs::exists(p));
  AtomicFile f(p);
  f.stream() << "x = " << 1.5 << '\n';
  f.write("end\n");
  EXPECT_FALSE(fs::exists(p));
  f.commit();
  EXPECT_TRUE(f.committed());
  EXPECT_EQ(read_file(p), "x = 1.5\nend\n");
  EXPECT_THROW(f.commit(), std::logic_error);
  EXPECT_EQ(listing(), std::vector<std::string>{"e.txt"});
}

TEST_F(AtomicTest, ReadingAMissingFileRaisesIoError) {
  try {
    (void)read_file(dir_ / "missing.txt");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.txt"), std::string::npos);
  }
}

TEST_F(AtomicTest, WriteFailuresAreWriteErrors) {
  write_file_atomic(dir_ / "plain", "x");
  EXPECT_THROW(write_file_atomic(dir_ / "plain" / "d.txt", "x"), WriteError);
}

TEST_F(AtomicTest, AStopRequestGivesUpAndLeavesTheOldFile) {
  const fs::path p = dir_ / "big.bin";
  write_file_atomic(p, "old");
  const std::string big(20u << 20, 'x');  // three chunks: the stop check is polled between them
  int polls = 0;
  EXPECT_THROW(write_file_atomic(p, big, [&] { return ++polls == 2; }), Cancelled);
  EXPECT_EQ(polls, 2);
  EXPECT_EQ(read_file(p), "old");
  EXPECT_EQ(listing(), std::vector<std::string>{"big.bin"});
  write_file_atomic(p, big, [] { return false; });
  EXPECT_EQ(read_file(p).size(), big.size());
}
