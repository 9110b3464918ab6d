// Shepard-normalized SPH interpolation of particle fields at arbitrary points (line probes):
//   f(x) = sum_j f_j W(x - x_j) w_j / sum_j W(x - x_j) w_j
// over fluid and boundary-surface particles (so that walls contribute their velocity).
#pragma once

#include <vector>

#include "particula/neighbors/domain.hpp"
#include "particula/solver/particles.hpp"
#include "particula/sph/kernel.hpp"

namespace particula {

struct PointSample {
  Vec2 v;
  real p = 0;
  real shepard = 0;  // sum_j W w_j (about 1 inside the fluid, 0 where no particle is near)
};

std::vector<PointSample> interpolate_at(const Particles& P, const Domain& domain, const WendlandC2& kernel,
                                        const std::vector<Vec2>& points);

}  // namespace particula
