#include "particula/run/checkpoint.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>

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
static_assert(sizeof(Particles) == sizeof(std::size_t) + sizeof(std::int64_t) +
                                       (kParticlesFields - 2) * sizeof(std::vector<real>),
              "Particles changed: update particles_fields() and kParticlesFields in run/checkpoint.hpp");
static_assert(sizeof(RigidGroup) == 312,
              "RigidGroup changed: update rigid_group_fields(), kRigidGroupFields and this size "
              "(run/checkpoint.hpp), then bump kCheckpointVersion");
static_assert(sizeof(SolverCounters) == kSolverCountersFields * sizeof(std::int64_t),
              "SolverCounters changed: update solver_counters_fields() and kSolverCountersFields");
static_assert(checkpoint_detail::aggregate_field_count<OpenFlux>() == kOpenFluxFields &&
                  sizeof(OpenFlux) == kOpenFluxFields * 8,
              "OpenFlux changed: update open_flux_fields() and kOpenFluxFields in run/checkpoint.hpp");
static_assert(
    checkpoint_detail::aggregate_field_count<LoadBandState>() == kLoadBandStateFields,
    "LoadBandState changed: update load_band_fields() and kLoadBandStateFields in run/checkpoint.hpp");

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
  ar(c.case_hash);
  ar(c.time);
  ar(c.step);
  solver_counters_fields(ar, c.counters);
  particles_fields(ar, c.particles);
}

bool finite(real v) { return std::isfinite(v); }
bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

using FailWith = std::function<void(const std::string&)>;

/// Time, step and guard counters in range; the per-particle and boundary arrays of one size.
void check_sizes(const Checkpoint& c, const FailWith& fail) {
  const Particles& P = c.particles;
  const std::size_t n = P.x.size(), nb = P.n_boundary;
  if (!std::isfinite(c.time) || c.time < 0 || c.step < 0) fail("time or step");
  for (std::int64_t counter :
       {c.counters.singular_B, c.counters.singular_Bhat, c.counters.wall_pressure_kept,
        c.counters.wall_pressure_extrapolated, c.counters.normal_fallback, c.counters.surface_pushed,
        c.counters.gap_squeezed, c.counters.isolated_left_out, c.counters.open_fit_fallback,
        c.counters.sparse_support, c.counters.wall_pressure_void})
    if (counter < 0) fail("negative guard counter");
  if (nb > n) fail("more boundary particles than particles");
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) fail("too many particles");
  for (std::size_t size :
       {P.v.size(), P.rho.size(), P.p.size(), P.m.size(), P.kind.size(), P.group.size(), P.id.size()})
    if (size != n) fail("per-particle arrays of different sizes");
  for (std::size_t size :
       {P.local.size(), P.normal_local.size(), P.ds.size(), P.acc.size(), P.normal.size(), P.wedge.size(),
        P.source.size()})
    if (size != nb) fail("boundary arrays of the wrong size");
}

/// Rigid groups: contiguous ranges covering the boundary block in order, walls first, bodies
/// numbered in order.
void check_groups(const Checkpoint& c, const FailWith& fail) {
  const std::size_t nb = c.particles.n_boundary;
  const std::size_t n_groups = c.groups.size();
  std::size_t next_first = 0;
  for (std::size_t k = 0; k < n_groups; ++k) {
    const RigidGroup& g = c.groups[k];
    if (g.motion != Motion::Fixed && g.motion != Motion::Prescribed && g.motion != Motion::Free)
      fail("group motion");
    if (g.first != next_first || g.count > nb - std::min(g.first, nb))
      fail(fmt::format("particle range of rigid group {}", k));
    next_first = g.first + g.count;
    if (g.is_wall ? g.body != -1 : g.body < 0) fail(fmt::format("body index of rigid group {}", k));
    if (g.is_wall && g.motion == Motion::Free) fail(fmt::format("free wall (rigid group {})", k));
    if (g.removed ? g.is_wall || g.count != 0 || g.removed_at < 0 ||
                        static_cast<std::size_t>(g.removed_at) >= c.open_flux.size()
                  : g.removed_at != -1)
      fail(fmt::format("removal of rigid group {}", k));
  }
  if (next_first != nb) fail("the rigid groups do not cover the boundary particles");
  for (std::size_t k = 0; k + 1 < n_groups; ++k)
    if (!c.groups[k].is_wall && c.groups[k + 1].is_wall) fail("a wall group after a body group");
  for (std::size_t k = 0; k < n_groups; ++k)
    if (!c.groups[k].is_wall) {
      std::size_t walls = 0;
      while (walls < n_groups && c.groups[walls].is_wall) ++walls;
      if (c.groups[k].body != static_cast<int>(k - walls))
        fail(fmt::format("body index of rigid group {}", k));
    }
}

/// Particles: kinds and groups by block, dummy sources within their group, ids unique and
/// below next_id (particles created at inlets take new ids; those removed at outlets leave gaps).
void check_particles(const Checkpoint& c, const FailWith& fail) {
  const Particles& P = c.particles;
  const std::size_t n = P.x.size(), nb = P.n_boundary;
  const std::size_t n_groups = c.groups.size();
  if (P.next_id < static_cast<std::int64_t>(n)) fail("next particle id below the particle count");
  for (std::size_t i = 0; i < n; ++i) {
    const auto kind = static_cast<std::uint8_t>(P.kind[i]);
    if (kind > static_cast<std::uint8_t>(Kind::Outlet)) fail(fmt::format("kind of particle {}", i));
    if (i < nb) {
      if (P.kind[i] != Kind::Boundary && P.kind[i] != Kind::Dummy)
        fail(fmt::format("fluid or buffer particle {} in the boundary block", i));
      const std::int32_t g = P.group[i];
      if (g < 0 || static_cast<std::size_t>(g) >= n_groups)
        fail(fmt::format("group index of particle {}", i));
      const RigidGroup& G = c.groups[static_cast<std::size_t>(g)];
      if (i < G.first || i >= G.first + G.count)
        fail(fmt::format("particle {} outside the range of its group", i));
      const std::int32_t s = P.source[i];
      if (P.kind[i] == Kind::Dummy) {
        if (s < 0 || static_cast<std::size_t>(s) >= nb ||
            P.kind[static_cast<std::size_t>(s)] != Kind::Boundary ||
            P.group[static_cast<std::size_t>(s)] != g)
          fail(fmt::format("source of dummy particle {}", i));
      } else if (s != -1) {
        fail(fmt::format("source of surface particle {}", i));
      }
    } else {
      if (P.kind[i] == Kind::Boundary || P.kind[i] == Kind::Dummy)
        fail(fmt::format("boundary particle {} in the fluid block", i));
      if (P.group[i] != -1) fail(fmt::format("group index of fluid particle {}", i));
    }
    if (P.id[i] < 0 || P.id[i] >= P.next_id)
      fail(fmt::format("id of particle {} (ids must be 0 .. next_id-1, each once)", i));
  }
  std::vector<std::int64_t> ids(P.id);
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) fail("two particles with one id");
}

/// Open-boundary fluxes non-negative, the kept band's build state for every particle and every
/// group or for none, output marks not after the checkpoint's time.
void check_fluxes_band_marks(const Checkpoint& c, const FailWith& fail) {
  for (const OpenFlux& f : c.open_flux)
    if (!std::isfinite(f.mass) || f.mass < 0 || !std::isfinite(f.backflow_mass) || f.backflow_mass < 0 ||
        f.created < 0 || f.deleted < 0 || f.bodies_removed < 0 || !std::isfinite(f.body_fill_mass) ||
        f.body_fill_mass < 0)
      fail("open-boundary flux");

  const LoadBandState& band = c.load_band;
  if ((band.held() || !band.pos.empty() || !band.angle.empty()) &&
      (band.x.size() != c.particles.x.size() || band.pos.size() != c.groups.size() ||
       band.angle.size() != c.groups.size()))
    fail("kept load band of the wrong size");

  for (const OutputMark& m : c.marks)
    if (std::isnan(m.last_scheduled) || m.last_scheduled == std::numeric_limits<real>::infinity() ||
        m.last_scheduled > c.time * (1 + 1e-9) + 1e-300)
      fail(fmt::format("output mark of '{}'", m.stream));
}

/// Every index and count of a checkpoint checked against the others, so that nothing the solver
/// indexes with them can point outside its arrays, and every value it computes with is finite.
void check_consistency(const Checkpoint& c, const std::string& what) {
  const FailWith fail = [&](const std::string& why) {
    throw io::IoError(fmt::format("{}: inconsistent content ({})", what, why));
  };
  check_sizes(c, fail);
  check_groups(c, fail);
  check_particles(c, fail);
  check_fluxes_band_marks(c, fail);
}

/// The values a resumed solver computes with: finite, positive densities and masses, bodies with
/// mass. (A diagnostic checkpoint of a numerical failure may hold anything else: it is read for
/// inspection, never resumed.)
void check_values(const Checkpoint& c, const FailWith& fail) {
  const Particles& P = c.particles;
  const std::size_t n = P.size(), nb = P.n_boundary;
  for (std::size_t k = 0; k < c.groups.size(); ++k) {
    const RigidGroup& g = c.groups[k];
    for (Vec2 v : {g.pos, g.vel, g.acc, g.pos0, g.force_pressure, g.force_viscous, g.force_collision,
                   g.force_damping, g.vel_n})
      if (!finite(v)) fail(fmt::format("non-finite vector of rigid group {}", k));
    for (real v : {g.angle, g.omega, g.alpha, g.angle0, g.mass, g.inertia, g.area, g.torque,
                   g.torque_collision, g.contact_speed, g.omega_n, g.removed_time})
      if (!finite(v)) fail(fmt::format("non-finite value of rigid group {}", k));
    if (g.mass < 0 || g.inertia < 0 || g.area < 0 || g.contact_speed < 0)
      fail(fmt::format("negative mass property of rigid group {}", k));
    if (g.motion == Motion::Free && !(g.mass > 0 && g.inertia > 0 && g.area > 0))
      fail(fmt::format("free body without mass (rigid group {})", k));
  }
  const LoadBandState& band = c.load_band;
  if (!std::all_of(band.x.begin(), band.x.end(), [](Vec2 v) { return finite(v); }) ||
      !std::all_of(band.pos.begin(), band.pos.end(), [](Vec2 v) { return finite(v); }) ||
      !std::all_of(band.angle.begin(), band.angle.end(), [](real v) { return finite(v); }))
    fail("non-finite kept load band");
  for (std::size_t i = 0; i < n; ++i) {
    if (i < nb && (!finite(P.local[i]) || !finite(P.normal_local[i]) || !finite(P.normal[i]) ||
                   !finite(P.acc[i]) || !std::isfinite(P.ds[i]) || P.ds[i] < 0 || !(P.wedge[i] >= 0) ||
                   !(P.wedge[i] < 0.5 * M_PI)))
      fail(fmt::format("boundary data of particle {}", i));
    if (!finite(P.x[i]) || !finite(P.v[i]) || !std::isfinite(P.p[i]))
      fail(fmt::format("non-finite state of particle {}", i));
    if (!(P.rho[i] > 0) || !std::isfinite(P.rho[i])) fail(fmt::format("density of particle {}", i));
    if (!(P.m[i] >= 0) || !std::isfinite(P.m[i]) || (i >= nb && P.m[i] == 0))
      fail(fmt::format("mass of particle {}", i));
  }
}

}  // namespace

std::uint64_t case_identity_hash(std::string_view resolved_case_toml) {
  toml::table t;
  try {
    t = toml::parse(resolved_case_toml);
  } catch (const toml::parse_error& e) {
    throw io::IoError(fmt::format("the case text is not TOML ({})", e.description()));
  }
  if (toml::table* time = t["time"].as_table()) time->erase("end");
  t.erase("output");
  std::ostringstream canonical;
  canonical << t;
  return io::fnv1a64(canonical.str());
}

void check_checkpoint_fits_case(const Checkpoint& k, const Case& c, const std::filesystem::path& source) {
  auto fail = [&](const std::string& why) {
    throw io::IoError(fmt::format("checkpoint '{}': does not fit its case ({})", source.string(), why));
  };
  const std::size_t nw = c.walls.size(), nbodies = c.bodies.size();
  if (k.groups.size() != nw + nbodies)
    fail(fmt::format("{} rigid groups, the case has {} walls and {} bodies", k.groups.size(), nw, nbodies));
  for (std::size_t g = 0; g < k.groups.size(); ++g) {
    const RigidGroup& G = k.groups[g];
    if (g < nw) {
      const WallSpec& w = c.walls[g];
      const Motion motion = norm(w.velocity) > 0 || w.omega != 0 ? Motion::Prescribed : Motion::Fixed;
      if (!G.is_wall || G.name != w.name || G.motion != motion)
        fail(fmt::format("rigid group {} is not wall '{}'", g, w.name));
    } else {
      const BodySpec& b = c.bodies[g - nw];
      const Motion motion = b.motion == BodyMotion::Free    ? Motion::Free
                            : b.motion == BodyMotion::Fixed ? Motion::Fixed
                                                            : Motion::Prescribed;
      if (G.is_wall || G.name != b.name || G.motion != motion || G.body != static_cast<int>(g - nw))
        fail(fmt::format("rigid group {} is not body '{}'", g, b.name));
      // removed only at an outlet of the case that removes bodies (inlets come first)
      const auto z = static_cast<std::size_t>(G.removed_at);
      if (G.removed && (z < c.inlets.size() || z >= c.inlets.size() + c.outlets.size() ||
                        c.outlets[z - c.inlets.size()].bodies != OutletBodies::Removed))
        fail(fmt::format("body '{}' removed at open boundary {}, which does not remove bodies", b.name,
                         G.removed_at));
    }
  }
  check_values(k, fail);
  const Particles& P = k.particles;
  if (k.open_flux.size() != c.inlets.size() + c.outlets.size())
    fail(fmt::format("{} open-boundary fluxes, the case has {} inlets and {} outlets", k.open_flux.size(),
                     c.inlets.size(), c.outlets.size()));
  for (std::size_t i = P.n_boundary; i < P.size(); ++i)
    if ((P.kind[i] == Kind::Inlet && c.inlets.empty()) || (P.kind[i] == Kind::Outlet && c.outlets.empty()))
      fail(fmt::format("buffer particle {} of an open boundary the case does not have", i));
  if (c.boundary != BoundaryModel::Dummy)
    for (std::size_t i = 0; i < P.n_boundary; ++i)
      if (P.kind[i] == Kind::Dummy) fail(fmt::format("dummy particle {} with the single-layer boundary", i));
  // Fluid particles within the domain enlarged by its size on every side (the solver stops a run
  // whose fluid leaves a closed domain by more than h, and wraps periodic axes); rigid groups and
  // their surfaces (a prescribed solid may travel) within 1e5 domain sizes, which keeps the cell
  // arithmetic of the neighbour search and the periodic wrap in range.
  const Vec2 L = c.domain_max - c.domain_min;
  const auto inside = [&](Vec2 x, real margin) {
    return x.x >= c.domain_min.x - margin * L.x && x.x <= c.domain_max.x + margin * L.x &&
           x.y >= c.domain_min.y - margin * L.y && x.y <= c.domain_max.y + margin * L.y;
  };
  for (std::size_t i = 0; i < P.size(); ++i)
    if (!inside(P.x[i], i < P.n_boundary ? 1e5 : 1.0))
      fail(fmt::format("particle {} far outside the domain", i));
  for (std::size_t g = 0; g < k.groups.size(); ++g)
    if (!inside(k.groups[g].pos, 1e5) || !inside(k.groups[g].pos0, 1e5))
      fail(fmt::format("rigid group {} far outside the domain", g));
}

std::filesystem::path checkpoint_path(const std::filesystem::path& run_dir) {
  return run_dir / "checkpoint" / "state.bin";
}

std::string encode_checkpoint(const Checkpoint& c) {
  return encode_checkpoint(CheckpointView{c.case_toml, c.case_hash, c.time, c.step, c.counters, c.marks,
                                          c.particles, c.groups, c.open_flux, c.load_band});
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
  ar(static_cast<std::uint64_t>(c.open_flux.size()));
  for (const OpenFlux& f : c.open_flux) open_flux_fields(ar, f);
  load_band_fields(ar, c.load_band);
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
  if (bytes.size() < kHeaderBytes)
    fail(fmt::format("truncated ({} bytes, the header alone has {})", bytes.size(), kHeaderBytes));
  const auto version = load<std::uint32_t>(bytes, 8);
  if (version != kCheckpointVersion)
    fail(
        fmt::format("format version {}, but this particula reads version {} (resume it with the particula "
                    "that wrote it)",
                    version, kCheckpointVersion));
  if (load<std::uint32_t>(bytes, 12) != kByteOrderMark) fail("written on a machine with another byte order");
  const auto payload_size = load<std::uint64_t>(bytes, 16);
  const std::size_t available = bytes.size() - kHeaderBytes;
  if (available < kTrailerBytes || payload_size > available - kTrailerBytes)
    fail(fmt::format("truncated ({} bytes; the header announces a payload of {} bytes)", bytes.size(),
                     payload_size));
  if (payload_size != available - kTrailerBytes)
    fail(fmt::format("corrupted ({} bytes after the end of the data)",
                     available - kTrailerBytes - payload_size));
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
  c.open_flux.resize(ar.read_size(1));
  for (OpenFlux& f : c.open_flux) open_flux_fields(ar, f);
  load_band_fields(ar, c.load_band);
  if (ar.remaining() != 0) fail("corrupted (unexpected data after the last field)");
  check_consistency(c, what);
  return c;
}

void write_checkpoint(const std::filesystem::path& file, const Checkpoint& c) {
  write_checkpoint(file, CheckpointView{c.case_toml, c.case_hash, c.time, c.step, c.counters, c.marks,
                                        c.particles, c.groups, c.open_flux, c.load_band});
}

void write_checkpoint(const std::filesystem::path& file, const CheckpointView& c) {
  // A bare file name ("state.bin") has no parent to create: it goes into the working directory.
  if (const std::filesystem::path dir = file.parent_path(); !dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw io::WriteError(fmt::format("cannot create '{}': {}", dir.string(), ec.message()));
  }
  io::write_file_atomic(file, encode_checkpoint(c));
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  return decode_checkpoint(io::read_file(file), file);
}

std::optional<std::string> why_not_checkpoint_target(const std::filesystem::path& file) {
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0) {
    if (errno == ENOENT) return std::nullopt;
    return fmt::format("it cannot be examined ({})", std::strerror(errno));
  }
  if (S_ISLNK(st.st_mode)) return "it is a symbolic link (particula replaces neither a link nor what it points to)";
  if (S_ISDIR(st.st_mode)) return "it is a directory";
  if (!S_ISREG(st.st_mode)) return "it is not a regular file (a device, a pipe or a socket)";
  char head[sizeof kMagic] = {};
  ssize_t n = -1;
  if (const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK); fd >= 0) {
    n = ::read(fd, head, sizeof head);
    ::close(fd);
  }
  if (n != static_cast<ssize_t>(sizeof head) || std::memcmp(head, kMagic, sizeof head) != 0)
    return "it is not a particula checkpoint (it does not start with the checkpoint's magic number); particula "
           "replaces only a checkpoint";
  return std::nullopt;
}

}  // namespace particula
