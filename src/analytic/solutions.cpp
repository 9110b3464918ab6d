#include "particula/analytic/solutions.hpp"

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

real duct_startup(real y, real z, real t, real Ly, real Lz, real F, real nu) {
  if (!(t > 0)) return 0;
  // Steady part: the plates' parabola in y less the cosh correction of the z walls,
  //   u_s = F y (Ly - y) / (2 nu) - sum_{m odd} 4 F / (m pi nu k^2) sin(k y) cosh(k (z - Lz/2)) / cosh(k Lz/2),
  // k = m pi / Ly; the ratio of the cosh is written with exponentials of negative arguments
  // (it is exp(-k d) at a distance d from the nearer z wall: the terms fall off exponentially).
  real u = F * y * (Ly - y) / (2 * nu);
  const real s = std::fabs(z - 0.5 * Lz);
  for (int m = 1; m < 200001; m += 2) {
    const real k = m * M_PI / Ly;
    const real ratio = std::exp(-k * (0.5 * Lz - s)) * (1 + std::exp(-2 * k * s)) / (1 + std::exp(-k * Lz));
    const real term = 4 * F / (m * M_PI * nu * k * k) * ratio;
    u -= term * std::sin(k * y);
    if (term < 1e-15 * F * Ly * Ly / nu) break;
  }
  // Transient part: sum_{m,n odd} 16 F / (pi^2 m n nu lambda) exp(-nu lambda t) sin(m pi y / Ly)
  // sin(n pi z / Lz), lambda = (m pi / Ly)^2 + (n pi / Lz)^2: the exponential ends both sums.
  for (int m = 1;; m += 2) {
    const real ky = m * M_PI / Ly;
    if (nu * ky * ky * t > 40) break;
    for (int n = 1;; n += 2) {
      const real kz = n * M_PI / Lz, lambda = ky * ky + kz * kz;
      if (nu * lambda * t > 40) break;
      u -= 16 * F / (M_PI * M_PI * m * n * nu * lambda) * std::exp(-nu * lambda * t) * std::sin(ky * y) *
           std::sin(kz * z);
    }
  }
  return u;
}

real bessel_j1_zero(int n) {
  // McMahon's expansion, then Newton on J1 (J1' = J0 - J1/x): converged to round-off.
  const real beta = (n + 0.25) * M_PI;
  real x = beta - 3 / (8 * beta) + 3 / (128 * beta * beta * beta);
  for (int it = 0; it < 8; ++it) {
    const real j1 = std::cyl_bessel_j(1.0, x), j0 = std::cyl_bessel_j(0.0, x);
    const real dx = j1 / (j0 - j1 / x);
    x -= dx;
    if (std::fabs(dx) < 1e-15 * x) break;
  }
  return x;
}

real spin_up_velocity(real r, real t, real R, real omega, real nu) {
  if (t <= 0) return r >= R ? omega * R : 0;
  real u = omega * r;
  // Terms decay as exp(-lambda_n^2 nu t / R^2); up to 20000 of them at the earliest times.
  for (int n = 1; n <= 20000; ++n) {
    const real lambda = bessel_j1_zero(n);
    const real decay = std::exp(-lambda * lambda * nu * t / (R * R));
    u += 2 * omega * R * std::cyl_bessel_j(1.0, lambda * r / R) / (lambda * std::cyl_bessel_j(0.0, lambda)) * decay;
    if (decay < 1e-17) break;
  }
  return u;
}

real spin_up_torque(real t, real R, real omega, real mu, real nu) {
  if (t <= 0) return -std::copysign(INFINITY, omega);
  real sum = 0;
  for (int n = 1; n <= 1000000; ++n) {
    const real lambda = n <= 50 ? bessel_j1_zero(n) : (n + 0.25) * M_PI - 3 / (8 * (n + 0.25) * M_PI);
    const real decay = std::exp(-lambda * lambda * nu * t / (R * R));
    sum += decay;
    if (decay < 1e-16 * sum) break;
  }
  return -4 * M_PI * mu * omega * R * R * sum;
}

real taylor_green_decay(real t, real reynolds) { return std::exp(-8 * M_PI * M_PI * t / reynolds); }

}  // namespace particula::analytic
