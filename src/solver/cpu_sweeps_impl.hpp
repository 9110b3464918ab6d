// The host's particle passes in D dimensions (solver/cpu_sweeps.hpp): OpenMP loops over the
// particles, each calling the PARTICULA_HD functions of sweeps.hpp; the time loop that orders
// them is Solver::step (solver.cpp, docs/method.md "One time step"). Instantiated for D = 2 and 3
// in one translation unit each (cpu_sweeps2.cpp, cpu_sweeps3.cpp), so that the 3D loops do not
// weigh on the compiler's inlining budget of the 2D ones.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>

#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/solver/cpu_sweeps.hpp"
#include "particula/sph/operators.hpp"
#include "phase_timer.hpp"

namespace particula {

template <int D>
CpuSweepsOf<D>::CpuSweepsOf(const FluidParamsOf<D>& prm, const DomainOf<D>& domain, const Wendland<D>& kernel,
                            ParticlesOf<D>& P, real margin)
    : prm_(prm), domain_(domain), kernel_(kernel), P_(P) {
  grid_.setup(domain_, prm_.h, margin);
}

// ---------------------------------------------------------------------------------------------
// Geometry: everything that depends on positions (and start-of-step volumes) only.

template <int D>
void CpuSweepsOf<D>::update_volumes() {
  const std::size_t n = P_.size();
  vol_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) vol_[i] = P_.m[i] / P_.rho[i];
}

template <int D>
SweepContextOf<D> CpuSweepsOf<D>::sweep_context() const {
  SweepContextOf<D> c;
  c.domain = domain_;
  c.kernel = kernel_;
  c.start = nl_.start.data();
  c.j = nl_.j.data();
  c.n = P_.size();
  c.nb = P_.n_boundary;
  c.x = P_.x.data();
  c.vol = vol_.data();
  c.kind = P_.kind.data();
  c.group = P_.group.data();
  c.normal = P_.normal.data();
  c.wedge = P_.wedge.data();
  c.ds = P_.ds.data();
  c.near_a = near_a_.empty() ? nullptr : near_a_.data();
  c.near_b = near_b_.empty() ? nullptr : near_b_.data();
  c.film = film_.empty() ? nullptr : film_.data();
  c.isolated = isolated_.empty() ? nullptr : isolated_.data();
  c.fatehi_manzari = prm_.fatehi_manzari;
  c.zeroth_order_gradient = prm_.zeroth_order_gradient;
  c.grad_w = pair_grad_w_.data();
  c.lap_w = pair_lap_w_.data();
  return c;
}

template <int D>
void CpuSweepsOf<D>::refresh_geometry(SolverCounters& cnt, PhaseTimes& times) {
  {
    PhaseTimer timer(times.neighbors);
    build_neighbor_list(P_.x, domain_, kernel_, grid_, nl_);
  }
  PhaseTimer timer(times.geometry);
  update_volumes();
  geometry_sweep(cnt);
}

template <int D>
void CpuSweepsOf<D>::geometry_sweep(SolverCounters& cnt) {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  B_.resize(n);
  Bhat_.resize(n);
  rbar_.resize(n);
  shift_dir_.resize(n);
  near_a_.resize(n);
  near_b_.resize(n);
  isolated_.resize(n);
  pair_grad_w_.resize(nl_.pair_count());
  pair_lap_w_.resize(nl_.pair_count());
  const SweepContextOf<D> c = sweep_context();
  Vec<D>* grad_w = pair_grad_w_.data();
  real* lap_w = pair_lap_w_.data();
  const bool kernel_normals = prm_.kernel_normals;
  const real one_neighbour = cell_volume<D>(prm_.d0) * kernel_.W(prm_.d0);
  std::uint8_t* isolated_out = isolated_.data();
  std::int64_t bad_B = 0, bad_Bhat = 0, bad_normal = 0, lone = 0, sparse = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad_B, bad_Bhat, bad_normal, lone, sparse)
  for (std::size_t i = 0; i < n; ++i) {
    const GeometryAtOf<D> g = geometry_at(c, i, prm_.d0, grad_w, lap_w);
    isolated_out[i] =
        i >= nb && P_.kind[i] == Kind::Fluid && isolated(g.others_fluid_support, one_neighbour, g.near.a) ? 1
                                                                                                          : 0;
    lone += isolated_out[i];
    B_[i] = g.B;
    Bhat_[i] = g.Bhat;
    rbar_[i] = g.rbar;
    shift_dir_[i] = g.shift_direction;
    near_a_[i] = g.near.a;
    near_b_[i] = g.near.b;
    // dummies, and buffer particles whose support is one-sided by design, are not events
    if (P_.kind[i] == Kind::Dummy || is_buffer(P_.kind[i])) continue;
    bad_B += g.B_ok ? 0 : 1;
    bad_Bhat += g.Bhat_ok ? 0 : 1;
    sparse += g.sparse ? 1 : 0;
    // P.18 normal; on failure the analytic normal set by the surfaces' placement stays.
    if (i < nb && kernel_normals && P_.kind[i] == Kind::Boundary &&
        !kernel_normal(g.normal_sum, P_.normal[i]))
      ++bad_normal;
  }
  cnt.singular_B += bad_B;
  cnt.singular_Bhat += bad_Bhat;
  cnt.normal_fallback += bad_normal;
  cnt.isolated_left_out += lone;
  cnt.sparse_support += sparse;
  // The unresolved-film fractions of this step, from the nearest surfaces and the normals just set.
  film_.resize(n);
  const SweepContextOf<D> cf = sweep_context();
  const real film_gap = prm_.film_gap * prm_.d0;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) film_[i] = film_fraction_at(cf, i, film_gap);
}

// ---------------------------------------------------------------------------------------------
// Sweeps over the pair list (solver/sweeps.hpp), fused where the data dependencies allow.

template <int D>
void CpuSweepsOf<D>::derivatives_sweep(const std::vector<Vec<D>>& v, std::vector<Vec<D>>* G_out) {
  const std::size_t n = P_.size();
  gradV_.resize(n);
  lapV_.resize(n);
  div_v_.resize(n);
  if (G_out) G_out->resize(n);
  const SweepContextOf<D> c = sweep_context();
  const Vec<D>* vp = v.data();
  const real* p = P_.p.data();
  const real* rho = P_.rho.data();
  Vec<D>* G = G_out ? G_out->data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    store_velocity_derivatives(c, i, vp, gradV_.data(), lapV_.data(), div_v_.data());
    if (G) G[i] = pressure_gradient_at(c, i, p, rho);
  }
}

template <int D>
void CpuSweepsOf<D>::start_of_step_derivatives() {
  derivatives_sweep(P_.v, &G_);
  gradV_n_ = gradV_;
}

template <int D>
void CpuSweepsOf<D>::compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho) {
  const std::size_t n = P_.size();
  G_.resize(n);
  const SweepContextOf<D> c = sweep_context();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) G_[i] = pressure_gradient_at(c, i, p.data(), rho.data());
}

template <int D>
void CpuSweepsOf<D>::rhie_chow_and_momentum(StageStart from, const StageParamsOf<D>& sp) {
  const std::size_t n = P_.size();
  rc_.resize(n);
  // the odd-even damping's acceleration, for the band sums of the same stage (its sink, reported
  // apart from the loads: band_share_damping)
  odd_even_.resize(n);
  Vec<D>* odd_even = prm_.momentum_force ? odd_even_.data() : nullptr;
  const SweepContextOf<D> c = sweep_context();
  const Vec<D>* v_start = (from == StageStart::StepStart ? v_n_ : v_s_).data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    rhie_chow_and_momentum_at(c, i, P_.p.data(), P_.rho.data(), G_.data(), gradV_.data(), lapV_.data(),
                              v_start, sp, rc_.data(), P_.v.data(), odd_even);
}

template <int D>
void CpuSweepsOf<D>::derivatives_and_continuity(StageStart from, const StageParamsOf<D>& sp) {
  const std::size_t n = P_.size();
  gradV_.resize(n);
  lapV_.resize(n);
  div_v_.resize(n);
  const SweepContextOf<D> c = sweep_context();
  const real* rho_start = (from == StageStart::StepStart ? rho_n_ : rho_s_).data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    derivatives_and_continuity_at(c, i, P_.v.data(), rho_start, rc_.data(), sp, gradV_.data(), lapV_.data(),
                                  div_v_.data(), P_.rho.data(), P_.p.data());
}

// ---------------------------------------------------------------------------------------------
// Boundary

template <int D>
void CpuSweepsOf<D>::copy_to_dummies() {
  // Dummy-particle baseline: surface particles evolve rho by continuity (done by the stages);
  // dummies copy P and rho of their nearest surface particle.
  for (std::size_t i = 0; i < P_.n_boundary; ++i)
    if (P_.kind[i] == Kind::Dummy) {
      P_.p[i] = P_.p[P_.source[i]];
      P_.rho[i] = P_.rho[P_.source[i]];
    }
}

template <int D>
void CpuSweepsOf<D>::boundary_pressure(int sweeps, const StageParamsOf<D>& sp, SolverCounters& cnt,
                                       const std::uint8_t* one_sided) {
  const std::size_t nb = P_.n_boundary;
  if (nb == 0) return;
  if (!prm_.single_layer) return copy_to_dummies();
  const Vec<D> f = sp.f;  // body force, plus gravity when it is kept in the fluid
  const SweepContextOf<D> c = sweep_context();
  p_new_.resize(nb);
  const real min_den = wall_pressure_min_den(prm_.rho0, prm_.h);
  const real void_distance = sp.void_distance;
  std::int64_t kept = 0, extrapolated = 0, far = 0, facing_void = 0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
#pragma omp parallel for schedule(static) reduction(+ : kept, extrapolated, far, facing_void)
    for (std::size_t i = 0; i < nb; ++i) {
      p_new_[i] = P_.p[i];
      if (P_.kind[i] != Kind::Boundary) continue;
      const WallPressureOutcome o =
          wall_pressure_at(c, i, P_.p.data(), P_.rho.data(), P_.normal[i], P_.acc[i], prm_.nu * lapV_[i], f,
                           min_den, void_distance, prm_.p0, p_new_[i]);
      // the tip of a wall continued through an open boundary's buffer is one-sided by design
      if (o != WallPressureOutcome::Solved && one_sided != nullptr && one_sided[i]) continue;
      kept += o == WallPressureOutcome::Kept ? 1 : 0;
      extrapolated += o == WallPressureOutcome::Extrapolated ? 1 : 0;
      far += o == WallPressureOutcome::ExtrapolatedFar ? 1 : 0;
      facing_void += o == WallPressureOutcome::Void ? 1 : 0;
    }
    for (std::size_t i = 0; i < nb; ++i) {
      if (P_.kind[i] != Kind::Boundary) continue;
      P_.p[i] = p_new_[i];
      P_.rho[i] = density_from_pressure(p_new_[i], prm_.rho0, prm_.c, prm_.p0);
    }
  }
  cnt.wall_pressure_kept += kept;
  cnt.wall_pressure_extrapolated += extrapolated;
  cnt.wall_pressure_extrapolated_far += far;
  cnt.wall_pressure_void += facing_void;
  isolated_pressures();
}

template <int D>
void CpuSweepsOf<D>::isolated_pressures() {
  // Isolated fluid particles take their pressure from the surfaces around them (sweeps.hpp).
  const std::size_t nb = P_.n_boundary;
  const SweepContextOf<D> c = sweep_context();
  const std::size_t n = isolated_.size() == P_.size() ? P_.size() : nb;
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (isolated_[i] && isolated_pressure_at(c, i, P_.p.data(), P_.p[i]))
      P_.rho[i] = density_from_pressure(P_.p[i], prm_.rho0, prm_.c, prm_.p0);
}

// ---------------------------------------------------------------------------------------------
// Time step

template <int D>
void CpuSweepsOf<D>::save_stage_start(StageStart which) {
  if (which == StageStart::StepStart) {
    v_n_ = P_.v;
    rho_n_ = P_.rho;
    p_n_ = P_.p;
  } else {
    v_s_ = P_.v;
    rho_s_ = P_.rho;
  }
}

template <int D>
real CpuSweepsOf<D>::end_of_step(real dt, bool single_layer) {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  real vmax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i)
    vmax2 = std::max(vmax2, end_of_step_update(i, nb, P_.kind[i], domain_, dt, single_layer, v_n_[i],
                                               rho_n_[i], p_n_[i], P_.x[i], P_.v[i], P_.rho[i], P_.p[i]));
  return vmax2;
}

template <int D>
void CpuSweepsOf<D>::shift(real scale, real c) {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  // <grad P>/rho of the new pressures with the step's geometry (the stored pair weights), and
  // the step's mean velocity gradient (stage start and end) for the Taylor corrections.
  compute_pressure_gradient(P_.p, P_.rho);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) gradV_[i] = 0.5 * (gradV_[i] + gradV_n_[i]);
  if (!(scale > 0)) return;
  const SurfaceArraysOf<D> surfaces = surface_arrays();
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (P_.kind[i] == Kind::Fluid)
      shift_particle(shift_dir_[i], scale, gradV_[i], G_[i],
                     gather_surfaces(near_a_[i], near_b_[i], surfaces), prm_.d0, domain_, c, P_.x[i], P_.v[i],
                     P_.p[i], P_.rho[i]);
}

template <int D>
SurfaceArraysOf<D> CpuSweepsOf<D>::surface_arrays() const {
  return SurfaceArraysOf<D>{P_.x.data(), P_.normal.data(), P_.wedge.data(), P_.ds.data(), P_.v.data()};
}

template <int D>
void CpuSweepsOf<D>::guard_surfaces(real keep, SolverCounters& cnt) {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  std::int64_t pushed = 0, gap = 0;
  const SurfaceArraysOf<D> surfaces = surface_arrays();
#pragma omp parallel for schedule(static) reduction(+ : pushed, gap)
  for (std::size_t i = nb; i < n; ++i) {
    if (P_.kind[i] != Kind::Fluid) continue;
    const GuardOutcome o = surface_guard_at(i, near_a_.data(), near_b_.data(), surfaces, P_.x.data(),
                                            P_.v.data(), keep, domain_);
    pushed += o == GuardOutcome::Pushed ? 1 : 0;
    gap += o == GuardOutcome::Gap ? 1 : 0;
  }
  cnt.surface_pushed += pushed;
  cnt.gap_squeezed += gap;
}

template <int D>
void CpuSweepsOf<D>::reorder_fluid() {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  if (n == nb) return;
  reorder_key_.resize(n - nb);
  for (std::size_t i = nb; i < n; ++i)
    reorder_key_[i - nb] = static_cast<std::uint32_t>(grid_.cell_index(P_.x[i]));
  reorder_order_.resize(n - nb);
  std::iota(reorder_order_.begin(), reorder_order_.end(), std::size_t{0});
  std::stable_sort(reorder_order_.begin(), reorder_order_.end(),
                   [&](std::size_t a, std::size_t b) { return reorder_key_[a] < reorder_key_[b]; });
  auto permute = [&](auto& vec) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    reorder_scratch_.resize((n - nb) * sizeof(T));
    T* copy = reinterpret_cast<T*>(reorder_scratch_.data());
    std::copy(vec.begin() + static_cast<std::ptrdiff_t>(nb), vec.end(), copy);
    for (std::size_t k = 0; k < reorder_order_.size(); ++k) vec[nb + k] = copy[reorder_order_[k]];
  };
  permute(P_.x);
  permute(P_.v);
  permute(P_.rho);
  permute(P_.p);
  permute(P_.m);
  permute(P_.kind);
  permute(P_.group);
  permute(P_.id);
}

// ---------------------------------------------------------------------------------------------
// Speeds, distances, health

template <int D>
real CpuSweepsOf<D>::max_speed() const {
  real vmax2 = 0;
  const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i) vmax2 = std::max(vmax2, norm2(P_.v[i]));
  return std::sqrt(vmax2);
}

template <int D>
void CpuSweepsOf<D>::skip_buffer_pairs_in_min_distance() {
  const std::size_t n = P_.size();
  real dmin2 = std::numeric_limits<real>::infinity();
#pragma omp parallel for schedule(static) reduction(min : dmin2)
  for (std::size_t i = 0; i < n; ++i) {
    const bool buffer_i = is_buffer(P_.kind[i]);
    for (std::uint32_t k = nl_.start[i]; k < nl_.start[i + 1]; ++k) {
      const std::uint32_t j = nl_.j[k];
      if (buffer_i && is_buffer(P_.kind[j])) continue;
      dmin2 = std::min(dmin2, norm2(domain_.separation(P_.x[i], P_.x[j])));
    }
  }
  nl_.min_distance = std::sqrt(dmin2);
}

template <int D>
std::int64_t CpuSweepsOf<D>::unhealthy_id(const HealthLimitsOf<D>& lim) const {
  std::int64_t worst = std::numeric_limits<std::int64_t>::max();
  const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) reduction(min : worst)
  for (std::size_t i = 0; i < n; ++i)
    if (particle_unhealthy(P_.kind[i] == Kind::Fluid, P_.x[i], P_.v[i], P_.rho[i], P_.p[i], lim))
      worst = std::min(worst, P_.id[i]);
  return worst == std::numeric_limits<std::int64_t>::max() ? -1 : worst;
}

}  // namespace particula
