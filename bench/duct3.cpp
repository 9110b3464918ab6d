// Start-up flow in a square duct in 3D (FluidSolverOf<3> on the box scene), at several
// resolutions: the rms and largest errors of the fluid particles' velocity against the series
// solution (analytic::duct_startup) at time T, the observed order between resolutions, and the
// cost: particle-steps per second, neighbour pairs per particle, nanoseconds per pair interaction,
// the process's peak resident memory per particle (an upper bound). With --plates, the 2D start-up channel
// (plates, the same fluid and spacing) runs through FluidSolverOf<2> for the cost per pair interaction in 2D.
//
//   particula_bench_duct3 [--across N]... [--time T] [--threads N] [--plates]
//
// Morris, Fox & Zhu's parameters (reference/README.md): side L = 1 mm, nu = 1e-6 m^2/s,
// F = 1e-4 m/s^2, c = 2.5e-4 m/s, periodic along the duct over 8 spacings, default numerics.
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "particula/analytic/solutions.hpp"
#include "particula/case/schema.hpp"
#include "particula/scene/box3.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/fluid_solver.hpp"

namespace {

using namespace particula;

constexpr real kL = 1e-3, kF = 1e-4, kNu = 1e-6, kC = 2.5e-4, kRho0 = 1000;

/// The fluid and numerics of the case: the schema's defaults (physics_params of the default
/// case), with the duct's fluid.
template <int D>
FluidParamsOf<D> duct_fluid(real d0) {
  Case c = default_case();
  c.d0 = d0;
  c.rho0 = kRho0;
  c.nu = kNu;
  c.c = kC;
  return fluid_scalars<D>(physics_params(c));
}

long peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

struct Cost {
  double seconds = 0;
  std::int64_t steps = 0;
  std::size_t particles = 0, pairs = 0;
};

template <int D>
Cost run_to(FluidSolverOf<D>& s, real t_end) {
  Cost cost;
  const auto t0 = std::chrono::steady_clock::now();
  while (s.time() < t_end) {
    if (auto f = s.step_to(t_end)) {
      std::fprintf(stderr, "failed at t = %g: %s\n", s.time(), f->what.c_str());
      std::exit(3);
    }
    cost.pairs += s.sweeps().pair_count();
  }
  cost.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cost.steps = s.step_count();
  cost.particles = s.particles().size();
  return cost;
}

void print_cost(const char* what, const Cost& c) {
  const double ps = static_cast<double>(c.particles) * static_cast<double>(c.steps);
  std::printf(
      "  %s: %zu particles, %lld steps, %.2f s: %.3g particle-steps/s, %.1f pairs per particle, "
      "%.2f ns per pair and step\n",
      what, c.particles, static_cast<long long>(c.steps), c.seconds, ps / c.seconds,
      static_cast<double>(c.pairs) / ps, 1e9 * c.seconds / static_cast<double>(c.pairs));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> across;
  real t_end = 0.1;
  bool plates = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--across" && a + 1 < argc) {
      across.push_back(std::atoi(argv[++a]));
    } else if (arg == "--time" && a + 1 < argc) {
      t_end = std::atof(argv[++a]);
    } else if (arg == "--threads" && a + 1 < argc) {
      omp_set_num_threads(std::atoi(argv[++a]));
    } else if (arg == "--plates") {
      plates = true;
    } else {
      std::fprintf(stderr, "usage: %s [--across N]... [--time T] [--threads N] [--plates]\n", argv[0]);
      return 2;
    }
  }
  if (across.empty()) across = {10, 20};
  std::printf("square duct start-up flow, side %g m, F %g m/s^2, nu %g m^2/s, t = %g s, %d threads\n", kL, kF,
              kNu, t_end, omp_get_max_threads());
  const real u_max = analytic::duct_startup(0.5 * kL, 0.5 * kL, 1e3, kL, kL, kF, kNu);
  real previous = 0;
  int previous_n = 0;
  for (const int n : across) {
    const real d0 = kL / n;
    BoxSpec3 spec;
    spec.lo = {0, 0, 0};
    spec.hi = {8 * d0, kL, kL};
    spec.periodic[0] = true;
    spec.d0 = d0;
    spec.rho0 = kRho0;
    FluidParamsOf<3> prm = duct_fluid<3>(d0);
    prm.body_force = {kF, 0, 0};
    BoxScene3 scene = build_box3(spec);
    FluidSolverOf<3> s(prm, scene.domain, std::move(scene.particles));
    const Cost cost = run_to(s, t_end);
    const Particles3& P = s.particles();
    real e2 = 0, emax = 0;
    for (std::size_t i = P.n_boundary; i < P.size(); ++i) {
      const real e = P.v[i].x - analytic::duct_startup(P.x[i].y, P.x[i].z, s.time(), kL, kL, kF, kNu);
      e2 += e * e;
      emax = std::fmax(emax, std::fabs(e));
    }
    const real rms = std::sqrt(e2 / static_cast<real>(P.size() - P.n_boundary)) / u_max;
    std::printf("%d across (d0 = %g m): rms error %.4g %% of u_max, largest %.4g %%", n, d0, 100 * rms,
                100 * emax / u_max);
    if (previous_n > 0)
      std::printf(", observed order %.2f",
                  std::log(previous / rms) / std::log(static_cast<real>(n) / previous_n));
    std::printf("\n");
    print_cost("3D", cost);
    // the process's peak so far over this run's particles: an upper bound of the bytes per particle
    // once this run is the largest
    std::printf("  peak resident memory %.1f MB: %.0f bytes per particle\n", peak_rss_kb() / 1024.0,
                1024.0 * static_cast<double>(peak_rss_kb()) / static_cast<double>(P.size()));
    previous = rms;
    previous_n = n;
    if (plates) {
      Case c = default_case();
      c.name = "plates";
      c.domain_min = {0, 0};
      c.domain_max = {8 * d0, kL};
      c.periodic_x = true;
      c.d0 = d0;
      c.rho0 = kRho0;
      c.nu = kNu;
      c.c = kC;
      c.body_force = {kF, 0};
      c.walls = {{"bottom", {0, 0}, {8 * d0, 0}, {}}, {"top", {8 * d0, kL}, {0, kL}, {}}};
      const Scene sc = build_scene(c);
      FluidSolverOf<2> s2(sc.params, sc.domain, sc.particles);
      print_cost("2D plates", run_to(s2, t_end));
    }
  }
  return 0;
}
