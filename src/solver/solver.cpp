#include "particula/solver/solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "particula/bodies/collision.hpp"
#include "particula/bodies/rigid_motion.hpp"
#include "particula/boundary/wall_pressure.hpp"
#include "particula/fluid/fluid.hpp"
#include "particula/solver/closest_pair.hpp"
#include "particula/solver/fluid_solver.hpp"
#include "particula/sph/operators.hpp"
#include "phase_timer.hpp"

namespace particula {

Solver::Solver(PhysicsParams params, Domain domain, Particles particles, std::vector<RigidGroup> groups,
               SolverStart start, real t0, std::int64_t step0)
    : prm_(params),
      domain_(domain),
      P_(std::move(particles)),
      bodies_(prm_, std::move(groups)),
      kernel_(params.h),
      t_(t0),
      steps_(step0),
      cpu_(std::make_unique<CpuBackend>(prm_, domain_, kernel_, P_)),
      backend_(cpu_.get()),
      open_(prm_.open.size()) {
  if (start == SolverStart::Fresh) {
    bodies_.place(*backend_);
    refresh_geometry();
    open_ghost_weights();
    open_velocities(t_);
    open_pressures();
    // Initial wall pressure consistent with the initial fluid state (P.20): iterate the Jacobi
    // sweeps to convergence once, since boundary particles start without a pressure.
    cpu_->derivatives_sweep(P_.v, nullptr);
    cpu_->boundary_pressure(50, stage_params(dt_), counters_);
  }
  // A restart takes the checkpointed state exactly as it is. The GPU backend starts from the
  // host state prepared above; everything derived is recomputed at the start of each step.
  if (prm_.cuda) {
    device_ = make_cuda_backend(prm_, cpu_->grid().geometry(), kernel_, P_);
    device_->upload(P_);
    backend_ = device_.get();
  }
}

Solver::~Solver() = default;

void Solver::sync_host() const {
  if (host_current_) return;
  backend_->download(P_);
  host_current_ = true;
}

void Solver::sync_device() {
  if (device_current_) return;
  backend_->upload(P_);
  device_current_ = true;
}

const Particles& Solver::particles() const {
  sync_host();
  return P_;
}

Particles& Solver::particles() {
  sync_host();
  device_current_ = false;
  return P_;
}

void Solver::refresh_geometry() {
  backend_->refresh_geometry(counters_, times_);
  host_current_ = backend_->on_host();
}

void Solver::boundary_pressure() {
  PhaseTimer timer(times_.wall_pressure);
  if (P_.n_boundary == 0) return;
  backend_->boundary_pressure(prm_.wall_pressure_sweeps, stage_params(dt_), counters_);
}

void Solver::group_loads() {
  if (prm_.momentum_force)
    band_.group_loads(band_scene(), *backend_, bodies_.groups());
  else
    bodies_.surface_loads(*backend_);
}

StageParams Solver::stage_params(real dt) const { return particula::stage_params<2>(prm_, dt); }

HealthLimits Solver::health_limits() const { return particula::health_limits<2>(prm_, domain_); }

StableStep Solver::stable_step() const {
  StableStep st = fluid_stable_step<2>(prm_, backend_->min_distance(), backend_->max_speed());
  const real contact_dt = contacts_.dt_limit();
  if (contact_dt > 0) st.tighten(contact_dt, StepLimit::Contact);  // t_c / 20 of the contacts
  st.tighten(body_force_dt(), StepLimit::BodyForce);
  return st;
}

real Solver::stable_dt() const { return stable_step().dt; }

real Solver::body_force_dt() const { return particula::body_force_dt<2>(prm_); }

real Solver::case_dt() const { return particula::case_dt<2>(prm_); }

std::optional<Failure> Solver::time_step_collapse(real dt) const {
  const real dt_scale = case_dt();
  if (!(dt < kTimeStepCollapse * dt_scale)) return std::nullopt;
  Failure f = time_step_limit(dt);
  f.what = fmt::format(
      "the time step collapsed to {:.3g} s, below {:g} of the case's {:.3g} s (cfl d0 / c, cfl d0^2 / nu); "
      "it is "
      "limited by {}",
      dt, kTimeStepCollapse, dt_scale, f.what);
  return f;
}

Failure Solver::time_step_limit(real dt) const {
  // Name the limit: a contact, the fastest particle or the closest particle pair (and where).
  const real dlist = backend_->min_distance();
  const real vmax = backend_->max_speed();
  std::string why;
  Failure f{{}, -1, Vec2{}};
  if (contacts_.dt_limit() > 0 && contacts_.dt_limit() <= dt) {
    why =
        "the stability limit of a contact (t_c / 20): a contact too stiff for its bodies' masses "
        "(collision.*)";
  } else if (vmax > prm_.c) {
    why = fmt::format("a particle at {:.3g} m/s, {:.3g} times the sound speed: the flow has blown up", vmax,
                      vmax / prm_.c);
  } else {
    why = fmt::format("two particles {:.3g} d0 apart: particles collapsing onto each other", dlist / prm_.d0);
    const Particles& P = particles();
    const ClosestPair pair = closest_pair(P, domain_, prm_.h);
    if (pair.found) {
      const auto describe = [&](std::uint32_t i) {
        return describe_particle(P, domain_, bodies_.groups(), prm_.h, prm_.d0, i);
      };
      why += fmt::format(" ({}; {})", describe(pair.i), describe(pair.j));
      f.particle_id = P.id[pair.i];
      f.position = P.x[pair.i];
    }
  }
  f.what = why;
  return f;
}

std::optional<Failure> Solver::step(real dt_cap) {
  return advance(dt_cap, std::numeric_limits<real>::quiet_NaN());
}

std::optional<Failure> Solver::step_to(real t_target) {
  const real cap = t_target - t_;
  return cap > 0 ? advance(cap, t_target) : advance(0, std::numeric_limits<real>::quiet_NaN());
}

std::optional<Failure> Solver::advance(real dt_cap, real land_at) {
  prepare_step();
  {
    PhaseTimer timer(times_.bodies);
    if (auto f = contacts_.find(prm_, domain_, bodies_.groups())) return f;
  }
  {
    PhaseTimer timer(times_.integration);
    const StableStep st = stable_step();
    dt_ = st.dt;
    limit_ = st.limit;
    if (auto f = time_step_collapse(dt_)) return f;
    if (dt_cap > 0 && dt_cap <= dt_) {
      dt_ = dt_cap;
      limit_ = StepLimit::Landing;
    }
  }
  const real dt = dt_;
  // The time at the end of the step: exactly land_at when the cap limits the step (t_ + dt can
  // miss it in the last bit), so that output times are the values they stand for.
  const real t_new = dt_cap > 0 && dt == dt_cap && std::isfinite(land_at) ? land_at : t_ + dt;
  {
    PhaseTimer timer(times_.bodies);
    contacts_.apply(prm_, domain_, bodies_.groups(), dt);
  }
  const StageParams sp = stage_params(dt);
  open_velocities(t_ + 0.5 * dt);
  open_pressures();
  // predictor: V* = V^n + dt A(V^n, P^n); bodies from the loads of P^n, tau^n;
  // rho* = rho^n + dt D(V*, P^n) (continuity uses the new velocity)
  stage(StageStart::StepStart, sp, t_new);
  // corrector: V** = V* + dt A(V*, P*); bodies likewise; rho** = rho* + dt D(V**, P*)
  stage(StageStart::Predicted, sp, t_new);
  update(dt, t_new);
  return finish_step();
}

void Solver::prepare_step() {
  sync_device();
  const bool reordered = prm_.reorder_interval > 0 && steps_ % prm_.reorder_interval == 0;
  if (reordered) {
    PhaseTimer timer(times_.neighbors);
    backend_->reorder_fluid();
  }
  refresh_geometry();
  open_ghost_weights();
  // buffer particles are not integrated: the time step does not see their pairs
  if (!prm_.open.empty()) backend_->skip_buffer_pairs_in_min_distance();
  if (prm_.momentum_force) {
    PhaseTimer timer(times_.bodies);
    band_.update(band_scene(), *backend_, reordered);
  }
}

void Solver::stage(StageStart from, const StageParams& sp, real t_new) {
  backend_->save_stage_start(from);
  bodies_.start_stage(from);
  {
    PhaseTimer timer(times_.operators);
    if (from == StageStart::StepStart)
      backend_->start_of_step_derivatives();  // grad V, lap V and grad P / rho of the step start
    else
      backend_->pressure_gradient();  // grad P* / rho* (the velocity's derivatives are those of V*)
    backend_->rhie_chow_and_momentum(from, sp);
  }
  {
    // Bodies advance one stage from the loads of the current P, tau; their surface particles then
    // carry the stage's velocity and acceleration (positions stay frozen during the stages).
    PhaseTimer timer(times_.bodies);
    group_loads();
    bodies_.stage(*backend_, sp.dt, t_new);
  }
  {
    PhaseTimer timer(times_.operators);
    backend_->derivatives_and_continuity(from, sp);
  }
  open_pressures();
  boundary_pressure();
}

void Solver::update(real dt, real t_new) {
  // P.28, P.32: averages of the stage-start and corrected values
  real vmax2 = 0;
  {
    PhaseTimer timer(times_.integration);
    vmax2 = backend_->end_of_step(dt, prm_.single_layer);
    open_move(dt);
  }
  if (!prm_.single_layer) boundary_pressure();  // dummies copy the averaged surface values
  t_ = t_new;
  ++steps_;
  {
    PhaseTimer timer(times_.bodies);
    bodies_.update(*backend_, dt, t_);
  }
  // particle shifting (P.33-P.36), with the step's geometry and the new fields
  if (prm_.shifting_beta > 0) {
    PhaseTimer timer(times_.shifting);
    backend_->shift(prm_.shifting_beta * std::sqrt(vmax2) * dt, prm_.c);
  }
}

std::optional<Failure> Solver::finish_step() {
  PhaseTimer timer(times_.integration);
  const real keep = prm_.surface_guard * prm_.d0;  // the surface guard's keep-out distance
  if (keep > 0) backend_->guard_surfaces(keep, counters_);
  open_end_of_step();
  return check_health();
}

std::optional<Failure> Solver::check_health() const {
  if (auto f = bodies_.at_open_boundary()) return f;
  const HealthLimits lim = health_limits();
  const std::int64_t worst = backend_->unhealthy_id(lim);
  if (worst < 0) return bodies_.unhealthy();
  sync_host();  // the host copy names the particle
  std::size_t i = 0;
  while (P_.id[i] != worst) ++i;
  Failure f;
  f.particle_id = worst;
  f.position = P_.x[i];
  f.what = unhealthy_particle<2>(P_, i, prm_);
  if (P_.is_fluid(i)) f.what += likely_cause(P_.x[i]);
  return f;
}

std::string Solver::likely_cause(Vec2 x) const {
  // Next to an open boundary: the flow through it.
  for (std::size_t z = 0; z < prm_.open.size(); ++z) {
    const OpenZone& oz = prm_.open[z];
    const real xi = open_depth(oz, x), s = open_along(oz, x);
    if (!(xi < 3 * prm_.h && s > -prm_.h && s < oz.width + prm_.h)) continue;
    return fmt::format(
        "; it is {:.3g} d0 from {} '{}': likely cause: flow back in through that boundary or a "
        "pressure wave reflected there (a channel between a velocity inlet and a pressure outlet "
        "rings at c / 4L; an inflow started faster than a few of its periods sets it ringing hard "
        "enough to reverse the flow at the outlet: raise inlet[].ramp_time; docs/method.md, "
        "\"Open boundaries\")",
        xi / prm_.d0, oz.inlet ? "inlet" : "outlet", prm_.open_specs[z].name);
  }
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
  const RigidGroup& g = bodies_.groups()[static_cast<std::size_t>(P_.group[s])];
  const std::string where = (g.is_wall ? "wall '" : "body '") + g.name + "'";
  char buf[640];
  if (d < 0.5)
    std::snprintf(
        buf, sizeof buf,
        "; it is %.3g d0 from the surface of %s: likely cause: fluid squeezed against that surface "
        "(two surfaces closing faster than the fluid can leave the gap, or a contact too soft to keep "
        "them apart: see the collision.* keys; numerics.surface_guard sets the keep-out distance)",
        d, where.c_str());
  else
    std::snprintf(
        buf, sizeof buf,
        "; the nearest surface (%s) is %.3g d0 away: likely cause: a flow too fast or too under-resolved "
        "for this resolution (Mach number V/fluid.c above about 0.1, or too few particles across a "
        "body or a gap: lower resolution.d0 or raise fluid.c)",
        where.c_str(), d);
  return buf + weak_compressibility_report(x);
}

std::string Solver::weak_compressibility_report(Vec2 failed_at) const {
  // The weakly compressible model holds while density varies by about 1 %: flow speeds below
  // c / 10 (rho varies as Ma^2) and, with gravity in the fluid, a hydrostatic head g H below
  // c^2 / 100 (rho0 g H / (rho0 c^2) is its relative density change). The fluid within 3 h of
  // the failed particle is left out: it moves with the blow-up, not with the flow.
  real vmax = 0;
  const real near2 = 9 * prm_.h * prm_.h;
  for (std::size_t k = P_.n_boundary; k < P_.size(); ++k)
    if (P_.is_fluid(k) && !(norm2(domain_.separation(P_.x[k], failed_at)) < near2))
      vmax = std::max(vmax, norm(P_.v[k]));
  std::string out;
  const real mach = vmax / prm_.c;
  if (std::isfinite(mach) && mach > 0.1)
    out += fmt::format(
        "; the fastest fluid particle (beyond 3 h of this one) moves at {:.3g} m/s, Mach {:.3g} "
        "(keep it below 0.1: fluid.c of at least {:.3g} m/s)",
        vmax, mach, 10 * vmax);
  const real g = norm(prm_.gravity);
  if (prm_.gravity_in_fluid && g > 0) {
    const Vec2 size = domain_.size();  // g H: |g| times the domain's extent along g (a box's diagonal reach)
    const real head = std::fabs(prm_.gravity.x) * size.x + std::fabs(prm_.gravity.y) * size.y;
    const real squeeze = head / (prm_.c * prm_.c);
    if (squeeze > 0.01)
      out += fmt::format(
          "; gravity compresses the fluid by g H / c^2 = {:.2g} over the domain's height (keep it "
          "below 0.01: fluid.c of at least {:.3g} m/s)",
          squeeze, 10 * std::sqrt(head));
  }
  return out;
}

}  // namespace particula
