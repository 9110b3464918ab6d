#include "particula/solver/solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/sph/operators.hpp"

namespace particula {

Solver::Solver(PhysicsParams params, Domain domain, Particles particles, std::vector<RigidGroup> groups,
               SolverStart start, real t0, std::int64_t step0)
    : prm_(params), domain_(domain), P_(std::move(particles)), groups_(std::move(groups)), kernel_(params.h),
      t_(t0), steps_(step0) {
  grid_.setup(domain_, prm_.h);
  if (start == SolverStart::Fresh) {
    place_boundary(t_);
    refresh_geometry();
    // Initial wall pressure consistent with the initial fluid state (P.20): iterate the Jacobi
    // sweeps to convergence once, since boundary particles start without a pressure.
    compute_velocity_derivatives(P_.v);
    const int sweeps = prm_.wall_pressure_sweeps;
    prm_.wall_pressure_sweeps = 50;
    boundary_pressure();
    prm_.wall_pressure_sweeps = sweeps;
  }
  // A restart takes the checkpointed state exactly as it is. The GPU backend starts from the
  // host state prepared above; everything derived is recomputed at the start of each step.
  if (prm_.cuda) {
    dev_ = make_cuda_backend(prm_, grid_.geometry(), kernel_, P_);
    dev_->upload(P_);
  }
}

Solver::~Solver() = default;
Solver::Solver(Solver&&) noexcept = default;
Solver& Solver::operator=(Solver&&) noexcept = default;

const Particles& Solver::particles() const {
  if (!host_current_) {
    dev_->download(P_);
    host_current_ = true;
  }
  return P_;
}

Particles& Solver::particles() {
  const Particles& p = std::as_const(*this).particles();
  (void)p;
  device_current_ = false;
  return P_;
}

StageParams Solver::stage_params(real dt) const {
  StageParams s;
  s.dt = dt;
  s.g_dt = prm_.rhie_chow_factor * dt;
  s.nu = prm_.nu;
  s.f = prm_.body_force + (prm_.gravity_in_fluid ? prm_.gravity : Vec2{});
  s.rho0 = prm_.rho0;
  s.c = prm_.c;
  s.p0 = prm_.p0;
  s.kappa = prm_.odd_even_damping * prm_.c * prm_.h;  // kappa = alpha c h (method-notes)
  s.single_layer = prm_.single_layer;
  return s;
}

HealthLimits Solver::health_limits() const {
  HealthLimits l;
  l.rho_lo = prm_.rho_min_ratio * prm_.rho0;
  l.rho_hi = prm_.rho_max_ratio * prm_.rho0;
  l.h = prm_.h;
  l.domain = domain_;
  return l;
}

namespace {

/// Adds the wall-clock time of a scope to one PhaseTimes entry.
class PhaseTimer {
 public:
  explicit PhaseTimer(double& slot) : slot_(slot), t0_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() { slot_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double& slot_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

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
  c.grad_w = pair_grad_w_.data();
  c.lap_w = pair_lap_w_.data();
  c.lap_esum = lap_esum_.data();
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
  lap_esum_.resize(n);
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
  std::int64_t bad_B = 0, bad_Bhat = 0, bad_normal = 0, lone = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad_B, bad_Bhat, bad_normal, lone)
  for (std::size_t i = 0; i < n; ++i) {
    const GeometryAt g = geometry_at(c, i, prm_.d0, grad_w, lap_w);
    isolated_out[i] = i >= nb && isolated(g.others_fluid_support, one_neighbour, g.near.a) ? 1 : 0;
    lone += isolated_out[i];
    B_[i] = g.B;
    Bhat_[i] = g.Bhat;
    rbar_[i] = g.rbar;
    shift_dir_[i] = g.shift_direction;
    lap_esum_[i] = g.lap_esum;
    near_a_[i] = g.near.a;
    near_b_[i] = g.near.b;
    if (P_.kind[i] == Kind::Dummy) continue;
    bad_B += g.B_ok ? 0 : 1;
    bad_Bhat += g.Bhat_ok ? 0 : 1;
    // P.18 normal; on failure the analytic normal set by place_boundary stays.
    if (i < nb && kernel_normals && P_.kind[i] == Kind::Boundary && !kernel_normal(g.normal_sum, P_.normal[i]))
      ++bad_normal;
  }
  counters_.singular_B += bad_B;
  counters_.singular_Bhat += bad_Bhat;
  counters_.normal_fallback += bad_normal;
  counters_.isolated_left_out += lone;
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
  const SweepContext c = sweep_context();
  const Vec2* v_start = (from == StageStart::StepStart ? v_n_ : v_s_).data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    rhie_chow_and_momentum_at(c, i, P_.p.data(), P_.rho.data(), G_.data(), gradV_.data(), lapV_.data(), v_start, sp, rc_.data(),
                              P_.v.data());
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
  std::int64_t kept = 0, extrapolated = 0, far = 0;
  for (int sweep = 0; sweep < prm_.wall_pressure_sweeps; ++sweep) {
#pragma omp parallel for schedule(static) reduction(+ : kept, extrapolated, far)
    for (std::size_t i = 0; i < nb; ++i) {
      p_new_[i] = P_.p[i];
      if (P_.kind[i] != Kind::Boundary) continue;
      const WallPressureOutcome o =
          wall_pressure_at(c, i, P_.p.data(), P_.rho.data(), P_.normal[i], P_.acc[i], prm_.nu * lapV_[i], f,
                           min_den, p_new_[i]);
      kept += o == WallPressureOutcome::Kept ? 1 : 0;
      extrapolated += o == WallPressureOutcome::Extrapolated ? 1 : 0;
      far += o == WallPressureOutcome::ExtrapolatedFar ? 1 : 0;
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
  // Isolated fluid particles take their pressure from the surfaces around them (sweeps.hpp).
  const std::size_t n = isolated_.size() == P_.size() ? P_.size() : nb;
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
    if (isolated_[i] && isolated_pressure_at(c, i, P_.p.data(), P_.p[i]))
      P_.rho[i] = density_from_pressure(P_.p[i], prm_.rho0, prm_.c, prm_.p0);
}

// ---------------------------------------------------------------------------------------------
// Time step

real Solver::max_speed() const {
  if (dev_) return dev_->max_speed();
  real vmax2 = 0;
  const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) reduction(max : vmax2)
  for (std::size_t i = 0; i < n; ++i) vmax2 = std::max(vmax2, norm2(P_.v[i]));
  return std::sqrt(vmax2);
}

real Solver::stable_dt() const {
  const real dlist = dev_ ? dev_->min_distance() : nl_.min_distance;
  const real dmin = dlist > 0 && std::isfinite(dlist) ? dlist : prm_.d0;
  const real vmax = max_speed();
  real dt = prm_.cfl * dmin / (prm_.c + vmax);  // P.30: Courant condition
  if (prm_.nu > 0) dt = std::min(dt, prm_.cfl * dmin * dmin / prm_.nu);  // P.31: viscous diffusion
  if (prm_.dt_max > 0) dt = std::min(dt, prm_.dt_max);
  if (contact_dt_ > 0) dt = std::min(dt, contact_dt_);  // t_c / 20 of the contacts (collisions())
  return std::min(dt, body_force_dt());
}

real Solver::body_force_dt() const {
  // Monaghan's force condition dt <= 0.25 sqrt(h / |f|) for the acceleration f every fluid
  // particle feels (body force, gravity kept in the fluid): without it a strong body force on a
  // fluid at rest moved particles by more than h in one step (gravity 1e6 m/s^2: exit 3 at step
  // 1, the Courant condition of a fluid at rest knowing nothing of f).
  Vec2 f = prm_.body_force;
  if (prm_.gravity_in_fluid) f += prm_.gravity;
  const real a = norm(f);
  return a > 0 ? 0.25 * std::sqrt(prm_.h / a) : std::numeric_limits<real>::infinity();
}

std::optional<Failure> Solver::time_step_collapse(real dt) const {
  // The step of the case's own scales: P.30 at the particle spacing and sound speed, P.31 at d0.
  real dt_scale = prm_.cfl * prm_.d0 / prm_.c;
  if (prm_.nu > 0) dt_scale = std::min(dt_scale, prm_.cfl * prm_.d0 * prm_.d0 / prm_.nu);
  if (prm_.dt_max > 0) dt_scale = std::min(dt_scale, prm_.dt_max);
  dt_scale = std::min(dt_scale, body_force_dt());
  if (!(dt < kTimeStepCollapse * dt_scale)) return std::nullopt;
  // Name the limit that collapsed: the closest particle pair, the fastest particle or a contact.
  const real dlist = dev_ ? dev_->min_distance() : nl_.min_distance;
  const real vmax = max_speed();
  std::string why;
  if (contact_dt_ > 0 && contact_dt_ <= dt)
    why = "the stability limit of a contact (t_c / 20): a contact too stiff for its bodies' masses (collision.*)";
  else if (vmax > prm_.c)
    why = fmt::format("a particle at {:.3g} m/s, {:.3g} times the sound speed: the flow has blown up", vmax, vmax / prm_.c);
  else
    why = fmt::format("two particles {:.3g} d0 apart: particles collapsing onto each other", dlist / prm_.d0);
  return Failure{fmt::format("the time step collapsed to {:.3g} s, below {:g} of the case's {:.3g} s (cfl d0 / c, "
                             "cfl d0^2 / nu); it is limited by {}",
                             dt, kTimeStepCollapse, dt_scale, why),
                 -1, Vec2{}};
}

std::optional<Failure> Solver::step(real dt_cap) {
  return advance(dt_cap, std::numeric_limits<real>::quiet_NaN());
}

std::optional<Failure> Solver::step_to(real t_target) {
  const real cap = t_target - t_;
  return cap > 0 ? advance(cap, t_target) : advance(0, std::numeric_limits<real>::quiet_NaN());
}

std::optional<Failure> Solver::advance(real dt_cap, real land_at) {
  if (dev_ && !device_current_) {
    dev_->upload(P_);
    device_current_ = true;
  }
  if (prm_.reorder_interval > 0 && steps_ % prm_.reorder_interval == 0) {
    PhaseTimer timer(times_.neighbors);
    if (dev_) dev_->reorder_fluid();
    else reorder_fluid();
  }
  if (dev_) {
    PhaseTimer timer(times_.geometry);
    dev_->refresh_geometry(counters_);
    host_current_ = false;
  } else {
    refresh_geometry();
  }
  if (prm_.momentum_force) {
    PhaseTimer timer(times_.bodies);
    build_load_band();
  }
  {
    PhaseTimer timer(times_.bodies);
    if (auto f = collisions()) return f;
  }
  {
    PhaseTimer timer(times_.integration);
    dt_ = stable_dt();
    if (auto f = time_step_collapse(dt_)) return f;
    if (dt_cap > 0) dt_ = std::min(dt_, dt_cap);
  }
  const real dt = dt_;
  // The time at the end of the step: exactly land_at when the cap limits the step (t_ + dt can
  // miss it in the last bit), so that output times are the values they stand for.
  const real t_new = dt_cap > 0 && dt == dt_cap && std::isfinite(land_at) ? land_at : t_ + dt;
  {
    PhaseTimer timer(times_.bodies);
    contact_forces(dt);
  }
  const StageParams sp = stage_params(dt);

  save_stage_start(StageStart::StepStart);
  std::vector<Vec2>& gv0 = group_v0_;
  std::vector<real>& gw0 = group_w0_;
  gv0.resize(groups_.size());
  gw0.resize(groups_.size());
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    groups_[k].vel_n = gv0[k] = groups_[k].vel;
    groups_[k].omega_n = gw0[k] = groups_[k].omega;
  }
  // Bodies advance one stage from the loads of the current P, tau; their surface particles then
  // carry the stage's velocity and acceleration (positions stay frozen during the stages).
  auto bodies_stage = [&] {
    PhaseTimer timer(times_.bodies);
    group_loads();
    body_stage(dt, t_new, gv0, gw0);
    set_boundary_kinematics();
  };

  // ---- predictor: V* = V^n + dt A(V^n, P^n); bodies from the loads of P^n, tau^n;
  //      rho* = rho^n + dt D(V*, P^n) (continuity uses the new velocity)
  {
    PhaseTimer timer(times_.operators);
    if (dev_) {
      dev_->start_of_step_derivatives();
    } else {
      derivatives_sweep(P_.v, &G_);
      gradV_n_ = gradV_;
    }
    rhie_chow_and_momentum(StageStart::StepStart, sp);
  }
  bodies_stage();
  {
    PhaseTimer timer(times_.operators);
    derivatives_and_continuity(StageStart::StepStart, sp);
  }
  boundary_pressure();

  // ---- corrector: V** = V* + dt A(V*, P*); bodies likewise; rho** = rho* + dt D(V**, P*)
  save_stage_start(StageStart::Predicted);
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    gv0[k] = groups_[k].vel;
    gw0[k] = groups_[k].omega;
  }
  {
    PhaseTimer timer(times_.operators);
    pressure_gradient();
    rhie_chow_and_momentum(StageStart::Predicted, sp);
  }
  bodies_stage();
  {
    PhaseTimer timer(times_.operators);
    derivatives_and_continuity(StageStart::Predicted, sp);
  }
  boundary_pressure();

  // ---- update (P.28, P.32): averages of the stage-start and corrected values
  real vmax2 = 0;
  {
    PhaseTimer timer(times_.integration);
    vmax2 = end_of_step(dt);
  }
  if (!prm_.single_layer) boundary_pressure();  // dummies copy the averaged surface values
  t_ = t_new;
  ++steps_;
  {
    PhaseTimer timer(times_.bodies);
    body_update(dt, t_);
    place_boundary(t_);
  }

  // ---- particle shifting (P.33-P.36), with the step's geometry and the new fields
  if (prm_.shifting_beta > 0) {
    PhaseTimer timer(times_.shifting);
    shift_particles(dt, std::sqrt(vmax2));
  }
  PhaseTimer timer(times_.integration);
  guard_surfaces();
  return check_health();
}

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
#pragma omp parallel for schedule(static)
  for (std::size_t i = nb; i < n; ++i)
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

namespace {
/// The first rigid group with a non-finite motion or load (what bodies.csv and walls.csv
/// hold), as a Failure; nullopt when all are finite.
std::optional<Failure> unhealthy_group(const std::vector<RigidGroup>& groups) {
  for (const RigidGroup& g : groups) {
    const real values[] = {g.pos.x, g.pos.y, g.vel.x, g.vel.y, g.angle, g.omega, g.torque,
                           g.force_pressure.x, g.force_pressure.y, g.force_viscous.x, g.force_viscous.y,
                           g.force_collision.x, g.force_collision.y};
    if (std::all_of(std::begin(values), std::end(values), [](real v) { return std::isfinite(v); })) continue;
    Failure f;
    f.position = std::isfinite(g.pos.x) && std::isfinite(g.pos.y) ? g.pos : Vec2{};
    f.what = std::string("non-finite value (NaN or Inf) in the motion or force of ") + (g.is_wall ? "wall '" : "body '") +
             g.name + "'";
    return f;
  }
  return std::nullopt;
}
}  // namespace

std::optional<Failure> Solver::check_health() const {
  const HealthLimits lim = health_limits();
  const real lo = lim.rho_lo, hi = lim.rho_hi;
  std::int64_t worst = std::numeric_limits<std::int64_t>::max();
  if (dev_) {
    const std::int64_t id = dev_->unhealthy_id(lim);
    if (id < 0) return unhealthy_group(groups_);
    worst = id;
    particles();  // the host copy names the particle
  } else {
    const std::size_t n = P_.size();
#pragma omp parallel for schedule(static) reduction(min : worst)
    for (std::size_t i = 0; i < n; ++i)
      if (particle_unhealthy(P_.is_fluid(i), P_.x[i], P_.v[i], P_.rho[i], P_.p[i], lim)) worst = std::min(worst, P_.id[i]);
    if (worst == std::numeric_limits<std::int64_t>::max()) return unhealthy_group(groups_);
  }
  std::size_t i = 0;
  while (P_.id[i] != worst) ++i;
  Failure f;
  f.particle_id = worst;
  f.position = P_.x[i];
  const char* kind = P_.is_fluid(i) ? "fluid" : "boundary";
  char buf[512];
  if (!(std::isfinite(P_.rho[i]) && std::isfinite(P_.p[i]) && std::isfinite(P_.v[i].x) && std::isfinite(P_.v[i].y)))
    std::snprintf(buf, sizeof buf, "non-finite value (NaN or Inf) at %s particle %lld", kind, static_cast<long long>(worst));
  else if (P_.rho[i] < lo || P_.rho[i] > hi)
    std::snprintf(buf, sizeof buf, "density %.6g kg/m^3 of %s particle %lld outside [%.4g, %.4g] (rho0 x [%g, %g])",
                  P_.rho[i], kind, static_cast<long long>(worst), lo, hi, prm_.rho_min_ratio, prm_.rho_max_ratio);
  else
    std::snprintf(buf, sizeof buf, "%s particle %lld left the closed domain", kind, static_cast<long long>(worst));
  f.what = buf;
  if (P_.is_fluid(i)) f.what += likely_cause(P_.x[i]);
  return f;
}

std::string Solver::likely_cause(Vec2 x) const {
  // The nearest surface particle (a search over the boundary block: only on failure).
  real best = 1e300;
  std::size_t s = P_.n_boundary;
  for (std::size_t k = 0; k < P_.n_boundary; ++k) {
    if (P_.kind[k] != Kind::Boundary) continue;
    const real d2 = norm2(domain_.separation(x, P_.x[k]));
    if (d2 < best) {
      best = d2;
      s = k;
    }
  }
  if (s == P_.n_boundary) return "";
  const real d = dot(domain_.separation(x, P_.x[s]), P_.normal[s]) / prm_.d0;
  if (!std::isfinite(d) || std::fabs(d) > 1e6) return "";  // a position already broken: no cause to name
  const RigidGroup& g = groups_[static_cast<std::size_t>(P_.group[s])];
  const std::string where = (g.is_wall ? "wall '" : "body '") + g.name + "'";
  char buf[640];
  if (d < 0.5)
    std::snprintf(buf, sizeof buf,
                  "; it is %.3g d0 from the surface of %s: likely cause: fluid squeezed against that surface "
                  "(two surfaces closing faster than the fluid can leave the gap, or a contact too soft to keep "
                  "them apart: see the collision.* keys; numerics.surface_guard sets the keep-out distance)",
                  d, where.c_str());
  else
    std::snprintf(buf, sizeof buf,
                  "; the nearest surface (%s) is %.3g d0 away: likely cause: a flow too fast or too under-resolved "
                  "for this resolution (Mach number V/fluid.c above about 0.1, or too few particles across a "
                  "body or a gap: lower resolution.d0 or raise fluid.c)",
                  where.c_str(), d);
  return buf;
}

}  // namespace particula
