#include "particula/validation/analytic.hpp"

#include <cmath>

namespace particula::analytic {

real couette_startup(real y, real t, real L, real V0, real nu) {
  real u = V0 * y / L;
  // The series converges like 1/n at t = 0; terms decay as exp(-n^2 ...) for t > 0.
  for (int n = 1; n <= 20000; ++n) {
    const real decay = std::exp(-n * n * M_PI * M_PI * nu * t / (L * L));
    const real term = 2 * V0 / (n * M_PI) * ((n % 2) ? -1.0 : 1.0) * std::sin(n * M_PI * y / L) * decay;
    u += term;
    if (decay < 1e-17) break;
  }
  return u;
}

real poiseuille_startup(real y, real t, real L, real F, real nu) {
  real u = F / (2 * nu) * y * (L - y);
  for (int n = 0; n <= 20000; ++n) {
    const int m = 2 * n + 1;
    const real decay = std::exp(-m * m * M_PI * M_PI * nu * t / (L * L));
    u -= 4 * F * L * L / (nu * M_PI * M_PI * M_PI * m * m * m) * std::sin(m * M_PI * y / L) * decay;
    if (decay < 1e-17) break;
  }
  return u;
}

real taylor_green_decay(real t, real reynolds) { return std::exp(-8 * M_PI * M_PI * t / reynolds); }

}  // namespace particula::analytic
