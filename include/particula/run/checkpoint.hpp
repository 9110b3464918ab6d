// Checkpoints: the complete restartable state of a run in one binary file,
// DIR/checkpoint/state.bin, written atomically (temporary file + rename).
//
// File layout (format version kCheckpointVersion):
//   8 bytes   magic "PRTCLCKP"
//   u32       format version
//   u32       byte-order mark 0x01020304 (values are in the writer's byte order)
//   u64       payload size in bytes
//   payload   case TOML text, case identity hash, time, step, SolverCounters, Particles,
//             RigidGroups, output marks, open-boundary fluxes, the kept load band's build state
//   u64       FNV-1a 64 checksum of the payload
//
// Reading refuses, with an io::IoError naming the file, a wrong magic, another format
// version, another byte order, a truncated file, a checksum mismatch, and content whose parts
// do not fit each other (array sizes, particle kinds and groups, group ranges and body indices,
// dummy sources, particle ids, output marks, the kept band's arrays). check_checkpoint_fits_case() then
// checks it against the case it is resumed with and checks its values, so that a checkpoint, however made, is
// either refused or safe to run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "particula/solver/particles.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/solver.hpp"

namespace particula {

/// Bump when the layout or any field list below changes; older files are then refused.
inline constexpr std::uint32_t kCheckpointVersion = 15;

/// When an output stream ("bodies", "snapshots", "probe:<name>") was last written on its
/// regular schedule. A resumed run drops rows after this time (the extra final-state rows of an
/// interrupted run), so that it continues exactly as an uninterrupted run would.
struct OutputMark {
  std::string stream;
  real last_scheduled = 0;
};

struct Checkpoint {
  std::string case_toml;  // the resolved case (resolved_case_toml), without overrides applied later
  std::uint64_t case_hash =
      0;  // the run's case identity (case_identity_hash), as in its run directory's marker
  real time = 0;
  std::int64_t step = 0;
  SolverCounters counters;
  std::vector<OutputMark> marks;
  Particles particles;
  std::vector<RigidGroup> groups;
  std::vector<OpenFlux> open_flux;  // one per open boundary (inlets, then outlets)
  LoadBandState load_band;          // where the kept load band was built (empty: none kept)
};

/// The same content by reference, so that a running solver's state is written without a copy.
struct CheckpointView {
  const std::string& case_toml;
  const std::uint64_t& case_hash;
  const real& time;
  const std::int64_t& step;
  const SolverCounters& counters;
  const std::vector<OutputMark>& marks;
  const Particles& particles;
  const std::vector<RigidGroup>& groups;
  const std::vector<OpenFlux>& open_flux;
  const LoadBandState& load_band;
};

/// The identity of a run's case: the FNV-1a 64 hash of the resolved case text (what particula
/// writes as case.toml) with the keys `resume` may change (time.end and the [output] table)
/// taken out, in a canonical TOML form. A run directory records it in its marker when `run`
/// creates it (run_dir.hpp) and every checkpoint of the run carries it unchanged, so `resume`
/// can refuse a checkpoint of another case. Throws io::IoError when the text is not TOML.
std::uint64_t case_identity_hash(std::string_view resolved_case_toml);

/// Checks a decoded checkpoint against the case it is resumed with: its rigid groups must be
/// the case's walls and then its bodies, in order, with their names and kinds of motion; dummy
/// particles only with the dummy boundary; every value finite, densities positive, masses not
/// negative (positive for fluid particles and free bodies), positions near the domain. Throws
/// io::IoError naming `source` otherwise. (decode_checkpoint checks only the structure, so that a
/// diagnostic checkpoint of a numerical failure, NaN and all, can still be read.)
void check_checkpoint_fits_case(const Checkpoint& k, const Case& c, const std::filesystem::path& source);

/// DIR/checkpoint/state.bin, the checkpoint `particula resume DIR` reads.
std::filesystem::path checkpoint_path(const std::filesystem::path& run_dir);

/// The file's bytes (header, payload, checksum).
std::string encode_checkpoint(const CheckpointView& c);
std::string encode_checkpoint(const Checkpoint& c);
/// Parses and checks a checkpoint; `source` names the file in messages. Throws io::IoError.
Checkpoint decode_checkpoint(std::string_view bytes, const std::filesystem::path& source);

/// Writes `c` to `file` atomically, creating its directory. Throws io::WriteError.
void write_checkpoint(const std::filesystem::path& file, const CheckpointView& c);
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& c);
/// Reads and checks a checkpoint file. Throws io::IoError naming the file.
Checkpoint read_checkpoint(const std::filesystem::path& file);
/// Why a checkpoint must not be written to `file`: it exists and is a symbolic link, not a
/// regular file (a directory, a device, a pipe), or a regular file that is not a particula
/// checkpoint (it does not start with the checkpoint's magic number, whatever its version);
/// nullopt when `file` does not exist or is a checkpoint.
std::optional<std::string> why_not_checkpoint_target(const std::filesystem::path& file);

// ---- the field lists ---------------------------------------------------------------------------
// ONE list per struct, used for writing (const object) and reading (non-const object). When you
// add a field to Particles, RigidGroup or SolverCounters: add one `ar(...)` line here, update
// the field count below, and bump kCheckpointVersion. tests/run/test_checkpoint.cpp and the
// static_asserts in src/run/checkpoint.cpp fail until you do.

inline constexpr std::size_t kParticlesFields = 17;  // n_boundary, next_id + 15 arrays
inline constexpr std::size_t kRigidGroupFields = 29;
inline constexpr std::size_t kSolverCountersFields = 12;
inline constexpr std::size_t kOpenFluxFields = 6;
inline constexpr std::size_t kLoadBandStateFields = 3;

template <class Ar, class P>
void particles_fields(Ar& ar, P& p) {
  ar(p.n_boundary);
  ar(p.next_id);
  // every particle
  ar(p.x);
  ar(p.v);
  ar(p.rho);
  ar(p.p);
  ar(p.m);
  ar(p.kind);
  ar(p.group);
  ar(p.id);
  // boundary block only
  ar(p.local);
  ar(p.normal_local);
  ar(p.ds);
  ar(p.acc);
  ar(p.normal);
  ar(p.wedge);
  ar(p.source);
}

template <class Ar, class G>
void rigid_group_fields(Ar& ar, G& g) {
  ar(g.name);
  ar(g.motion);
  ar(g.is_wall);
  ar(g.removed);
  ar(g.removed_at);
  ar(g.removed_time);
  ar(g.pos);
  ar(g.vel);
  ar(g.acc);
  ar(g.angle);
  ar(g.omega);
  ar(g.alpha);
  ar(g.pos0);
  ar(g.angle0);
  ar(g.first);
  ar(g.count);
  ar(g.body);
  ar(g.mass);
  ar(g.inertia);
  ar(g.area);
  ar(g.force_pressure);
  ar(g.force_viscous);
  ar(g.force_collision);
  ar(g.force_damping);
  ar(g.torque);
  ar(g.torque_collision);
  ar(g.contact_speed);
  ar(g.vel_n);
  ar(g.omega_n);
}

template <class Ar, class C>
void solver_counters_fields(Ar& ar, C& c) {
  ar(c.singular_B);
  ar(c.singular_Bhat);
  ar(c.wall_pressure_kept);
  ar(c.wall_pressure_extrapolated);
  ar(c.wall_pressure_extrapolated_far);
  ar(c.normal_fallback);
  ar(c.surface_pushed);
  ar(c.gap_squeezed);
  ar(c.isolated_left_out);
  ar(c.open_fit_fallback);
  ar(c.sparse_support);
  ar(c.wall_pressure_void);
}

template <class Ar, class F>
void open_flux_fields(Ar& ar, F& f) {
  ar(f.mass);
  ar(f.backflow_mass);
  ar(f.created);
  ar(f.deleted);
  ar(f.bodies_removed);
  ar(f.body_fill_mass);
}

template <class Ar, class B>
void load_band_fields(Ar& ar, B& b) {
  ar(b.x);
  ar(b.pos);
  ar(b.angle);
}

namespace checkpoint_detail {
/// Number of members of an aggregate (brace-initialization probing): catches a field added to
/// a struct without a line in its field list, even when it fits in padding.
struct AnyField {
  template <class T>
  operator T() const;  // never defined: only used in unevaluated contexts
};
template <class T, std::size_t... I>
constexpr bool brace_initializable(std::index_sequence<I...>) {
  return requires { T{(static_cast<void>(I), AnyField{})...}; };
}
template <class T, std::size_t N = 0>
constexpr std::size_t aggregate_field_count() {
  if constexpr (!brace_initializable<T>(std::make_index_sequence<N + 1>{}))
    return N;
  else
    return aggregate_field_count<T, N + 1>();
}
}  // namespace checkpoint_detail

}  // namespace particula
