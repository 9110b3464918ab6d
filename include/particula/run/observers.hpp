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
#include "particula/io/json.hpp"
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

/// One probe: probe_<name>.csv with time,x,y,vx,vy,p and, when the case declares an exact
/// solution, vx_exact (units in the file's "# units:" line), one row per point; a line probe also
/// writes flow_<name>.csv, its flow rate (flow_rate_of). Tracks the profile error against the
/// exact solution. The rows of one time are written together, or (io::Cancelled) not at all.
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
  std::optional<io::CsvWriter> flow_;  // line probes: flow_<name>.csv
  std::optional<double> last_error_;
  io::StopCheck stop_;
};

/// The flow rate through a line from `from` to `to` sampled at equally spaced points (both
/// ends included) with velocities `v`: Q = integral of u . n ds by the trapezoidal rule, n the
/// unit normal to the right of the line walking from `from` to `to` (n = (t_y, -t_x), t the unit
/// tangent: a line from bottom to top counts flow in +x). m^2/s in 2D (per unit depth).
double flow_rate_of(Vec2 from, Vec2 to, const std::vector<Vec2>& v);

/// The dimensionless coefficients of a body with reference velocity U (free stream relative to
/// the body) and length L, from its hydrodynamic force F and torque T (per unit depth):
///   Re = |U| L / nu, Re_body = |v_body| L / nu,
///   C_D = F . e / q, C_L = F . n / q, C_M = T / (q L),  q = 0.5 rho0 |U|^2 L,
/// e = U / |U| and n = e turned 90 degrees counter-clockwise.
struct Coefficients {
  double re = 0, re_body = 0, cd = 0, cl = 0, cm = 0;
};
Coefficients body_coefficients(const BodyReference& ref, Vec2 force, double torque, Vec2 body_velocity,
                               double rho0, double nu);

/// bodies.csv: one row per body per output, columns of design.md (f = hydrodynamic force,
/// pressure part fp + viscous part fv; fc = collision force, P.38), and walls.csv: the
/// hydrodynamic force on each wall segment (e.g. the wall shear of a Couette flow). Bodies and
/// walls by their case index; units (forces per unit depth) in each file's "# units:" line.
/// With a case whose bodies have references (analysis.*, body[].reference_*), also
/// coefficients.csv: time,body,re,re_body,cd,cl,cm for those bodies (body_coefficients).
class BodyHistoryWriter {
 public:
  explicit BodyHistoryWriter(const std::filesystem::path& run_dir);
  BodyHistoryWriter(const std::filesystem::path& run_dir, const Case& c);
  /// Writes one row per body and wall; writes nothing and returns the failure when a value is
  /// not finite.
  std::optional<Failure> write(const Solver& s);
  /// Whether the case makes coefficients.csv (some body has a complete reference).
  static bool writes_coefficients(const Case& c);

 private:
  io::CsvWriter csv_, walls_;
  std::optional<io::CsvWriter> coefficients_;
  std::vector<std::optional<BodyReference>> references_;  // per case body index
  double rho0_ = 0, nu_ = 0;
};

/// open_boundaries.csv (cases with inlets or outlets): one row per open boundary per output,
/// time,boundary,mass,backflow_mass,created,deleted,buffer_particles,fluid_mass: the boundary's
/// index (inlets, then outlets, in case order), the mass that crossed it since t = 0 (kg/m: into
/// the fluid at an inlet, out of it at an outlet), the mass that crossed it the other way (fluid
/// that left backwards through an inlet, or came back in through an outlet), the buffer particles
/// created and the particles deleted there, its buffer particles now, and the mass of all fluid
/// particles (the same on each row of a time). The fluid mass changes by exactly the net inflows
/// (mass - backflow_mass) minus the net outflows, so the file checks mass conservation.
class OpenBoundaryWriter {
 public:
  explicit OpenBoundaryWriter(const std::filesystem::path& run_dir);
  std::optional<Failure> write(const Solver& s);

 private:
  io::CsvWriter csv_;
};

/// The fluid mass (kind Fluid) and the buffer particles of each open boundary now.
real fluid_mass(const Particles& P);
std::vector<std::int64_t> buffer_counts(const Solver& s);
/// summary.json's "open_boundaries": per open boundary its index, name, kind and what crossed it.
std::vector<io::JsonObject> open_boundary_summary(const Solver& s);
/// The log's line of what crossed each open boundary, the fluid mass and the fit fallbacks.
std::string open_boundary_log_line(const Solver& s);

/// The velocity of the exact solution the case declares at (x, t); nullopt when it has none.
std::optional<Vec2> exact_velocity(const Case& c, Vec2 x, double t);
/// The squared error of a velocity against the exact one: of vx for the channel flows (couette,
/// poiseuille), of the vector for spin_up.
double exact_error2(const Case& c, Vec2 v, Vec2 exact);
/// L2 error over all fluid particles (at their own positions) against the exact solution
/// (exact_error2), relative to the peak speed; nullopt without an exact solution, or when `stop`
/// (polled every few hundred particles: the series is slow at early times) returns true.
std::optional<double> particle_profile_error(const Solver& s, const Case& c, const io::StopCheck& stop = {});
/// Peak speed used to normalize profile errors.
double exact_peak_speed(const Case& c);

}  // namespace particula
