// The CUDA backend's state: construction, whole-state transfers, the fluid's reordering by cell,
// the neighbour list and the geometry sweep, the device's event counters; and the factory
// (the class and its layout: cuda_backend.cuh).
#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>

#include "cuda_backend.cuh"

namespace particula::gpu {

CudaBackend::CudaBackend(const PhysicsParams& prm, const GridGeometry& grid, const WendlandC2& kernel,
                         const Particles& P)
    : grid_(grid),
      kernel_(kernel),
      d0_(prm.d0),
      film_gap_(prm.film_gap * prm.d0),
      kernel_normals_(prm.kernel_normals),
      fatehi_manzari_(prm.fatehi_manzari),
      zeroth_order_gradient_(prm.zeroth_order_gradient),
      single_layer_(prm.single_layer) {
  counters_.resize(kCounters);
  zero_counters();
  real margin = 0;  // the buffers behind open boundaries lie outside the domain
  for (const OpenZone& z : prm.open) margin = std::max(margin, z.depth);
  host_grid_.setup(grid.domain, prm.h, margin);
  band_grid_.setup(grid.domain, prm.h);
  zones_.upload(prm.open);  // the open lines, for the shifting limit next to them
  // Surface particles are addressed through their group index: check the layout once.
  for (std::size_t i = 0; i < P.n_boundary; ++i)
    if (P.group[i] < 0) throw std::logic_error("cuda backend: boundary particle without a rigid group");
}

void CudaBackend::upload(const Particles& P) {
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
  wedge_.upload(P.wedge);
  source_.upload(P.source);
  for (auto* a : {&rho_n_, &rho_s_, &p_n_, &vol_, &rc_, &div_v_, &scratch_real_}) a->resize(n_);
  for (auto* a : {&v_n_, &v_s_, &lapV_, &G_, &shift_dir_, &odd_even_}) a->resize(n_);
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

void CudaBackend::download(Particles& P) {
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

/// Applies the permutation order_ to the fluid block of a field.
template <class T>
void CudaBackend::permute(DArray<T>& a) {
  const std::size_t nf = n_ - nb_;
  scratch_bytes_.resize(nf * sizeof(T));
  T* tmp = reinterpret_cast<T*>(scratch_bytes_.data());
  T* f = a.data() + nb_;
  const std::size_t* order = order_.data();
  each(0, nf, [=] __device__(std::size_t k) { tmp[k] = f[order[k]]; });
  check(cudaMemcpy(f, tmp, nf * sizeof(T), cudaMemcpyDeviceToDevice), "permute");
}

void CudaBackend::reorder_fluid() {
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

void CudaBackend::refresh_geometry(SolverCounters& cnt, PhaseTimes& times) {
  const auto t0 = std::chrono::steady_clock::now();
  device_geometry(cnt);
  times.geometry += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const CellGrid& CudaBackend::host_grid(const Particles& P) {
  host_grid_.bin(P.x);
  return host_grid_;
}

HostNeighbors CudaBackend::band_neighbors(const std::vector<Vec2>& x) {
  band_grid_.bin(x);
  return HostNeighbors{nullptr, &band_grid_, kernel_.h * kernel_.h};
}

void CudaBackend::device_geometry(SolverCounters& cnt) {
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
  thrust::lower_bound(
      thrust::device, keys_.begin(), keys_.begin() + n, thrust::counting_iterator<std::uint32_t>(0),
      thrust::counting_iterator<std::uint32_t>(static_cast<std::uint32_t>(ncell + 1)), cell_start_.begin());
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
  const std::uint32_t width =
      thrust::reduce(thrust::device, count_.begin(), count_.end(), 0u, thrust::maximum<std::uint32_t>());
  pairs_ = thrust::reduce(thrust::device, count_.begin(), count_.end(), std::size_t{0},
                          thrust::plus<std::size_t>());
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
    visit_neighbors(grid, h2, x, sorted, cstart, cell_of[i], static_cast<std::uint32_t>(i),
                    [&](std::uint32_t j, real d2) {
                      jj[q] = j;
                      q += n;
                      // two buffer particles do not set the step (Backend::skip_buffer_pairs_in_min_distance)
                      if (!(is_buffer(kinds[i]) && is_buffer(kinds[j]))) m = d2 < m ? d2 : m;
                    });
    dmin2[i] = m;
  });
  const real m2 = thrust::reduce(thrust::device, scratch_real_.begin(), scratch_real_.end(), 1e300,
                                 thrust::minimum<real>());
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
    isolated_out[i] =
        i >= nb && kind[i] == Kind::Fluid && isolated(g.others_fluid_support, one_neighbour, g.near.a) ? 1
                                                                                                       : 0;
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

real CudaBackend::max_speed() {
  const real m2 = thrust::transform_reduce(
      thrust::device, v_.begin(), v_.end(), [] __device__(Vec2 v) -> real { return norm2(v); }, 0.0,
      thrust::maximum<real>());
  return std::sqrt(m2);
}

void CudaBackend::save_stage_start(StageStart which) {
  if (which == StageStart::StepStart) {
    v_n_.copy_from(v_);
    rho_n_.copy_from(rho_);
    p_n_.copy_from(p_);
  } else {
    v_s_.copy_from(v_);
    rho_s_.copy_from(rho_);
  }
}

SweepContext CudaBackend::context() const {
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
  c.wedge = wedge_.data();
  c.ds = ds_.data();
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

void CudaBackend::collect_counters(SolverCounters& cnt) {
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

}  // namespace particula::gpu

namespace particula {

bool cuda_backend_available(std::string* why) {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    if (why)
      *why = std::string("no CUDA GPU is available (") +
             (e != cudaSuccess ? cudaGetErrorString(e) : "0 devices") + ")";
    return false;
  }
  if (why) why->clear();
  return true;
}

std::unique_ptr<Backend> make_cuda_backend(const PhysicsParams& prm, const GridGeometry& grid,
                                                 const WendlandC2& kernel, const Particles& P) {
  std::string why;
  if (!cuda_backend_available(&why)) throw std::runtime_error(why);
  return std::make_unique<gpu::CudaBackend>(prm, grid, kernel, P);
}

}  // namespace particula
