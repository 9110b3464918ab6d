#include "particula/solver/particles.hpp"

namespace particula {

template <int D>
void ParticlesOf<D>::resize(std::size_t n) {
  x.resize(n);
  v.resize(n);
  rho.resize(n);
  p.resize(n);
  m.resize(n);
  kind.resize(n, Kind::Fluid);
  group.resize(n, -1);
  id.resize(n);
}

template <int D>
void ParticlesOf<D>::resize_boundary(std::size_t nb) {
  n_boundary = nb;
  local.resize(nb);
  normal_local.resize(nb);
  ds.resize(nb);
  acc.resize(nb);
  normal.resize(nb);
  wedge.resize(nb, 0);
  source.resize(nb, -1);
}

template struct ParticlesOf<2>;
template struct ParticlesOf<3>;

}  // namespace particula
