// Exact solutions of the flows that have one: the profile error of a run whose case names one
// (case key `exact`, run/observers.cpp) and the checks of `particula validate` (reference/README.md).
#pragma once

#include "particula/core/types.hpp"

namespace particula::analytic {

/// Start-up Couette flow between y = 0 (fixed) and y = L (moving at V0 from t = 0):
/// u = V0 y/L + sum_{n>=1} 2 V0/(n pi) (-1)^n sin(n pi y/L) exp(-n^2 pi^2 nu t/L^2).
real couette_startup(real y, real t, real L, real V0, real nu);

/// Start-up Poiseuille flow driven by a body force F between fixed plates y = 0 and y = L:
/// u = F/(2 nu) y (L - y) - sum_{n>=0} 4 F L^2/(nu pi^3 (2n+1)^3) sin((2n+1) pi y/L) exp(-(2n+1)^2 pi^2 nu t/L^2).
real poiseuille_startup(real y, real t, real L, real F, real nu);

/// Start-up flow in a rectangular duct 0 < y < Ly, 0 < z < Lz with no-slip walls, driven by a
/// body force F along the duct from rest at t = 0: the eigenfunction expansion of
/// du/dt = F + nu (u_yy + u_zz), u = sum_{m,n odd} 16 F / (pi^2 m n lambda_mn nu)
/// (1 - exp(-nu lambda_mn t)) sin(m pi y / Ly) sin(n pi z / Lz), lambda_mn = (m pi / Ly)^2 + (n pi / Lz)^2,
/// evaluated as the steady solution (the plates' parabola less a series that falls off
/// exponentially away from the z walls) less the transient double series (which falls off as
/// exp(-nu lambda t)); t > 0 (0 at t <= 0).
real duct_startup(real y, real z, real t, real Ly, real Lz, real F, real nu);

/// The n-th positive zero of the Bessel function J1 (n >= 1: 3.8317, 7.0156, ...).
real bessel_j1_zero(int n);

/// Spin-up of fluid at rest in a circular container of radius R that turns at omega from t = 0
/// (no-slip): u_theta = omega r + sum_{n>=1} 2 omega R J1(lambda_n r/R) / (lambda_n J0(lambda_n))
/// exp(-lambda_n^2 nu t/R^2), lambda_n the zeros of J1 (the expansion of -omega r in J1(lambda_n r/R)).
real spin_up_velocity(real r, real t, real R, real omega, real nu);

/// Torque per unit depth of the fluid on the spinning-up container: 2 pi R^2 times the wall
/// shear stress mu r d(u/r)/dr at r = R, T = -4 pi mu omega R^2 sum_{n>=1} exp(-lambda_n^2 nu t/R^2)
/// (against the rotation, decaying to 0 as the fluid reaches solid-body rotation).
real spin_up_torque(real t, real R, real omega, real mu, real nu);

/// Taylor-Green vortex amplitude decay exp(b t), b = -8 pi^2 / Re (unit square, U = 1).
real taylor_green_decay(real t, real reynolds);

}  // namespace particula::analytic
