// End-to-end throughput benchmark: builds a case (by default the falling
// cylinder of paper 7.2), advances it a fixed number of steps and prints particles, steps, wall
// seconds, particle-steps per second and the per-phase breakdown of Solver::phase_times().
//
//   particula_bench_e2e [--case FILE] [--d0 M] [--advance T] [--steps N] [--warmup N]
//                       [--threads N] [--backend cpu|cuda] [--set key=value]...
//
// --advance T runs the case, untimed, to simulated time T before the warm-up, so that the timed
// steps are those of a developed flow: with numerics.load_band_motion > 0 (the default) how often
// the band of the momentum loads is built depends on how far things move, and from rest it is
// hardly built at all. The output counts the builds in the timed steps.
//
// Output is one human-readable block and one machine-readable line starting with "RESULT".
// It ends with an estimate of the time to solution of the whole case (to its time.end): the
// steps still to go at the mean time step of the timed steps, at the measured wall time per
// step. The time step changes with the flow (P.29-P.31), so the estimate is only as good as the
// timed steps are typical; `make bench-cases` prints it for the five paper cases.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "particula/case/load.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"

namespace {

using namespace particula;

struct Options {
  std::string case_file = std::string(PARTICULA_SOURCE_DIR) + "/cases/falling_cylinder.toml";
  std::string d0;  // empty: the case file's
  double advance = 0;  // simulated time, untimed, before the warm-up
  int steps = 50, warmup = 3, threads = 0;
  bool cuda = false;
  std::vector<std::string> overrides;
};

[[noreturn]] void usage(const char* msg) {
  std::fprintf(stderr,
               "error: %s\nusage: particula_bench_e2e [--case FILE] [--d0 M] [--advance T] [--steps N] "
               "[--warmup N] [--threads N] [--backend cpu|cuda] [--set key=value]...\n",
               msg);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) usage(("missing value after " + arg).c_str());
      return argv[++a];
    };
    if (arg == "--case") o.case_file = value();
    else if (arg == "--d0") o.d0 = value();
    else if (arg == "--advance")
      o.advance = std::atof(value().c_str());
    else if (arg == "--steps") o.steps = std::atoi(value().c_str());
    else if (arg == "--warmup") o.warmup = std::atoi(value().c_str());
    else if (arg == "--threads") o.threads = std::atoi(value().c_str());
    else if (arg == "--set") o.overrides.push_back(value());
    else if (arg == "--backend") {
      const std::string b = value();
      if (b != "cpu" && b != "cuda") usage("--backend is cpu or cuda");
      o.cuda = b == "cuda";
    }
    else usage(("unknown argument " + arg).c_str());
  }
  if (o.steps < 1 || o.warmup < 0 || !(o.advance >= 0))
    usage("--steps must be >= 1, --warmup >= 0 and --advance >= 0");
  if (!o.d0.empty()) o.overrides.push_back("resolution.d0=" + o.d0);
  return o;
}

PhaseTimes minus(const PhaseTimes& a, const PhaseTimes& b) {
  PhaseTimes d;
  d.neighbors = a.neighbors - b.neighbors;
  d.geometry = a.geometry - b.geometry;
  d.operators = a.operators - b.operators;
  d.wall_pressure = a.wall_pressure - b.wall_pressure;
  d.bodies = a.bodies - b.bodies;
  d.integration = a.integration - b.integration;
  d.shifting = a.shifting - b.shifting;
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (o.threads > 0) omp_set_num_threads(o.threads);
  Case c;
  try {
    c = load_case(o.case_file, o.overrides);
  } catch (const CaseError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  const auto t_setup = std::chrono::steady_clock::now();
  Scene scene = build_scene(c);
  scene.params.cuda = o.cuda;
  Solver solver(scene.params, scene.domain, std::move(scene.particles), scene.groups);
  const double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_setup).count();
  while (solver.time() < o.advance)
    if (auto f = solver.step()) {
      std::fprintf(stderr, "error: the run failed at t = %g s, before the timed steps: %s\n", solver.time(),
                   f->what.c_str());
      return 3;
    }
  for (int s = 0; s < o.warmup; ++s)
    if (solver.step()) {
      std::fprintf(stderr, "error: the run failed during warm-up\n");
      return 3;
    }
  const PhaseTimes before = solver.phase_times();
  const double t_sim0 = solver.time();
  const std::int64_t builds0 = solver.load_band_builds();
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < o.steps; ++s)
    if (auto f = solver.step()) {
      std::fprintf(stderr, "error: the run failed at step %d: %s\n", s, f->what.c_str());
      return 3;
    }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const PhaseTimes p = minus(solver.phase_times(), before);
  const double n = static_cast<double>(solver.particle_count());
  const double rate = n * o.steps / wall;
  const int threads = omp_get_max_threads();
  // Time to solution: the steps taken so far plus those left at the mean dt of the timed steps.
  const double mean_dt = (solver.time() - t_sim0) / o.steps;
  const double steps_total =
      static_cast<double>(solver.step_count()) + std::max(0.0, (c.t_end - solver.time()) / mean_dt);
  const double solution_s = steps_total * wall / o.steps;
  std::printf("case              %s, d0 = %g m\n", c.name.c_str(), c.d0);
  std::printf("particles         %.0f (%zu pairs, %.1f per particle)\n", n, solver.last_pair_count(),
              static_cast<double>(solver.last_pair_count()) / n);
  std::printf("threads           %d (backend %s)\n", threads, solver.backend_name());
  std::printf("setup             %.3f s\n", setup_s);
  std::printf("steps             %d (after %d warm-up, from t = %g s)\n", o.steps, o.warmup, t_sim0);
  if (solver.params().load_band_motion > 0)
    std::printf(
        "band builds       %lld of the timed steps (numerics.load_band_motion kept the band in the others)\n",
        static_cast<long long>(solver.load_band_builds() - builds0));
  std::printf("wall              %.3f s (%.4g s per step)\n", wall, wall / o.steps);
  std::printf("throughput        %.4g particle-steps/s\n", rate);
  std::printf("phases (s per step, share of the timed phases)\n");
  const double tot = p.total();
  auto line = [&](const char* name, double v) {
    std::printf("  %-15s %.5f  %5.1f %%\n", name, v / o.steps, tot > 0 ? 100 * v / tot : 0.0);
  };
  line("neighbours", p.neighbors);
  line("geometry", p.geometry);
  line("operators", p.operators);
  line("wall pressure", p.wall_pressure);
  line("bodies", p.bodies);
  line("integration", p.integration);
  line("shifting", p.shifting);
  std::printf("  %-15s %.5f  (outside the timed phases: %.5f)\n", "total", tot / o.steps, (wall - tot) / o.steps);
  std::printf("to the end, t = %g s: about %.0f steps at the mean dt %.4g s of the timed steps, %.0f s (%.1f min) of wall time "
              "(estimate)\n",
              c.t_end, steps_total, mean_dt, solution_s, solution_s / 60);
  std::printf(
      "RESULT case=%s d0=%g backend=%s threads=%d particles=%.0f steps=%d wall_s=%.4f "
      "particle_steps_per_s=%.4g "
      "neighbors=%.4f geometry=%.4f operators=%.4f wall_pressure=%.4f bodies=%.4f integration=%.4f "
      "shifting=%.4f "
      "t_end=%g steps_to_end=%.0f time_to_solution_s=%.0f t_start=%g band_builds=%lld\n",
      c.name.c_str(), c.d0, solver.backend_name(), threads, n, o.steps, wall, rate, p.neighbors, p.geometry,
      p.operators, p.wall_pressure, p.bodies, p.integration, p.shifting, c.t_end, steps_total, solution_s,
      t_sim0, static_cast<long long>(solver.load_band_builds() - builds0));
  return 0;
}
