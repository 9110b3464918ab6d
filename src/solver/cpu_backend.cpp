// The CPU backend (solver/cpu_backend.hpp): the fluid's passes are CpuSweeps' (cpu_sweeps.cpp);
// here are the open boundaries' share of them, the rigid surfaces' motion, their loads from the
// surface sums and the load band's entries, as OpenMP loops over the host particles.
#include "particula/solver/cpu_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "particula/boundary/open_boundary.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/solver/counters.hpp"
#include "particula/sph/operators.hpp"
#include "phase_timer.hpp"

namespace particula {

namespace {

/// The depth of the deepest buffer behind an open boundary: the cell grid reaches that far
/// beyond the domain.
real open_buffer_margin(const PhysicsParams& prm) {
  real margin = 0;
  for (const OpenZone& z : prm.open) margin = std::max(margin, z.depth);
  return margin;
}

}  // namespace

CpuBackend::CpuBackend(const PhysicsParams& prm, const Domain& domain, const WendlandC2& kernel, Particles& P)
    : prm_(prm),
      domain_(domain),
      kernel_(kernel),
      P_(P),
      sweeps_(prm, domain, kernel, P, open_buffer_margin(prm)) {}

bool CpuBackend::in_open_buffer(Vec2 x) const {
  for (const OpenZone& z : prm_.open)
    if (beyond_open_line(z, x)) return true;
  return false;
}

void CpuBackend::boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) {
  const std::uint8_t* one_sided = nullptr;
  if (!prm_.open.empty()) {
    one_sided_.resize(P_.n_boundary);
    for (std::size_t i = 0; i < P_.n_boundary; ++i) one_sided_[i] = in_open_buffer(P_.x[i]) ? 1 : 0;
    one_sided = one_sided_.data();
  }
  sweeps_.boundary_pressure(sweeps, s, cnt, one_sided);
}

void CpuBackend::shift(real scale, real c) {
  // the open lines' limit first: it changes only the shifting directions, which the shift alone reads
  if (scale > 0) limit_shifting_at_open_lines();
  sweeps_.shift(scale, c);
}
void CpuBackend::limit_shifting_at_open_lines() {
  if (prm_.open.empty()) return;
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  const OpenZone* zones = prm_.open.data();
  const std::size_t nz = prm_.open.size();
  const real h = prm_.h;
  Vec2* dir = sweeps_.shift_directions().data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (P_.kind[i] == Kind::Fluid) limit_shift_at_open_lines(zones, nz, P_.x[i], h, dir[i]);
}

// ---------------------------------------------------------------------------------------------
// Surfaces and loads

void CpuBackend::surface_motion(const std::vector<GroupMotion>& motions, bool place) {
  const std::size_t nb = P_.n_boundary;
  for (std::size_t i = 0; i < nb; ++i) {
    if (P_.group[i] < 0) continue;
    const GroupMotion& m = motions[static_cast<std::size_t>(P_.group[i])];
    if (place) {
      P_.x[i] = surface_position(domain_, m, P_.local[i]);
      // Analytic normal; replaced by P.18 in the geometry sweep when kernel normals are used.
      P_.normal[i] = rotate(P_.normal_local[i], m.cos_angle, m.sin_angle);
    }
    surface_kinematics(m, P_.local[i], P_.v[i], P_.acc[i]);
  }
}

void CpuBackend::group_loads(const std::vector<RigidGroup>& groups, real mu, std::vector<GroupLoads>& out) {
  out.assign(groups.size(), GroupLoads{});
  const std::vector<Mat2>& grad_v = sweeps_.grad_v();
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const RigidGroup& g = groups[k];
    GroupLoads& l = out[k];
    for (std::size_t i = g.first; i < g.first + g.count; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      Vec2 tp, tv;
      surface_traction(P_.p[i], P_.ds[i], P_.normal[i], grad_v[i], mu, tp, tv);
      l.force_pressure += tp;
      l.force_viscous += tv;
      l.torque += cross(domain_.separation(P_.x[i], g.pos), tp + tv);
    }
  }
}

void CpuBackend::set_load_band(const std::vector<BandEntry>& band) { band_ = band; }

LoadArrays CpuBackend::band_arrays(const LoadArrays& scalars) const {
  LoadArrays a = scalars;
  a.x = P_.x.data();
  a.m = P_.m.data();
  a.rho = P_.rho.data();
  a.p = P_.p.data();
  a.grad_v = sweeps_.grad_v().data();
  a.lap_v = sweeps_.lap_v().data();
  a.odd_even = odd_even();  // the damping's accelerations of the stage, or none
  a.grad_p_over_rho = sweeps_.grad_p_over_rho().data();
  return a;
}

namespace {

/// Calls share(e, sample) for every entry e of `band` with the sample of its particle, read once
/// for the consecutive entries of one particle; blocks of kBandBlock entries in parallel.
template <class Share>
void each_band_sample(const LoadArrays& a, const std::vector<BandEntry>& band, Share share) {
  const std::size_t ne = band.size(), nblocks = (ne + kBandBlock - 1) / kBandBlock;
#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < nblocks; ++b) {
    std::uint32_t sampled = std::numeric_limits<std::uint32_t>::max();
    BandSample s;
    for (std::size_t e = b * kBandBlock; e < std::min(ne, (b + 1) * kBandBlock); ++e) {
      if (band[e].particle != sampled) s = band_sample(a, sampled = band[e].particle, band[e].area);
      share(e, s);
    }
  }
}

}  // namespace

void CpuBackend::band_levels(const LoadArrays& scalars, std::vector<Vec2>& num_den) {
  const LoadArrays a = band_arrays(scalars);
  num_den.resize(band_.size());
  each_band_sample(a, band_, [&](std::size_t e, const BandSample& s) {
    band_share_level(s, band_[e].phi, num_den[e].x, num_den[e].y);
  });
}

void CpuBackend::band_loads(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                            const std::vector<real>& group_level, std::vector<Vec2>& fp,
                            std::vector<Vec2>& fv, std::vector<Vec2>& torque, std::vector<Vec2>& fd) {
  LoadArrays a = band_arrays(scalars);
  a.group_pos = group_pos.data();
  a.group_level = group_level.data();
  const std::size_t ne = band_.size();
  fp.resize(ne);
  fv.resize(ne);
  torque.resize(ne);
  fd.resize(ne);
  each_band_sample(a, band_, [&](std::size_t e, const BandSample& s) {
    band_entry_share(a, s, band_[e], fp[e], fv[e], torque[e]);
    fd[e] = band_share_damping(s, band_[e].phi);
  });
}

void CpuBackend::band_level_sums(const LoadArrays& scalars, const std::vector<std::size_t>& block_first,
                                 std::vector<Vec2>& partial) {
  const LoadArrays a = band_arrays(scalars);
  partial.assign(block_first.empty() ? 0 : block_first.back(), Vec2{});
  each_band_sample(a, band_, [&](std::size_t e, const BandSample& s) {
    Vec2 num_den;
    band_share_level(s, band_[e].phi, num_den.x, num_den.y);
    partial[block_first[e / kBandBlock] + band_[e].slot] += num_den;
  });
}

void CpuBackend::band_load_sums(const LoadArrays& scalars, const std::vector<Vec2>& group_pos,
                                const std::vector<real>& group_level, const std::vector<std::uint8_t>& circle,
                                const std::vector<std::size_t>& block_first,
                                std::vector<BandLoadSum>& partial) {
  LoadArrays a = band_arrays(scalars);
  a.group_pos = group_pos.data();
  a.group_level = group_level.data();
  partial.assign(block_first.empty() ? 0 : block_first.back(), BandLoadSum{});
  // each block's entries run on one thread in band order, the order sum_band_entry_loads adds in
  each_band_sample(a, band_, [&](std::size_t e, const BandSample& s) {
    const BandEntry& be = band_[e];
    Vec2 fp, fv, torque;
    band_entry_share(a, s, be, fp, fv, torque);
    add_band_entry_load(partial[block_first[e / kBandBlock] + be.slot], fp, fv, torque,
                        band_share_damping(s, be.phi),
                        circle[static_cast<std::size_t>(be.group)] && be.in_film);
  });
}

}  // namespace particula
