// The CUDA backend (`--backend cuda`): the particle state lives on the GPU and every
// per-particle pass is a kernel that calls the same PARTICULA_HD function as the CPU loop in
// src/solver/cpu_backend.cpp (solver/sweeps.hpp for the physics, neighbors/neighbor_list.hpp for
// the search). One thread per particle; every neighbour sum is a gather in list order, and the
// list is built in the CPU's order (cells sorted stably by index, neighbour cells in the same
// order), so the GPU computes the same sums in the same order as the CPU. The list and the pair
// weights are stored column-major (ELL: neighbour q of particle i at q n + i) instead of the
// CPU's CSR rows, so that the loads of a warp are coalesced.
//
// The class is declared here and defined in three translation units by responsibility:
// cuda_backend.cu (state, transfers, the neighbour list and geometry, counters), cuda_passes.cu
// (the fluid passes of a step) and cuda_bodies.cu (surfaces, body loads, open-boundary buffers).
#pragma once

#include <cstdint>
#include <vector>

#include "device_array.cuh"
#include "particula/solver/backend.hpp"
#include "particula/solver/solver.hpp"

namespace particula::gpu {

/// A buffer particle's fields as the host's open-boundary passes set them.
struct BufferState {
  std::uint32_t i = 0;
  Vec2 x, v;
  real p = 0, rho = 0;
};

struct GroupRange {
  std::uint32_t first = 0, count = 0;
  Vec2 pos;
};

/// Slots of the device's event counters (SolverCounters), and the health check's result.
enum Counter {
  kSingularB = 0,
  kSingularBhat,
  kWallKept,
  kWallExtrapolated,
  kWallExtrapolatedFar,
  kNormalFallback,
  kSurfacePushed,
  kGapSqueezed,
  kIsolatedLeftOut,
  kSparseSupport,
  kWallVoid,
  kUnhealthy,
  kCounters
};

class CudaBackend final : public Backend {
 public:
  CudaBackend(const PhysicsParams& prm, const GridGeometry& grid, const WendlandC2& kernel,
              const Particles& P);

  const char* name() const override { return "cuda"; }
  bool on_host() const override { return false; }
  // state and transfers (cuda_backend.cu)
  void upload(const Particles& P) override;
  void download(Particles& P) override;
  const std::vector<Vec2>& host_positions() override {
    x_.download(host_x_);
    return host_x_;
  }
  void download_pressures(std::vector<real>& p) override { p_.download(p); }
  void reorder_fluid() override;
  void refresh_geometry(SolverCounters& cnt, PhaseTimes& times) override;
  /// The neighbour list, volumes and geometry sweep on the device (refresh_geometry's work).
  void device_geometry(SolverCounters& cnt);
  const CellGrid& host_grid(const Particles& P) override;
  HostNeighbors band_neighbors(const std::vector<Vec2>& x) override;
  /// Nothing to do: the device's list build already leaves the pairs of two buffer particles out
  /// of min_distance (device_geometry).
  void skip_buffer_pairs_in_min_distance() override {}
  std::size_t pair_count() const override { return pairs_; }
  real min_distance() const override { return min_distance_; }
  real max_speed() override;
  void save_stage_start(StageStart which) override;

  // the fluid passes of a step (cuda_passes.cu)
  void start_of_step_derivatives() override;
  void pressure_gradient() override;
  void rhie_chow_and_momentum(StageStart from, const StageParams& s) override;
  void derivatives_and_continuity(StageStart from, const StageParams& s) override;
  void boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) override;
  real end_of_step(real dt, bool single_layer) override;
  void shift(real scale, real c_sound) override;
  void guard_surfaces(real keep, SolverCounters& cnt) override;
  std::int64_t unhealthy_id(const HealthLimits& lim) override;

  // surfaces, body loads and open-boundary buffers (cuda_bodies.cu)
  void group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) override;
  void set_buffer_particles(const std::vector<std::uint32_t>& index, const Particles& P) override;
  void set_load_band(const std::vector<BandEntry>& band) override {
    band_.upload(band);
    band_host_ = band;  // the slots the host sums the downloaded entries into
  }
  void band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) override;
  void band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                  const std::vector<real>& group_level, std::vector<Vec2>& fp, std::vector<Vec2>& fv,
                  std::vector<Vec2>& torque, std::vector<Vec2>& fd) override;
  void band_level_sums(const LoadArrays& scalars, const std::vector<std::size_t>& block_first,
                       std::vector<Vec2>& partial) override;
  void band_load_sums(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                      const std::vector<real>& group_level, const std::vector<std::uint8_t>& circle,
                      const std::vector<std::size_t>& block_first, std::vector<BandLoadSum>& partial) override;
  void surface_motion(const std::vector<GroupMotion>& motions, bool place) override;

  // (public: nvcc's extended device lambdas may not live in private member functions)
  /// The device's neighbour list and geometry as the sweeps of sweeps.hpp read them.
  SweepContext context() const;
  /// The constants of `scalars` with the device's arrays of the current stage.
  LoadArrays device_load_arrays(const LoadArrays& scalars);
  /// Applies the permutation order_ to the fluid block of a field.
  template <class T>
  void permute(DArray<T>& a);
  void zero_counters() {
    check(cudaMemset(counters_.data(), 0, kCounters * sizeof(unsigned long long)), "counters");
  }
  /// Adds the device's event counts to `cnt` and zeroes them.
  void collect_counters(SolverCounters& cnt);

 private:
  GridGeometry grid_;
  CellGrid host_grid_;  // the host's binning of the downloaded positions (open boundaries' fits)
  std::vector<Vec2> host_x_;  // the downloaded positions (host_positions)
  CellGrid band_grid_;        // the host's binning of host_x_ for the load band's Voronoi cells
  WendlandC2 kernel_;
  real d0_, film_gap_;
  bool kernel_normals_, fatehi_manzari_, zeroth_order_gradient_, single_layer_;
  bool odd_even_written_ = false;  // odd_even_ holds the damping's accelerations of the stage
  std::size_t n_ = 0, nb_ = 0, pairs_ = 0;
  real min_distance_ = 0;

  // particle state
  DArray<Vec2> x_, v_, local_, normal_local_, acc_, normal_;
  DArray<real> rho_, p_, m_, ds_, wedge_;
  DArray<Kind> kind_;
  DArray<std::int32_t> group_, source_;
  DArray<std::int64_t> id_;
  // work arrays
  DArray<real> rho_n_, rho_s_, p_n_, vol_, rc_, div_v_, p_new_, scratch_real_;
  DArray<Vec2> v_n_, v_s_, lapV_, G_, shift_dir_, grad_w_, odd_even_;
  DArray<Mat2> gradV_, gradV_n_;
  DArray<real> lap_w_, film_;
  DArray<std::uint8_t> isolated_;
  DArray<std::uint32_t> count_, j_, cell_of_, sorted_, keys_, cell_start_, near_a_, near_b_;
  DArray<std::size_t> order_;
  DArray<unsigned char> scratch_bytes_;
  DArray<unsigned long long> counters_;
  // bodies
  std::vector<GroupRange> ranges_host_;
  DArray<GroupRange> ranges_;
  DArray<GroupLoads> loads_;
  // band momentum loads (numerics.force = momentum): the step's entries, per-entry loads
  DArray<BandEntry> band_;
  std::vector<BandEntry> band_host_;
  std::vector<Vec2> entry_fp_, entry_fv_, entry_torque_, entry_fd_;  // downloaded per-entry loads (fp: levels too)
  DArray<Vec2> group_pos_, band_fp_, band_fv_, band_fd_;
  DArray<Vec2> band_torque_;
  DArray<real> group_level_;
  DArray<GroupMotion> motions_;
  // open boundaries: the lines, and the buffer particles' fields set on the host
  DArray<OpenZone> zones_;
  std::vector<BufferState> buffer_host_;
  DArray<BufferState> buffer_;
};

}  // namespace particula::gpu
