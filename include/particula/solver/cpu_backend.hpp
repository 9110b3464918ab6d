// The CPU backend: the particle passes of a step as OpenMP loops over the host particles, each
// calling the PARTICULA_HD functions of solver/sweeps.hpp (docs/architecture.md). The fluid's
// passes, with the cell grid, the neighbour list, the pair weights and the work arrays, are
// `CpuSweeps` (solver/cpu_sweeps.hpp, written once for D = 2 and 3); this class adds the 2D
// solids' part (surface motion, loads, the load band's entries) and the open boundaries' share.
// The particles are the solver's own (transfers do nothing).
#pragma once

#include <cstdint>
#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/neighbors/neighbor_list.hpp"
#include "particula/solver/backend.hpp"
#include "particula/solver/cpu_sweeps.hpp"
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

  void reorder_fluid() override { sweeps_.reorder_fluid(); }
  void refresh_geometry(SolverCounters& cnt, PhaseTimes& times) override { sweeps_.refresh_geometry(cnt, times); }
  const CellGrid& host_grid(const Particles&) override { return sweeps_.grid(); }
  void skip_buffer_pairs_in_min_distance() override { sweeps_.skip_buffer_pairs_in_min_distance(); }
  std::size_t pair_count() const override { return sweeps_.pair_count(); }
  real min_distance() const override { return sweeps_.min_distance(); }
  real max_speed() override { return sweeps_.max_speed(); }

  void save_stage_start(StageStart which) override { sweeps_.save_stage_start(which); }
  void start_of_step_derivatives() override { sweeps_.start_of_step_derivatives(); }
  void pressure_gradient() override { sweeps_.pressure_gradient(); }
  void rhie_chow_and_momentum(StageStart from, const StageParams& s) override {
    sweeps_.rhie_chow_and_momentum(from, s);
  }
  void derivatives_and_continuity(StageStart from, const StageParams& s) override {
    sweeps_.derivatives_and_continuity(from, s);
  }
  void boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) override;

  void group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) override;
  const std::vector<Vec2>& host_positions() override { return P_.x; }
  /// The step's neighbour list, built at the particles' positions (`x`).
  HostNeighbors band_neighbors(const std::vector<Vec2>&) override {
    return HostNeighbors{&sweeps_.neighbors(), &sweeps_.grid(), kernel_.h * kernel_.h};
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

  real end_of_step(real dt, bool single_layer) override { return sweeps_.end_of_step(dt, single_layer); }
  void shift(real scale, real c) override;
  void guard_surfaces(real keep, SolverCounters& cnt) override { sweeps_.guard_surfaces(keep, cnt); }
  std::int64_t unhealthy_id(const HealthLimits& limits) override { return sweeps_.unhealthy_id(limits); }

  // The host's view of the step (tests, benchmarks).
  const CellGrid& grid() const { return sweeps_.grid(); }
  const NeighborList& neighbors() const { return sweeps_.neighbors(); }
  const std::vector<Mat2>& B() const { return sweeps_.B(); }
  const std::vector<Mat2>& Bhat() const { return sweeps_.Bhat(); }
  const std::vector<Mat2>& grad_v() const { return sweeps_.grad_v(); }
  const std::vector<Vec2>& lap_v() const { return sweeps_.lap_v(); }
  const std::vector<Vec2>& grad_p_over_rho() const { return sweeps_.grad_p_over_rho(); }
  /// The odd-even damping's accelerations of the current stage, or null when the stage wrote none.
  const Vec2* odd_even() const { return sweeps_.odd_even(); }
  /// The arrays every sweep reads (neighbour list, positions, volumes, B, Bhat) as plain
  /// pointers for the per-particle functions of solver/sweeps.hpp.
  SweepContext sweep_context() const { return sweeps_.sweep_context(); }
  /// Velocity derivatives of `v` and, when `G_out` is set, the pressure gradient, in one sweep.
  void derivatives_sweep(const std::vector<Vec2>& v, std::vector<Vec2>* G_out) {
    sweeps_.derivatives_sweep(v, G_out);
  }
  /// The velocity derivatives of `v` on the current neighbour list.
  void compute_velocity_derivatives(const std::vector<Vec2>& v) { sweeps_.derivatives_sweep(v, nullptr); }
  /// The pressure gradient of the given fields on the current neighbour list.
  void compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho) {
    sweeps_.compute_pressure_gradient(p, rho);
  }

 private:
  /// Whether x lies beyond an open boundary's line, in its buffer.
  bool in_open_buffer(Vec2 x) const;
  /// Takes the normal part out of the shifting direction of fluid particles within h of an open line.
  void limit_shifting_at_open_lines();
  /// The constants of `scalars` with the host's particles and fields of the current stage.
  LoadArrays band_arrays(const LoadArrays& scalars) const;

  const PhysicsParams& prm_;
  const Domain& domain_;
  const WendlandC2& kernel_;
  Particles& P_;
  CpuSweeps sweeps_;  // the fluid's passes (solver/cpu_sweeps.hpp)
  std::vector<std::uint8_t> one_sided_;  // surface particles in an open boundary's buffer (P.20 counts)
  // the band entries of the step (set_load_band), evaluated by band_levels and band_loads
  std::vector<BandEntry> band_;
};

}  // namespace particula
