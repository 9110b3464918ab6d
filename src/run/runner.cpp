#include "particula/run/runner.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
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
  real next_output = 0, next_snapshot = 0;
  std::vector<real> next_probe;
  // time of the last write of each stream (bodies, snapshots, probes...), so that the final
  // state is written once at the end of a run
  real last_bodies = -1, last_snapshot = -1;
  std::vector<real> last_probe;
};

/// Runs tools/plot_run.py on the run directory when Debian's matplotlib is available, and says
/// so when it is not (plots are optional; the data files are complete without them).
template <class Say>
void draw_plots(const std::filesystem::path& dir, bool quiet, Say&& say) {
  const std::filesystem::path script = std::filesystem::path(PARTICULA_SOURCE_DIR) / "tools" / "plot_run.py";
  const char* python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string probe = fmt::format("{} -c 'import matplotlib' >/dev/null 2>&1", python);
  if (!std::filesystem::exists(script) || std::system(probe.c_str()) != 0) {
    say("note: no plots drawn (python3-matplotlib is not installed; scripts/install-deps installs it)");
    return;
  }
  const std::string cmd = fmt::format("{} '{}' '{}' >> '{}' 2>&1", python, script.string(), dir.string(),
                                      (dir / "log.txt").string());
  if (std::system(cmd.c_str()) == 0) {
    if (!quiet) say(fmt::format("plots in {}", (dir / "plots").string()));
  } else {
    say("warning: plotting failed (see log.txt); the data files are complete");
  }
}

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
  // Writes every stream that is due (or, with `force`, every stream not yet written at this time).
  auto write_outputs = [&](bool force) {
    const real t = solver.time();
    if ((force && out.last_bodies < t) || t >= out.next_output - eps) {
      out.bodies->write(solver);
      out.last_bodies = t;
      out.next_output = next_stop(t, 1e300, c.output_interval);
    }
    if (out.snapshots && ((force && out.last_snapshot < t) || t >= out.next_snapshot - eps)) {
      out.snapshots->write(solver);
      out.last_snapshot = t;
      out.next_snapshot = next_stop(t, 1e300, snap_interval);
    }
    out.next_probe.resize(out.probes.size(), 0);
    out.last_probe.resize(out.probes.size(), -1);
    for (std::size_t k = 0; k < out.probes.size(); ++k)
      if ((force && out.last_probe[k] < t) || t >= out.next_probe[k] - eps) {
        out.probes[k]->write(solver);
        out.last_probe[k] = t;
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
  if (exit_code != 3) write_outputs(true);  // the final state (a failure already wrote it)
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
    if (auto e = p->last_error()) summary.set("probe_error_" + p->spec().name, *e);
  const auto particle_error = particle_profile_error(solver, c);
  if (particle_error) summary.set("profile_error", *particle_error);
  io::write_file_atomic(dir / "summary.json", summary.dump());

  say(fmt::format("{}: t = {:.6g} s after {} steps in {:.2f} s ({:.3g} particle-steps/s on {} threads)", status,
                  solver.time(), solver.step_count(), wall, wall > 0 ? particle_steps / wall : 0.0,
                  omp_get_max_threads()));
  say(fmt::format("guard events: singular B {}, singular Bhat {}, wall pressure kept {}, normal fallback {}",
                  cnt.singular_B, cnt.singular_Bhat, cnt.wall_pressure_kept, cnt.normal_fallback));
  if (particle_error)
    say(fmt::format("L2 error of the fluid particles' vx against the exact solution: {:.4f} % of the peak speed",
                    100 * *particle_error));
  for (const auto& p : out.probes)
    if (auto e = p->last_error())
      say(fmt::format("probe '{}' (Shepard-interpolated): L2 error of vx {:.4f} % of the peak speed at t = {:.6g} s",
                      p->spec().name, 100 * *e, solver.time()));
  if (exit_code == 0 && opt.plots) draw_plots(dir, opt.quiet, say);
  say(fmt::format("results in {}", dir.string()));
  return exit_code;
}

}  // namespace particula
