// The CUDA backend's bodies: the surfaces' motion, the loads on rigid groups (the P.26-P.27
// block reduction and the momentum band of numerics.force = momentum), and the fields of the
// open boundaries' buffer particles set on the host.
#include "cuda_backend.cuh"

namespace particula::gpu {

namespace {

/// One block per rigid group: the P.26-P.27 loads as a block reduction (fixed order for a given
/// block size, so the result is reproducible run to run).
constexpr int kLoadBlock = 256;
__global__ void group_loads_kernel(const GroupRange* ranges, const Kind* kind, const real* p, const real* ds,
                                   const Vec2* normal, const Mat2* gradV, const Vec2* x, Domain domain,
                                   real mu, GroupLoads* out) {
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

}  // namespace

void CudaBackend::surface_motion(const std::vector<GroupMotion>& motions, bool place) {
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

void CudaBackend::group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) {
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
      ranges_.data(), kind_.data(), p_.data(), ds_.data(), normal_.data(), gradV_.data(), x_.data(),
      grid_.domain, mu, loads_.data());
  check(cudaGetLastError(), "group loads");
  loads_.download(out);
}

/// The constants of `scalars` with the device's arrays of the current stage.
LoadArrays CudaBackend::device_load_arrays(const LoadArrays& scalars) {
  LoadArrays a = scalars;
  a.x = x_.data();
  a.m = m_.data();
  a.rho = rho_.data();
  a.p = p_.data();
  a.grad_v = gradV_.data();
  a.lap_v = lapV_.data();
  // the damping's accelerations of the stage, written by this device's momentum pass (the host's
  // array is not: the host does not run that pass)
  a.odd_even = odd_even_written_ ? odd_even_.data() : nullptr;
  a.grad_p_over_rho = G_.data();
  a.group_pos = group_pos_.data();
  a.group_level = group_level_.data();
  return a;
}

void CudaBackend::band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) {
  const LoadArrays a = device_load_arrays(scalars);
  const std::size_t ne = band_.size();
  band_fp_.resize(ne);
  const BandEntry* band = band_.data();
  Vec2* out = band_fp_.data();
  each(0, ne, [=] __device__(std::size_t e) { band_entry_level(a, band[e], out[e].x, out[e].y); });
  band_fp_.download(num_den);
}

void CudaBackend::band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                             const std::vector<real>& group_level, std::vector<Vec2>& fp,
                             std::vector<Vec2>& fv, std::vector<Vec2>& torque, std::vector<Vec2>& fd) {
  group_pos_.upload(group_pos);
  group_level_.upload(group_level);
  const LoadArrays a = device_load_arrays(scalars);
  const std::size_t ne = band_.size();
  band_fp_.resize(ne);
  band_fv_.resize(ne);
  band_torque_.resize(ne);
  band_fd_.resize(ne);
  const BandEntry* band = band_.data();
  Vec2* out_fp = band_fp_.data();
  Vec2* out_fv = band_fv_.data();
  Vec2* out_t = band_torque_.data();
  Vec2* out_fd = band_fd_.data();
  each(0, ne, [=] __device__(std::size_t e) {
    band_entry_load(a, band[e], out_fp[e], out_fv[e], out_t[e], out_fd[e]);
  });
  band_fp_.download(fp);
  band_fv_.download(fv);
  band_torque_.download(torque);
  band_fd_.download(fd);
}

void CudaBackend::band_level_sums(const LoadArrays& scalars, const std::vector<std::size_t>& block_first,
                                  std::vector<Vec2>& partial) {
  band_levels(scalars, entry_fp_);
  sum_band_entry_levels(band_host_, block_first, entry_fp_, partial);
}

void CudaBackend::band_load_sums(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                                 const std::vector<real>& group_level, const std::vector<std::uint8_t>& circle,
                                 const std::vector<std::size_t>& block_first, std::vector<BandLoadSum>& partial) {
  band_loads(scalars, group_pos, group_level, entry_fp_, entry_fv_, entry_torque_, entry_fd_);
  sum_band_entry_loads(band_host_, block_first, circle, entry_fp_, entry_fv_, entry_torque_, entry_fd_, partial);
}

void CudaBackend::set_buffer_particles(const std::vector<std::uint32_t>& index, const Particles& P) {
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

}  // namespace particula::gpu
