// The time loop of method.md section 9: predictor-corrector with frozen positions, the
// single-layer wall pressure, rigid groups, adaptive dt and particle shifting.
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
#include "particula/solver/device_backend.hpp"
#include "particula/solver/momentum_loads.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"
#include "particula/solver/sweeps.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

/// What crossed an open boundary (zone) since the start of the run; checkpointed.
struct OpenFlux {
  real mass = 0;                    // kg/m: into the fluid at an inlet, out of it at an outlet
  real backflow_mass = 0;           // kg/m: the other way: fluid that left through an inlet (deleted), or
                                    // that came back in through an outlet; the net flux is mass - backflow
  std::int64_t created = 0;         // buffer particles created (behind those that entered the fluid)
  std::int64_t deleted = 0;         // particles deleted (outlet: past the buffer; inlet: backflow)
  std::int64_t bodies_removed = 0;  // outlet with bodies = "removed": bodies taken out at its screen
  real body_fill_mass = 0;          // kg/m: fluid created in their places (it enters the fluid there)
};

/// Counters of guarded events (written to the run log).
struct SolverCounters {
  std::int64_t singular_B = 0;          // renormalization matrix singular -> B = I
  std::int64_t singular_Bhat = 0;       // fluid particle's Laplacian system singular -> Bhat = k I
  std::int64_t wall_pressure_kept = 0;  // P.20 denominator vanished -> previous P kept
  std::int64_t wall_pressure_extrapolated =
      0;  // P.20 ill-conditioned (sharp corner, contact wedge) -> extrapolated
  std::int64_t wall_pressure_extrapolated_far = 0;  // fluid out of P.20's reach (narrow gap) -> extrapolated
  std::int64_t normal_fallback = 0;                 // P.18 sum vanished -> analytic normal used
  std::int64_t surface_pushed = 0;     // fluid particle put back to the keep-out distance of a surface
  std::int64_t gap_squeezed = 0;       // fluid particle centred in a gap narrower than twice that
  std::int64_t isolated_left_out = 0;  // isolated fluid particle left out of P.20 (particle-steps)
  std::int64_t open_fit_fallback = 0;  // buffer particle whose mirrored fit was singular -> Shepard mean
  std::int64_t sparse_support = 0;     // fluid particle's gradient moment bounded below (particle-steps)
  std::int64_t wall_pressure_void = 0;  // surface particle with no fluid within kVoidDistance -> the void's pressure
};

/// The counters by the names summary.json and the Python module give them (one list for both).
inline std::vector<std::pair<const char*, std::int64_t>> guard_events(const SolverCounters& c) {
  return {{"singular_B", c.singular_B},
          {"singular_Bhat", c.singular_Bhat},
          {"wall_pressure_kept", c.wall_pressure_kept},
          {"wall_pressure_extrapolated", c.wall_pressure_extrapolated},
          {"wall_pressure_extrapolated_far", c.wall_pressure_extrapolated_far},
          {"normal_fallback", c.normal_fallback},
          {"surface_pushed", c.surface_pushed},
          {"gap_squeezed", c.gap_squeezed},
          {"isolated_left_out", c.isolated_left_out},
          {"open_fit_fallback", c.open_fit_fallback},
          {"sparse_support", c.sparse_support},
          {"wall_pressure_void", c.wall_pressure_void}};
}

/// Wall-clock seconds spent in each phase of the time step, summed over the steps taken (the
/// benchmark's per-phase breakdown; a handful of clock reads per step).
struct PhaseTimes {
  double neighbors = 0;      // cell binning, neighbour list, fluid reordering
  double geometry = 0;       // B, Bhat, normals, rbar, shifting direction, the fits of open boundaries
  double operators = 0;      // velocity derivatives, pressure gradient, Rhie-Chow, fluid stages
  double wall_pressure = 0;  // P.20 (or the dummy copy), and the fields of open boundaries' buffers
  double bodies = 0;         // loads, collisions, rigid motion, surface placement
  double integration = 0;    // end-of-step averages, dt, health check
  double shifting = 0;       // pressure gradient of the new state and the shift
  double total() const {
    return neighbors + geometry + operators + wall_pressure + bodies + integration + shifting;
  }
};

/// A numerical failure detected after a step (exit code 3).
/// A stable time step below this fraction of the case's own (cfl d0 / c, cfl d0^2 / nu) is a
/// collapse: 1e4 times more steps than the case was sized for.
inline constexpr real kTimeStepCollapse = 1e-4;

struct Failure {
  std::string what;
  std::int64_t particle_id = -1;
  Vec2 position;
};

/// Where the kept band of the momentum loads was last built (numerics.load_band_motion > 0):
/// every particle's position and every rigid group's position and angle then. Checkpoints carry
/// it, so that a resumed run rebuilds the band the uninterrupted run holds at that step
/// (Solver::set_load_band_state). Empty while no band is kept.
struct LoadBandState {
  std::vector<Vec2> x;      // every particle (boundary block first), in the particle order of the build
  std::vector<Vec2> pos;    // every rigid group
  std::vector<real> angle;  // every rigid group
  bool held() const { return !x.empty(); }
};

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
  Solver(Solver&&) noexcept;
  Solver& operator=(Solver&&) noexcept;

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
  const char* backend_name() const { return dev_ ? "cuda" : "cpu"; }
  const std::vector<RigidGroup>& groups() const { return groups_; }
  const Domain& domain() const { return domain_; }
  const PhysicsParams& params() const { return prm_; }
  const SolverCounters& counters() const { return counters_; }
  const WendlandC2& kernel() const { return kernel_; }
  std::size_t last_pair_count() const { return dev_ ? dev_->pair_count() : nl_.pair_count(); }
  const PhaseTimes& phase_times() const { return times_; }

  /// Time step of P.29-P.31 for the current state (rebuilds nothing: uses the last list).
  real stable_dt() const;
  /// The force condition 0.25 sqrt(h / |f|) of the body force and gravity on the fluid
  /// (infinite without either).
  real body_force_dt() const;

  /// Guard counters (checkpoints carry them so a resumed run reports totals).
  void set_counters(const SolverCounters& c) { counters_ = c; }
  /// What crossed each open boundary (inlets, then outlets) since the start of the run.
  const std::vector<OpenFlux>& open_flux() const { return open_flux_; }
  /// Restores the fluxes of a checkpoint (one per open boundary).
  void set_open_flux(const std::vector<OpenFlux>& f) { open_flux_ = f; }
  /// Where the kept load band was built (checkpoints carry it); empty while none is kept.
  const LoadBandState& load_band_state() const { return band_built_; }
  /// Restores a checkpoint's kept band: the next step builds it again from the positions and
  /// poses it was built from (the same band, bitwise), then tests the motion since as always.
  void set_load_band_state(const LoadBandState& s);
  /// Builds of the load band by this solver (a kept band is built less often than once a step).
  std::int64_t load_band_builds() const { return band_builds_; }
  /// The kept band's last build: each particle's motion limit, squared (m^2), and the solid it
  /// moves relative to (its closest, for a particle in the band; -1: its own motion counts).
  const std::vector<real>& load_band_limits2() const { return band_limit2_; }
  const std::vector<std::int32_t>& load_band_anchors() const { return band_anchor_; }

  /// A body taken out of the run at an outlet in the last step (remove_bodies_at_outlets).
  struct BodyRemoval {
    std::size_t group = 0, zone = 0;
    std::size_t fill_particles = 0;
    real fill_mass = 0;  // kg/m
  };
  /// The bodies removed in the last step (empty in most steps), for the run log.
  const std::vector<BodyRemoval>& removed_in_last_step() const { return removed_now_; }

  /// Rebuilds neighbours and position-only quantities for the current positions (used before
  /// output and by tests of the operators).
  void refresh_geometry();

  // Read-only views of the per-particle fields of the last evaluation (tests, output).
  const std::vector<Mat2>& B() const { return B_; }
  const std::vector<Mat2>& Bhat() const { return Bhat_; }
  const std::vector<Mat2>& grad_v() const { return gradV_; }
  const std::vector<Vec2>& lap_v() const { return lapV_; }
  const std::vector<Vec2>& grad_p_over_rho() const { return G_; }
  const NeighborList& neighbors() const { return nl_; }
  /// The arrays every sweep reads (neighbour list, positions, volumes, B, Bhat) as plain
  /// pointers for the per-particle functions of solver/sweeps.hpp (micro-benchmarks, tests).
  SweepContext sweep_context() const;

  /// Sweeps exposed for tests: derivatives of given fields on the current neighbour list.
  void compute_velocity_derivatives(const std::vector<Vec2>& v);
  void compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho);

 private:
  /// The step of step() and step_to(): at most dt_cap (0: no cap), ending exactly at land_at
  /// (when finite) if the cap limits it.
  std::optional<Failure> advance(real dt_cap, real land_at);
  void place_boundary(real t);
  void set_boundary_kinematics();
  void update_volumes();
  void geometry_sweep();
  /// Velocity derivatives of `v` and, when `G_out` is set, the pressure gradient, in one sweep.
  void derivatives_sweep(const std::vector<Vec2>& v, std::vector<Vec2>* G_out);
  /// Rhie-Chow bracket of the current P, then the fluid momentum stage V = V_start + dt A.
  void rhie_chow_and_momentum(StageStart from, const StageParams& sp);
  /// Velocity derivatives of the new V, then the continuity stage rho = rho_start + dt D.
  void derivatives_and_continuity(StageStart from, const StageParams& sp);
  void boundary_pressure();
  /// Hydrodynamic loads of every group for the current stage: P.26-P.27 (`numerics.force =
  /// paper`) or the band momentum balance (momentum_loads.hpp).
  void group_loads();
  /// The band entries (phi_B and its gradient at each fluid particle near a solid; positions
  /// are frozen during the stages), in particle order, for the particles at positions x and the
  /// solids at the poses band_pos_, band_angle_; the CPU's Voronoi cells from neighbour list nl,
  /// built at x (the GPU backend bins x itself).
  void build_load_band(const std::vector<Vec2>& x, const NeighborList& nl);
  /// The band of this step: built every step, or with numerics.load_band_motion kept until
  /// load_band_moved() (or rebuilt from a checkpoint's LoadBandState).
  void update_load_band(bool reordered);
  /// Whether, since the kept band was built (positions x now), a solid surface has moved more
  /// than numerics.load_band_motion, two solids near each other have closed in by more than
  /// solids_closed_in allows, or a particle has moved more than its limit (band_limit2_),
  /// relative to its closest solid (band_anchor_) for a particle in the band. Fills
  /// band_shift_, band_turn_reach_ and band_turn_cs_.
  bool load_band_moved(const std::vector<Vec2>& x);
  /// Whether two solids whose gap g is below load_band_motion / kBandGapShare have moved
  /// relative to each other by more than kBandGapShare max(g, kBandGapFloor d0) since the build.
  bool solids_closed_in();
  /// Each band entry's slot among the groups of its block of kBandBlock entries, and each
  /// block's groups (band_block_first_, band_slot_group_).
  void assign_band_slots();
  /// A per-entry quantity summed per group into `total` (size: groups) in one fixed order:
  /// block_sum(e0, e1, sums) adds entries [e0, e1) of one block into sums[slot], the blocks run
  /// in parallel into `partial`, and their sums are added per group in block order.
  template <class T, class BlockSum>
  void sum_band(std::vector<T>& partial, std::vector<T>& total, BlockSum block_sum) const;
  /// The solids within `reach` of x (walls, then the bodies of the cells round x): at most `max`.
  int near_solids(Vec2 x, real reach, NearSolid* out, int max) const;
  /// The area that weighs fluid particle i's grad(phi) terms in the band (positions x): its
  /// Voronoi cell among the particles within h (the step's neighbour list; band_grid_ with the
  /// GPU backend), or 0 (its volume m / rho) when a
  /// surface particle is within h or the cell is not closed.
  real band_cell_area(std::size_t i, const std::vector<Vec2>& x, const NeighborList& nl) const;
  /// Solid k's distance and its gradient at x into `out` when x is within `reach` of it.
  bool offer_near_solid(Vec2 x, real reach, std::size_t k, NearSolid& out) const;
  /// The walls at the band's poses (band_walls_) and the bodies' cos / sin of their angles
  /// (band_turn_), for offer_near_solid, once a build.
  void place_solids_for_band();
  /// Wall group k's geometry now (a turning wall rotated about its pivot; a sliding wall runs
  /// along a periodic axis and keeps its line).
  WallPiece wall_now(std::size_t k) const { return wall_at(k, groups_[k].angle); }
  /// Wall group k's geometry at angle `angle` of its group.
  WallPiece wall_at(std::size_t k, real angle) const;
  /// The bodies binned into cells of (largest bounding radius + reach), once a build of the band.
  void bin_bodies_for_band(real reach);
  /// The band momentum balance of every group (numerics.force = momentum).
  void momentum_group_loads();
  /// The load of group k's smooth pressure P_h (momentum_loads.hpp), added exactly: the segment
  /// integral for a wall, -rho_h g_h A for a body with fluid all round, else the surface sum.
  void smooth_pressure_load(const LoadArrays& a, std::size_t k, Vec2& force, real& torque) const;
  /// The stage's fields as the load sum reads them (host arrays).
  LoadArrays load_arrays() const;
  /// Contacts of the step (positions frozen): finds the touching solids, fails when they
  /// interpenetrate, and computes the paper's forces, or for the spring-dashpot the stiffness
  /// of each contact and the time-step limit they impose (contact_dt_).
  std::optional<Failure> collisions();
  /// Spring-dashpot contacts: every pair within `reach` with a free body (as side a), and the
  /// free bodies' walls, into contacts_; a failure when solids interpenetrate.
  std::optional<Failure> find_contacts(real reach);
  /// Contact episodes: a body near another solid (gap below `imminent`) keeps the largest
  /// approach speed of the episode (RigidGroup::contact_speed), so that the derived stiffness of
  /// an impact does not drop as the impact slows the bodies down; 0 once it is clear.
  void hold_contact_speeds(real imminent);
  /// The stiffness of each contact (the user's, or derived from the impact speed) and the step
  /// limit t_c / 20 of the active and imminent ones (contact_dt_).
  void contact_stiffness(real imminent);
  /// Spring-dashpot forces and torques of the contacts found by collisions(), over the step dt.
  void contact_forces(real dt);
  /// The paper's P.38 repulsion on the candidate pairs (the code path of the paper's cases).
  std::optional<Failure> paper_collisions();
  /// U_c: the characteristic impact speed of the step (docs/method-notes.md, Contacts).
  real characteristic_impact_speed() const;
  /// The contact parameters of this run (delta_c, damping ratio, friction, lubrication).
  ContactLaw contact_law() const;
  /// Failure of solids overlapping by more than the sampling noise (exit code 3).
  Failure overlap_failure(const RigidGroup& a, const std::string& other, real gap) const;
  /// Body group g's shape at its current pose.
  PlacedBody placed_body(const RigidGroup& g) const;
  /// The bodies still in the domain: their groups, positions and bounding radii (body_groups_,
  /// body_pos_, body_bound_).
  void list_bodies();
  /// One side of a contact: a body's group, or a wall group (mass 0, radius 0).
  ContactSide contact_side(const RigidGroup& g) const;
  /// Advances the velocities of free and prescribed groups by one stage to time t_stage_end,
  /// from the stage-start velocities v0/omega0 of each group.
  void body_stage(real dt, real t_stage_end, const std::vector<Vec2>& v0, const std::vector<real>& omega0);
  void body_update(real dt, real t_new);
  void shift_particles(real dt, real vmax);
  // ---- open boundaries (solver_open.cpp; boundary/open_boundary.hpp)
  /// The buffer particles of this step and, for each, the coefficients of the linear MLS fit
  /// over the fluid round its ghost point (value there, and continued to the particle).
  void open_ghost_weights();
  /// Buffer velocities for the step to t_mid (the middle of the step): the inlet's profile,
  /// the fluid's fitted velocity at an outlet.
  void open_velocities(real t_mid);
  /// Buffer pressures and densities from the fluid's current pressure (inlet: continued
  /// linearly; outlet: mirrored about the line's pressure).
  void open_pressures();
  /// The closest pair of this step's list for the time step, leaving out pairs of two buffer
  /// particles: they are not integrated, and converted outlet particles of different speeds may
  /// close up on each other in the buffer.
  void open_min_distance();
  /// Moves the buffer particles along their zone's normal by dt times their normal velocity.
  void open_move(real dt);
  /// Takes the normal part out of the shifting direction of fluid particles within h of an open line.
  void open_limit_shifting();
  /// Converts, deletes and creates particles at the open boundaries (end of step, index order).
  void open_transfer();
  /// The step's last open-boundary work: open_transfer and remove_bodies_at_outlets (on the GPU
  /// with the whole state on the host, sent back afterwards).
  void open_end_of_step();
  /// The zone of a buffer particle of kind `k` at x: the zone of that kind whose line is nearest.
  int open_zone_of(Vec2 x, Kind k) const;
  /// Whether x lies beyond an open boundary's line, in its buffer.
  bool in_open_buffer(Vec2 x) const {
    for (const OpenZone& z : prm_.open)
      if (beyond_open_line(z, x)) return true;
    return false;
  }
  /// The inlet's inflow speed at distance s along it, at time t.
  real inlet_speed(std::size_t zone, real s, real t) const;
  /// Whether fluid-block particle i takes part in the band momentum balance (not a buffer particle).
  bool in_load_band(std::size_t i) const { return prm_.open.empty() || !is_buffer(P_.kind[i]); }
  /// The surface guard (boundary/surface_guard.hpp) on every fluid particle.
  void guard_surfaces();
  GroupMotion group_motion(const RigidGroup& g) const;
  void reorder_fluid();
  std::optional<Failure> check_health() const;
  /// A body whose surface has come within h of an open boundary's line (its screen should have
  /// held it back, or removed it): a failure naming both.
  std::optional<Failure> body_at_open_boundary() const;
  /// Whether open boundary z is an outlet with bodies = "removed" (its screen removes bodies
  /// instead of holding them).
  bool removes_bodies(std::size_t z) const {
    return !prm_.open[z].inlet && prm_.open_specs[z].bodies == OutletBodies::Removed;
  }
  /// Takes out every body whose surface has reached the screen of an outlet that removes bodies.
  void remove_bodies_at_outlets();
  /// Takes body group k out of the run at open boundary z: its particles leave the boundary
  /// block and fluid particles fill the place it held (docs/method-notes.md, "Screens").
  void remove_body(std::size_t k, std::size_t z);
  /// What a failure at fluid position x most likely comes from, for the exit-3 message.
  std::string likely_cause(Vec2 x) const;
  /// The flow's Mach number (away from a failure at `failed_at`) and hydrostatic compression where
  /// they exceed the weakly compressible model's range (for the exit-3 message), or "".
  std::string weak_compressibility_report(Vec2 failed_at) const;
  real max_speed() const;
  /// A failure when the stable time step `dt` has fallen below kTimeStepCollapse of the case's
  /// own step (P.30-P.31 at d0 and c): a run that would crawl for ever is stopped with exit 3,
  /// naming the limit that collapsed (closest pair, fastest particle or a contact).
  std::optional<Failure> time_step_collapse(real dt) const;

  StageParams stage_params(real dt) const;
  HealthLimits health_limits() const;
  const std::vector<GroupMotion>& group_motions();
  void save_stage_start(StageStart which);
  void pressure_gradient();
  real end_of_step(real dt);

  PhysicsParams prm_;
  Domain domain_;
  mutable Particles P_;
  std::vector<RigidGroup> groups_;
  WendlandC2 kernel_;
  CellGrid grid_;
  NeighborList nl_;
  SolverCounters counters_;
  real t_ = 0, dt_ = 0;
  std::int64_t steps_ = 0;
  PhaseTimes times_;

  // per-particle work arrays (sized once; the step loop allocates nothing)
  std::vector<real> vol_, rbar_, rc_, rho_n_, rho_s_, div_v_, p_n_, p_new_;
  std::vector<Vec2> group_v0_;
  std::vector<real> group_w0_;
  std::vector<Mat2> B_, Bhat_, gradV_, gradV_n_;
  std::vector<Vec2> lapV_, G_, v_n_, v_s_, shift_dir_;
  std::vector<Vec2> odd_even_;  // the odd-even damping's acceleration of the stage (band sums)
  // per-pair weights of the geometry sweep (solver/sweeps.hpp)
  std::vector<std::uint32_t> near_a_, near_b_;  // nearest surface particles (surface guard)
  std::vector<real> film_;                      // unresolved-film fraction of each particle, this step
  std::vector<std::uint8_t> isolated_;          // 1: isolated fluid particle this step (left out of P.20)
  std::vector<Vec2> pair_grad_w_;
  std::vector<real> pair_lap_w_;
  // GPU backend: the device holds the particle state; the host copy is refreshed on demand
  std::unique_ptr<DeviceBackend> dev_;
  mutable bool host_current_ = true;  // P_ equals the device state
  bool device_current_ = true;        // the device state equals P_
  std::vector<GroupLoads> loads_;
  // band momentum balance (numerics.force = momentum): entries of this step in particle order,
  // the groups of each block of entries, per-entry loads (GPU backend) and scratch
  std::vector<BandEntry> band_;
  std::vector<std::vector<BandEntry>> band_parts_;  // per thread: the entries of its range of particles
  std::vector<std::size_t> band_part_first_;        // where thread t's entries start in band_
  std::vector<std::size_t> band_block_first_;       // block b's groups: band_slot_group_[first[b]...]
  std::vector<std::int32_t> band_slot_group_;       // the group of each block's slot
  struct BandLoadSum {
    Vec2 fp, fv, fd;  // fd: the odd-even damping's share (band_share_damping), not a load
    real torque = 0;
    BandLoadSum& operator+=(const BandLoadSum& o) {
      fp += o.fp;
      fv += o.fv;
      fd += o.fd;
      torque += o.torque;
      return *this;
    }
  };
  std::vector<Vec2> band_level_partial_, band_level_total_;  // (num, den) of K_B per block slot / group
  std::vector<BandLoadSum> band_load_partial_, band_load_total_;
  std::vector<std::uint8_t> group_circle_;  // group k is a circular body
  std::vector<Vec2> band_fp_, band_fv_, band_fd_, band_x_, group_pos_;
  std::vector<Vec2> band_torque_;  // per band entry: torque of its pressure part (x) and viscous part (y)
  std::vector<real> group_level_;
  BodyCells band_bodies_;  // the bodies binned once a build for near_solids
  std::vector<BodyCells::Item> band_body_items_;
  CellGrid band_grid_;  // GPU backend: every particle binned once a build for band_cell_area
  std::vector<WallPiece> band_walls_;  // wall group k at the band's build (walls come first)
  std::vector<Vec2> band_turn_;        // body group k: cos and sin of its angle at the band's build
  std::vector<Vec2> band_pos_;         // group k's position the band is built at
  std::vector<real> band_angle_;       // group k's angle the band is built at
  LoadBandState band_built_;           // numerics.load_band_motion: where the kept band was built
  bool band_restore_ = false;          // band_built_ came from a checkpoint: build the band from it
  std::vector<Vec2> band_shift_;       // group k's displacement since the band's build
  std::vector<real> band_turn_reach_;  // how far group k's turn since the build can move its surface
  std::vector<BodyPair> band_pairs_;   // bodies near each other (solids_closed_in)
  std::vector<real> band_limit2_;      // each particle's kept-band motion limit, squared
  std::vector<std::int32_t> band_anchor_;  // the solid a particle next to one moves relative to, or -1
  std::vector<Vec2> band_turn_cs_;         // cos and sin of group k's turn since the band's build
  std::int64_t band_builds_ = 0;
  std::vector<GroupMotion> motions_;

  // contacts of the step (spring-dashpot): the groups a (a body) and b (a body or a wall), the
  // geometry and the stiffness, found by collisions() and loaded by contact_forces()
  struct StepContact {
    std::size_t a = 0, b = 0;  // b: a group, or an open boundary's screen (screen = true)
    bool screen = false;
    Contact c;
    real k = 0;
  };
  std::vector<StepContact> contacts_;
  /// The fluid force and reduced weight of a body (what presses it into its contacts).
  Vec2 non_contact_load(const RigidGroup& g) const;
  /// Raise the held contact speed of a contact's free bodies so that the derived stiffness holds
  /// the part of their non-contact loads that presses them into it within delta_max / 4.
  void hold_sustained_load(RigidGroup& a, RigidGroup* b, Vec2 normal, real k, real delta_max);
  /// The other side of a contact: its group, or a fixed wall at rest standing for a screen.
  const RigidGroup& contact_partner(const StepContact& sc) const;
  real contact_dt_ = 0;                   // dt limit of the active and imminent contacts, 0 = none
  std::vector<std::size_t> body_groups_;  // group index of each body, in group order
  std::vector<Vec2> body_pos_;
  std::vector<real> body_bound_;
  std::vector<BodyPair> body_pairs_;
  std::vector<real> contact_approach_;

  // open boundaries: the buffer particles of this step, their zones, and the CSR of their ghost
  // fits (fluid particle, coefficient of the value at the ghost point, of the value continued to
  // the buffer particle)
  std::vector<std::uint32_t> buffer_;
  std::vector<int> buffer_zone_;
  std::vector<std::uint32_t> ghost_start_, ghost_j_;
  std::vector<real> ghost_val_, ghost_lin_;
  std::vector<OpenFlux> open_flux_;
  // scratch of the fits and the transfer (kept between steps: the step loop allocates nothing once grown)
  std::vector<std::uint32_t> fit_j_;
  std::vector<Vec2> fit_d_;
  std::vector<real> fit_w_;
  struct CreatedParticle {
    Vec2 x, v;
    real p, rho, m;
    Kind kind;
  };
  std::vector<CreatedParticle> created_;
  /// Appends `created` at the end of the fluid block, with new ids (Particles::next_id).
  void append_created(const std::vector<CreatedParticle>& created);
  std::vector<BodyRemoval> removed_now_;
  std::vector<unsigned char> keep_;

  // reordering scratch
  std::vector<std::uint32_t> reorder_key_;
  std::vector<std::size_t> reorder_order_;
  std::vector<unsigned char> reorder_scratch_;
};

}  // namespace particula
