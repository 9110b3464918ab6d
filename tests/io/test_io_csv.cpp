// io: CSV writer (round trip, flushing, append for resumed runs) and reader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

#include "particula/io/atomic_file.hpp"
#include "particula/io/csv.hpp"

namespace fs = std::filesystem;
using namespace particula::io;

namespace {

class CsvTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("particula_io_csv_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

const std::vector<std::string> kHeader = {"time", "body", "x"};

}  // namespace

TEST_F(CsvTest, RoundTripOfDoublesIsBitwise) {
  const std::vector<double> values = {
      1.0 / 3.0, 1e-300,       -0.0, 12345678.9, 0.1, -2.5e-310, std::numeric_limits<double>::max(),
      1e16,      6.02214076e23};
  const fs::path p = dir_ / "v.csv";
  {
    CsvWriter w(p, {"a", "b", "c"});
    for (std::size_t i = 0; i + 2 < values.size(); i += 3) w.row({values[i], values[i + 1], values[i + 2]});
  }
  const CsvTable t = read_csv(p);
  ASSERT_EQ(t.header, (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(t.size(), 3u);
  for (std::size_t i = 0; i < values.size(); ++i)
    EXPECT_TRUE(same_bits(t.rows[i / 3][i % 3], values[i])) << i;
}

TEST_F(CsvTest, IntegersPrintWithoutFraction) {
  const fs::path p = dir_ / "i.csv";
  CsvWriter w(p, kHeader);
  w.row(std::vector<double>{0.5, 1, -3});
  EXPECT_EQ(read_file(p), "time,body,x\n0.5,1,-3\n");
}

TEST_F(CsvTest, RowsAreOnDiskBeforeTheWriterCloses) {
  const fs::path p = dir_ / "f.csv";
  CsvWriter w(p, kHeader);
  w.row({0.0, 0, 1.5});
  EXPECT_EQ(read_csv(p).size(), 1u);  // read while still open: flushed
  w.row({0.1, 0, 1.75});
  EXPECT_EQ(read_csv(p).column("x"), (std::vector<double>{1.5, 1.75}));
}

TEST_F(CsvTest, WrongRowLengthAndBadColumnNamesAreRejected) {
  CsvWriter w(dir_ / "r.csv", kHeader);
  EXPECT_THROW(w.row({1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir_ / "s.csv", {"a,b"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir_ / "no_dir" / "s.csv", kHeader), IoError);
}

TEST_F(CsvTest, AppendWithMatchingHeaderContinues) {
  const fs::path p = dir_ / "bodies.csv";
  {
    CsvWriter w(p, kHeader);
    w.row({0.0, 0, 1});
  }
  {
    CsvWriter w = CsvWriter::append(p, kHeader);
    w.row({0.1, 0, 2});
  }
  EXPECT_EQ(read_file(p), "time,body,x\n0,0,1\n0.1,0,2\n");
}

TEST_F(CsvTest, AppendCutsAPartialLastLine) {
  const fs::path p = dir_ / "bodies.csv";
  write_file_atomic(p, "time,body,x\n0,0,1\n0.1,0,2\n0.2,0,");  // killed mid-row
  CsvWriter w = CsvWriter::append(p, kHeader);
  w.row({0.2, 0, 3});
  EXPECT_EQ(read_file(p), "time,body,x\n0,0,1\n0.1,0,2\n0.2,0,3\n");
}

TEST_F(CsvTest, AppendDropsRowsAfterTheCheckpointTime) {
  const fs::path p = dir_ / "bodies.csv";
  write_file_atomic(p, "time,body,x\n0,0,1\n0,1,1\n0.1,0,2\n0.1,1,2\n0.2,0,3\n");
  CsvWriter w = CsvWriter::append(p, kHeader, 0.1);
  w.row({0.2, 0, 4});
  EXPECT_EQ(read_csv(p).column("x"), (std::vector<double>{1, 1, 2, 2, 4}));
}

TEST_F(CsvTest, AppendWithMismatchingHeaderRaisesIoError) {
  const fs::path p = dir_ / "bodies.csv";
  { CsvWriter w(p, {"time", "body", "y"}); }
  try {
    (void)CsvWriter::append(p, kHeader);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bodies.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("time,body,y"), std::string::npos) << msg;
  }
  EXPECT_EQ(read_file(p), "time,body,y\n");  // untouched
}

TEST_F(CsvTest, AppendToMissingOrHeaderlessFileStartsFresh) {
  const fs::path p = dir_ / "new.csv";
  { CsvWriter w = CsvWriter::append(p, kHeader); }
  EXPECT_EQ(read_file(p), "time,body,x\n");
  write_file_atomic(p, "time,bo");  // killed while writing the header
  { CsvWriter w = CsvWriter::append(p, kHeader); }
  EXPECT_EQ(read_file(p), "time,body,x\n");
}

TEST_F(CsvTest, ReaderSkipsCommentsAndNamesMissingColumns) {
  const fs::path p = dir_ / "ref.csv";
  write_file_atomic(p, "# reference data\n# units SI\n\nt, v\r\n0, 1.5\r\n1, inf\n2,nan\n");
  const CsvTable t = read_csv(p);
  EXPECT_EQ(t.header, (std::vector<std::string>{"t", "v"}));
  const auto v = t.column("v");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 1.5);
  EXPECT_TRUE(std::isinf(v[1]));
  EXPECT_TRUE(std::isnan(v[2]));
  try {
    (void)t.column("w");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("ref.csv"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("'w'"), std::string::npos);
  }
}

TEST_F(CsvTest, ReaderRejectsBadCells) {
  const fs::path p = dir_ / "bad.csv";
  write_file_atomic(p, "a,b\n1,2\n3,x\n");
  try {
    (void)read_csv(p);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  write_file_atomic(p, "a,b\n1,2,3\n");
  EXPECT_THROW((void)read_csv(p), IoError);
  write_file_atomic(p, "# only a comment\n");
  EXPECT_THROW((void)read_csv(p), IoError);
}

TEST_F(CsvTest, AFullDiskIsAWriteErrorNamingTheFile) {
  // /dev/full: every write fails with ENOSPC, as on a full disk.
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  try {
    CsvWriter w("/dev/full", kHeader);
    w.row({0.0, 0, 1.5});
    FAIL() << "expected WriteError";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

TEST_F(CsvTest, RowsAreWrittenTogetherOrNotAtAll) {
  const fs::path p = dir_ / "block.csv";
  CsvWriter w(p, kHeader);
  const std::vector<double> values{0.0, 0, 1.5, 0.0, 1, 2.5};
  EXPECT_THROW(w.rows(values, [] { return true; }), Cancelled);
  EXPECT_EQ(read_file(p), "time,body,x\n");
  w.rows(values, [] { return false; });
  EXPECT_EQ(read_file(p), "time,body,x\n0,0,1.5\n0,1,2.5\n");
  EXPECT_THROW(w.rows(std::vector<double>{1.0, 2.0}), std::invalid_argument);
}

TEST_F(CsvTest, UnitsLineFollowsTheHeaderAndIsReadBack) {
  const fs::path p = dir_ / "u.csv";
  {
    CsvWriter w(p, kHeader, {"s", "-", "m"});
    w.row({0.35, 0, 1.5});
  }
  EXPECT_EQ(read_file(p), "time,body,x\n# units: time [s], body [-], x [m]\n0.35,0,1.5\n");
  const CsvTable t = read_csv(p);
  EXPECT_EQ(t.units, (std::vector<std::string>{"s", "-", "m"}));
  EXPECT_EQ(t.size(), 1u);
  // a units line that does not name the columns in order is an ordinary comment
  write_file_atomic(p, "time,body,x\n# units: body [-], time [s], x [m]\n0,0,0\n");
  EXPECT_TRUE(read_csv(p).units.empty());
  EXPECT_THROW(CsvWriter(dir_ / "v.csv", kHeader, {"s", "m"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir_ / "w.csv", kHeader, {"s", "", "m"}), std::invalid_argument);
  EXPECT_THROW(CsvWriter(dir_ / "x.csv", kHeader, {"s", "[-]", "m"}), std::invalid_argument);
}

TEST_F(CsvTest, AppendKeepsTheUnitsLineAndWritesItToANewFile) {
  const fs::path p = dir_ / "bodies.csv";
  {
    CsvWriter w(p, kHeader, {"s", "-", "m"});
    w.row({0.0, 0, 1});
    w.row({0.1, 0, 2});
  }
  {
    auto w = CsvWriter::append(p, kHeader, 0.05, {"s", "-", "m"});
    w.row({0.1, 0, 3});
  }
  EXPECT_EQ(read_file(p), "time,body,x\n# units: time [s], body [-], x [m]\n0,0,1\n0.1,0,3\n");
  const fs::path q = dir_ / "new.csv";
  { auto w = CsvWriter::append(q, kHeader, 1.0, {"s", "-", "m"}); }
  EXPECT_EQ(read_file(q), "time,body,x\n# units: time [s], body [-], x [m]\n");
}

TEST_F(CsvTest, NumbersAreWrittenInTheirShortestExactForm) {
  const fs::path p = dir_ / "s.csv";
  {
    CsvWriter w(p, {"a", "b", "c"});
    w.row({0.35, 7 * 0.05, 1e-5});
  }
  EXPECT_EQ(read_file(p), "a,b,c\n0.35,0.35000000000000003,1e-05\n");
}
