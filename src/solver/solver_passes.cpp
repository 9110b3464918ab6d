// The CPU passes of a step (docs/architecture.md, data flow): geometry, derivatives, Rhie-Chow
// and momentum, continuity, the wall pressure P.20, the end-of-step update, shifting, the
// surface guard and the reordering of the fluid. Each loops over particles and calls the
// PARTICULA_HD functions of sweeps.hpp (or hands the pass to the GPU backend); the time loop
// that orders them is in solver.cpp.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/solver/solver.hpp"
#include "particula/sph/operators.hpp"
#include "phase_timer.hpp"

namespace particula {

// ---------------------------------------------------------------------------------------------
// Geometry: everything that depends on positions (and start-of-step volumes) only.

void Solver::update_volumes() {
  const std::size_t n = P_.size();
  vol_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) vol_[i] = P_.m[i] / P_.rho[i];
}

SweepContext Solver::sweep_context() const {
  SweepContext c;
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

void Solver::refresh_geometry() {
  if (dev_) {
    dev_->refresh_geometry(counters_);
    return;
  }
  {
    PhaseTimer timer(times_.neighbors);
    build_neighbor_list(P_.x, domain_, kernel_, grid_, nl_);
  }
  PhaseTimer timer(times_.geometry);
  update_volumes();
  geometry_sweep();
}

void Solver::geometry_sweep() {
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
  const SweepContext c = sweep_context();
  Vec2* grad_w = pair_grad_w_.data();
  real* lap_w = pair_lap_w_.data();
  const bool kernel_normals = prm_.kernel_normals;
  const real one_neighbour = prm_.d0 * prm_.d0 * kernel_.W(prm_.d0);
  std::uint8_t* isolated_out = isolated_.data();
  std::int64_t bad_B = 0, bad_Bhat = 0, bad_normal = 0, lone = 0, sparse = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad_B, bad_Bhat, bad_normal, lone, sparse)
  for (std::size_t i = 0; i < n; ++i) {
    const GeometryAt g = geometry_at(c, i, prm_.d0, grad_w, lap_w);
    isolated_out[i] = i >= nb && P_.kind[i] == Kind::Fluid && isolated(g.others_fluid_support, one_neighbour, g.near.a) ? 1 : 0;
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
    // P.18 normal; on failure the analytic normal set by place_boundary stays.
    if (i < nb && kernel_normals && P_.kind[i] == Kind::Boundary && !kernel_normal(g.normal_sum, P_.normal[i]))
      ++bad_normal;
  }
  counters_.singular_B += bad_B;
  counters_.singular_Bhat += bad_Bhat;
  counters_.normal_fallback += bad_normal;
  counters_.isolated_left_out += lone;
  counters_.sparse_support += sparse;
  // The unresolved-film fractions of this step, from the nearest surfaces and the normals just set.
  film_.resize(n);
  const SweepContext cf = sweep_context();
  const real film_gap = prm_.film_gap * prm_.d0;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) film_[i] = film_fraction_at(cf, i, film_gap);
}

// ---------------------------------------------------------------------------------------------
// Sweeps over the pair list (solver/sweeps.hpp), fused where the data dependencies allow.

void Solver::derivatives_sweep(const std::vector<Vec2>& v, std::vector<Vec2>* G_out) {
  const std::size_t n = P_.size();
  gradV_.resize(n);
  lapV_.resize(n);
  div_v_.resize(n);
  if (G_out) G_out->resize(n);
  const SweepContext c = sweep_context();
  const Vec2* vp = v.data();
  const real* p = P_.p.data();
  const real* rho = P_.rho.data();
  Vec2* G = G_out ? G_out->data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    store_velocity_derivatives(c, i, vp, gradV_.data(), lapV_.data(), div_v_.data());
    if (G) G[i] = pressure_gradient_at(c, i, p, rho);
  }
}

void Solver::compute_velocity_derivatives(const std::vector<Vec2>& v) { derivatives_sweep(v, nullptr); }

void Solver::compute_pressure_gradient(const std::vector<real>& p, const std::vector<real>& rho) {
  const std::size_t n = P_.size();
  G_.resize(n);
  const SweepContext c = sweep_context();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) G_[i] = pressure_gradient_at(c, i, p.data(), rho.data());
}

void Solver::rhie_chow_and_momentum(StageStart from, const StageParams& sp) {
  if (dev_) return dev_->rhie_chow_and_momentum(from, sp);
  const std::size_t n = P_.size();
  rc_.resize(n);
  // the odd-even damping's acceleration, for the band sums of the same stage (its sink, reported
  // apart from the loads: band_share_damping)
  odd_even_.resize(n);
  Vec2* odd_even = prm_.momentum_force ? odd_even_.data() : nullptr;
  const SweepContext c = sweep_context();
  const Vec2* v_start = (from == StageStart::StepStart ? v_n_ : v_s_).data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    rhie_chow_and_momentum_at(c, i, P_.p.data(), P_.rho.data(), G_.data(), gradV_.data(), lapV_.data(),
                              v_start, sp, rc_.data(), P_.v.data(), odd_even);
}

void Solver::derivatives_and_continuity(StageStart from, const StageParams& sp) {
  if (dev_) return dev_->derivatives_and_continuity(from, sp);
  const std::size_t n = P_.size();
  gradV_.resize(n);
  lapV_.resize(n);
  div_v_.resize(n);
  const SweepContext c = sweep_context();
  const real* rho_start = (from == StageStart::StepStart ? rho_n_ : rho_s_).data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    derivatives_and_continuity_at(c, i, P_.v.data(), rho_start, rc_.data(), sp, gradV_.data(), lapV_.data(),
                                  div_v_.data(), P_.rho.data(), P_.p.data());
}

// ---------------------------------------------------------------------------------------------
// Boundary

void Solver::boundary_pressure() {
  PhaseTimer timer(times_.wall_pressure);
  const std::size_t nb = P_.n_boundary;
  if (nb == 0) return;
  if (dev_) return dev_->boundary_pressure(prm_.wall_pressure_sweeps, stage_params(dt_), counters_);
  if (!prm_.single_layer) {
    // Dummy-particle baseline: surface particles evolve rho by continuity (done by the
    // stages); dummies copy P and rho of their nearest surface particle.
    for (std::size_t i = 0; i < nb; ++i)
      if (P_.kind[i] == Kind::Dummy) {
        P_.p[i] = P_.p[P_.source[i]];
        P_.rho[i] = P_.rho[P_.source[i]];
      }
    return;
  }
  const Vec2 f = prm_.body_force + (prm_.gravity_in_fluid ? prm_.gravity : Vec2{});
  const SweepContext c = sweep_context();
  p_new_.resize(nb);
  const real min_den = wall_pressure_min_den(prm_.rho0, prm_.h);
  const real void_distance = stage_params(dt_).void_distance;
  std::int64_t kept = 0, extrapolated = 0, far = 0, facing_void = 0;
  for (int sweep = 0; sweep < prm_.wall_pressure_sweeps; ++sweep) {
#pragma omp parallel for schedule(static) reduction(+ : kept, extrapolated, far, facing_void)
    for (std::size_t i = 0; i < nb; ++i) {
      p_new_[i] = P_.p[i];
      if (P_.kind[i] != Kind::Boundary) continue;
      const WallPressureOutcome o =
          wall_pressure_at(c, i, P_.p.data(), P_.rho.data(), P_.normal[i], P_.acc[i], prm_.nu * lapV_[i], f,
                           min_den, void_distance, prm_.p0, p_new_[i]);
      // the tip of a wall continued through an open boundary's buffer is one-sided by design
      if (o != WallPressureOutcome::Solved && in_open_buffer(P_.x[i])) continue;
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
  counters_.wall_pressure_kept += kept;
  counters_.wall_pressure_extrapolated += extrapolated;
  counters_.wall_pressure_extrapolated_far += far;
  counters_.wall_pressure_void += facing_void;
  // Isolated fluid particles take their pressure from the surfaces around them (sweeps.hpp).
  const std::size_t n = isolated_.size() == P_.size() ? P_.size() : nb;
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (isolated_[i] && isolated_pressure_at(c, i, P_.p.data(), P_.p[i]))
      P_.rho[i] = density_from_pressure(P_.p[i], prm_.rho0, prm_.c, prm_.p0);
}

// ---------------------------------------------------------------------------------------------
// Time step

void Solver::save_stage_start(StageStart which) {
  if (dev_) return dev_->save_stage_start(which);
  if (which == StageStart::StepStart) {
    v_n_ = P_.v;
    rho_n_ = P_.rho;
    p_n_ = P_.p;
  } else {
    v_s_ = P_.v;
    rho_s_ = P_.rho;
  }
}

void Solver::pressure_gradient() {
  if (dev_) return dev_->pressure_gradient();
  compute_pressure_gradient(P_.p, P_.rho);
}

real Solver::end_of_step(real dt) {
  if (dev_) return dev_->end_of_step(dt, prm_.single_layer);
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  const bool single_layer = prm_.single_layer;
  real vmax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i)
    vmax2 = std::max(vmax2, end_of_step_update(i, nb, P_.kind[i], domain_, dt, single_layer, v_n_[i], rho_n_[i],
                                               p_n_[i], P_.x[i], P_.v[i], P_.rho[i], P_.p[i]));
  return vmax2;
}

void Solver::shift_particles(real dt, real vmax) {
  const real scale = prm_.shifting_beta * vmax * dt;
  if (dev_) return dev_->shift(scale, prm_.c);
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  // <grad P>/rho of the new pressures with the step's geometry (the stored pair weights), and
  // the step's mean velocity gradient (stage start and end) for the Taylor corrections.
  compute_pressure_gradient(P_.p, P_.rho);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) gradV_[i] = 0.5 * (gradV_[i] + gradV_n_[i]);
  if (!(scale > 0)) return;
  open_limit_shifting();
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (P_.kind[i] == Kind::Fluid)
      shift_particle(shift_dir_[i], scale, gradV_[i], G_[i],
                   gather_surfaces(near_a_[i], near_b_[i], P_.x.data(), P_.normal.data(), P_.v.data()), prm_.d0,
                   domain_, prm_.c, P_.x[i], P_.v[i], P_.p[i], P_.rho[i]);
}

void Solver::guard_surfaces() {
  const real keep = prm_.surface_guard * prm_.d0;
  if (!(keep > 0)) return;
  if (dev_) return dev_->guard_surfaces(keep, counters_);
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  std::int64_t pushed = 0, gap = 0;
#pragma omp parallel for schedule(static) reduction(+ : pushed, gap)
  for (std::size_t i = nb; i < n; ++i) {
    if (P_.kind[i] != Kind::Fluid) continue;
    const GuardOutcome o =
        surface_guard_at(i, near_a_.data(), near_b_.data(), P_.x.data(), P_.normal.data(), P_.v.data(), keep, domain_);
    pushed += o == GuardOutcome::Pushed ? 1 : 0;
    gap += o == GuardOutcome::Gap ? 1 : 0;
  }
  counters_.surface_pushed += pushed;
  counters_.gap_squeezed += gap;
}

void Solver::reorder_fluid() {
  const std::size_t n = P_.size(), nb = P_.n_boundary;
  if (n == nb) return;
  reorder_key_.resize(n - nb);
  for (std::size_t i = nb; i < n; ++i) reorder_key_[i - nb] = static_cast<std::uint32_t>(grid_.cell_index(P_.x[i]));
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

}  // namespace particula
