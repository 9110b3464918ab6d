// The CUDA backend's fluid passes of a step: derivatives, the Rhie-Chow term and momentum,
// continuity, the single-layer wall pressure (P.20 and its guards), the end-of-step update,
// shifting, the surface guard and the health check. Each kernel calls the PARTICULA_HD function
// of solver/sweeps.hpp that the CPU loop in src/solver/cpu_backend.cpp calls.
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/reduce.h>

#include <climits>

#include "cuda_backend.cuh"

namespace particula::gpu {

void CudaBackend::start_of_step_derivatives() {
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

void CudaBackend::pressure_gradient() {
  const SweepContext c = context();
  const real* p = p_.data();
  const real* rho = rho_.data();
  Vec2* G = G_.data();
  each(0, n_, [=] __device__(std::size_t i) { G[i] = pressure_gradient_at(c, i, p, rho); });
}

void CudaBackend::rhie_chow_and_momentum(StageStart from, const StageParams& s) {
  const SweepContext c = context();
  const real* p = p_.data();
  const real* rho = rho_.data();
  const Vec2* G = G_.data();
  const Mat2* gradV = gradV_.data();
  const Vec2* lapV = lapV_.data();
  const Vec2* v_start = (from == StageStart::StepStart ? v_n_ : v_s_).data();
  Vec2* v = v_.data();
  real* rc = rc_.data();
  Vec2* odd_even = odd_even_.data();
  odd_even_written_ = s.kappa > 0;  // rhie_chow_and_momentum_at writes it only then
  each(0, n_, [=] __device__(std::size_t i) {
    rhie_chow_and_momentum_at(c, i, p, rho, G, gradV, lapV, v_start, s, rc, v, odd_even);
  });
}

void CudaBackend::derivatives_and_continuity(StageStart from, const StageParams& s) {
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

void CudaBackend::boundary_pressure(int sweeps, const StageParams& s, SolverCounters& cnt) {
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
      const WallPressureOutcome o = wall_pressure_at(c, i, p, rho, normal[i], acc[i], s.nu * lapV[i], s.f,
                                                     min_den, void_distance, s.p0, p_new[i]);
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
    if (lone[i] && isolated_pressure_at(c, i, p, p[i]))
      rho[i] = density_from_pressure(p[i], s.rho0, s.c, s.p0);
  });
  collect_counters(cnt);
}

real CudaBackend::end_of_step(real dt, bool single_layer) {
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
    v2[i] = end_of_step_update(i, nb, kind[i], domain, dt, single_layer, v_n[i], rho_n[i], p_n[i], x[i], v[i],
                               rho[i], p[i]);
  });
  return thrust::reduce(thrust::device, scratch_real_.begin(), scratch_real_.end(), 0.0,
                        thrust::maximum<real>());
}

void CudaBackend::shift(real scale, real c_sound) {
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
  const SurfaceArrays surfaces{x, normal_.data(), wedge_.data(), ds_.data(), v};
  const Kind* kind = kind_.data();
  const OpenZone* zones = zones_.data();
  const std::size_t nz = zones_.size();
  const real range = d0_, h = kernel_.h;
  each(nb_, n_, [=] __device__(std::size_t i) {
    if (kind[i] != Kind::Fluid) return;  // buffers move with their boundary
    Vec2 d = dir[i];
    limit_shift_at_open_lines(zones, nz, x[i], h, d);
    shift_particle(d, scale, gradV[i], G[i], gather_surfaces(near_a[i], near_b[i], surfaces), range,
                   domain, c_sound, x[i], v[i], p[i], rho[i]);
  });
}

void CudaBackend::guard_surfaces(real keep, SolverCounters& cnt) {
  const std::uint32_t* near_a = near_a_.data();
  const std::uint32_t* near_b = near_b_.data();
  const Domain domain = grid_.domain;
  Vec2* x = x_.data();
  Vec2* v = v_.data();
  const SurfaceArrays surfaces{x, normal_.data(), wedge_.data(), ds_.data(), v};
  unsigned long long* counters = counters_.data();
  const Kind* kind = kind_.data();
  each(nb_, n_, [=] __device__(std::size_t i) {
    if (kind[i] != Kind::Fluid) return;
    const GuardOutcome o = surface_guard_at(i, near_a, near_b, surfaces, x, v, keep, domain);
    if (o == GuardOutcome::Pushed) atomicAdd(&counters[kSurfacePushed], 1ull);
    if (o == GuardOutcome::Gap) atomicAdd(&counters[kGapSqueezed], 1ull);
  });
  collect_counters(cnt);
}

std::int64_t CudaBackend::unhealthy_id(const HealthLimits& lim) {
  const Vec2* x = x_.data();
  const Vec2* v = v_.data();
  const real* rho = rho_.data();
  const real* p = p_.data();
  const std::int64_t* id = id_.data();
  const Kind* kind = kind_.data();
  unsigned long long* worst = counters_.data() + kUnhealthy;
  const unsigned long long none = ULLONG_MAX;
  check(cudaMemcpy(worst, &none, sizeof none, cudaMemcpyHostToDevice), "health");
  each(0, n_, [=] __device__(std::size_t i) {
    // Fluid by kind, as on the CPU: the buffer particles of open boundaries lie outside the
    // domain and carry the boundary's prescribed state, not a density to check.
    if (particle_unhealthy(kind[i] == Kind::Fluid, x[i], v[i], rho[i], p[i], lim))
      atomicMin(worst, static_cast<unsigned long long>(id[i]));
  });
  unsigned long long w = 0;
  check(cudaMemcpy(&w, worst, sizeof w, cudaMemcpyDeviceToHost), "health");
  return w == none ? -1 : static_cast<std::int64_t>(w);
}

}  // namespace particula::gpu
