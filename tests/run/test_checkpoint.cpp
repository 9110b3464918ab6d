// Checkpoint files: every field survives a round trip, the field lists cover every member of
// Particles, RigidGroup and SolverCounters, damaged files are refused with a message naming the
// file, and tampered content with a valid checksum is refused or, when it fits together, runs
// without harm (tests/checkpoint_tamper.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "checkpoint_tamper.hpp"
#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/binary.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/scene/scene.hpp"
#include "scratch_dir.hpp"

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
  a.force_damping = {-1e-9, 2.5e-10};
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
  P.next_id = 9;  // ids 0..6 in use, 7 and 8 were removed (open boundaries)
  c.open_flux = {{0.5, 0.25, 3, 2}, {1e-300, 0, 0, 7}};
  return c;
}

/// The bytes of every field of a checkpoint, through the field lists (for comparisons).
std::string field_bytes(const Checkpoint& c) {
  io::BinaryWriter w;
  particles_fields(w, c.particles);
  for (const auto& g : c.groups) rigid_group_fields(w, g);
  solver_counters_fields(w, c.counters);
  for (const auto& f : c.open_flux) open_flux_fields(w, f);
  return w.take();
}

fs::path scratch() {
  static const fs::path d = test_scratch::scratch_dir("ckpt");
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
  OpenFlux f;
  AddressArchive af;
  open_flux_fields(af, f);
  expect_covers(af, f, kOpenFluxFields);
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
  EXPECT_EQ(r.particles.next_id, 9);
  ASSERT_EQ(r.open_flux.size(), 2u);
  EXPECT_EQ(r.open_flux[0].backflow_mass, 0.25);
  EXPECT_EQ(r.open_flux[1].deleted, 7);
  EXPECT_EQ(field_bytes(r), field_bytes(c));
  EXPECT_EQ(encode_checkpoint(r), encode_checkpoint(c));
}

TEST(Checkpoint, ABareFileNameIsWrittenIntoTheWorkingDirectory) {
  const fs::path dir = scratch() / "bare";
  fs::create_directories(dir);
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  try {
    write_checkpoint("state.bin", sample());  // no parent directory to create
  } catch (...) {
    fs::current_path(before);
    throw;
  }
  fs::current_path(before);
  EXPECT_EQ(encode_checkpoint(read_checkpoint(dir / "state.bin")), encode_checkpoint(sample()));
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

// ---- tampering -----------------------------------------------------------------------------------

namespace {

/// The state of tamper::kCase after a few steps, as `particula run` would checkpoint it.
Checkpoint tamper_checkpoint() {
  const Case c = load_case_text(tamper::kCase, "tamper.toml");
  Scene scene = build_scene(c);
  Solver solver(scene.params, scene.domain, std::move(scene.particles), std::move(scene.groups));
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(solver.step().has_value());
  Checkpoint k;
  k.case_toml = resolved_case_toml(c);
  k.case_hash = case_identity_hash(k.case_toml);
  k.time = solver.time();
  k.step = solver.step_count();
  k.counters = solver.counters();
  k.marks = {{"bodies", 0.0}, {"snapshots", 0.0}};
  k.particles = solver.particles();
  k.groups = solver.groups();
  return k;
}

/// How the checks of `resume` treat a checkpoint's bytes.
enum class Verdict { RefusedAtDecode, RefusedCase, RefusedAgainstCase, Accepted };

/// Decodes `bytes`, loads its case and checks the one against the other, as `resume` does; an
/// accepted checkpoint is then run for a step, which must not crash (the sanitizer build checks
/// memory) or throw.
Verdict judge(const std::string& bytes, std::string* why = nullptr) {
  Checkpoint k;
  try {
    k = decode_checkpoint(bytes, "state.bin");
  } catch (const io::IoError& e) {
    if (why) *why = e.what();
    return Verdict::RefusedAtDecode;
  }
  Case c;
  try {
    c = load_case_text(k.case_toml, "state.bin");
  } catch (const CaseError& e) {
    if (why) *why = e.what();
    return Verdict::RefusedCase;
  }
  try {
    check_checkpoint_fits_case(k, c, "state.bin");
  } catch (const io::IoError& e) {
    if (why) *why = e.what();
    return Verdict::RefusedAgainstCase;
  }
  const Domain domain{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  Solver solver(physics_params(c), domain, std::move(k.particles), std::move(k.groups), SolverStart::Restart,
                k.time, k.step);
  (void)solver.step();  // a numerical failure (exit 3) is a fine outcome; a crash is not
  return Verdict::Accepted;
}

/// The file's checksum recomputed after its payload was edited.
void reseal(std::string& bytes) {
  const std::size_t header = 24, trailer = 8;
  const std::uint64_t sum =
      io::fnv1a64(std::string_view(bytes).substr(header, bytes.size() - header - trailer));
  std::memcpy(bytes.data() + bytes.size() - trailer, &sum, sizeof sum);
}

}  // namespace

TEST(CheckpointTampering, EveryEditedIndexCountOrValueIsRefused) {
  const Checkpoint good = tamper_checkpoint();
  ASSERT_EQ(judge(encode_checkpoint(good)), Verdict::Accepted);
  int refused = 0, checked = 0;
  for (const auto& t : tamper::structured()) {
    if (t.needs_run_directory) continue;  // tests/run/test_resume.cpp: the identity is checked against the marker
    Checkpoint k = good;
    t.apply(k);
    std::string why;
    const Verdict v = judge(encode_checkpoint(k), &why);
    ++checked;
    if (v != Verdict::Accepted) ++refused;
    EXPECT_NE(v, Verdict::Accepted) << t.name;
    EXPECT_NE(why.find("state.bin"), std::string::npos) << t.name << ": " << why;
  }
  std::printf("tampered fields (valid checksum): %d edits, %d refused\n", checked, refused);
  EXPECT_GE(checked, 45);
}

TEST(CheckpointTampering, RandomBytesWithAValidChecksumAreRefusedOrRunSafely) {
  const std::string good = encode_checkpoint(tamper_checkpoint());
  SplitMix64 rng(15);
  int counts[4] = {0, 0, 0, 0};
  const int mutants = 1000;
  const std::size_t payload = good.size() - 24 - 8;
  for (int m = 0; m < mutants; ++m) {
    std::string bytes = good;
    // One to three bytes set at random places of the payload, half of the edits in its first
    // tenth (the case text, time, counters and the index-heavy start of the arrays).
    const int edits = 1 + static_cast<int>(rng.next() % 3);
    for (int e = 0; e < edits; ++e) {
      const std::size_t span = rng.next() % 2 ? payload : payload / 10;
      bytes[24 + rng.next() % span] = static_cast<char>(rng.next() & 0xff);
    }
    reseal(bytes);
    ++counts[static_cast<int>(judge(bytes))];
  }
  std::printf(
      "random payload edits (valid checksum): %d mutants: %d refused at decode, %d with a broken case, %d "
      "refused against the case, %d accepted and stepped without a crash\n",
      mutants, counts[0], counts[1], counts[2], counts[3]);
  EXPECT_EQ(counts[0] + counts[1] + counts[2] + counts[3], mutants);
  EXPECT_GT(counts[0], 0);
}
