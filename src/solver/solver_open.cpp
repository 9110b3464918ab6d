// The open boundaries' passes in the step (solver/open_boundaries.hpp): they run on the host
// state, so on a device the state comes down before the fits and the transfer, and what they set
// goes back up (docs/architecture.md, "Backends"; on the CPU these transfers do nothing).
#include "particula/solver/solver.hpp"
#include "phase_timer.hpp"

namespace particula {

void Solver::open_ghost_weights() {
  PhaseTimer timer(times_.geometry);
  open_.clear();
  if (prm_.open.empty()) return;
  sync_host();
  open_.fit(open_scene(), P_, backend_->host_grid(P_), counters_);
}

void Solver::open_velocities(real t_mid) {
  PhaseTimer timer(times_.wall_pressure);
  open_.set_velocities(open_scene(), P_, t_mid);
  backend_->set_buffer_particles(open_.buffer(), P_);
}

void Solver::open_pressures() {
  PhaseTimer timer(times_.wall_pressure);
  if (!open_.buffer().empty()) backend_->download_pressures(P_.p);  // the fluid's stage pressures
  open_.set_pressures(open_scene(), P_);
  backend_->set_buffer_particles(open_.buffer(), P_);
}

void Solver::open_move(real dt) {
  open_.move(open_scene(), P_, dt);
  backend_->set_buffer_particles(open_.buffer(), P_);
}

void Solver::open_end_of_step() {
  if (prm_.open.empty()) return;
  // The transfer and a body's removal change the particle count: done on the whole host state,
  // which goes back to a device afterwards (one download and one upload a step).
  sync_host();
  open_.transfer(open_scene(), P_);
  open_.remove_bodies_at_outlets(open_scene(), P_, bodies_.groups(), t_);
  backend_->upload(P_);
  host_current_ = true;
  device_current_ = true;
}

}  // namespace particula
