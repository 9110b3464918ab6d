#include "particula/run/runner.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fmt/format.h>

#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/json.hpp"
#include "particula/io/log.hpp"
#include "particula/run/observers.hpp"
#include "particula/scene/scene.hpp"

namespace particula {

namespace {

std::atomic<int> g_signal{0};
extern "C" void on_signal(int sig) { g_signal.store(sig); }

/// Installs SIGINT/SIGTERM handlers for the lifetime of a run; the loop checks the flag
/// between steps, so a step is never left half-done.
struct SignalGuard {
  void (*old_int)(int), (*old_term)(int);
  SignalGuard() {
    g_signal.store(0);
    old_int = std::signal(SIGINT, on_signal);
    old_term = std::signal(SIGTERM, on_signal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, old_int);
    std::signal(SIGTERM, old_term);
  }
};

/// Prepares the run directory: refuses an existing one unless --overwrite (exit 2).
std::filesystem::path prepare_run_dir(const Case& c, const RunOptions& opt) {
  namespace fs = std::filesystem;
  const fs::path dir = opt.out_dir.empty() ? fs::path("runs") / c.name : opt.out_dir;
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!opt.overwrite)
      throw io::IoError(fmt::format("run directory '{}' already exists (use --overwrite to replace it)", dir.string()));
    fs::remove_all(dir, ec);
    if (ec) throw io::IoError(fmt::format("cannot remove run directory '{}': {}", dir.string(), ec.message()));
  }
  fs::create_directories(dir, ec);
  if (ec) throw io::IoError(fmt::format("cannot create run directory '{}': {}", dir.string(), ec.message()));
  return dir;
}

/// Largest step that lands exactly on the next output time or the end time.
real next_stop(real t, real t_end, real interval) {
  const real k = std::floor(t / interval + 1e-9) + 1;
  return std::min(t_end, k * interval);
}

struct Outputs {
  std::unique_ptr<SnapshotWriter> snapshots;
  std::vector<std::unique_ptr<ProbeWriter>> probes;
  std::unique_ptr<BodyHistoryWriter> bodies;
  real next_output = 0, next_snapshot = 0, next_probe_check = 0;
  std::vector<real> next_probe;
};

}  // namespace

int run_command(const std::filesystem::path& case_file, const RunOptions& opt) {
  Case c;
  std::filesystem::path dir;
  try {
    c = load_case(case_file, opt.overrides);
    dir = prepare_run_dir(c, opt);
  } catch (const CaseError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);

  io::RunLog log(dir / "log.txt", false);
  auto say = [&](const std::string& text) {
    log.line(text);
    if (!opt.quiet) std::fprintf(stderr, "%s\n", text.c_str());
  };
  io::write_file_atomic(dir / "case.toml", resolved_case_toml(c));

  Scene scene = build_scene(c);
  const std::size_t n_fluid = scene.particles.size() - scene.particles.n_boundary;
  say(fmt::format("particula: case '{}' from {}, {} particles ({} fluid, {} boundary), {} threads", c.name,
                  case_file.string(), scene.particles.size(), n_fluid, scene.particles.n_boundary,
                  omp_get_max_threads()));
  Solver solver(scene.params, scene.domain, std::move(scene.particles), std::move(scene.groups));

  Outputs out;
  const real snap_interval = c.snapshot_interval > 0 ? c.snapshot_interval : c.output_interval;
  if (c.snapshots) out.snapshots = std::make_unique<SnapshotWriter>(dir);
  for (const auto& p : c.probes) out.probes.push_back(std::make_unique<ProbeWriter>(dir, p, c));
  out.bodies = std::make_unique<BodyHistoryWriter>(dir);

  const real eps = 1e-9 * c.t_end;
  auto write_outputs = [&](bool force) {
    const real t = solver.time();
    if (force || t >= out.next_output - eps) {
      out.bodies->write(solver);
      out.next_output = next_stop(t, 1e300, c.output_interval);
    }
    if (out.snapshots && (force || t >= out.next_snapshot - eps)) {
      out.snapshots->write(solver);
      out.next_snapshot = next_stop(t, 1e300, snap_interval);
    }
    out.next_probe.resize(out.probes.size(), 0);
    for (std::size_t k = 0; k < out.probes.size(); ++k)
      if (force || t >= out.next_probe[k] - eps) {
        out.probes[k]->write(solver);
        out.next_probe[k] = next_stop(t, 1e300, out.probes[k]->spec().interval);
      }
  };
  auto next_event = [&] {
    real t = std::min({c.t_end, out.next_output, out.snapshots ? out.next_snapshot : 1e300});
    for (real tp : out.next_probe) t = std::min(t, tp);
    return t;
  };

  SignalGuard signals;
  io::ProgressOptions popt;
  popt.quiet = opt.quiet;
  io::ProgressLine progress(&log, popt);
  const auto wall0 = std::chrono::steady_clock::now();
  write_outputs(true);
  std::string status = "completed";
  int exit_code = 0;
  double particle_steps = 0, interactions = 0;
  while (solver.time() < c.t_end - eps) {
    if (c.max_steps > 0 && solver.step_count() >= c.max_steps) {
      status = "max_steps";
      break;
    }
    if (g_signal.load() != 0) {
      status = "interrupted";
      exit_code = 130;
      break;
    }
    const auto failure = solver.step(next_event() - solver.time());
    particle_steps += static_cast<double>(solver.particles().size());
    interactions += static_cast<double>(solver.last_pair_count());
    if (failure) {
      write_outputs(true);
      const std::string msg = fmt::format(
          "numerical failure at t = {:.9g} s, step {}: {} at ({:.6g}, {:.6g}); last snapshot written", solver.time(),
          solver.step_count(), failure->what, failure->position.x, failure->position.y);
      progress.finish();
      log.warn(msg);
      std::fprintf(stderr, "error: %s\n", msg.c_str());
      status = "failed";
      exit_code = 3;
      break;
    }
    write_outputs(false);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    progress.update(solver.step_count(), solver.time(), c.t_end, solver.last_dt(),
                    wall > 0 ? particle_steps / wall : 0);
  }
  progress.finish();
  if (exit_code == 130 && out.snapshots) out.snapshots->write(solver);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  const auto& cnt = solver.counters();
  io::JsonObject summary;
  summary.set("case", c.name);
  summary.set("status", status);
  summary.set("particles", static_cast<std::int64_t>(solver.particles().size()));
  summary.set("fluid_particles", static_cast<std::int64_t>(n_fluid));
  summary.set("steps", solver.step_count());
  summary.set("end_time", solver.time());
  summary.set("wall_seconds", wall);
  summary.set("threads", static_cast<std::int64_t>(omp_get_max_threads()));
  summary.set("particle_steps_per_second", wall > 0 ? particle_steps / wall : 0.0);
  summary.set("interactions_per_second", wall > 0 ? interactions / wall : 0.0);
  io::JsonObject guards;
  guards.set("singular_B", cnt.singular_B);
  guards.set("singular_Bhat", cnt.singular_Bhat);
  guards.set("wall_pressure_kept", cnt.wall_pressure_kept);
  guards.set("normal_fallback", cnt.normal_fallback);
  summary.set("guard_events", guards);
  for (const auto& p : out.probes)
    if (auto e = p->last_error()) summary.set("profile_error_" + p->spec().name, *e);
  io::write_file_atomic(dir / "summary.json", summary.dump());

  say(fmt::format("{}: t = {:.6g} s after {} steps in {:.2f} s ({:.3g} particle-steps/s on {} threads)", status,
                  solver.time(), solver.step_count(), wall, wall > 0 ? particle_steps / wall : 0.0,
                  omp_get_max_threads()));
  say(fmt::format("guard events: singular B {}, singular Bhat {}, wall pressure kept {}, normal fallback {}",
                  cnt.singular_B, cnt.singular_Bhat, cnt.wall_pressure_kept, cnt.normal_fallback));
  for (const auto& p : out.probes)
    if (auto e = p->last_error())
      say(fmt::format("probe '{}': L2 error of vx against the exact solution {:.4f} % of the peak speed at t = {:.6g} s",
                      p->spec().name, 100 * *e, solver.time()));
  say(fmt::format("results in {}", dir.string()));
  return exit_code;
}

}  // namespace particula
