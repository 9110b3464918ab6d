// The particle passes of a step behind one interface, with two implementations: the CPU
// (OpenMP loops over the host particles, solver/cpu_backend.hpp) and a CUDA device (src/cuda/,
// `--backend cuda`: the particle state lives on the GPU). Both call the same PARTICULA_HD
// functions (solver/sweeps.hpp, neighbors/neighbor_list.hpp), so that the Solver's step is the
// same list of stages whichever runs it. The Solver keeps the time loop, the rigid bodies and the
// host copy of the particles for output and checkpoints: on a device, per stage only the group
// loads (down) and the group poses and velocities (up) cross the bus, a few dozen bytes per body;
// with numerics.force = momentum also the positions once a step (the load band is built on the
// host) and the per-entry band loads once a stage (reduced on the host in a fixed order). On the
// CPU the transfers are nothing: the backend works on the host particles themselves.
//
// This header is plain C++: the CUDA implementation is compiled only when the CUDA toolkit is
// found (CMake option PARTICULA_CUDA).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/sweeps.hpp"

namespace particula {

struct PhysicsParams;
struct SolverCounters;
struct PhaseTimes;

/// Loads of one rigid group as reduced on the device (P.26-P.27, numerics.force = paper).
struct GroupLoads {
  Vec2 force_pressure, force_viscous;
  real torque = 0;
};

class Backend {
 public:
  virtual ~Backend() = default;

  /// "cpu" or "cuda".
  virtual const char* name() const = 0;
  /// Whether the particle state the passes work on is the host's own (the CPU): then the
  /// transfers do nothing.
  virtual bool on_host() const = 0;

  /// Whole-state transfers (start, after the host changed the state, output, checkpoints).
  virtual void upload(const Particles& P) = 0;
  virtual void download(Particles& P) = 0;

  /// Stable reorder of the fluid block by cell (the particles' cells at the last binning).
  virtual void reorder_fluid() = 0;
  /// Neighbour list, volumes and the geometry sweep (counts guarded events into `cnt`, times
  /// the phases into `times`).
  virtual void refresh_geometry(SolverCounters& cnt, PhaseTimes& times) = 0;
  /// A host cell grid binned at the step's positions of P (the open boundaries' fits search it).
  virtual const CellGrid& host_grid(const Particles& P) = 0;
  /// Leaves the pairs of two buffer particles out of min_distance (open boundaries: they are not
  /// integrated, and converted outlet particles of different speeds may close up in the buffer).
  virtual void skip_buffer_pairs_in_min_distance() = 0;
  virtual std::size_t pair_count() const = 0;
  virtual real min_distance() const = 0;
  virtual real max_speed() = 0;

  /// V^n, rho^n, P^n (StepStart) or V*, rho* (Predicted) := the current values.
  virtual void save_stage_start(StageStart which) = 0;
  /// Velocity derivatives of the current V and the pressure gradient, in one sweep; keeps
  /// grad V as the step-start gradient for shifting.
  virtual void start_of_step_derivatives() = 0;
  virtual void pressure_gradient() = 0;
  virtual void rhie_chow_and_momentum(StageStart from, const StageParams& s) = 0;
  virtual void derivatives_and_continuity(StageStart from, const StageParams& s) = 0;
  virtual void boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) = 0;

  /// Loads of every group from the surface sum P.26-P.27 (pressure and viscous parts, torque
  /// about its position).
  virtual void group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) = 0;
  /// Positions of every particle on the host (the band of the momentum loads is built from them,
  /// and its motion tested, once a step): the CPU's own, a device's downloaded.
  virtual const std::vector<Vec2>& host_positions() = 0;
  /// The neighbours at `x`, this step's host_positions() (the band's Voronoi cells read them): the
  /// CPU's neighbour list of the step, or a device's binning of x on the host.
  virtual HostNeighbors band_neighbors(const std::vector<Vec2>& x) = 0;
  /// Pressures of every particle (the open-boundary fits read the fluid's stage pressures).
  virtual void download_pressures(std::vector<real>& p) = 0;
  /// Position, velocity, pressure and density of the particles `index` from P (the buffer
  /// particles, whose fields the open-boundary passes set on the host).
  virtual void set_buffer_particles(const std::vector<std::uint32_t>& index, const Particles& P) = 0;
  /// The band entries of this step (numerics.force = momentum), in the load band's order.
  virtual void set_load_band(const std::vector<BandEntry>& band) = 0;
  /// band_entry_level of every entry (num, den in x, y) with the backend's fields of the current
  /// stage; `scalars` gives the constants (its pointers are ignored).
  virtual void band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) = 0;
  /// band_entry_load of every entry, with each group's X_B and smooth-pressure level (torque:
  /// of the pressure part in x, of the viscous part in y; fd: the odd-even damping's share).
  virtual void band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                          const std::vector<real>& group_level, std::vector<Vec2>& fp, std::vector<Vec2>& fv,
                          std::vector<Vec2>& torque, std::vector<Vec2>& fd) = 0;
  /// band_levels summed per block slot as sum_band_entry_levels does (num, den of each group's K_B
  /// per block); the CPU adds each entry as it evaluates it, a device sums its downloaded entries.
  virtual void band_level_sums(const LoadArrays& scalars, const std::vector<std::size_t>& block_first,
                               std::vector<Vec2>& partial) = 0;
  /// band_loads summed per block slot as sum_band_entry_loads does: the partial sums LoadBand
  /// adds up per group (`circle[k]`: group k is a circular body). The CPU adds each entry as it
  /// evaluates it; a device sums its downloaded entries on the host.
  virtual void band_load_sums(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                              const std::vector<real>& group_level, const std::vector<std::uint8_t>& circle,
                              const std::vector<std::size_t>& block_first,
                              std::vector<BandLoadSum>& partial) = 0;
  /// Surface particle velocities and accelerations from the group motions; with `place`, also
  /// positions and analytic normals.
  virtual void surface_motion(const std::vector<GroupMotion>& motions, bool place) = 0;

  /// End-of-step averages (P.28); returns max |V|^2.
  virtual real end_of_step(real dt, bool single_layer) = 0;
  /// Mean velocity gradient of the step, new pressure gradient, shift with `scale` = beta V_max dt
  /// (limited at open boundaries' lines).
  virtual void shift(real scale, real c) = 0;
  /// The surface guard on every fluid particle with keep-out distance `keep` (m); counts into `cnt`.
  virtual void guard_surfaces(real keep, SolverCounters& cnt) = 0;
  /// Smallest id of an unhealthy particle, or -1.
  virtual std::int64_t unhealthy_id(const HealthLimits& limits) = 0;
};

/// Whether this build has a CUDA backend and a GPU to run it on; `why` says what is missing.
bool cuda_backend_available(std::string* why);

/// The CUDA backend for the given physics and grid (throws std::runtime_error when this build
/// has none or no GPU is present).
std::unique_ptr<Backend> make_cuda_backend(const PhysicsParams& prm, const GridGeometry& grid,
                                           const WendlandC2& kernel, const Particles& P);

}  // namespace particula
