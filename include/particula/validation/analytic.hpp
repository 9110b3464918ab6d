// Exact solutions used for validation (reference/README.md).
#pragma once

#include "particula/core/types.hpp"

namespace particula::analytic {

/// Start-up Couette flow between y = 0 (fixed) and y = L (moving at V0 from t = 0):
/// u = V0 y/L + sum_{n>=1} 2 V0/(n pi) (-1)^n sin(n pi y/L) exp(-n^2 pi^2 nu t/L^2).
real couette_startup(real y, real t, real L, real V0, real nu);

/// Start-up Poiseuille flow driven by a body force F between fixed plates y = 0 and y = L:
/// u = F/(2 nu) y (L - y) - sum_{n>=0} 4 F L^2/(nu pi^3 (2n+1)^3) sin((2n+1) pi y/L) exp(-(2n+1)^2 pi^2 nu t/L^2).
real poiseuille_startup(real y, real t, real L, real F, real nu);

/// Taylor-Green vortex amplitude decay exp(b t), b = -8 pi^2 / Re (unit square, U = 1).
real taylor_green_decay(real t, real reynolds);

}  // namespace particula::analytic
