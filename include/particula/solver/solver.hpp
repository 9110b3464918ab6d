// The time loop of docs/method.md, "One time step" and section 9: predictor-corrector with
// frozen positions, the single-layer wall pressure, rigid groups, adaptive dt and particle shifting.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/contact_pairs.hpp"
#include "particula/boundary/open_boundary.hpp"
#include "particula/case/case.hpp"
#include "particula/geometry/shape.hpp"
#include "particula/neighbors/body_cells.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/contacts.hpp"
#include "particula/solver/counters.hpp"
#include "particula/solver/cpu_backend.hpp"
#include "particula/solver/failure.hpp"
#include "particula/solver/load_band.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/open_boundaries.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_bodies.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/sweeps.hpp"
#include "particula/solver/time_step.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

/// How a solver starts: from a freshly built scene (boundary pressures are initialized from
/// P.20) or from a checkpointed state (taken exactly as it is, so a resumed run is bitwise
/// identical to an uninterrupted one).
enum class SolverStart { Fresh, Restart };

class Solver {
 public:
  /// With params.cuda the particle passes run on the GPU (throws std::runtime_error when this
  /// build or machine has none).
  Solver(PhysicsParams params, Domain domain, Particles particles, std::vector<RigidGroup> groups,
         SolverStart start = SolverStart::Fresh, real t0 = 0, std::int64_t step0 = 0);
  ~Solver();
  // The components hold references to the solver's parameters and particles: not copied, not moved.
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  /// Advances one full time step of at most `dt_cap` (used to land on output and end times).
  /// Returns the failure, if any, detected at its end.
  std::optional<Failure> step(real dt_cap = 0);
  /// Advances one full time step of at most t_target - time(); when that cap is what limits the
  /// step, the new time is exactly t_target (time() + dt may differ in the last bit), so that a
  /// run lands on its output times. t_target <= time() means no cap, as step(0).
  std::optional<Failure> step_to(real t_target);

  real time() const { return t_; }
  real last_dt() const { return dt_; }
  std::int64_t step_count() const { return steps_; }
  /// The particle state (with the GPU backend, copied from the device when it changed).
  const Particles& particles() const;
  /// Mutable access: with the GPU backend the state is uploaded again before the next step.
  Particles& particles();
  std::size_t particle_count() const { return P_.size(); }
  const char* backend_name() const { return backend_->name(); }
  const std::vector<RigidGroup>& groups() const { return bodies_.groups(); }
  const Domain& domain() const { return domain_; }
  const PhysicsParams& params() const { return prm_; }
  const SolverCounters& counters() const { return counters_; }
  const WendlandC2& kernel() const { return kernel_; }
  std::size_t last_pair_count() const { return backend_->pair_count(); }
  const PhaseTimes& phase_times() const { return times_; }

  /// Time step of P.29-P.31 and M.9 for the current state (rebuilds nothing: uses the last list).
  real stable_dt() const;
  /// What set the last step's length.
  StepLimit last_step_limit() const { return limit_; }
  /// The force condition 0.25 sqrt(h / |f|) of the body force and gravity on the fluid
  /// (infinite without either).
  real body_force_dt() const;
  /// The step of the case's own scales: P.30 at d0 and the sound speed, P.31 at d0, dt_max and
  /// the force condition. A step far below it has collapsed (kTimeStepCollapse, kTimeStepDrop).
  real case_dt() const;
  /// What limits a step of `dt` now, in words (a contact, a particle faster than sound, or the
  /// closest pair with both particles and their nearest surfaces), with the place (the first
  /// particle of the closest pair; none for the other two).
  Failure time_step_limit(real dt) const;

  /// Guard counters (checkpoints carry them so a resumed run reports totals).
  void set_counters(const SolverCounters& c) { counters_ = c; }
  /// What crossed each open boundary (inlets, then outlets) since the start of the run.
  const std::vector<OpenFlux>& open_flux() const { return open_.flux(); }
  /// Restores the fluxes of a checkpoint (one per open boundary).
  void set_open_flux(const std::vector<OpenFlux>& f) { open_.set_flux(f); }
  /// Where the kept load band was built (checkpoints carry it); empty while none is kept.
  const LoadBandState& load_band_state() const { return band_.state(); }
  /// Restores a checkpoint's kept band: the next step builds it again from the positions and
  /// poses it was built from (the same band, bitwise), then tests the motion since as always.
  void set_load_band_state(const LoadBandState& s) { band_.restore(s); }
  /// Builds of the load band by this solver (a kept band is built less often than once a step).
  std::int64_t load_band_builds() const { return band_.builds(); }
  /// The kept band's last build: each particle's motion limit, squared (m^2), and the solid it
  /// moves relative to (its closest, for a particle in the band; -1: its own motion counts).
  const std::vector<real>& load_band_limits2() const { return band_.limits2(); }
  const std::vector<std::int32_t>& load_band_anchors() const { return band_.anchors(); }

  /// A body taken out of the run at an outlet.
  using BodyRemoval = OpenBoundaries::BodyRemoval;
  /// The bodies removed in the last step (empty in most steps), for the run log.
  const std::vector<BodyRemoval>& removed_in_last_step() const { return open_.removed_in_last_step(); }

  /// Rebuilds neighbours and position-only quantities for the current positions (used before
  /// output and by tests of the operators).
  void refresh_geometry();

  /// The host's passes and the per-particle fields of their last evaluation (tests, benchmarks;
  /// with the GPU backend, those of the initial state).
  CpuBackend& host() { return *cpu_; }
  const CpuBackend& host() const { return *cpu_; }

 private:
  /// The step of step() and step_to(): at most dt_cap (0: no cap), ending exactly at land_at
  /// (when finite) if the cap limits it.
  std::optional<Failure> advance(real dt_cap, real land_at);
  /// The step's frozen geometry: reordering, neighbour list and geometry sweep, the open
  /// boundaries' fits, the load band.
  void prepare_step();
  /// One stage of the predictor-corrector from the stage start `from`: the fluid's momentum, the
  /// bodies from their loads, the continuity, the buffers' and the walls' pressure.
  void stage(StageStart from, const StageParams& sp, real t_new);
  /// The end of the step: averages (P.28), positions, the bodies' update and placement, shifting.
  void update(real dt, real t_new);
  /// The surface guard, the open boundaries' transfer, and the health check.
  std::optional<Failure> finish_step();
  /// P.20 on the surfaces (or the dummy copy), then isolated fluid particles' pressure.
  void boundary_pressure();
  /// Hydrodynamic loads of every group for the current stage: P.26-P.27 (`numerics.force =
  /// paper`) or the band momentum balance (load_band.hpp).
  void group_loads();
  /// What the load band reads of this solver's state.
  BandScene band_scene() const { return BandScene{prm_, domain_, P_, bodies_.groups()}; }
  // ---- open boundaries (solver_open.cpp): the component's passes on the host state, and the
  // transfers of what they set
  OpenScene open_scene() const { return OpenScene{prm_, domain_, kernel_}; }
  /// The buffer particles of this step and their ghost fits.
  void open_ghost_weights();
  /// Buffer velocities for the step to t_mid.
  void open_velocities(real t_mid);
  /// Buffer pressures from the fluid's current pressure.
  void open_pressures();
  /// Moves the buffer particles along their zone's normal.
  void open_move(real dt);
  /// The step's last open-boundary work: the transfer and the bodies removed at outlets, on the
  /// host state, sent back to a device afterwards.
  void open_end_of_step();
  std::optional<Failure> check_health() const;
  /// What a failure at fluid position x most likely comes from, for the exit-3 message.
  std::string likely_cause(Vec2 x) const;
  /// The flow's Mach number (away from a failure at `failed_at`) and hydrostatic compression where
  /// they exceed the weakly compressible model's range (for the exit-3 message), or "".
  std::string weak_compressibility_report(Vec2 failed_at) const;
  /// A failure when the stable time step `dt` has fallen below kTimeStepCollapse of the case's
  /// own step (P.30-P.31 at d0 and c): a run that would crawl for ever is stopped with exit 3,
  /// naming the limit that collapsed (closest pair, fastest particle or a contact).
  std::optional<Failure> time_step_collapse(real dt) const;

  /// The stable step and the limit that sets it.
  StableStep stable_step() const;
  StageParams stage_params(real dt) const;
  HealthLimits health_limits() const;
  /// The host copy of the particles made current (downloaded from a device when it changed).
  void sync_host() const;
  /// The device's copy made current (uploaded when the host changed the particles).
  void sync_device();

  PhysicsParams prm_;
  Domain domain_;
  mutable Particles P_;
  RigidBodies bodies_;  // the rigid groups (solver/rigid_bodies.hpp)
  WendlandC2 kernel_;
  SolverCounters counters_;
  real t_ = 0, dt_ = 0;
  StepLimit limit_ = StepLimit::Acoustic;
  std::int64_t steps_ = 0;
  PhaseTimes times_;

  // the passes: on the host (cpu_) or on a device; backend_ is the one that runs the step
  std::unique_ptr<CpuBackend> cpu_;
  std::unique_ptr<Backend> device_;
  Backend* backend_ = nullptr;
  mutable bool host_current_ = true;  // P_ equals the backend's state
  bool device_current_ = true;        // the backend's state equals P_
  LoadBand band_;                     // the band of the momentum loads (solver/load_band.hpp)
  Contacts contacts_;                 // the contacts of the step (solver/contacts.hpp)
  OpenBoundaries open_;               // inlets and outlets (solver/open_boundaries.hpp)
};

}  // namespace particula
