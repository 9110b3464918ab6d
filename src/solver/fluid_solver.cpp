#include "particula/solver/fluid_solver.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <utility>

#include "phase_timer.hpp"

namespace particula {

template <int D>
std::string unhealthy_particle(const ParticlesOf<D>& P, std::size_t i, const FluidParamsOf<D>& prm) {
  const char* kind = P.is_fluid(i) ? "fluid" : "boundary";
  const auto id = static_cast<long long>(P.id[i]);
  if (!(std::isfinite(P.rho[i]) && std::isfinite(P.p[i]) && all_finite(P.v[i])))
    return fmt::format("non-finite value (NaN or Inf) at {} particle {}", kind, id);
  const real lo = prm.rho_min_ratio * prm.rho0, hi = prm.rho_max_ratio * prm.rho0;
  if (P.rho[i] < lo || P.rho[i] > hi)
    return fmt::format(
        "density {:.6g} kg/m^3 of {} particle {} outside [{:.4g}, {:.4g}] (rho0 x [{:g}, {:g}])", P.rho[i],
        kind, id, lo, hi, prm.rho_min_ratio, prm.rho_max_ratio);
  return fmt::format("{} particle {} left the closed domain", kind, id);
}

template <int D>
FluidSolverOf<D>::FluidSolverOf(const FluidParamsOf<D>& params, const DomainOf<D>& domain,
                                ParticlesOf<D> particles)
    : prm_(params),
      domain_(domain),
      P_(std::move(particles)),
      kernel_(params.h),
      sweeps_(prm_, domain_, kernel_, P_) {
  // the walls keep their places and velocities (at rest, or a plane sliding along itself): their
  // acceleration (P.20) is zero; a wall particle on a periodic side is taken into the box as a
  // rigid group's placement takes it (Solver)
  for (std::size_t i = 0; i < P_.n_boundary; ++i) {
    P_.x[i] = domain_.wrap(P_.x[i]);
    P_.acc[i] = Vec<D>{};
  }
  sweeps_.refresh_geometry(counters_, times_);
  // Initial wall pressure consistent with the initial fluid state (P.20): the Jacobi sweeps
  // iterated to convergence once, since boundary particles start without a pressure.
  sweeps_.derivatives_sweep(P_.v, nullptr);
  sweeps_.boundary_pressure(50, stage_params(prm_, dt_), counters_);
}

template <int D>
StableStep FluidSolverOf<D>::stable_step() const {
  StableStep st = fluid_stable_step(prm_, sweeps_.min_distance(), sweeps_.max_speed());
  st.tighten(body_force_dt(prm_), StepLimit::BodyForce);
  return st;
}

template <int D>
std::optional<FailureOf<D>> FluidSolverOf<D>::step(real dt_cap) {
  return advance(dt_cap, std::numeric_limits<real>::quiet_NaN());
}

template <int D>
std::optional<FailureOf<D>> FluidSolverOf<D>::step_to(real t_target) {
  const real cap = t_target - t_;
  return cap > 0 ? advance(cap, t_target) : advance(0, std::numeric_limits<real>::quiet_NaN());
}

template <int D>
std::optional<FailureOf<D>> FluidSolverOf<D>::advance(real dt_cap, real land_at) {
  const bool reordered = prm_.reorder_interval > 0 && steps_ % prm_.reorder_interval == 0;
  if (reordered) {
    PhaseTimer timer(times_.neighbors);
    sweeps_.reorder_fluid();
  }
  sweeps_.refresh_geometry(counters_, times_);
  {
    PhaseTimer timer(times_.integration);
    const StableStep st = stable_step();
    dt_ = st.dt;
    limit_ = st.limit;
    const real own = case_dt(prm_);
    if (dt_ < kTimeStepCollapse * own)
      return FailureOf<D>{
          fmt::format("the time step collapsed to {:.3g} s, below {:g} of the case's {:.3g} s "
                      "(cfl d0 / c, cfl d0^2 / nu)",
                      dt_, kTimeStepCollapse, own),
          -1, Vec<D>{}};
    if (dt_cap > 0 && dt_cap <= dt_) {
      dt_ = dt_cap;
      limit_ = StepLimit::Landing;
    }
  }
  const real dt = dt_;
  const real t_new = dt_cap > 0 && dt == dt_cap && std::isfinite(land_at) ? land_at : t_ + dt;
  const StageParamsOf<D> sp = stage_params(prm_, dt);
  stage(StageStart::StepStart, sp);  // predictor: V* = V^n + dt A(V^n, P^n); rho* from V*
  stage(StageStart::Predicted, sp);  // corrector: V** = V* + dt A(V*, P*); rho** from V**
  update(dt, t_new);
  return finish_step();
}

template <int D>
void FluidSolverOf<D>::stage(StageStart from, const StageParamsOf<D>& sp) {
  sweeps_.save_stage_start(from);
  {
    PhaseTimer timer(times_.operators);
    if (from == StageStart::StepStart)
      sweeps_.start_of_step_derivatives();  // grad V, lap V and grad P / rho of the step start
    else
      sweeps_.pressure_gradient();  // grad P* / rho* (the velocity's derivatives are those of V*)
    sweeps_.rhie_chow_and_momentum(from, sp);
    sweeps_.derivatives_and_continuity(from, sp);
  }
  PhaseTimer timer(times_.wall_pressure);
  sweeps_.boundary_pressure(prm_.wall_pressure_sweeps, sp, counters_);
}

template <int D>
void FluidSolverOf<D>::update(real dt, real t_new) {
  real vmax2 = 0;
  {
    PhaseTimer timer(times_.integration);
    vmax2 = sweeps_.end_of_step(dt, prm_.single_layer);  // P.28, P.32
  }
  if (!prm_.single_layer) {  // dummies copy the averaged surface values
    PhaseTimer timer(times_.wall_pressure);
    sweeps_.boundary_pressure(prm_.wall_pressure_sweeps, stage_params(prm_, dt_), counters_);
  }
  t_ = t_new;
  ++steps_;
  if (prm_.shifting_beta > 0) {  // P.33-P.36, with the step's geometry and the new fields
    PhaseTimer timer(times_.shifting);
    sweeps_.shift(prm_.shifting_beta * std::sqrt(vmax2) * dt, prm_.c);
  }
}

template <int D>
std::optional<FailureOf<D>> FluidSolverOf<D>::finish_step() {
  PhaseTimer timer(times_.integration);
  const real keep = prm_.surface_guard * prm_.d0;  // the surface guard's keep-out distance
  if (keep > 0) sweeps_.guard_surfaces(keep, counters_);
  const std::int64_t worst = sweeps_.unhealthy_id(health_limits(prm_, domain_));
  if (worst < 0) return std::nullopt;
  std::size_t i = 0;
  while (P_.id[i] != worst) ++i;
  return FailureOf<D>{unhealthy_particle(P_, i, prm_), worst, P_.x[i]};
}

template std::string unhealthy_particle<2>(const ParticlesOf<2>&, std::size_t, const FluidParamsOf<2>&);
template std::string unhealthy_particle<3>(const ParticlesOf<3>&, std::size_t, const FluidParamsOf<3>&);
template class FluidSolverOf<2>;
template class FluidSolverOf<3>;

}  // namespace particula
