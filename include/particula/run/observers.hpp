// Observers of a run: each writes one kind of output from the solver's state.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/vtk.hpp"
#include "particula/solver/solver.hpp"

namespace particula {

/// Per particle: the case index of the body ([[body]] order) it belongs to, or with `walls` of
/// its wall ([[wall]] order); -1 for fluid particles and particles of the other kind of group.
/// The `body` and `wall` arrays of the snapshots (bodies.csv and walls.csv number them alike).
std::vector<std::int32_t> particle_case_index(const Particles& P, const std::vector<RigidGroup>& groups, bool walls);

// Long writes (a probe of many points, a snapshot of many particles) poll a stop check (the run's
// SIGINT/SIGTERM flag) and give up with io::Cancelled, having written nothing, when it is set.

/// particles.pvd + particles/step_<n>.vtp snapshots: pressure, velocity, density, kind (Kind:
/// 0 fluid, 1 wall or body surface, 2 dummy), body (case index of the body a particle belongs to,
/// -1 otherwise), wall (case index of its wall, -1 otherwise) and id.
class SnapshotWriter {
 public:
  explicit SnapshotWriter(std::filesystem::path run_dir, io::StopCheck stop = {});
  void write(const Solver& s);

 private:
  std::filesystem::path dir_;
  io::PvdIndex pvd_;
  io::StopCheck stop_;
};

/// One line probe: probe_<name>.csv with time,x,y,vx,vy,p and, when the case declares an
/// exact solution, vx_exact (units in the file's "# units:" line); also tracks the profile error against it. The rows of one time
/// are written together, or (io::Cancelled) not at all.
class ProbeWriter {
 public:
  ProbeWriter(const std::filesystem::path& run_dir, const ProbeSpec& spec, const Case& c, io::StopCheck stop = {});
  /// Interpolates and writes one row per point; writes nothing and returns the failure when a
  /// value is not finite (no success with broken numbers: the run ends with exit 3). Throws
  /// io::Cancelled, having written nothing, when the stop check fires.
  std::optional<Failure> write(const Solver& s);
  /// L2 error of vx against the exact solution at the last write, relative to the peak speed
  /// (nullopt without an exact solution).
  std::optional<double> last_error() const { return last_error_; }
  const ProbeSpec& spec() const { return spec_; }

 private:
  ProbeSpec spec_;
  const Case& case_;
  std::vector<Vec2> points_;
  io::CsvWriter csv_;
  std::optional<double> last_error_;
  io::StopCheck stop_;
};

/// bodies.csv: one row per body per output, columns of design.md (f = hydrodynamic force,
/// pressure part fp + viscous part fv; fc = collision force, P.38), and walls.csv: the
/// hydrodynamic force on each wall segment (e.g. the wall shear of a Couette flow). Bodies and
/// walls by their case index; units (forces per unit depth) in each file's "# units:" line.
class BodyHistoryWriter {
 public:
  explicit BodyHistoryWriter(const std::filesystem::path& run_dir);
  /// Writes one row per body and wall; writes nothing and returns the failure when a value is
  /// not finite.
  std::optional<Failure> write(const Solver& s);

 private:
  io::CsvWriter csv_, walls_;
};

/// The exact solution the case declares, evaluated at (y, t); nullopt when it has none.
std::optional<double> exact_vx(const Case& c, Vec2 x, double t);
/// L2 error of vx over all fluid particles (at their own positions) against the exact
/// solution, relative to the peak speed; nullopt without an exact solution, or when `stop`
/// (polled every few hundred particles: the series is slow at early times) returns true.
std::optional<double> particle_profile_error(const Solver& s, const Case& c, const io::StopCheck& stop = {});
/// Peak speed used to normalize profile errors.
double exact_peak_speed(const Case& c);

}  // namespace particula
