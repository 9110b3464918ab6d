// io: base64, .vtp write/read round trip, malformed input, .pvd index.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>

#include "particula/io/atomic_file.hpp"
#include "particula/io/base64.hpp"
#include "particula/io/vtk.hpp"

namespace fs = std::filesystem;
using namespace particula;
using namespace particula::io;

namespace {

class VtkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("particula_io_vtk_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

/// Writes a test input quickly (no fsync, unlike write_file_atomic), for the many-file loops.
void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

/// Bitwise equality of two doubles (distinguishes -0.0 and compares NaN payloads).
bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// A small deterministic particle set with awkward values.
struct Sample {
  std::vector<Vec2> points;
  std::vector<VtkArray> arrays;
  std::vector<VtkIntArray> ints;
};

/// n >= 5: the first entries are overwritten with special values.
Sample make_sample(std::size_t n) {
  if (n < 5) throw std::invalid_argument("make_sample needs at least 5 points");
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Sample s;
  VtkArray p{"pressure", 1, {}};
  VtkArray v2{"velocity2", 2, {}};
  VtkIntArray kind{"kind", 1, {}};
  for (std::size_t i = 0; i < n; ++i) {
    s.points.push_back({u(rng), u(rng) * 1e-7});
    p.data.push_back(u(rng) * 1e5);
    v2.data.push_back(u(rng));
    v2.data.push_back(-u(rng));
    kind.data.push_back(static_cast<std::int32_t>(i % 3) - 1);
  }
  p.data[0] = -0.0;
  p.data[1] = 1.0 / 3.0;
  p.data[2] = 1e-300;
  p.data[3] = std::numeric_limits<double>::denorm_min();
  kind.data[4] = std::numeric_limits<std::int32_t>::min();
  std::vector<Vec2> vel;
  for (std::size_t i = 0; i < n; ++i) vel.push_back({u(rng), u(rng)});
  s.arrays = {p, v2, vector_array("velocity", vel)};
  s.ints = {kind, VtkIntArray{"body", 1, std::vector<std::int32_t>(n, 7)}};
  return s;
}

}  // namespace

TEST(Base64, KnownVectors) {
  const std::pair<std::string, std::string> cases[] = {{"", ""},
                                                       {"f", "Zg=="},
                                                       {"fo", "Zm8="},
                                                       {"foo", "Zm9v"},
                                                       {"foob", "Zm9vYg=="},
                                                       {"fooba", "Zm9vYmE="},
                                                       {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : cases) {
    EXPECT_EQ(base64_encode(plain), encoded) << plain;
    EXPECT_EQ(base64_decode(encoded), plain) << encoded;
  }
}

TEST(Base64, AllByteValuesRoundTrip) {
  std::string bytes;
  for (int rep = 0; rep < 3; ++rep)
    for (int b = 0; b < 256; ++b) bytes += static_cast<char>(b);
  for (std::size_t len = 0; len < 20; ++len)
    EXPECT_EQ(base64_decode(base64_encode(bytes.substr(0, len))), bytes.substr(0, len));
  EXPECT_EQ(base64_decode(base64_encode(bytes)), bytes);
}

TEST(Base64, RejectsMalformedText) {
  EXPECT_THROW(base64_decode("Zm9"), IoError);       // bad length
  EXPECT_THROW(base64_decode("Zm9*"), IoError);      // bad character
  EXPECT_THROW(base64_decode("Zg==Zm9v"), IoError);  // padding in the middle
  EXPECT_THROW(base64_decode("Z==="), IoError);      // too much padding
  EXPECT_EQ(base64_decode(" Zm9v\nYmFy "), "foobar");
}

TEST_F(VtkTest, RoundTripIsBitwise) {
  const Sample s = make_sample(300);
  const fs::path p = dir_ / "step_0.vtp";
  write_vtp(p, s.points, s.arrays, s.ints);
  const VtpData d = read_vtp(p);
  ASSERT_EQ(d.num_points, s.points.size());
  ASSERT_EQ(d.points.size(), s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    EXPECT_TRUE(same_bits(d.points[i].x, s.points[i].x)) << i;
    EXPECT_TRUE(same_bits(d.points[i].y, s.points[i].y)) << i;
  }
  ASSERT_EQ(d.arrays.size(), s.arrays.size());
  for (const auto& a : s.arrays) {
    const VtkArray& b = d.array(a.name);
    EXPECT_EQ(b.components, a.components) << a.name;
    ASSERT_EQ(b.data.size(), a.data.size()) << a.name;
    for (std::size_t i = 0; i < a.data.size(); ++i)
      EXPECT_TRUE(same_bits(a.data[i], b.data[i])) << a.name << i;
  }
  ASSERT_EQ(d.int_arrays.size(), s.ints.size());
  for (const auto& a : s.ints) EXPECT_EQ(d.int_array(a.name).data, a.data) << a.name;
  EXPECT_EQ(d.array("velocity").components, 3);
  EXPECT_THROW((void)d.array("kind"), IoError);  // an Int32 array is not a Float64 one
  EXPECT_THROW((void)d.int_array("nope"), IoError);
}

TEST_F(VtkTest, HeaderMatchesParaViewExpectations) {
  const Sample s = make_sample(5);
  const fs::path p = dir_ / "h.vtp";
  write_vtp(p, s.points, s.arrays, s.ints);
  const std::string text = read_file(p);
  EXPECT_NE(
      text.find(R"(<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)"),
      std::string::npos);
  EXPECT_NE(text.find(R"(NumberOfPoints="5" NumberOfVerts="5")"), std::string::npos);
  EXPECT_NE(text.find(R"(<DataArray type="Int64" Name="connectivity")"), std::string::npos);
  EXPECT_NE(text.find(R"(<DataArray type="Int32" Name="kind" NumberOfComponents="1" format="binary">)"),
            std::string::npos);
  // The first array's block: base64 of the UInt64 byte count 40 (5 doubles) then the data.
  const std::string count = base64_encode(std::string("\x28\0\0\0\0\0\0\0", 8)).substr(0, 10);
  EXPECT_NE(text.find(R"(Name="pressure" NumberOfComponents="1" format="binary">)" + count),
            std::string::npos);
}

TEST_F(VtkTest, EmptyPointSetRoundTrips) {
  const fs::path p = dir_ / "empty.vtp";
  write_vtp(p, {}, {VtkArray{"pressure", 1, {}}}, {});
  const VtpData d = read_vtp(p);
  EXPECT_EQ(d.num_points, 0u);
  EXPECT_TRUE(d.array("pressure").data.empty());
}

TEST_F(VtkTest, WriterRejectsInconsistentArrays) {
  const std::vector<Vec2> pts(4);
  EXPECT_THROW(write_vtp(dir_ / "x.vtp", pts, {VtkArray{"p", 1, std::vector<double>(3)}}),
               std::invalid_argument);
  EXPECT_THROW(write_vtp(dir_ / "x.vtp", pts, {VtkArray{"p", 2, std::vector<double>(4)}}),
               std::invalid_argument);
  EXPECT_THROW(write_vtp(dir_ / "x.vtp", pts, {VtkArray{"p", 1, std::vector<double>(4)}},
                         {VtkIntArray{"p", 1, std::vector<std::int32_t>(4)}}),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "x.vtp"));
}

TEST_F(VtkTest, EveryTruncationRaisesIoErrorNamingTheFile) {
  const Sample s = make_sample(6);
  const fs::path good = dir_ / "good.vtp", bad = dir_ / "bad.vtp";
  write_vtp(good, s.points, s.arrays, s.ints);
  const std::string text = read_file(good);
  const std::size_t complete = text.rfind("</VTKFile>") + std::string("</VTKFile>").size();
  for (std::size_t len = 0; len < complete; ++len) {
    put(bad, text.substr(0, len));
    try {
      (void)read_vtp(bad);
      ADD_FAILURE() << "no error for a file truncated to " << len << " bytes";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.vtp"), std::string::npos) << e.what();
    }
  }
}

TEST_F(VtkTest, GarbageRaisesIoErrorAndNeverCrashes) {
  const fs::path bad = dir_ / "garbage.vtp";
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::string junk(rng() % 400, '\0');
    for (auto& c : junk) c = static_cast<char>(rng());
    put(bad, junk);
    EXPECT_THROW((void)read_vtp(bad), IoError);
  }
  // Mutating single bytes of a valid file: either a valid read or IoError, nothing else.
  const Sample s = make_sample(5);
  write_vtp(dir_ / "good.vtp", s.points, s.arrays, s.ints);
  const std::string text = read_file(dir_ / "good.vtp");
  const std::string alphabet = "<>/=\"' 0123456789AZaz+&;?!-\n\x01\xff";
  for (int trial = 0; trial < 2000; ++trial) {
    std::string m = text;
    m[rng() % m.size()] = alphabet[rng() % alphabet.size()];
    put(bad, m);
    try {
      (void)read_vtp(bad);
    } catch (const IoError&) {
    }
  }
  // Hostile counts must be rejected before anything is allocated from them.
  std::string huge = text;
  const std::string from = R"(NumberOfPoints="5")";
  huge.replace(huge.find(from), from.size(), R"(NumberOfPoints="18446744073709551615")");
  write_file_atomic(bad, huge);
  EXPECT_THROW((void)read_vtp(bad), IoError);
  EXPECT_THROW((void)read_vtp(dir_ / "missing.vtp"), IoError);
}

TEST_F(VtkTest, ByteCountHeaderIsChecked) {
  // Replace the pressure block with one whose header claims one byte too many.
  const fs::path p = dir_ / "count.vtp";
  write_vtp(p, std::vector<Vec2>(2), {VtkArray{"pressure", 1, {1.0, 2.0}}}, {});
  std::string text = read_file(p);
  const std::string wrong_raw = std::string("\x11\0\0\0\0\0\0\0", 8) + std::string(16, '\0');
  const std::size_t open = text.find(R"(Name="pressure")");
  const std::size_t start = text.find('>', open) + 1, end = text.find("</DataArray>", start);
  text.replace(start, end - start, base64_encode(wrong_raw));
  write_file_atomic(p, text);
  try {
    (void)read_vtp(p);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("pressure"), std::string::npos) << e.what();
  }
}

TEST_F(VtkTest, PvdListsEveryEntryInOrderWithFullPrecision) {
  PvdIndex pvd;
  const double times[] = {0.0, 2.5e-7, 0.1, 1.0 / 3.0, 1e10};
  for (int i = 0; i < 5; ++i) pvd.add(times[i], "particles/step_" + std::to_string(i) + ".vtp");
  const fs::path p = dir_ / "particles.pvd";
  pvd.write(p);
  const std::string text = read_file(p);
  std::size_t pos = 0;
  for (int i = 0; i < 5; ++i) {
    const std::string file = "file=\"particles/step_" + std::to_string(i) + ".vtp\"";
    const std::size_t at = text.find(file, pos);
    ASSERT_NE(at, std::string::npos) << file;
    pos = at;
  }
  EXPECT_NE(text.find(R"(timestep="0.3333333333333333")"), std::string::npos) << text;
  const PvdIndex back = PvdIndex::read(p);
  ASSERT_EQ(back.entries().size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(same_bits(back.entries()[i].time, times[i]));
    EXPECT_EQ(back.entries()[i].file, pvd.entries()[i].file);
  }
  // Rewriting after more snapshots keeps the file whole; resumed runs drop later entries.
  PvdIndex more = back;
  more.drop_after(0.2);
  more.add(0.2, "particles/step_9.vtp");
  more.write(p);
  const PvdIndex again = PvdIndex::read(p);
  ASSERT_EQ(again.entries().size(), 4u);
  EXPECT_EQ(again.entries()[2].file, "particles/step_2.vtp");
  EXPECT_EQ(again.entries()[3].file, "particles/step_9.vtp");
  EXPECT_THROW(pvd.add(std::nan(""), "x.vtp"), std::invalid_argument);
}

// Written by VTK 9.1's vtkXMLPolyDataWriter (binary, no compression, UInt64 headers) from a
// 3-point file of write_vtp: VTK encodes count and data as one base64 block, as we do, and adds
// RangeMin/RangeMax, <InformationKey> children and empty Lines/Strips/Polys.
const char* const kWrittenByVtk = R"vtk(<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <Piece NumberOfPoints="3" NumberOfVerts="3" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="0">
      <PointData>
        <DataArray type="Float64" Name="pressure" format="binary" RangeMin="33333.333333333336" RangeMax="100000">
          GAAAAAAAAAAAAAAAAGr4QAAAAAAAauhAq6qqqqpG4EA=
        </DataArray>
        <DataArray type="Float64" Name="v2" NumberOfComponents="2" format="binary" RangeMin="0" RangeMax="2.8284271247461903">
          MAAAAAAAAAAAAAAAAAAAAAAAAAAAAACAAAAAAAAA8D8AAAAAAADwvwAAAAAAAABAAAAAAAAAAMA=
          <InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
            <Value index="0">
              0
            </Value>
            <Value index="1">
              2.8284271247
            </Value>
          </InformationKey>
        </DataArray>
        <DataArray type="Float64" Name="velocity" NumberOfComponents="3" format="binary" RangeMin="0" RangeMax="4.47213595499958">
          SAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAADwPwAAAAAAAABAAAAAAAAAAAAAAAAAAAAAQAAAAAAAABBAAAAAAAAAAAA=
          <InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
            <Value index="0">
              0
            </Value>
            <Value index="1">
              4.472135955
            </Value>
          </InformationKey>
        </DataArray>
        <DataArray type="Int32" Name="kind" format="binary" RangeMin="-1" RangeMax="1">
          DAAAAAAAAAD/////AAAAAAEAAAA=
        </DataArray>
        <DataArray type="Int32" Name="body" format="binary" RangeMin="7" RangeMax="7">
          DAAAAAAAAAAHAAAABwAAAAcAAAA=
        </DataArray>
      </PointData>
      <CellData>
      </CellData>
      <Points>
        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="binary" RangeMin="0.16666966663966717" RangeMax="0.6666696666599168">
          SAAAAAAAAAAAAAAAAAAAAFVVVVVVVdU/AAAAAAAAAAD8qfHSTWJQP1ZVVVVVVcW/AAAAAAAAAAD8qfHSTWJgP1ZVVVVVVeW/AAAAAAAAAAA=
          <InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
            <Value index="0">
              0.16666966664
            </Value>
            <Value index="1">
              0.66666966666
            </Value>
          </InformationKey>
        </DataArray>
      </Points>
      <Verts>
        <DataArray type="Int64" Name="connectivity" format="binary" RangeMin="0" RangeMax="2">
          GAAAAAAAAAAAAAAAAAAAAAEAAAAAAAAAAgAAAAAAAAA=
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="binary" RangeMin="1" RangeMax="3">
          GAAAAAAAAAABAAAAAAAAAAIAAAAAAAAAAwAAAAAAAAA=
        </DataArray>
      </Verts>
      <Lines>
        <DataArray type="Int64" Name="connectivity" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
      </Lines>
      <Strips>
        <DataArray type="Int64" Name="connectivity" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
      </Strips>
      <Polys>
        <DataArray type="Int64" Name="connectivity" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="binary" RangeMin="1e+299" RangeMax="-1e+299">
          AAAAAAAAAAA=
        </DataArray>
      </Polys>
    </Piece>
  </PolyData>
</VTKFile>
)vtk";

TEST_F(VtkTest, ReadsAFileWrittenByVtk) {
  const fs::path p = dir_ / "by_vtk.vtp";
  write_file_atomic(p, kWrittenByVtk);
  const VtpData d = read_vtp(p);
  ASSERT_EQ(d.num_points, 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(d.points[i].x, 0.001 * i);
    EXPECT_EQ(d.points[i].y, -0.5 * i + 1.0 / 3.0);
    EXPECT_EQ(d.array("pressure").data[i], 1e5 / (i + 1));
    EXPECT_EQ(d.array("velocity").data[3 * i + 1], 2.0 * i);
    EXPECT_EQ(d.int_array("kind").data[i], i % 3 - 1);
    EXPECT_EQ(d.int_array("body").data[i], 7);
  }
  EXPECT_EQ(d.array("v2").components, 2);
}
