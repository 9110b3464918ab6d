// The particle passes of a step on the host, in D dimensions: OpenMP loops over the particles,
// each calling the PARTICULA_HD functions of solver/sweeps.hpp. It owns the cell grid, the
// neighbour list (CSR rows), the per-pair weights of the geometry sweep and the per-particle work
// arrays; the particles are the solver's own. The CPU backend of the 2D solver
// (solver/cpu_backend.hpp) runs its fluid passes through `CpuSweepsOf<2>` and adds what is 2D
// only (open boundaries, the load band, the rigid surfaces' motion); the 3D passes are the same
// loops instantiated for D = 3.
#pragma once

#include <cstdint>
#include <vector>

#include "particula/core/types.hpp"
#include "particula/core/types3.hpp"
#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/counters.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/sweeps.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

template <int D>
class CpuSweepsOf {
 public:
  /// Passes over `P` for the fluid `prm` in `domain` (all four outlive the passes); the cell grid
  /// reaches `margin` beyond the domain (the buffers behind open boundaries).
  CpuSweepsOf(const FluidParamsOf<D>& prm, const DomainOf<D>& domain, const Wendland<D>& kernel,
              ParticlesOf<D>& P, real margin = 0);

  /// Stable reorder of the fluid block by cell (the particles' cells at the last binning).
  void reorder_fluid();
  /// Neighbour list, volumes and the geometry sweep (counts guarded events into `cnt`, times
  /// the phases into `times`).
  void refresh_geometry(SolverCounters& cnt, PhaseTimes& times);
  /// Leaves the pairs of two buffer particles out of min_distance.
  void skip_buffer_pairs_in_min_distance();
  std::size_t pair_count() const { return nl_.pair_count(); }
  real min_distance() const { return nl_.min_distance; }
  real max_speed() const;

  /// V^n, rho^n, P^n (StepStart) or V*, rho* (Predicted) := the current values.
  void save_stage_start(StageStart which);
  /// Velocity derivatives of the current V and the pressure gradient, in one sweep; keeps
  /// grad V as the step-start gradient for shifting.
  void start_of_step_derivatives();
  void pressure_gradient() { compute_pressure_gradient(P_.p, P_.rho); }
  void rhie_chow_and_momentum(StageStart from, const StageParamsOf<D>& s);
  void derivatives_and_continuity(StageStart from, const StageParamsOf<D>& s);
  /// P.20 on the surface particles, `sweeps` Jacobi sweeps (or the dummies' copy), then the
  /// isolated fluid particles' pressure. Outcomes other than Solved at surface particles flagged
  /// in `one_sided` (null: none; the tip of a wall continued through an open boundary's buffer,
  /// one-sided by design) are not counted.
  void boundary_pressure(int sweeps, const StageParamsOf<D>& s, SolverCounters& cnt,
                         const std::uint8_t* one_sided = nullptr);

  /// End-of-step averages (P.28); returns max |V|^2.
  real end_of_step(real dt, bool single_layer);
  /// Mean velocity gradient of the step, new pressure gradient, shift with `scale` = beta V_max dt
  /// along the shifting directions (shift_directions(), which the caller may limit first).
  void shift(real scale, real c);
  /// The surface guard on every fluid particle with keep-out distance `keep` (m); counts into `cnt`.
  void guard_surfaces(real keep, SolverCounters& cnt);
  /// Smallest id of an unhealthy particle, or -1.
  std::int64_t unhealthy_id(const HealthLimitsOf<D>& limits) const;

  // The host's view of the step (tests, benchmarks, the 2D backend's band and loads).
  const CellGridOf<D>& grid() const { return grid_; }
  const NeighborList& neighbors() const { return nl_; }
  const std::vector<Mat<D>>& B() const { return B_; }
  const std::vector<Mat<D>>& Bhat() const { return Bhat_; }
  const std::vector<Mat<D>>& grad_v() const { return gradV_; }
  const std::vector<Vec<D>>& lap_v() const { return lapV_; }
  const std::vector<Vec<D>>& grad_p_over_rho() const { return G_; }
  /// This step's shifting directions of the geometry sweep (P.33 before the factor beta V_max dt).
  std::vector<Vec<D>>& shift_directions() { return shift_dir_; }
  /// The odd-even damping's accelerations of the current stage, or null when the stage wrote none.
  const Vec<D>* odd_even() const {
    return prm_.odd_even_damping > 0 && odd_even_.size() == P_.size() ? odd_even_.data() : nullptr;
  }
  /// The arrays every sweep reads (neighbour list, positions, volumes, B, Bhat) as plain
  /// pointers for the per-particle functions of solver/sweeps.hpp.
  SweepContextOf<D> sweep_context() const;
  /// Velocity derivatives of `v` and, when `G_out` is set, the pressure gradient, in one sweep.
  void derivatives_sweep(const std::vector<Vec<D>>& v, std::vector<Vec<D>>* G_out);
  /// The pressure gradient of the given fields on the current neighbour list.
  void compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho);
  /// The surface particles as the surface guard and the shifting limit read them.
  SurfaceArraysOf<D> surface_arrays() const;

 private:
  void update_volumes();
  /// B, Bhat, normals (P.18), the pair weights, the nearest surfaces and the film fractions.
  void geometry_sweep(SolverCounters& cnt);
  /// The dummy-particle baseline: dummies copy P and rho of their nearest surface particle.
  void copy_to_dummies();
  /// Isolated fluid particles take their pressure from the surfaces around them.
  void isolated_pressures();

  const FluidParamsOf<D>& prm_;
  const DomainOf<D>& domain_;
  const Wendland<D>& kernel_;
  ParticlesOf<D>& P_;
  CellGridOf<D> grid_;
  NeighborList nl_;
  // per-particle work arrays (sized once; the step loop allocates nothing)
  std::vector<real> vol_, rbar_, rc_, rho_n_, rho_s_, div_v_, p_n_, p_new_;
  std::vector<Mat<D>> B_, Bhat_, gradV_, gradV_n_;
  std::vector<Vec<D>> lapV_, G_, v_n_, v_s_, shift_dir_;
  std::vector<Vec<D>> odd_even_;  // the odd-even damping's acceleration of the stage (band sums)
  std::vector<std::uint32_t> near_a_, near_b_;  // nearest surface particles (surface guard)
  std::vector<real> film_;                      // unresolved-film fraction of each particle, this step
  std::vector<std::uint8_t> isolated_;          // 1: isolated fluid particle this step (left out of P.20)
  // per-pair weights of the geometry sweep (solver/sweeps.hpp)
  std::vector<Vec<D>> pair_grad_w_;
  std::vector<real> pair_lap_w_;
  // reordering scratch
  std::vector<std::uint32_t> reorder_key_;
  std::vector<std::size_t> reorder_order_;
  std::vector<unsigned char> reorder_scratch_;
};

using CpuSweeps = CpuSweepsOf<2>;
using CpuSweeps3 = CpuSweepsOf<3>;

}  // namespace particula
