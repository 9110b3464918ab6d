// The time loop of a fluid between fixed walls in D dimensions (docs/method.md, "One time
// step"): the predictor-corrector with frozen positions, the single-layer wall pressure P.20,
// adaptive dt, particle shifting and the surface guard, on the host's passes (CpuSweepsOf<D>).
// It is the step of Solver without what Solver adds for its solids (rigid groups, contacts, the
// load band) and open boundaries, and it is the 3D solver while those have no 3D form: its 2D
// instantiation gives a wall-bounded flow bitwise the same fluid as Solver (tested), so the two
// cannot drift apart.
//
// The walls are the boundary block [0, n_boundary) of the particles: kind Boundary, in place, at
// rest or sliding along themselves with the velocity they start with (scene/box3.hpp), with their
// analytic normals (P.18 replaces them with kernel normals when asked for) and areas ds.
#pragma once

#include <cstdint>
#include <optional>

#include "particula/neighbors/domain.hpp"
#include "particula/solver/counters.hpp"
#include "particula/solver/cpu_sweeps.hpp"
#include "particula/solver/failure.hpp"
#include "particula/solver/particles.hpp"
#include "particula/solver/physics_params.hpp"
#include "particula/solver/time_step.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

/// What is wrong with particle i of `P` that the health check flagged (a non-finite value, a
/// density out of range, or a fluid particle out of the closed domain), as Failure::what.
template <int D>
std::string unhealthy_particle(const ParticlesOf<D>& P, std::size_t i, const FluidParamsOf<D>& prm);

template <int D>
class FluidSolverOf {
 public:
  /// A fresh run: the wall pressure starts from P.20 iterated to convergence on the initial state.
  /// The walls' velocities are theirs for the whole run.
  FluidSolverOf(const FluidParamsOf<D>& params, const DomainOf<D>& domain, ParticlesOf<D> particles);
  // The passes hold references to the solver's members: not copied, not moved.
  FluidSolverOf(const FluidSolverOf&) = delete;
  FluidSolverOf& operator=(const FluidSolverOf&) = delete;

  /// Advances one full time step of at most `dt_cap` (0: no cap). Returns the failure, if any.
  std::optional<FailureOf<D>> step(real dt_cap = 0);
  /// Advances one step of at most t_target - time(), ending exactly at t_target when that cap
  /// limits the step.
  std::optional<FailureOf<D>> step_to(real t_target);

  real time() const { return t_; }
  real last_dt() const { return dt_; }
  StepLimit last_step_limit() const { return limit_; }
  std::int64_t step_count() const { return steps_; }
  const ParticlesOf<D>& particles() const { return P_; }
  const DomainOf<D>& domain() const { return domain_; }
  const FluidParamsOf<D>& params() const { return prm_; }
  const SolverCounters& counters() const { return counters_; }
  const PhaseTimes& phase_times() const { return times_; }
  /// The host's passes and the per-particle fields of their last evaluation.
  const CpuSweepsOf<D>& sweeps() const { return sweeps_; }
  /// The stable step for the current state (P.29-P.31 and M.9).
  StableStep stable_step() const;

 private:
  std::optional<FailureOf<D>> advance(real dt_cap, real land_at);
  /// One stage of the predictor-corrector from the stage start `from`: momentum, continuity, P.20.
  void stage(StageStart from, const StageParamsOf<D>& sp);
  /// The end of the step: averages (P.28), positions, shifting.
  void update(real dt, real t_new);
  /// The surface guard and the health check.
  std::optional<FailureOf<D>> finish_step();

  FluidParamsOf<D> prm_;
  DomainOf<D> domain_;
  ParticlesOf<D> P_;
  Wendland<D> kernel_;
  CpuSweepsOf<D> sweeps_;
  SolverCounters counters_;
  PhaseTimes times_;
  real t_ = 0, dt_ = 0;
  StepLimit limit_ = StepLimit::Acoustic;
  std::int64_t steps_ = 0;
};

using FluidSolver3 = FluidSolverOf<3>;

}  // namespace particula
