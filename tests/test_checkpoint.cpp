// Checkpoint files: every field survives a round trip, the field lists cover every member of
// Particles, RigidGroup and SolverCounters, and damaged files are refused with a message
// naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <filesystem>
#include <string>
#include <vector>

#include "particula/io/atomic_file.hpp"
#include "particula/io/binary.hpp"
#include "particula/run/checkpoint.hpp"

using namespace particula;
namespace fs = std::filesystem;

// If one of these fails to compile, a member was added to or removed from the struct: add its
// line to the field list in include/particula/run/checkpoint.hpp, update the count there (and
// the size in src/run/checkpoint.cpp), and bump kCheckpointVersion.
static_assert(checkpoint_detail::aggregate_field_count<Particles>() == kParticlesFields);
static_assert(checkpoint_detail::aggregate_field_count<RigidGroup>() == kRigidGroupFields);
static_assert(checkpoint_detail::aggregate_field_count<SolverCounters>() == kSolverCountersFields);

namespace {

/// Records the address range of every field a field list visits.
struct AddressArchive {
  std::vector<std::pair<const char*, std::size_t>> ranges;
  template <class T>
  void operator()(const T& v) {
    ranges.emplace_back(reinterpret_cast<const char*>(&v), sizeof(T));
  }
};

/// Checks that a field list visits `expected` distinct, non-overlapping members of `obj`.
template <class T>
void expect_covers(const AddressArchive& ar, const T& obj, std::size_t expected) {
  EXPECT_EQ(ar.ranges.size(), expected);
  auto r = ar.ranges;
  std::sort(r.begin(), r.end());
  const char* lo = reinterpret_cast<const char*>(&obj);
  for (std::size_t k = 0; k < r.size(); ++k) {
    EXPECT_GE(r[k].first, lo);
    EXPECT_LE(r[k].first + r[k].second, lo + sizeof(T));
    if (k > 0) {
      EXPECT_GE(r[k].first, r[k - 1].first + r[k - 1].second) << "a field is visited twice";
    }
  }
}

Checkpoint sample() {
  Checkpoint c;
  c.case_toml = "name = \"sample\"\n# every byte \x01\xff survives\n";
  c.case_hash = 0x0123456789abcdefull;
  c.time = 0.123456789012345;
  c.step = 987654321;
  c.counters = {1, 2, 3, 4};
  c.marks = {{"bodies", 0.1}, {"snapshots", -std::numeric_limits<real>::infinity()}, {"probe:profile", 0.09}};
  // Boundary block: a wall group of two surface particles [0, 2), then a body group [2, 4) with a
  // surface particle and a dummy copying it; three fluid particles follow.
  Particles& P = c.particles;
  const std::size_t n = 7, nb = 4;
  P.resize(n);
  P.resize_boundary(nb);
  for (std::size_t i = 0; i < n; ++i) {
    P.x[i] = {0.1 * i, -0.2 * i};
    P.v[i] = {1e-300 * i, std::nextafter(1.0, 2.0) * i};
    P.rho[i] = 1000 + i;
    P.p[i] = -3.5 * i;
    P.m[i] = 1e-6 * (i + 1);
    P.kind[i] = i < nb ? (i == 3 ? Kind::Dummy : Kind::Boundary) : Kind::Fluid;
    P.group[i] = i < nb ? static_cast<std::int32_t>(i / 2) : -1;
    P.id[i] = static_cast<std::int64_t>(n - 1 - i);
  }
  for (std::size_t i = 0; i < nb; ++i) {
    P.local[i] = {2.0 * i, 3.0 * i};
    P.normal_local[i] = {0, 1};
    P.ds[i] = 0.5 + i;
    P.acc[i] = {-1.0 * i, 4.0};
    P.normal[i] = {1, 0};
    P.source[i] = i == 3 ? 2 : -1;
  }
  RigidGroup a;
  a.name = "lower wall";
  a.motion = Motion::Prescribed;
  a.is_wall = true;
  a.pos = {1, 2};
  a.vel = {3, 4};
  a.acc = {5, 6};
  a.angle = 7;
  a.omega = 8;
  a.alpha = 9;
  a.pos0 = {10, 11};
  a.angle0 = 12;
  a.first = 0;
  a.count = 2;
  a.force_pressure = {13, 14};
  a.force_viscous = {15, 16};
  a.torque = 17;
  RigidGroup b = a;
  b.name = "disc";
  b.motion = Motion::Free;
  b.is_wall = false;
  b.body = 0;
  b.mass = 0.5;
  b.inertia = 0.25;
  b.area = 1e-4;
  b.first = 2;
  b.count = 2;
  b.torque = -0.0;
  c.groups = {a, b};
  return c;
}

/// The bytes of every field of a checkpoint, through the field lists (for comparisons).
std::string field_bytes(const Checkpoint& c) {
  io::BinaryWriter w;
  particles_fields(w, c.particles);
  for (const auto& g : c.groups) rigid_group_fields(w, g);
  solver_counters_fields(w, c.counters);
  return w.take();
}

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("particula_ckpt_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

/// Expects decoding `bytes` to fail with a message naming the file and containing `why`.
void expect_refused(const std::string& bytes, const std::string& why) {
  const fs::path name = "run/checkpoint/state.bin";
  try {
    decode_checkpoint(bytes, name);
    ADD_FAILURE() << "accepted a damaged checkpoint (expected: " << why << ")";
  } catch (const io::IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(name.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(why), std::string::npos) << msg;
  }
}

}  // namespace

TEST(CheckpointFields, ListsVisitEveryMemberOnce) {
  Particles P;
  AddressArchive ap;
  particles_fields(ap, P);
  expect_covers(ap, P, kParticlesFields);
  RigidGroup g;
  AddressArchive ag;
  rigid_group_fields(ag, g);
  expect_covers(ag, g, kRigidGroupFields);
  SolverCounters s;
  AddressArchive as;
  solver_counters_fields(as, s);
  expect_covers(as, s, kSolverCountersFields);
}

TEST(Checkpoint, RoundTripKeepsEveryFieldBitwise) {
  const Checkpoint c = sample();
  const fs::path file = scratch() / "checkpoint" / "state.bin";
  write_checkpoint(file, c);
  const Checkpoint r = read_checkpoint(file);
  EXPECT_EQ(r.case_toml, c.case_toml);
  EXPECT_EQ(r.case_hash, c.case_hash);
  EXPECT_EQ(r.time, c.time);
  EXPECT_EQ(r.step, c.step);
  EXPECT_EQ(r.counters.wall_pressure_kept, 3);
  ASSERT_EQ(r.marks.size(), c.marks.size());
  for (std::size_t k = 0; k < c.marks.size(); ++k) {
    EXPECT_EQ(r.marks[k].stream, c.marks[k].stream);
    EXPECT_EQ(r.marks[k].last_scheduled, c.marks[k].last_scheduled);
  }
  EXPECT_EQ(r.particles.n_boundary, 4u);
  EXPECT_EQ(r.particles.kind[3], Kind::Dummy);
  EXPECT_EQ(r.particles.source[3], 2);
  EXPECT_EQ(r.particles.v[3].y, std::nextafter(1.0, 2.0) * 3);
  ASSERT_EQ(r.groups.size(), 2u);
  EXPECT_EQ(r.groups[0].name, "lower wall");
  EXPECT_EQ(r.groups[1].motion, Motion::Free);
  EXPECT_FALSE(r.groups[1].is_wall);
  EXPECT_EQ(r.groups[0].pos0.y, 11);
  EXPECT_TRUE(std::signbit(r.groups[1].torque));
  EXPECT_EQ(field_bytes(r), field_bytes(c));
  EXPECT_EQ(encode_checkpoint(r), encode_checkpoint(c));
}

TEST(Checkpoint, WrongMagicIsRefused) {
  std::string bytes = encode_checkpoint(sample());
  bytes[0] = 'X';
  expect_refused(bytes, "not a particula checkpoint");
  expect_refused("hello, world: not a checkpoint at all", "not a particula checkpoint");
}

TEST(Checkpoint, OtherFormatVersionIsRefused) {
  std::string bytes = encode_checkpoint(sample());
  const std::uint32_t other = kCheckpointVersion + 1;
  std::memcpy(bytes.data() + 8, &other, sizeof other);
  expect_refused(bytes, "format version");
}

TEST(Checkpoint, FlippedByteIsRefusedByTheChecksum) {
  const std::string good = encode_checkpoint(sample());
  // Every byte of the payload and of the checksum itself.
  for (std::size_t k = 24; k < good.size(); ++k) {
    std::string bytes = good;
    bytes[k] = static_cast<char>(bytes[k] ^ 0x10);
    expect_refused(bytes, "checksum mismatch");
  }
}

TEST(Checkpoint, TruncatedFileIsRefused) {
  const std::string good = encode_checkpoint(sample());
  for (std::size_t len = 0; len < good.size(); ++len) {
    const std::string bytes = good.substr(0, len);
    expect_refused(bytes, "truncated");
  }
  expect_refused(good + "x", "corrupted");
}

TEST(Checkpoint, InconsistentArraysAreRefused) {
  Checkpoint c = sample();
  c.particles.rho.pop_back();
  expect_refused(encode_checkpoint(c), "inconsistent");
  c = sample();
  c.groups[1].count = 5;
  expect_refused(encode_checkpoint(c), "inconsistent");
}

TEST(Checkpoint, MissingFileNamesIt) {
  const fs::path file = scratch() / "nowhere" / "state.bin";
  try {
    read_checkpoint(file);
    FAIL();
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(BinaryArchive, ReaderChecksBounds) {
  io::BinaryWriter w;
  w(std::string("abc"));
  w(std::vector<double>{1, 2, 3});
  w(true);
  const std::string bytes = w.take();
  {
    io::BinaryReader r(bytes, "test");
    std::string s;
    std::vector<double> v;
    bool b = false;
    r(s);
    r(v);
    r(b);
    EXPECT_EQ(s, "abc");
    EXPECT_EQ(v.size(), 3u);
    EXPECT_TRUE(b);
    EXPECT_EQ(r.remaining(), 0u);
    EXPECT_THROW(r(b), io::IoError);
  }
  {
    std::string huge = bytes;
    const std::uint64_t n = 1ull << 60;
    std::memcpy(huge.data(), &n, sizeof n);
    io::BinaryReader r(huge, "test");
    std::string s;
    EXPECT_THROW(r(s), io::IoError);  // no 2^60-byte allocation
  }
  EXPECT_EQ(io::fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(io::fnv1a64("a"), 0xaf63dc4c8601ec8cull);
}
