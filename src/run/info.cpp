#include "particula/run/info.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <fmt/format.h>

#include "particula/case/load.hpp"
#include "particula/run/limits.hpp"
#include "particula/scene/scene.hpp"

namespace particula {

int info_command(const std::filesystem::path& case_file, const std::vector<std::string>& overrides, bool timing) {
  Case c;
  try {
    c = load_case(case_file, overrides);
    check_case_size(c);  // before the scene is allocated
  } catch (const CaseError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  Scene scene = build_scene(c);
  const Particles& P = scene.particles;
  std::size_t n_fluid = 0, n_surface = 0, n_dummy = 0, n_buffer = 0;
  for (std::size_t i = 0; i < P.size(); ++i) {
    if (P.kind[i] == Kind::Fluid) ++n_fluid;
    else if (P.kind[i] == Kind::Boundary) ++n_surface;
    else if (is_buffer(P.kind[i])) ++n_buffer;
    else ++n_dummy;
  }
  // With timing: build the solver (neighbour list, initial wall pressure) and time 5 steps.
  // Without: estimate dt from the lattice alone (nearest pair: a wall particle and the fluid
  // particle d0/2 off the wall diagonally, both perturbed), so huge cases answer at once.
  double dt = 0, pairs = 0, per_step = 0;
  int timed = 0;
  if (timing) {
    Solver solver(scene.params, scene.domain, scene.particles, scene.groups);
    dt = solver.stable_dt();
    pairs = static_cast<double>(solver.last_pair_count());
    const auto t0 = std::chrono::steady_clock::now();
    for (; timed < 5; ++timed)
      if (solver.step()) break;
    per_step = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / std::max(1, timed);
  } else {
    dt = estimated_dt(c);  // as the load checks estimate it
    // about pi (h/d0)^2 - 1 neighbours in the interior
    pairs = static_cast<double>(P.size()) * (M_PI * c.h_over_d0 * c.h_over_d0 - 1);
  }
  const double steps = std::ceil(c.t_end / dt);
  // Particle arrays (about 48 doubles each with the work arrays), the pair list (4 bytes a pair)
  // and the probes.
  const SizeEstimate size = estimate_size(c);
  const double bytes = static_cast<double>(P.size()) * 48 * 8 + pairs * 4 + size.probe_bytes;
  std::printf("case            %s (%s)\n", c.name.c_str(), case_file.string().c_str());
  std::printf("particles       %zu: %zu fluid, %zu boundary surface, %zu dummy", P.size(), n_fluid, n_surface, n_dummy);
  if (n_buffer > 0) std::printf(", %zu in the buffers of open boundaries", n_buffer);
  std::printf("\n");
  std::printf("rigid groups    %zu\n", scene.groups.size());
  std::printf("d0, h           %.6g m, %.6g m (%.3g neighbours per particle)\n", c.d0, c.h(), pairs / P.size());
  std::printf("initial dt      %.6g s (P.29-P.31, alpha = %g%s)\n", dt, c.cfl,
              timing ? "" : "; estimated from the lattice");
  std::printf("steps           about %.0f to t = %g s\n", steps, c.t_end);
  std::printf("memory          about %.1f MiB (probes: %.0f points, %.1f MiB)\n", bytes / (1024.0 * 1024.0),
              size.probe_points, size.probe_bytes / (1024.0 * 1024.0));
  if (timing)
    std::printf("wall time       about %s on %d threads (%.3g s per step measured over %d steps)\n",
                fmt::format("{:.0f} s", steps * per_step).c_str(), omp_get_max_threads(), per_step, timed);
  return 0;
}

}  // namespace particula
