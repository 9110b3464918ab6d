// What a step of the fluid is made with, written once for D = 2 and 3: the constants of its
// pointwise updates (StageParamsOf, from the fluid's parameters and dt), the limits of a healthy
// state, and the stable time step of the fluid (P.29-P.31 and M.9: the Courant and viscous
// conditions, time.dt_max, the force condition). The solvers add their own limits (a contact's
// t_c / 20) and the landing on output times.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "particula/solver/physics_params.hpp"
#include "particula/solver/sweeps.hpp"

namespace particula {

/// A stable time step below this fraction of the case's own (cfl d0 / c, cfl d0^2 / nu) is a
/// collapse: 1e4 times more steps than the case was sized for.
inline constexpr real kTimeStepCollapse = 1e-4;

/// A stable time step below this fraction of the case's own for kTimeStepDropSteps steps in a
/// row is reported in the log and summary.json (the run goes on): a thousand times more steps
/// than the case was sized for is a defect to look at, even where the run reaches its end.
inline constexpr real kTimeStepDrop = 1e-3;
inline constexpr int kTimeStepDropSteps = 10;

/// What set a step's length (M.9): the Courant condition (P.30), viscous diffusion (P.31),
/// time.dt_max, the force condition, a contact's t_c / 20, or the next output or end time the
/// step was shortened to land on.
enum class StepLimit { Acoustic, Viscous, DtMax, BodyForce, Contact, Landing };
inline constexpr int kStepLimits = 6;
/// The limit's name in summary.json (time_step.limited_by).
const char* step_limit_name(StepLimit l);

/// The stable step and the limit that sets it.
struct StableStep {
  real dt;
  StepLimit limit;
  /// Tightens the step to `limit_dt` when that is shorter, `why` then being what sets it.
  void tighten(real limit_dt, StepLimit why) {
    if (limit_dt < dt) {
      dt = limit_dt;
      limit = why;
    }
  }
};

/// The acceleration every fluid particle feels: the body force, plus gravity when it is kept in
/// the fluid.
template <int D>
Vec<D> fluid_body_force(const FluidParamsOf<D>& prm) {
  return prm.body_force + (prm.gravity_in_fluid ? prm.gravity : Vec<D>{});
}

/// Monaghan's force condition dt <= 0.25 sqrt(h / |f|) for the acceleration f every fluid
/// particle feels (body force, gravity kept in the fluid): without it a strong body force on a
/// fluid at rest moved particles by more than h in one step (gravity 1e6 m/s^2: exit 3 at step
/// 1, the Courant condition of a fluid at rest knowing nothing of f). Infinite without either.
template <int D>
real body_force_dt(const FluidParamsOf<D>& prm) {
  Vec<D> f = prm.body_force;
  if (prm.gravity_in_fluid) f += prm.gravity;
  const real a = norm(f);
  return a > 0 ? 0.25 * std::sqrt(prm.h / a) : std::numeric_limits<real>::infinity();
}

/// The fluid's stable step for the closest pair `dmin` of the neighbour list (d0 when the list
/// has none) and the fastest particle `vmax`: P.30, P.31, time.dt_max; the force condition is
/// the caller's last limit (body_force_dt), after its own.
template <int D>
StableStep fluid_stable_step(const FluidParamsOf<D>& prm, real dlist, real vmax) {
  const real dmin = dlist > 0 && std::isfinite(dlist) ? dlist : prm.d0;
  StableStep st{prm.cfl * dmin / (prm.c + vmax), StepLimit::Acoustic};             // P.30: Courant condition
  if (prm.nu > 0) st.tighten(prm.cfl * dmin * dmin / prm.nu, StepLimit::Viscous);  // P.31: viscous diffusion
  if (prm.dt_max > 0) st.tighten(prm.dt_max, StepLimit::DtMax);
  return st;
}

/// The step of the case's own scales: P.30 at d0 and the sound speed, P.31 at d0, dt_max and
/// the force condition. A step far below it has collapsed.
template <int D>
real case_dt(const FluidParamsOf<D>& prm) {
  real dt_scale = prm.cfl * prm.d0 / prm.c;
  if (prm.nu > 0) dt_scale = std::min(dt_scale, prm.cfl * prm.d0 * prm.d0 / prm.nu);
  if (prm.dt_max > 0) dt_scale = std::min(dt_scale, prm.dt_max);
  return std::min(dt_scale, body_force_dt(prm));
}

/// The constants of a stage of length dt.
template <int D>
StageParamsOf<D> stage_params(const FluidParamsOf<D>& prm, real dt) {
  StageParamsOf<D> s;
  s.dt = dt;
  s.g_dt = prm.rhie_chow_factor * dt;
  s.nu = prm.nu;
  s.f = fluid_body_force(prm);
  s.rho0 = prm.rho0;
  s.c = prm.c;
  s.p0 = prm.p0;
  // kappa = alpha c h (docs/method.md, "Odd-even velocity damping")
  s.kappa = prm.odd_even_damping * prm.c * prm.h;
  s.void_distance = kVoidDistance * prm.d0;
  s.single_layer = prm.single_layer;
  return s;
}

/// The limits of a healthy state of the fluid in `domain`.
template <int D>
HealthLimitsOf<D> health_limits(const FluidParamsOf<D>& prm, const DomainOf<D>& domain) {
  HealthLimitsOf<D> l;
  l.rho_lo = prm.rho_min_ratio * prm.rho0;
  l.rho_hi = prm.rho_max_ratio * prm.rho0;
  l.h = prm.h;
  l.domain = domain;
  return l;
}

}  // namespace particula
