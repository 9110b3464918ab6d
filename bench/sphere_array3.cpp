// Stokes flow through a simple cubic array of fixed spheres in 3D (FluidSolverOf<3> on a
// periodic box with one sphere, scene/box3.hpp): the dimensionless drag K = F / (6 pi mu a U)
// against Zick & Homsy (1982, J. Fluid Mech. 115, 13, table 2; reference/zick_homsy1982_sc_drag.csv),
// U the superficial velocity (the fluid's volume flux over the whole cell's section).
//
//   particula_bench_sphere_array3 [--c C]... [--across N]... [--threads N]
//
// The flow is driven by a body force f on the fluid, which is the mean pressure gradient
// G = rho f of a pressure-driven flow through the array: the same velocity field. Zick & Homsy's F
// is the force on a sphere in that flow, G L^3 (Hasimoto: the mean pressure gradient is n F, n
// the number of spheres per volume); it holds the fluid's drag, rho f V_f (V_f the fluid's
// volume, sum_i m_i / rho_i), and the mean pressure's push on the sphere's own volume. So
// K = rho0 f L^3 / (6 pi mu a U). The lattice leaves the fluid out within d0 / 2 of the sphere:
// the fluid's volume is short of (1 - c) L^3 by a shell that shrinks with d0 (printed). The run goes until U
// changes by less than 1e-4 relative over one viscous time a^2 / nu, at Re = U 2a / nu of about 0.01, with
// default numerics and a sound speed for Stokes flow (below).
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "particula/case/schema.hpp"
#include "particula/scene/box3.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/fluid_solver.hpp"

namespace {

using namespace particula;

/// Zick & Homsy (1982), table 2, simple cubic arrays: volume fraction c and K.
struct ZickHomsy {
  real c, K;
};
constexpr ZickHomsy kZickHomsy[] = {{0.027, 2.008}, {0.064, 2.810}, {0.125, 4.292}, {0.216, 7.442},
                                    {0.343, 15.4},  {0.45, 28.1},   {0.5236, 42.1}};

FluidParamsOf<3> fluid(real d0, real nu, real c) {
  Case cs = default_case();
  cs.d0 = d0;
  cs.rho0 = 1000;
  cs.nu = nu;
  cs.c = c;
  return fluid_scalars<3>(physics_params(cs));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<real> fractions;
  std::vector<int> resolutions;  // particles across the sphere's diameter
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--c" && a + 1 < argc) {
      fractions.push_back(std::atof(argv[++a]));
    } else if (arg == "--across" && a + 1 < argc) {
      resolutions.push_back(std::atoi(argv[++a]));
    } else if (arg == "--threads" && a + 1 < argc) {
      omp_set_num_threads(std::atoi(argv[++a]));
    } else {
      std::fprintf(stderr, "usage: %s [--c C]... [--across N]... [--threads N]\n", argv[0]);
      return 2;
    }
  }
  if (fractions.empty()) fractions = {0.064};
  if (resolutions.empty()) resolutions = {8};
  std::printf("simple cubic array of spheres, %d threads\n", omp_get_max_threads());
  std::vector<std::pair<real, int>> runs;
  for (const real c : fractions)
    for (const int n : resolutions) runs.emplace_back(c, n);
  for (const auto& [c, across] : runs) {
    const ZickHomsy* ref = nullptr;
    for (const ZickHomsy& z : kZickHomsy)
      if (std::fabs(z.c - c) < 1e-9) ref = &z;
    if (ref == nullptr) {
      std::fprintf(stderr, "no Zick & Homsy value at c = %g\n", c);
      return 2;
    }
    // the cell of side L = 1 mm holds one sphere of radius a; the lattice fits the cell exactly
    const real L = 1e-3, a = std::cbrt(3 * c / (4 * M_PI)) * L, nu = 1e-6;
    const int n = static_cast<int>(std::lround(L / (2 * a / across)));
    const real d0 = L / n;
    // Re = U 2a / nu of about 0.01 with the expected U
    const real U_expected = 0.005 * nu / a;
    const real f = 6 * M_PI * nu * a * ref->K * U_expected / ((1 - c) * L * L * L);
    BoxSpec3 spec;
    spec.lo = {0, 0, 0};
    spec.hi = {L, L, L};
    spec.periodic[0] = spec.periodic[1] = spec.periodic[2] = true;
    spec.d0 = d0;
    spec.rho0 = 1000;
    spec.solids.push_back(FixedSolid3{Shape3::sphere(a), {0.5 * L, 0.5 * L, 0.5 * L}, Quat{}});
    BoxScene3 scene = build_box3(spec);
    // The sound speed: in Stokes flow the pressure scales as mu U K / a, not rho U^2, so the usual
    // 20 U leaves the fluid compressible (at c = 0.064 the density spread grew past 5 %, and the
    // drag came out 28 % low); c is chosen so that 3 mu K U / a is 1 % of rho c^2.
    const real sound = std::fmax(20 * U_expected, 10 * std::sqrt(3 * nu * ref->K * U_expected / a));
    FluidParamsOf<3> prm = fluid(d0, nu, sound);
    prm.body_force = {f, 0, 0};
    FluidSolverOf<3> s(prm, scene.domain, std::move(scene.particles));
    const Particles3& P = s.particles();
    const auto superficial = [&]() {
      real q = 0;
      for (std::size_t i = P.n_boundary; i < P.size(); ++i) q += P.m[i] / P.rho[i] * P.v[i].x;
      return q / (L * L * L);
    };
    real fluid_volume = 0;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) fluid_volume += P.m[i] / P.rho[i];
    const real t_visc = a * a / nu;
    const auto t0 = std::chrono::steady_clock::now();
    real U = 0, U_prev = -1;
    for (int k = 1; k <= 400; ++k) {
      while (s.time() < k * t_visc)
        if (auto fail = s.step_to(k * t_visc)) {
          std::fprintf(stderr, "failed at t = %g: %s\n", s.time(), fail->what.c_str());
          return 3;
        }
      U = superficial();
      if (std::getenv("PARTICULA_VERBOSE")) std::printf("  t = %.4g s: U = %.6g m/s\n", s.time(), U);
      if (std::fabs(U - U_prev) < 1e-4 * std::fabs(U)) break;
      U_prev = U;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const real mu = spec.rho0 * nu;
    const real K = spec.rho0 * f * L * L * L / (6 * M_PI * mu * a * U);  // G L^3 over Stokes's drag
    std::printf(
        "c = %g (a = %.4g L, d0 = L / %d): K = %.4f against Zick & Homsy's %.4g (%+.2f %%); Re %.2g; "
        "fluid volume %.4f of (1 - c) L^3; %zu particles (%zu on the sphere), %lld steps to t = %.3g s "
        "(%.1f a^2 / nu), %.1f s\n",
        c, a / L, n, K, ref->K, 100 * (K / ref->K - 1), U * 2 * a / nu, fluid_volume / ((1 - c) * L * L * L),
        P.size(), P.n_boundary, static_cast<long long>(s.step_count()), s.time(), s.time() / t_visc, seconds);
  }
  return 0;
}
