// The CUDA backend (`--backend cuda`): the particle state lives on the GPU and every
// per-particle pass is a kernel that calls the same PARTICULA_HD function as the CPU loop in
// src/solver/solver_passes.cpp (solver/sweeps.hpp for the physics, neighbors/neighbor_list.hpp for
// the search). One thread per particle; every neighbour sum is a gather in list order, and the
// list is built in the CPU's order (cells sorted stably by index, neighbour cells in the same
// order), so the GPU computes the same sums in the same order as the CPU. The list and the pair
// weights are stored column-major (ELL: neighbour q of particle i at q n + i) instead of the
// CPU's CSR rows, so that the loads of a warp are coalesced.
#include <cuda_runtime.h>
#include <thrust/binary_search.h>
#include <thrust/device_ptr.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include <climits>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "particula/solver/device_backend.hpp"
#include "particula/solver/solver.hpp"

namespace particula {

namespace {

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e));
}

/// A device array that only grows (no allocation once the sizes have settled).
template <class T>
class DArray {
 public:
  DArray() = default;
  DArray(const DArray&) = delete;
  DArray& operator=(const DArray&) = delete;
  ~DArray() {
    if (p_) cudaFree(p_);
  }
  void resize(std::size_t n) {
    if (n > cap_) {
      if (p_) check(cudaFree(p_), "cudaFree");
      p_ = nullptr;
      check(cudaMalloc(&p_, std::max<std::size_t>(n, 1) * sizeof(T)), "cudaMalloc");
      cap_ = n;
    }
    n_ = n;
  }
  T* data() { return p_; }
  const T* data() const { return p_; }
  std::size_t size() const { return n_; }
  void upload(const std::vector<T>& v) {
    resize(v.size());
    if (!v.empty()) check(cudaMemcpy(p_, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
  }
  void download(std::vector<T>& v) const {
    v.resize(n_);
    if (n_) check(cudaMemcpy(v.data(), p_, n_ * sizeof(T), cudaMemcpyDeviceToHost), "download");
  }
  void copy_from(const DArray& o) {
    resize(o.n_);
    if (n_) check(cudaMemcpy(p_, o.p_, n_ * sizeof(T), cudaMemcpyDeviceToDevice), "copy");
  }
  thrust::device_ptr<T> begin() { return thrust::device_pointer_cast(p_); }
  thrust::device_ptr<T> end() { return thrust::device_pointer_cast(p_ + n_); }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0, cap_ = 0;
};

template <class F>
__global__ void each_kernel(std::size_t first, std::size_t last, F f) {
  const std::size_t i = first + static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < last) f(i);
}

/// Runs f(i) for i in [first, last), one thread each.
template <class F>
void each(std::size_t first, std::size_t last, F f) {
  if (last <= first) return;
  const std::size_t n = last - first;
  constexpr unsigned block = 128;
  each_kernel<<<static_cast<unsigned>((n + block - 1) / block), block>>>(first, last, f);
  check(cudaGetLastError(), "kernel launch");
}

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

/// One block per rigid group: the P.26-P.27 loads as a block reduction (fixed order for a given
/// block size, so the result is reproducible run to run).
constexpr int kLoadBlock = 256;
__global__ void group_loads_kernel(const GroupRange* ranges, const Kind* kind, const real* p, const real* ds,
                                   const Vec2* normal, const Mat2* gradV, const Vec2* x, Domain domain, real mu,
                                   GroupLoads* out) {
  __shared__ real s[5][kLoadBlock];
  const GroupRange r = ranges[blockIdx.x];
  real a[5] = {0, 0, 0, 0, 0};
  for (std::uint32_t k = threadIdx.x; k < r.count; k += blockDim.x) {
    const std::uint32_t i = r.first + k;
    if (kind[i] != Kind::Boundary) continue;
    Vec2 tp, tv;
    surface_traction(p[i], ds[i], normal[i], gradV[i], mu, tp, tv);
    a[0] += tp.x;
    a[1] += tp.y;
    a[2] += tv.x;
    a[3] += tv.y;
    a[4] += cross(domain.separation(x[i], r.pos), tp + tv);
  }
  for (int q = 0; q < 5; ++q) s[q][threadIdx.x] = a[q];
  __syncthreads();
  for (int stride = kLoadBlock / 2; stride > 0; stride /= 2) {
    if (static_cast<int>(threadIdx.x) < stride)
      for (int q = 0; q < 5; ++q) s[q][threadIdx.x] += s[q][threadIdx.x + stride];
    __syncthreads();
  }
  if (threadIdx.x == 0) {
    GroupLoads g;
    g.force_pressure = Vec2{s[0][0], s[1][0]};
    g.force_viscous = Vec2{s[2][0], s[3][0]};
    g.torque = s[4][0];
    out[blockIdx.x] = g;
  }
}

enum Counter {
  kSingularB = 0, kSingularBhat, kWallKept, kWallExtrapolated, kWallExtrapolatedFar, kNormalFallback, kSurfacePushed,
  kGapSqueezed, kIsolatedLeftOut, kSparseSupport, kWallVoid,
  kUnhealthy,
  kCounters
};

class CudaBackend final : public DeviceBackend {
 public:
  CudaBackend(const PhysicsParams& prm, const GridGeometry& grid, const WendlandC2& kernel, const Particles& P)
      : grid_(grid), kernel_(kernel), d0_(prm.d0), film_gap_(prm.film_gap * prm.d0), kernel_normals_(prm.kernel_normals),
        fatehi_manzari_(prm.fatehi_manzari), zeroth_order_gradient_(prm.zeroth_order_gradient), single_layer_(prm.single_layer) {
    counters_.resize(kCounters);
    zero_counters();
    zones_.upload(prm.open);  // the open lines, for the shifting limit next to them
    // Surface particles are addressed through their group index: check the layout once.
    for (std::size_t i = 0; i < P.n_boundary; ++i)
      if (P.group[i] < 0) throw std::logic_error("cuda backend: boundary particle without a rigid group");
  }

  void upload(const Particles& P) override {
    n_ = P.size();
    nb_ = P.n_boundary;
    x_.upload(P.x);
    v_.upload(P.v);
    rho_.upload(P.rho);
    p_.upload(P.p);
    m_.upload(P.m);
    kind_.upload(P.kind);
    group_.upload(P.group);
    id_.upload(P.id);
    local_.upload(P.local);
    normal_local_.upload(P.normal_local);
    ds_.upload(P.ds);
    acc_.upload(P.acc);
    normal_.upload(P.normal);
    source_.upload(P.source);
    for (auto* a : {&rho_n_, &rho_s_, &p_n_, &vol_, &rc_, &div_v_, &scratch_real_}) a->resize(n_);
    for (auto* a : {&v_n_, &v_s_, &lapV_, &G_, &shift_dir_}) a->resize(n_);
    for (auto* a : {&gradV_, &gradV_n_}) a->resize(n_);
    for (auto* a : {&near_a_, &near_b_}) a->resize(n_);
    film_.resize(n_);
    isolated_.resize(n_);
    p_new_.resize(nb_);
    count_.resize(n_);
    cell_of_.resize(n_);
    sorted_.resize(n_);
    keys_.resize(n_);
    cell_start_.resize(static_cast<std::size_t>(grid_.cell_count()) + 1);
  }

  void download(Particles& P) override {
    x_.download(P.x);
    v_.download(P.v);
    rho_.download(P.rho);
    p_.download(P.p);
    m_.download(P.m);
    kind_.download(P.kind);
    group_.download(P.group);
    id_.download(P.id);
    acc_.download(P.acc);
    normal_.download(P.normal);
  }

  void reorder_fluid() override {
    if (n_ == nb_) return;
    const std::size_t nf = n_ - nb_;
    const GridGeometry grid = grid_;
    const Vec2* x = x_.data() + nb_;
    std::uint32_t* keys = keys_.data();
    each(0, nf, [=] __device__(std::size_t k) { keys[k] = static_cast<std::uint32_t>(grid.cell_index(x[k])); });
    order_.resize(nf);
    thrust::sequence(thrust::device, order_.begin(), order_.end());
    thrust::stable_sort_by_key(thrust::device, keys_.begin(), keys_.begin() + nf, order_.begin());
    permute(x_);
    permute(v_);
    permute(rho_);
    permute(p_);
    permute(m_);
    permute(kind_);
    permute(group_);
    permute(id_);
  }

  void refresh_geometry(SolverCounters& cnt) override {
    const std::size_t n = n_;
    const GridGeometry grid = grid_;
    const Vec2* x = x_.data();
    // Bin: cell of every particle, indices sorted stably by cell, first particle of each cell.
    std::uint32_t* cell_of = cell_of_.data();
    std::uint32_t* keys = keys_.data();
    each(0, n, [=] __device__(std::size_t i) {
      cell_of[i] = keys[i] = static_cast<std::uint32_t>(grid.cell_index(x[i]));
    });
    thrust::sequence(thrust::device, sorted_.begin(), sorted_.end());
    thrust::stable_sort_by_key(thrust::device, keys_.begin(), keys_.begin() + n, sorted_.begin());
    const std::size_t ncell = static_cast<std::size_t>(grid.cell_count());
    thrust::lower_bound(thrust::device, keys_.begin(), keys_.begin() + n, thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(static_cast<std::uint32_t>(ncell + 1)),
                        cell_start_.begin());
    // Count, then fill: the list in the CPU's order, stored column-major (ELL): the q-th
    // neighbour of particle i at q * n + i, so that a warp's loads are coalesced.
    const real h2 = kernel_.h * kernel_.h;
    const std::uint32_t* sorted = sorted_.data();
    const std::uint32_t* cstart = cell_start_.data();
    std::uint32_t* count = count_.data();
    each(0, n, [=] __device__(std::size_t i) {
      std::uint32_t k = 0;
      visit_neighbors(grid, h2, x, sorted, cstart, cell_of[i], static_cast<std::uint32_t>(i),
                      [&](std::uint32_t, real) { ++k; });
      count[i] = k;
    });
    const std::uint32_t width = thrust::reduce(thrust::device, count_.begin(), count_.end(), 0u, thrust::maximum<std::uint32_t>());
    pairs_ = thrust::reduce(thrust::device, count_.begin(), count_.end(), std::size_t{0}, thrust::plus<std::size_t>());
    const std::size_t slots = static_cast<std::size_t>(width) * n;
    j_.resize(slots);
    grad_w_.resize(slots);
    lap_w_.resize(slots);
    std::uint32_t* jj = j_.data();
    real* dmin2 = scratch_real_.data();
    const Kind* kinds = kind_.data();
    each(0, n, [=] __device__(std::size_t i) {
      std::size_t q = i;
      real m = 1e300;
      visit_neighbors(grid, h2, x, sorted, cstart, cell_of[i], static_cast<std::uint32_t>(i), [&](std::uint32_t j, real d2) {
        jj[q] = j;
        q += n;
        // two buffer particles do not set the step (Solver::open_min_distance)
        if (!(is_buffer(kinds[i]) && is_buffer(kinds[j]))) m = d2 < m ? d2 : m;
      });
      dmin2[i] = m;
    });
    const real m2 = thrust::reduce(thrust::device, scratch_real_.begin(), scratch_real_.end(), 1e300, thrust::minimum<real>());
    min_distance_ = m2 < 1e299 ? std::sqrt(m2) : 0;

    // Volumes and the geometry sweep.
    const real* m = m_.data();
    const real* rho = rho_.data();
    real* vol = vol_.data();
    each(0, n, [=] __device__(std::size_t i) { vol[i] = m[i] / rho[i]; });
    const SweepContext c = context();
    const real d0 = d0_;
    const bool kernel_normals = kernel_normals_;
    const std::size_t nb = nb_;
    Vec2* grad_w = grad_w_.data();
    real* lap_w = lap_w_.data();
    Vec2* shift_dir = shift_dir_.data();
    std::uint32_t* near_a = near_a_.data();
    std::uint32_t* near_b = near_b_.data();
    Vec2* normal = normal_.data();
    const Kind* kind = kind_.data();
    unsigned long long* counters = counters_.data();
    std::uint8_t* isolated_out = isolated_.data();
    const real one_neighbour = d0 * d0 * kernel_.W(d0);
    each(0, n, [=] __device__(std::size_t i) {
      const GeometryAt g = geometry_at(c, i, d0, grad_w, lap_w);
      isolated_out[i] = i >= nb && kind[i] == Kind::Fluid && isolated(g.others_fluid_support, one_neighbour, g.near.a) ? 1 : 0;
      if (isolated_out[i]) atomicAdd(&counters[kIsolatedLeftOut], 1ull);
      shift_dir[i] = g.shift_direction;
      near_a[i] = g.near.a;
      near_b[i] = g.near.b;
      // dummies, and buffer particles whose support is one-sided by design, are not events
      if (kind[i] == Kind::Dummy || is_buffer(kind[i])) return;
      if (!g.B_ok) atomicAdd(&counters[kSingularB], 1ull);
      if (!g.Bhat_ok) atomicAdd(&counters[kSingularBhat], 1ull);
      if (g.sparse) atomicAdd(&counters[kSparseSupport], 1ull);
      if (i < nb && kernel_normals && kind[i] == Kind::Boundary && !kernel_normal(g.normal_sum, normal[i]))
        atomicAdd(&counters[kNormalFallback], 1ull);
    });
    // The unresolved-film fractions of this step (a second pass: the first one writes the normals).
    const SweepContext cf = context();
    const real film_gap = film_gap_;
    real* film = film_.data();
    each(0, n, [=] __device__(std::size_t i) { film[i] = film_fraction_at(cf, i, film_gap); });
    collect_counters(cnt);
  }

  std::size_t pair_count() const override { return pairs_; }
  real min_distance() const override { return min_distance_; }

  real max_speed() override {
    const real m2 = thrust::transform_reduce(
        thrust::device, v_.begin(), v_.end(), [] __device__(Vec2 v) -> real { return norm2(v); }, 0.0, thrust::maximum<real>());
    return std::sqrt(m2);
  }

  void save_stage_start(StageStart which) override {
    if (which == StageStart::StepStart) {
      v_n_.copy_from(v_);
      rho_n_.copy_from(rho_);
      p_n_.copy_from(p_);
    } else {
      v_s_.copy_from(v_);
      rho_s_.copy_from(rho_);
    }
  }

  void start_of_step_derivatives() override {
    const SweepContext c = context();
    const Vec2* v = v_.data();
    const real* p = p_.data();
    const real* rho = rho_.data();
    Mat2* gradV = gradV_.data();
    Vec2* lapV = lapV_.data();
    Vec2* G = G_.data();
    real* div_v = div_v_.data();
    each(0, n_, [=] __device__(std::size_t i) {
      store_velocity_derivatives(c, i, v, gradV, lapV, div_v);
      G[i] = pressure_gradient_at(c, i, p, rho);
    });
    gradV_n_.copy_from(gradV_);
  }

  void pressure_gradient() override {
    const SweepContext c = context();
    const real* p = p_.data();
    const real* rho = rho_.data();
    Vec2* G = G_.data();
    each(0, n_, [=] __device__(std::size_t i) { G[i] = pressure_gradient_at(c, i, p, rho); });
  }

  void rhie_chow_and_momentum(StageStart from, const StageParams& s) override {
    const SweepContext c = context();
    const real* p = p_.data();
    const real* rho = rho_.data();
    const Vec2* G = G_.data();
    const Mat2* gradV = gradV_.data();
    const Vec2* lapV = lapV_.data();
    const Vec2* v_start = (from == StageStart::StepStart ? v_n_ : v_s_).data();
    Vec2* v = v_.data();
    real* rc = rc_.data();
    each(0, n_, [=] __device__(std::size_t i) { rhie_chow_and_momentum_at(c, i, p, rho, G, gradV, lapV, v_start, s, rc, v); });
  }

  void derivatives_and_continuity(StageStart from, const StageParams& s) override {
    const SweepContext c = context();
    const Vec2* v = v_.data();
    const real* rho_start = (from == StageStart::StepStart ? rho_n_ : rho_s_).data();
    const real* rc = rc_.data();
    Mat2* gradV = gradV_.data();
    Vec2* lapV = lapV_.data();
    real* div_v = div_v_.data();
    real* rho = rho_.data();
    real* p = p_.data();
    each(0, n_, [=] __device__(std::size_t i) {
      derivatives_and_continuity_at(c, i, v, rho_start, rc, s, gradV, lapV, div_v, rho, p);
    });
  }

  void boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) override {
    const Kind* kind = kind_.data();
    real* p = p_.data();
    real* rho = rho_.data();
    if (!single_layer_) {
      const std::int32_t* source = source_.data();
      each(0, nb_, [=] __device__(std::size_t i) {
        if (kind[i] != Kind::Dummy) return;
        p[i] = p[source[i]];
        rho[i] = rho[source[i]];
      });
      return;
    }
    const SweepContext c = context();
    const Vec2* normal = normal_.data();
    const Vec2* acc = acc_.data();
    const Vec2* lapV = lapV_.data();
    real* p_new = p_new_.data();
    unsigned long long* counters = counters_.data();
    const real min_den = wall_pressure_min_den(s.rho0, c.kernel.h);
    const real void_distance = s.void_distance;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
      each(0, nb_, [=] __device__(std::size_t i) {
        p_new[i] = p[i];
        if (kind[i] != Kind::Boundary) return;
        const WallPressureOutcome o = wall_pressure_at(c, i, p, rho, normal[i], acc[i], s.nu * lapV[i], s.f, min_den,
                                                       void_distance, s.p0, p_new[i]);
        if (o == WallPressureOutcome::Kept) atomicAdd(&counters[kWallKept], 1ull);
        if (o == WallPressureOutcome::Extrapolated) atomicAdd(&counters[kWallExtrapolated], 1ull);
        if (o == WallPressureOutcome::ExtrapolatedFar) atomicAdd(&counters[kWallExtrapolatedFar], 1ull);
        if (o == WallPressureOutcome::Void) atomicAdd(&counters[kWallVoid], 1ull);
      });
      each(0, nb_, [=] __device__(std::size_t i) {
        if (kind[i] != Kind::Boundary) return;
        p[i] = p_new[i];
        rho[i] = density_from_pressure(p_new[i], s.rho0, s.c, s.p0);
      });
    }
    const std::uint8_t* lone = isolated_.data();
    each(nb_, n_, [=] __device__(std::size_t i) {
      if (lone[i] && isolated_pressure_at(c, i, p, p[i])) rho[i] = density_from_pressure(p[i], s.rho0, s.c, s.p0);
    });
    collect_counters(cnt);
  }

  void group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) override {
    ranges_host_.resize(groups.size());
    for (std::size_t k = 0; k < groups.size(); ++k) {
      ranges_host_[k].first = static_cast<std::uint32_t>(groups[k].first);
      ranges_host_[k].count = static_cast<std::uint32_t>(groups[k].count);
      ranges_host_[k].pos = groups[k].pos;
    }
    out.resize(groups.size());
    if (groups.empty()) return;
    ranges_.upload(ranges_host_);
    loads_.resize(groups.size());
    group_loads_kernel<<<static_cast<unsigned>(groups.size()), kLoadBlock>>>(
        ranges_.data(), kind_.data(), p_.data(), ds_.data(), normal_.data(), gradV_.data(), x_.data(), grid_.domain, mu,
        loads_.data());
    check(cudaGetLastError(), "group loads");
    loads_.download(out);
  }

  void download_positions(std::vector<Vec2>& x) override { x_.download(x); }

  void download_pressures(std::vector<real>& p) override { p_.download(p); }

  void set_buffer_particles(const std::vector<std::uint32_t>& index, const Particles& P) override {
    buffer_host_.resize(index.size());
    for (std::size_t k = 0; k < index.size(); ++k) {
      const std::uint32_t i = index[k];
      buffer_host_[k] = BufferState{i, P.x[i], P.v[i], P.p[i], P.rho[i]};
    }
    if (buffer_host_.empty()) return;
    buffer_.upload(buffer_host_);
    const BufferState* b = buffer_.data();
    Vec2* x = x_.data();
    Vec2* v = v_.data();
    real* p = p_.data();
    real* rho = rho_.data();
    each(0, buffer_host_.size(), [=] __device__(std::size_t k) {
      const BufferState s = b[k];
      x[s.i] = s.x;
      v[s.i] = s.v;
      p[s.i] = s.p;
      rho[s.i] = s.rho;
    });
  }

  void set_load_band(const std::vector<BandEntry>& band) override { band_.upload(band); }

  /// The constants of `scalars` with the device's arrays of the current stage.
  LoadArrays device_load_arrays(const LoadArrays& scalars) {
    LoadArrays a = scalars;
    a.x = x_.data();
    a.m = m_.data();
    a.rho = rho_.data();
    a.p = p_.data();
    a.grad_v = gradV_.data();
    a.lap_v = lapV_.data();
    a.grad_p_over_rho = G_.data();
    a.group_pos = group_pos_.data();
    a.group_level = group_level_.data();
    return a;
  }

  void band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) override {
    const LoadArrays a = device_load_arrays(scalars);
    const std::size_t ne = band_.size();
    band_fp_.resize(ne);
    const BandEntry* band = band_.data();
    Vec2* out = band_fp_.data();
    each(0, ne, [=] __device__(std::size_t e) { band_entry_level(a, band[e], out[e].x, out[e].y); });
    band_fp_.download(num_den);
  }

  void band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos, const std::vector<real>& group_level,
                  std::vector<Vec2>& fp, std::vector<Vec2>& fv, std::vector<Vec2>& torque) override {
    group_pos_.upload(group_pos);
    group_level_.upload(group_level);
    const LoadArrays a = device_load_arrays(scalars);
    const std::size_t ne = band_.size();
    band_fp_.resize(ne);
    band_fv_.resize(ne);
    band_torque_.resize(ne);
    const BandEntry* band = band_.data();
    Vec2* out_fp = band_fp_.data();
    Vec2* out_fv = band_fv_.data();
    Vec2* out_t = band_torque_.data();
    each(0, ne, [=] __device__(std::size_t e) { band_entry_load(a, band[e], out_fp[e], out_fv[e], out_t[e]); });
    band_fp_.download(fp);
    band_fv_.download(fv);
    band_torque_.download(torque);
  }

  void surface_motion(const std::vector<GroupMotion>& motions, bool place) override {
    if (motions.empty()) return;
    motions_.upload(motions);
    const GroupMotion* mo = motions_.data();
    const std::int32_t* group = group_.data();
    const Vec2* local = local_.data();
    const Vec2* normal_local = normal_local_.data();
    Vec2* x = x_.data();
    Vec2* v = v_.data();
    Vec2* acc = acc_.data();
    Vec2* normal = normal_.data();
    const Domain domain = grid_.domain;
    each(0, nb_, [=] __device__(std::size_t i) {
      const GroupMotion m = mo[group[i]];
      if (place) {
        x[i] = surface_position(domain, m, local[i]);
        normal[i] = rotate(normal_local[i], m.cos_angle, m.sin_angle);
      }
      surface_kinematics(m, local[i], v[i], acc[i]);
    });
  }

  real end_of_step(real dt, bool single_layer) override {
    const std::size_t nb = nb_;
    const Kind* kind = kind_.data();
    const Domain domain = grid_.domain;
    const Vec2* v_n = v_n_.data();
    const real* rho_n = rho_n_.data();
    const real* p_n = p_n_.data();
    Vec2* x = x_.data();
    Vec2* v = v_.data();
    real* rho = rho_.data();
    real* p = p_.data();
    real* v2 = scratch_real_.data();
    each(0, n_, [=] __device__(std::size_t i) {
      v2[i] = end_of_step_update(i, nb, kind[i], domain, dt, single_layer, v_n[i], rho_n[i], p_n[i], x[i], v[i], rho[i], p[i]);
    });
    return thrust::reduce(thrust::device, scratch_real_.begin(), scratch_real_.end(), 0.0, thrust::maximum<real>());
  }

  void shift(real scale, real c_sound) override {
    pressure_gradient();
    Mat2* gradV = gradV_.data();
    const Mat2* gradV_n = gradV_n_.data();
    each(0, n_, [=] __device__(std::size_t i) { gradV[i] = 0.5 * (gradV[i] + gradV_n[i]); });
    if (!(scale > 0)) return;
    const Vec2* dir = shift_dir_.data();
    const Vec2* G = G_.data();
    const Domain domain = grid_.domain;
    Vec2* x = x_.data();
    Vec2* v = v_.data();
    real* p = p_.data();
    real* rho = rho_.data();
    const std::uint32_t* near_a = near_a_.data();
    const std::uint32_t* near_b = near_b_.data();
    const Vec2* normal = normal_.data();
    const Kind* kind = kind_.data();
    const OpenZone* zones = zones_.data();
    const std::size_t nz = zones_.size();
    const real range = d0_, h = kernel_.h;
    each(nb_, n_, [=] __device__(std::size_t i) {
      if (kind[i] != Kind::Fluid) return;  // buffers move with their boundary
      Vec2 d = dir[i];
      limit_shift_at_open_lines(zones, nz, x[i], h, d);
      shift_particle(d, scale, gradV[i], G[i], gather_surfaces(near_a[i], near_b[i], x, normal, v), range, domain,
                     c_sound, x[i], v[i], p[i], rho[i]);
    });
  }

  void guard_surfaces(real keep, SolverCounters& cnt) override {
    const std::uint32_t* near_a = near_a_.data();
    const std::uint32_t* near_b = near_b_.data();
    const Vec2* normal = normal_.data();
    const Domain domain = grid_.domain;
    Vec2* x = x_.data();
    Vec2* v = v_.data();
    unsigned long long* counters = counters_.data();
    const Kind* kind = kind_.data();
    each(nb_, n_, [=] __device__(std::size_t i) {
      if (kind[i] != Kind::Fluid) return;
      const GuardOutcome o = surface_guard_at(i, near_a, near_b, x, normal, v, keep, domain);
      if (o == GuardOutcome::Pushed) atomicAdd(&counters[kSurfacePushed], 1ull);
      if (o == GuardOutcome::Gap) atomicAdd(&counters[kGapSqueezed], 1ull);
    });
    collect_counters(cnt);
  }

  std::int64_t unhealthy_id(const HealthLimits& lim) override {
    const std::size_t nb = nb_;
    const Vec2* x = x_.data();
    const Vec2* v = v_.data();
    const real* rho = rho_.data();
    const real* p = p_.data();
    const std::int64_t* id = id_.data();
    unsigned long long* worst = counters_.data() + kUnhealthy;
    const unsigned long long none = ULLONG_MAX;
    check(cudaMemcpy(worst, &none, sizeof none, cudaMemcpyHostToDevice), "health");
    each(0, n_, [=] __device__(std::size_t i) {
      if (particle_unhealthy(i >= nb, x[i], v[i], rho[i], p[i], lim))
        atomicMin(worst, static_cast<unsigned long long>(id[i]));
    });
    unsigned long long w = 0;
    check(cudaMemcpy(&w, worst, sizeof w, cudaMemcpyDeviceToHost), "health");
    return w == none ? -1 : static_cast<std::int64_t>(w);
  }

 // (public: nvcc's extended device lambdas may not live in private member functions)
  SweepContext context() const {
    SweepContext c;
    c.domain = grid_.domain;
    c.kernel = kernel_;
    c.start = nullptr;  // ELL layout
    c.count = count_.data();
    c.stride = n_;
    c.j = j_.data();
    c.n = n_;
    c.nb = nb_;
    c.x = x_.data();
    c.vol = vol_.data();
    c.kind = kind_.data();
    c.group = group_.data();
    c.normal = normal_.data();
    c.near_a = near_a_.data();
    c.near_b = near_b_.data();
    c.film = film_.data();
    c.isolated = isolated_.data();
    c.fatehi_manzari = fatehi_manzari_;
    c.zeroth_order_gradient = zeroth_order_gradient_;
    c.grad_w = grad_w_.data();
    c.lap_w = lap_w_.data();
    return c;
  }

  /// Applies the permutation order_ to the fluid block of a field.
  template <class T>
  void permute(DArray<T>& a) {
    const std::size_t nf = n_ - nb_;
    scratch_bytes_.resize(nf * sizeof(T));
    T* tmp = reinterpret_cast<T*>(scratch_bytes_.data());
    T* f = a.data() + nb_;
    const std::size_t* order = order_.data();
    each(0, nf, [=] __device__(std::size_t k) { tmp[k] = f[order[k]]; });
    check(cudaMemcpy(f, tmp, nf * sizeof(T), cudaMemcpyDeviceToDevice), "permute");
  }

  void zero_counters() { check(cudaMemset(counters_.data(), 0, kCounters * sizeof(unsigned long long)), "counters"); }

  void collect_counters(SolverCounters& cnt) {
    unsigned long long h[kCounters];
    check(cudaMemcpy(h, counters_.data(), sizeof h, cudaMemcpyDeviceToHost), "counters");
    cnt.singular_B += static_cast<std::int64_t>(h[kSingularB]);
    cnt.singular_Bhat += static_cast<std::int64_t>(h[kSingularBhat]);
    cnt.wall_pressure_kept += static_cast<std::int64_t>(h[kWallKept]);
    cnt.wall_pressure_extrapolated += static_cast<std::int64_t>(h[kWallExtrapolated]);
    cnt.wall_pressure_extrapolated_far += static_cast<std::int64_t>(h[kWallExtrapolatedFar]);
    cnt.normal_fallback += static_cast<std::int64_t>(h[kNormalFallback]);
    cnt.surface_pushed += static_cast<std::int64_t>(h[kSurfacePushed]);
    cnt.gap_squeezed += static_cast<std::int64_t>(h[kGapSqueezed]);
    cnt.isolated_left_out += static_cast<std::int64_t>(h[kIsolatedLeftOut]);
    cnt.sparse_support += static_cast<std::int64_t>(h[kSparseSupport]);
    cnt.wall_pressure_void += static_cast<std::int64_t>(h[kWallVoid]);
    zero_counters();
  }

 private:
  GridGeometry grid_;
  WendlandC2 kernel_;
  real d0_, film_gap_;
  bool kernel_normals_, fatehi_manzari_, zeroth_order_gradient_, single_layer_;
  std::size_t n_ = 0, nb_ = 0, pairs_ = 0;
  real min_distance_ = 0;

  // particle state
  DArray<Vec2> x_, v_, local_, normal_local_, acc_, normal_;
  DArray<real> rho_, p_, m_, ds_;
  DArray<Kind> kind_;
  DArray<std::int32_t> group_, source_;
  DArray<std::int64_t> id_;
  // work arrays
  DArray<real> rho_n_, rho_s_, p_n_, vol_, rc_, div_v_, p_new_, scratch_real_;
  DArray<Vec2> v_n_, v_s_, lapV_, G_, shift_dir_, grad_w_;
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
  DArray<Vec2> group_pos_, band_fp_, band_fv_;
  DArray<Vec2> band_torque_;
  DArray<real> group_level_;
  DArray<GroupMotion> motions_;
  // open boundaries: the lines, and the buffer particles' fields set on the host
  DArray<OpenZone> zones_;
  std::vector<BufferState> buffer_host_;
  DArray<BufferState> buffer_;
};

}  // namespace

bool cuda_backend_available(std::string* why) {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    if (why)
      *why = std::string("no CUDA GPU is available (") + (e != cudaSuccess ? cudaGetErrorString(e) : "0 devices") + ")";
    return false;
  }
  if (why) why->clear();
  return true;
}

std::unique_ptr<DeviceBackend> make_cuda_backend(const PhysicsParams& prm, const GridGeometry& grid,
                                                 const WendlandC2& kernel, const Particles& P) {
  std::string why;
  if (!cuda_backend_available(&why)) throw std::runtime_error(why);
  return std::make_unique<CudaBackend>(prm, grid, kernel, P);
}

}  // namespace particula
