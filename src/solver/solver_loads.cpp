// Hydrodynamic loads on the rigid groups (walls and bodies): the paper's surface sum
// (P.26-P.27) or the band momentum balance (solver/load_band.hpp).
#include "particula/solver/solver.hpp"

namespace particula {

void Solver::group_loads() {
  if (prm_.momentum_force) return momentum_group_loads();
  backend_->group_loads(groups_, prm_.nu * prm_.rho0, loads_);
  for (std::size_t k = 0; k < groups_.size(); ++k) {
    groups_[k].force_pressure = loads_[k].force_pressure;
    groups_[k].force_viscous = loads_[k].force_viscous;
    groups_[k].torque = loads_[k].torque;
  }
}

BandScene Solver::band_scene() const {
  // the host evaluates each entry as it sums them; a device evaluates them all first
  return BandScene{prm_, domain_, P_, groups_, backend_->on_host() ? nullptr : backend_};
}

void Solver::momentum_group_loads() {
  BandFields f;  // the host's fields of the stage (a device reads its own)
  f.grad_v = cpu_->grad_v().data();
  f.lap_v = cpu_->lap_v().data();
  f.odd_even = cpu_->odd_even();
  f.grad_p_over_rho = cpu_->grad_p_over_rho().data();
  band_.group_loads(band_scene(), f, groups_);
}

}  // namespace particula
