#include "particula/run/checkpoint.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>

#include "particula/io/atomic_file.hpp"
#include "particula/io/binary.hpp"

namespace particula {

// If one of these fails, a field was added to (or removed from) the struct without updating its
// field list in include/particula/run/checkpoint.hpp: add the `ar(...)` line there, set the
// field count and the size here, and bump kCheckpointVersion.
static_assert(checkpoint_detail::aggregate_field_count<Particles>() == kParticlesFields,
              "Particles changed: update particles_fields() and kParticlesFields in run/checkpoint.hpp");
static_assert(checkpoint_detail::aggregate_field_count<RigidGroup>() == kRigidGroupFields,
              "RigidGroup changed: update rigid_group_fields() and kRigidGroupFields in run/checkpoint.hpp");
static_assert(checkpoint_detail::aggregate_field_count<SolverCounters>() == kSolverCountersFields,
              "SolverCounters changed: update solver_counters_fields() and kSolverCountersFields");
static_assert(sizeof(Particles) == sizeof(std::size_t) + (kParticlesFields - 1) * sizeof(std::vector<real>),
              "Particles changed: update particles_fields() and kParticlesFields in run/checkpoint.hpp");
static_assert(sizeof(RigidGroup) == 280,
              "RigidGroup changed: update rigid_group_fields(), kRigidGroupFields and this size "
              "(run/checkpoint.hpp), then bump kCheckpointVersion");
static_assert(sizeof(SolverCounters) == kSolverCountersFields * sizeof(std::int64_t),
              "SolverCounters changed: update solver_counters_fields() and kSolverCountersFields");

namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'C', 'L', 'C', 'K', 'P'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8;
constexpr std::size_t kTrailerBytes = 8;

template <class T>
T load(std::string_view bytes, std::size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

template <class T>
void store(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// Writes or reads the payload; `C` is `const Checkpoint` for writing, `Checkpoint` for reading.
template <class Ar, class C>
void payload_fields(Ar& ar, C& c) {
  ar(c.case_toml);
  ar(c.time);
  ar(c.step);
  solver_counters_fields(ar, c.counters);
  particles_fields(ar, c.particles);
}

void check_consistency(const Checkpoint& c, const std::string& what) {
  auto fail = [&](const std::string& why) { throw io::IoError(fmt::format("{}: inconsistent content ({})", what, why)); };
  const Particles& P = c.particles;
  const std::size_t n = P.x.size(), nb = P.n_boundary;
  if (!std::isfinite(c.time) || c.step < 0) fail("time or step");
  if (nb > n) fail("more boundary particles than particles");
  for (std::size_t size : {P.v.size(), P.rho.size(), P.p.size(), P.m.size(), P.kind.size(), P.group.size(), P.id.size()})
    if (size != n) fail("per-particle arrays of different sizes");
  for (std::size_t size : {P.local.size(), P.normal_local.size(), P.ds.size(), P.acc.size(), P.normal.size(), P.source.size()})
    if (size != nb) fail("boundary arrays of the wrong size");
  const auto n_groups = static_cast<std::int64_t>(c.groups.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (static_cast<std::uint8_t>(P.kind[i]) > static_cast<std::uint8_t>(Kind::Dummy)) fail("particle kind");
    if (P.group[i] < -1 || P.group[i] >= n_groups) fail("particle group index");
  }
  for (std::size_t i = 0; i < nb; ++i)
    if (P.source[i] < -1 || P.source[i] >= static_cast<std::int64_t>(nb)) fail("dummy source index");
  for (const RigidGroup& g : c.groups) {
    if (g.first > nb || g.count > nb - g.first) fail("rigid group particle range");
    if (g.motion != Motion::Fixed && g.motion != Motion::Prescribed && g.motion != Motion::Free) fail("group motion");
  }
}

}  // namespace

std::filesystem::path checkpoint_path(const std::filesystem::path& run_dir) {
  return run_dir / "checkpoint" / "state.bin";
}

std::string encode_checkpoint(const Checkpoint& c) {
  return encode_checkpoint(
      CheckpointView{c.case_toml, c.time, c.step, c.counters, c.marks, c.particles, c.groups});
}

std::string encode_checkpoint(const CheckpointView& c) {
  io::BinaryWriter ar;
  payload_fields(ar, c);
  ar(static_cast<std::uint64_t>(c.groups.size()));
  for (const RigidGroup& g : c.groups) rigid_group_fields(ar, g);
  ar(static_cast<std::uint64_t>(c.marks.size()));
  for (const OutputMark& m : c.marks) {
    ar(m.stream);
    ar(m.last_scheduled);
  }
  const std::string payload = ar.take();

  std::string out;
  out.reserve(kHeaderBytes + payload.size() + kTrailerBytes);
  out.append(kMagic, sizeof kMagic);
  store(out, kCheckpointVersion);
  store(out, kByteOrderMark);
  store(out, static_cast<std::uint64_t>(payload.size()));
  out += payload;
  store(out, io::fnv1a64(payload));
  return out;
}

Checkpoint decode_checkpoint(std::string_view bytes, const std::filesystem::path& source) {
  const std::string what = fmt::format("checkpoint '{}'", source.string());
  auto fail = [&](const std::string& why) { throw io::IoError(fmt::format("{}: {}", what, why)); };
  const std::string_view magic(kMagic, sizeof kMagic);
  if (bytes.size() < magic.size() && magic.substr(0, bytes.size()) == bytes)
    fail(fmt::format("truncated ({} bytes)", bytes.size()));
  if (bytes.size() < magic.size() || bytes.substr(0, magic.size()) != magic)
    fail("not a particula checkpoint (wrong magic number)");
  if (bytes.size() < kHeaderBytes) fail(fmt::format("truncated ({} bytes, the header alone has {})", bytes.size(), kHeaderBytes));
  const auto version = load<std::uint32_t>(bytes, 8);
  if (version != kCheckpointVersion)
    fail(fmt::format("format version {}, but this particula reads version {} (resume it with the particula "
                     "that wrote it)",
                     version, kCheckpointVersion));
  if (load<std::uint32_t>(bytes, 12) != kByteOrderMark) fail("written on a machine with another byte order");
  const auto payload_size = load<std::uint64_t>(bytes, 16);
  const std::size_t available = bytes.size() - kHeaderBytes;
  if (available < kTrailerBytes || payload_size > available - kTrailerBytes)
    fail(fmt::format("truncated ({} bytes; the header announces a payload of {} bytes)", bytes.size(), payload_size));
  if (payload_size != available - kTrailerBytes)
    fail(fmt::format("corrupted ({} bytes after the end of the data)", available - kTrailerBytes - payload_size));
  const std::string_view payload = bytes.substr(kHeaderBytes, payload_size);
  if (load<std::uint64_t>(bytes, kHeaderBytes + payload_size) != io::fnv1a64(payload))
    fail("checksum mismatch (the file is corrupted)");

  Checkpoint c;
  io::BinaryReader ar(payload, what);
  payload_fields(ar, c);
  c.groups.resize(ar.read_size(1));
  for (RigidGroup& g : c.groups) rigid_group_fields(ar, g);
  c.marks.resize(ar.read_size(1));
  for (OutputMark& m : c.marks) {
    ar(m.stream);
    ar(m.last_scheduled);
  }
  if (ar.remaining() != 0) fail("corrupted (unexpected data after the last field)");
  check_consistency(c, what);
  return c;
}

void write_checkpoint(const std::filesystem::path& file, const Checkpoint& c) {
  write_checkpoint(file, CheckpointView{c.case_toml, c.time, c.step, c.counters, c.marks, c.particles, c.groups});
}

void write_checkpoint(const std::filesystem::path& file, const CheckpointView& c) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) throw io::IoError(fmt::format("cannot create '{}': {}", file.parent_path().string(), ec.message()));
  io::write_file_atomic(file, encode_checkpoint(c));
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  return decode_checkpoint(io::read_file(file), file);
}

}  // namespace particula
