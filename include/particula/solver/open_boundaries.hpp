// Open boundaries in the time step (docs/method.md, "Open boundaries"; the zone geometry and the
// per-particle formulas are in boundary/open_boundary.hpp): each step the buffer particles behind
// every inlet and outlet get their fields from a linear moving-least-squares fit of the fluid at
// their mirrored ghost points (the fit's coefficients once a step, a CSR), move along their
// zone's normal, and at the end of the step the fluid block changes: buffer particles that
// entered become fluid (a new one created behind each), fluid that left joins an outlet's buffer
// or is removed, and bodies whose surface reached the screen of an outlet with
// bodies = "removed" are taken out and fluid fills their place. What crossed each boundary is
// counted (OpenFlux, checkpointed). The passes run on the host.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/counters.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/rigid_group.hpp"
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

/// What the open boundaries read of the solver.
struct OpenScene {
  const PhysicsParams& prm;
  const Domain& domain;
  const WendlandC2& kernel;
};

class OpenBoundaries {
 public:
  /// A body taken out of the run at an outlet (remove_bodies_at_outlets).
  struct BodyRemoval {
    std::size_t group = 0, zone = 0;
    std::size_t fill_particles = 0;
    real fill_mass = 0;  // kg/m
  };

  explicit OpenBoundaries(std::size_t zones) : flux_(zones) {}

  /// Forgets the buffer particles of the last step.
  void clear();
  /// The buffer particles of this step and, for each, the coefficients of the linear MLS fit over
  /// the fluid round its ghost point (value there, and continued to the particle); `grid` is
  /// binned at P's positions.
  void fit(const OpenScene& s, const Particles& P, const CellGrid& grid, SolverCounters& cnt);
  /// Buffer velocities for the step to t_mid (its middle): the inlet's profile, the fluid's fitted
  /// velocity at an outlet.
  void set_velocities(const OpenScene& s, Particles& P, real t_mid) const;
  /// Buffer pressures and densities from the fluid's current pressure (inlet: continued linearly;
  /// outlet: mirrored about the line's pressure).
  void set_pressures(const OpenScene& s, Particles& P) const;
  /// Moves the buffer particles along their zone's normal by dt times their normal velocity.
  void move(const OpenScene& s, Particles& P, real dt) const;
  /// Converts, deletes and creates particles at the open boundaries (end of step, index order).
  void transfer(const OpenScene& s, Particles& P);
  /// Takes out every body whose surface has reached the screen of an outlet that removes bodies
  /// (at time t).
  void remove_bodies_at_outlets(const OpenScene& s, Particles& P, std::vector<RigidGroup>& groups, real t);

  /// The buffer particles of this step (indices into the particles).
  const std::vector<std::uint32_t>& buffer() const { return buffer_; }
  /// What crossed each open boundary (inlets, then outlets) since the start of the run.
  const std::vector<OpenFlux>& flux() const { return flux_; }
  /// Restores the fluxes of a checkpoint (one per open boundary).
  void set_flux(const std::vector<OpenFlux>& f) { flux_ = f; }
  /// The bodies removed in the last step (empty in most steps), for the run log.
  const std::vector<BodyRemoval>& removed_in_last_step() const { return removed_now_; }

 private:
  struct CreatedParticle {
    Vec2 x, v;
    real p, rho, m;
    Kind kind;
  };
  /// The zone of a buffer particle of kind `k` at x: the zone of that kind whose line is nearest.
  static int zone_of(const PhysicsParams& prm, Vec2 x, Kind k);
  /// The inlet's inflow speed at distance s along it, at time t.
  static real inlet_speed(const PhysicsParams& prm, std::size_t zone, real s, real t);
  /// Appends `created` at the end of the fluid block, with new ids (Particles::next_id).
  static void append_created(Particles& P, const std::vector<CreatedParticle>& created);
  /// Takes body group k out of the run at open boundary z: its particles leave the boundary block
  /// and fluid particles fill the place it held (docs/method.md, "Bodies removed at an outlet").
  void remove_body(const OpenScene& s, Particles& P, std::vector<RigidGroup>& groups, std::size_t k, std::size_t z,
                   real t);

  // the buffer particles of this step, their zones, and the CSR of their ghost fits (fluid
  // particle, coefficient of the value at the ghost point, of the value continued to the particle)
  std::vector<std::uint32_t> buffer_;
  std::vector<int> buffer_zone_;
  std::vector<std::uint32_t> ghost_start_{0}, ghost_j_;
  std::vector<real> ghost_val_, ghost_lin_;
  std::vector<OpenFlux> flux_;
  // scratch of the fits and the transfer (kept between steps: the step loop allocates nothing once grown)
  std::vector<std::uint32_t> fit_j_;
  std::vector<Vec2> fit_d_;
  std::vector<real> fit_w_;
  std::vector<CreatedParticle> created_;
  std::vector<BodyRemoval> removed_now_;
  std::vector<unsigned char> keep_;
};

}  // namespace particula
