// The CPU backend: the particle passes of a step as OpenMP loops over the host particles, each
// calling the PARTICULA_HD functions of solver/sweeps.hpp (docs/architecture.md). It owns the
// cell grid, the neighbour list (CSR rows), the per-pair weights of the geometry sweep and the
// per-particle work arrays; the particles are the solver's own (transfers do nothing).
#pragma once

#include <cstdint>
#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/sweeps.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

class CpuBackend final : public Backend {
 public:
  /// Passes over `P` for the physics `prm` in `domain` (all three outlive the backend).
  CpuBackend(const PhysicsParams& prm, const Domain& domain, const WendlandC2& kernel, Particles& P);

  const char* name() const override { return "cpu"; }
  bool on_host() const override { return true; }
  void upload(const Particles&) override {}
  void download(Particles&) override {}

  void reorder_fluid() override;
  void refresh_geometry(SolverCounters& cnt, PhaseTimes& times) override;
  const CellGrid& host_grid(const Particles&) override { return grid_; }
  void skip_buffer_pairs_in_min_distance() override;
  std::size_t pair_count() const override { return nl_.pair_count(); }
  real min_distance() const override { return nl_.min_distance; }
  real max_speed() override;

  void save_stage_start(StageStart which) override;
  void start_of_step_derivatives() override;
  void pressure_gradient() override { compute_pressure_gradient(P_.p, P_.rho); }
  void rhie_chow_and_momentum(StageStart from, const StageParams& s) override;
  void derivatives_and_continuity(StageStart from, const StageParams& s) override;
  void boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) override;

  void group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) override;
  const std::vector<Vec2>& host_positions() override { return P_.x; }
  /// The step's neighbour list, built at the particles' positions (`x`).
  HostNeighbors band_neighbors(const std::vector<Vec2>&) override {
    return HostNeighbors{&nl_, &grid_, kernel_.h * kernel_.h};
  }
  void download_pressures(std::vector<real>&) override {}
  void set_buffer_particles(const std::vector<std::uint32_t>&, const Particles&) override {}
  void set_load_band(const std::vector<BandEntry>& band) override;
  void band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) override;
  /// Fused: each entry's level added into its slot as it is evaluated (no per-entry array).
  void band_level_sums(const LoadArrays& scalars, const std::vector<std::size_t>& block_first,
                       std::vector<Vec2>& partial) override;
  /// Fused: each entry's load added into its slot as it is evaluated (no per-entry arrays).
  void band_load_sums(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                      const std::vector<real>& group_level, const std::vector<std::uint8_t>& circle,
                      const std::vector<std::size_t>& block_first,
                      std::vector<BandLoadSum>& partial) override;
  void band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                  const std::vector<real>& group_level, std::vector<Vec2>& fp, std::vector<Vec2>& fv,
                  std::vector<Vec2>& torque, std::vector<Vec2>& fd) override;
  void surface_motion(const std::vector<GroupMotion>& motions, bool place) override;

  real end_of_step(real dt, bool single_layer) override;
  void shift(real scale, real c) override;
  void guard_surfaces(real keep, SolverCounters& cnt) override;
  std::int64_t unhealthy_id(const HealthLimits& limits) override;

  // The host's view of the step (tests, benchmarks).
  const CellGrid& grid() const { return grid_; }
  const NeighborList& neighbors() const { return nl_; }
  const std::vector<Mat2>& B() const { return B_; }
  const std::vector<Mat2>& Bhat() const { return Bhat_; }
  const std::vector<Mat2>& grad_v() const { return gradV_; }
  const std::vector<Vec2>& lap_v() const { return lapV_; }
  const std::vector<Vec2>& grad_p_over_rho() const { return G_; }
  /// The odd-even damping's accelerations of the current stage, or null when the stage wrote none.
  const Vec2* odd_even() const {
    return prm_.odd_even_damping > 0 && odd_even_.size() == P_.size() ? odd_even_.data() : nullptr;
  }
  /// The arrays every sweep reads (neighbour list, positions, volumes, B, Bhat) as plain
  /// pointers for the per-particle functions of solver/sweeps.hpp.
  SweepContext sweep_context() const;
  /// Velocity derivatives of `v` and, when `G_out` is set, the pressure gradient, in one sweep.
  void derivatives_sweep(const std::vector<Vec2>& v, std::vector<Vec2>* G_out);
  /// The velocity derivatives of `v` on the current neighbour list.
  void compute_velocity_derivatives(const std::vector<Vec2>& v) { derivatives_sweep(v, nullptr); }
  /// The pressure gradient of the given fields on the current neighbour list.
  void compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho);

 private:
  void update_volumes();
  /// B, Bhat, normals (P.18), the pair weights, the nearest surfaces and the film fractions.
  void geometry_sweep(SolverCounters& cnt);
  /// The dummy-particle baseline: dummies copy P and rho of their nearest surface particle.
  void copy_to_dummies();
  /// Isolated fluid particles take their pressure from the surfaces around them.
  void isolated_pressures();
  /// Whether x lies beyond an open boundary's line, in its buffer.
  bool in_open_buffer(Vec2 x) const;
  /// Takes the normal part out of the shifting direction of fluid particles within h of an open line.
  void limit_shifting_at_open_lines();
  /// The surface particles as the surface guard and the shifting limit read them.
  SurfaceArrays surface_arrays() const;
  /// The constants of `scalars` with the host's particles and fields of the current stage.
  LoadArrays band_arrays(const LoadArrays& scalars) const;

  const PhysicsParams& prm_;
  const Domain& domain_;
  const WendlandC2& kernel_;
  Particles& P_;
  CellGrid grid_;
  NeighborList nl_;
  // per-particle work arrays (sized once; the step loop allocates nothing)
  std::vector<real> vol_, rbar_, rc_, rho_n_, rho_s_, div_v_, p_n_, p_new_;
  std::vector<Mat2> B_, Bhat_, gradV_, gradV_n_;
  std::vector<Vec2> lapV_, G_, v_n_, v_s_, shift_dir_;
  std::vector<Vec2> odd_even_;  // the odd-even damping's acceleration of the stage (band sums)
  std::vector<std::uint32_t> near_a_, near_b_;  // nearest surface particles (surface guard)
  std::vector<real> film_;                      // unresolved-film fraction of each particle, this step
  std::vector<std::uint8_t> isolated_;          // 1: isolated fluid particle this step (left out of P.20)
  // per-pair weights of the geometry sweep (solver/sweeps.hpp)
  std::vector<Vec2> pair_grad_w_;
  std::vector<real> pair_lap_w_;
  // the band entries of the step (set_load_band), evaluated by band_levels and band_loads
  std::vector<BandEntry> band_;
  // reordering scratch
  std::vector<std::uint32_t> reorder_key_;
  std::vector<std::size_t> reorder_order_;
  std::vector<unsigned char> reorder_scratch_;
};

}  // namespace particula
