#include "particula/run/runner.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>

#include "outputs.hpp"
#include "particula/case/load.hpp"
#include "particula/case/schema.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/json.hpp"
#include "particula/io/log.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/run/limits.hpp"
#include "particula/run/observers.hpp"
#include "particula/run/plots.hpp"
#include "particula/run/run_dir.hpp"
#include "particula/run/version.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/backend.hpp"
#include "run_loop.hpp"
#include "session.hpp"

namespace particula {

namespace {

namespace fs = std::filesystem;
using run_detail::RunEnd;
using run_detail::RunOutputs;
using run_detail::RunStats;
using run_detail::Session;
using namespace run_detail;

std::atomic<int> g_signal{0};
extern "C" void on_signal(int sig) {
  // The first signal asks the loop to stop after the current step (outputs and checkpoint
  // written); a second one stops at once.
  if (g_signal.exchange(sig) != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

}  // namespace

namespace run_detail {

bool stop_requested() { return g_signal.load() != 0; }

SignalGuard::SignalGuard() {
  g_signal.store(0);
  old_int = std::signal(SIGINT, on_signal);
  old_term = std::signal(SIGTERM, on_signal);
}

SignalGuard::~SignalGuard() {
  std::signal(SIGINT, old_int);
  std::signal(SIGTERM, old_term);
}

}  // namespace run_detail

namespace {

void save_checkpoint(const fs::path& file, const Session& s) {
  const Solver& solver = *s.solver;
  const std::string toml = resolved_case_toml(s.c);
  const real t = solver.time();
  const std::int64_t step = solver.step_count();
  const std::vector<OutputMark> marks = s.outputs->marks();
  write_checkpoint(file,
                   CheckpointView{toml, s.case_hash, t, step, solver.counters(), marks, solver.particles(),
                                  solver.groups(), solver.open_flux(), solver.load_band_state()});
}

/// The run has written its initial state: a checkpoint of it is written too, and only then is
/// the run directory kept (and an old one it replaces deleted). So a run directory that exists
/// can always be resumed: a failure before this point (a full disk at the first snapshot or at
/// this checkpoint) removes the new directory and puts an old one back, one after it leaves the
/// last checkpoint, which is replaced atomically.
void mark_started(Session& s, Reporter& rep) {
  if (!s.run_dir || s.run_dir->committed()) return;
  save_checkpoint(checkpoint_path(s.dir), s);
  if (auto warning = s.run_dir->commit()) rep.tell("warning: " + *warning);
}

/// Writes the outputs that are due (all of them with `force`). A long output given up on a stop
/// request (io::Cancelled) ends the run as interrupted; what it would have written is written by
/// the resumed run. Every output is checked before it is written: a non-finite value ends the run
/// as a numerical failure (exit 3), as a failed step does.
struct OutputWriter {
  RunOutputs& out;
  const Solver& solver;
  bool cancelled = false;
  std::optional<Failure> operator()(bool force) {
    try {
      return out.write(solver, force);
    } catch (const io::Cancelled&) {
      cancelled = true;
      return std::nullopt;
    }
  }
};

/// How the time loop ended: its status in summary.json, the exit code and the failure, if any.
struct LoopEnd {
  std::string status = "completed";
  int exit_code = 0;
  std::optional<Failure> failure;
};

/// The bodies that reached an outlet's screen in the last step and were removed, one line each.
void report_removed_bodies(const Solver& solver, Reporter& rep) {
  for (const Solver::BodyRemoval& r : solver.removed_in_last_step())
    rep.say(
        fmt::format("t = {:.9g} s, step {}: body '{}' reached the screen of outlet '{}' and was removed; {} "
                    "fluid particles ({:.6g} kg/m) fill its place",
                    solver.time(), solver.step_count(), solver.groups()[r.group].name,
                    solver.params().open_specs[r.zone].name, r.fill_particles, r.fill_mass));
}

/// The caller's progress callback, when it is due (every kProgressInterval s of wall time, and
/// after the last step); it may ask the run to stop.
void tell_caller(Session& s, double wall, bool last) {
  if (!s.progress || (!last && wall < s.next_progress_wall)) return;
  s.next_progress_wall = wall + kProgressInterval;
  if (!s.progress(s.solver->time(), s.c.t_end, s.solver->step_count())) s.stopped_by_caller = true;
}

/// A run of kTimeStepDropSteps steps below kTimeStepDrop of the case's step: a warning in the
/// log naming what limits the step and where (the run goes on; summary.json counts them).
void report_time_step_drop(const Solver& solver, RunStats& stats, Reporter& rep) {
  const real dt = solver.last_dt();
  if (std::isnan(stats.dt_drop_first_time)) stats.dt_drop_first_time = solver.time();
  const Failure why = solver.time_step_limit(dt);
  rep.say(fmt::format(
      "warning: the time step has been below {:g} of the case's {:.3g} s for {} steps (t = {:.9g} s, "
      "step {}, dt = {:.3g} s); it is limited by {}",
      kTimeStepDrop, solver.case_dt(), kTimeStepDropSteps, solver.time(), solver.step_count(), dt, why.what));
}

/// Steps to time.end, writing the outputs on their schedule and a checkpoint every
/// output.checkpoint_interval; stops on max_steps, a signal or a failure (recorded in `end`).
void step_to_end(Session& s, Reporter& rep, OutputWriter& write_outputs, io::ProgressLine& progress,
                 LoopEnd& end) {
  Solver& solver = *s.solver;
  const Case& c = s.c;
  RunStats& stats = s.stats;
  const fs::path checkpoint_file = checkpoint_path(s.dir);
  const real ci = c.checkpoint_interval;
  real next_checkpoint =
      ci > 0 ? run_detail::next_multiple(solver.time(), ci) : std::numeric_limits<real>::infinity();
  const real eps = 1e-9 * c.t_end;
  while (!end.failure && solver.time() < c.t_end - eps) {
    if (c.max_steps > 0 && solver.step_count() >= c.max_steps) {
      end.status = "max_steps";
      break;
    }
    if (stop_requested() || write_outputs.cancelled || s.stopped_by_caller) {
      end.status = "interrupted";
      end.exit_code = 130;
      break;
    }
    const real target = s.outputs->next_event(c.t_end);
    end.failure = solver.step_to(target);
    if (!end.failure) report_removed_bodies(solver, rep);
    if (stats.add_step(solver.last_dt(), solver.time() == target, solver.last_step_limit(),
                       solver.particle_count(), solver.last_pair_count(), solver.case_dt()))
      report_time_step_drop(solver, stats, rep);
    if (!end.failure) end.failure = write_outputs(false);
    if (end.failure) break;
    if (write_outputs.cancelled) continue;  // interrupted: the checkpoint is written below
    if (solver.time() >= next_checkpoint - 1e-9 * ci) {
      save_checkpoint(checkpoint_file, s);
      next_checkpoint = run_detail::next_multiple(solver.time(), ci);
    }
    const double wall = stats.wall_seconds();
    progress.update(solver.step_count(), solver.time(), c.t_end, solver.last_dt(),
                    wall > 0 ? stats.particle_steps / wall : 0);
    tell_caller(s, wall, solver.time() >= c.t_end - eps);
  }
}

/// The final state (after a stop request, long outputs are skipped at once) and the restartable
/// checkpoint; after a failure, the state as far as it is finite and a diagnostic checkpoint.
void write_final_state(Session& s, Reporter& rep, OutputWriter& write_outputs, LoopEnd& end) {
  const Solver& solver = *s.solver;
  const fs::path checkpoint_file = checkpoint_path(s.dir);
  if (!end.failure) end.failure = write_outputs(true);
  if (end.failure) {
    write_outputs(true);
    const fs::path diag = checkpoint_file.parent_path() / kFailureCheckpoint;
    save_checkpoint(diag, s);
    const std::string msg = fmt::format(
        "numerical failure at t = {:.9g} s, step {}: {} at ({:.6g}, {:.6g}); last snapshot and a diagnostic "
        "checkpoint ({}) written",
        solver.time(), solver.step_count(), end.failure->what, end.failure->position.x,
        end.failure->position.y, diag.string());
    rep.log.record("error: " + msg);
    std::fprintf(stderr, "error: %s\n", msg.c_str());
    end.status = "failed";
    end.exit_code = 3;
  } else {
    save_checkpoint(checkpoint_file, s);
  }
  if (end.exit_code == 130)
    rep.tell(
        fmt::format("interrupted at t = {:.9g} s: checkpoint written; continue with: particula resume {}",
                    solver.time(), s.dir.string()));
}

/// The run's totals in the log: steps and speed, guard events, open-boundary fluxes, errors
/// against the exact solution.
void report_totals(const Session& s, Reporter& rep, const std::string& status, double wall,
                   const std::optional<double>& particle_error) {
  const Solver& solver = *s.solver;
  const auto& cnt = solver.counters();
  rep.say(fmt::format("{}: t = {:.6g} s after {} steps in {:.2f} s ({:.3g} particle-steps/s on {} threads)",
                      status, solver.time(), solver.step_count(), wall,
                      wall > 0 ? s.stats.particle_steps / wall : 0.0, omp_get_max_threads()));
  rep.say(
      fmt::format("guard events: singular B {}, singular Bhat at fluid particles {}, wall pressure kept {}, "
                  "extrapolated where ill-conditioned (corners, contact wedges) {}, extrapolated in narrow "
                  "gaps {}, normal fallback {}, surface guard {} (closing gaps {}), isolated particles left "
                  "out of P.20 {}, sparse supports bounded {}, surfaces facing a void {}",
                  cnt.singular_B, cnt.singular_Bhat, cnt.wall_pressure_kept, cnt.wall_pressure_extrapolated,
                  cnt.wall_pressure_extrapolated_far, cnt.normal_fallback, cnt.surface_pushed,
                  cnt.gap_squeezed, cnt.isolated_left_out, cnt.sparse_support, cnt.wall_pressure_void));
  if (!solver.open_flux().empty()) rep.say(open_boundary_log_line(solver));
  const char* compared = s.c.exact == ExactSolution::SpinUp ? "velocity" : "vx";
  if (particle_error)
    rep.say(fmt::format(
        "L2 error of the fluid particles' {} against the exact solution: {:.4f} % of the peak speed",
        compared, 100 * *particle_error));
  for (const auto& p : s.outputs->probes())
    if (auto e = p->last_error())
      rep.say(fmt::format(
          "probe '{}' (MLS-interpolated): L2 error of {} {:.4f} % of the peak speed at t = {:.6g} s",
          p->spec().name, compared, 100 * *e, solver.time()));
}

/// Plots of a run that has data to show: completed, failed (up to the failure: where it went
/// wrong is what one wants to see) and interrupted. An interrupted run has stopped and saved its
/// state, so its stop request is cleared: a second Ctrl-C stops the plotting. Returns the exit
/// code, 130 when the plotting was interrupted.
int plot_run(const Session& s, Reporter& rep, int exit_code) {
  if (exit_code == 130) g_signal.store(0);
  switch (draw_plots(s.dir, s.dir / "log.txt", stop_requested)) {
    case PlotOutcome::Drawn:
      if (!rep.quiet || exit_code != 0)
        rep.say(fmt::format("plots{} in {}",
                            exit_code == 3     ? " up to the failure"
                            : exit_code == 130 ? " up to the interruption"
                                               : "",
                            (s.dir / "plots").string()));
      break;
    case PlotOutcome::NoMatplotlib:
    case PlotOutcome::NoScript:
      rep.say("note: no plots drawn (python3-matplotlib is not installed; scripts/install-deps installs it)");
      break;
    case PlotOutcome::Failed:
      rep.say("warning: plotting failed (see log.txt); the data files are complete");
      break;
    case PlotOutcome::Interrupted:
      rep.tell(
          fmt::format("interrupted while drawing the plots: the data files are complete; draw them with: "
                      "particula plot {}",
                      s.dir.string()));
      return 130;
  }
  return exit_code;
}

}  // namespace

namespace run_detail {

/// The time loop shared by `run` and `resume`: steps to time.end, writes the outputs on their
/// schedule and checkpoints every output.checkpoint_interval, stops on a signal (exit 130),
/// max_steps or a numerical failure (exit 3), then writes the final state, a checkpoint and
/// summary.json.
int run_loop(Session& s, Reporter& rep, bool plots) {
  io::ProgressOptions popt;
  popt.quiet = rep.quiet;
  io::ProgressLine progress(&rep.log, popt);
  s.stats = RunStats{};
  OutputWriter write_outputs{*s.outputs, *s.solver};
  LoopEnd end;
  // The initial state; a resumed run has it already, but writes what was due at its checkpoint
  // and given up then.
  end.failure = write_outputs(!s.resumed);
  mark_started(s, rep);
  step_to_end(s, rep, write_outputs, progress, end);
  progress.finish();
  write_final_state(s, rep, write_outputs, end);
  const double wall = s.stats.wall_seconds();
  const auto particle_error = particle_profile_error(*s.solver, s.c, stop_requested);
  io::write_file_atomic(
      s.dir / "summary.json",
      run_summary(s, RunEnd{end.status, end.exit_code, end.failure, {}}, particle_error).dump());
  report_totals(s, rep, end.status, wall, particle_error);
  if (plots && (end.exit_code == 0 || end.exit_code == 3 || end.exit_code == 130))
    end.exit_code = plot_run(s, rep, end.exit_code);
  rep.say(fmt::format("results in {}", s.dir.string()));
  return end.exit_code;
}

int bad_input(const std::exception& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 2;
}

}  // namespace run_detail

namespace {

/// Undoes a `run` that had not started yet (the new run directory removed, the old one put back).
void undo_run_dir(Session& s) {
  if (!s.run_dir || s.run_dir->committed()) return;
  const bool replacing = s.run_dir->replacing();
  if (auto warning = s.run_dir->rollback())
    std::fprintf(stderr, "warning: %s\n", warning->c_str());
  else if (replacing)
    std::fprintf(stderr, "note: the previous run directory '%s' is left as it was\n", s.dir.string().c_str());
}

/// Bad input found after the run directory was made: undone if the run had not started.
int bad_input(const std::exception& e, Session& s) {
  const int code = run_detail::bad_input(e);
  undo_run_dir(s);
  return code;
}

}  // namespace

namespace run_detail {

/// A file-system failure (disk full, permission denied, ...): exit code kExitIoFailure, in
/// log.txt when the run directory is kept (the run had started; its last checkpoint stays).
int io_failure(const io::WriteError& e, Session& s, Reporter* rep) {
  const std::string msg = fmt::format("I/O failure: {}", e.what());
  std::fprintf(stderr, "error: %s\n", msg.c_str());
  if (s.run_dir && !s.run_dir->committed()) {
    undo_run_dir(s);
    return kExitIoFailure;
  }
  if (rep) rep->log.record("error: " + msg);
  if (s.solver && s.outputs) {  // summary.json says how the run ended, if the disk takes it
    try {
      io::write_file_atomic(
          s.dir / "summary.json",
          run_summary(s, RunEnd{"io_failure", kExitIoFailure, std::nullopt, msg}, std::nullopt).dump());
    } catch (const std::exception&) {
    }
  }
  std::error_code ec;
  if (!s.dir.empty() && fs::exists(checkpoint_path(s.dir), ec)) {
    const std::string hint = fmt::format(
        "the last checkpoint ({}) is kept: once the cause is fixed, continue with: "
        "particula resume {}",
        checkpoint_path(s.dir).string(), s.dir.string());
    std::fprintf(stderr, "%s\n", hint.c_str());
    if (rep) rep->log.record(hint);
  }
  return kExitIoFailure;
}

/// A stop request before the time loop: nothing is run.
int interrupted_before_start(Session& s, Reporter& rep, const char* what) {
  rep.tell(fmt::format("interrupted before the run started: {}", what));
  undo_run_dir(s);
  return 130;
}

/// Checks that the requested backend exists here (before anything is written).
bool backend_usable(const std::string& backend) {
  if (backend == "cpu") return true;
  std::string why;
  if (backend == "cuda" && cuda_backend_available(&why)) return true;
  std::fprintf(stderr, "error: --backend %s: %s\n", backend.c_str(),
               backend == "cuda" ? why.c_str() : "unknown backend (cpu or cuda)");
  return false;
}

}  // namespace run_detail

int run_command(const fs::path& case_file, const RunOptions& opt) {
  Session s;
  if (!backend_usable(opt.backend)) return 2;
  SignalGuard signals;
  std::unique_ptr<RunDirectory> run_dir;
  try {
    s.c = opt.case_text ? load_case_text(*opt.case_text, case_file, opt.overrides)
                        : load_case(case_file, opt.overrides);
    check_case_size(s.c);  // before anything is allocated or written
    s.case_hash = case_identity_hash(resolved_case_toml(s.c));
    run_dir = std::make_unique<RunDirectory>(opt.out_dir.empty() ? fs::path("runs") / s.c.name : opt.out_dir,
                                             opt.overwrite, RunMarker{MarkedKind::Run, s.case_hash});
    s.dir = run_dir->path();
    s.run_dir = run_dir.get();
    s.overrides = opt.overrides;
    s.progress = opt.progress;
  } catch (const CaseError& e) {
    return bad_input(e);
  } catch (const RunDirRefused& e) {
    return bad_input(e);
  } catch (const io::WriteError& e) {
    return io_failure(e, s, nullptr);
  } catch (const io::IoError& e) {
    return bad_input(e);
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  std::unique_ptr<Reporter> rep;
  try {
    rep = std::make_unique<Reporter>(s.dir / "log.txt", opt.quiet);
    for (const auto& note : run_dir->notes()) rep->tell(note);
    io::write_file_atomic(s.dir / "case.toml", resolved_case_toml(s.c));
    Scene scene = build_scene(s.c);
    s.n_fluid = scene.particles.size() - scene.particles.n_boundary;
    rep->say(
        fmt::format("{}: case '{}' from {}, {} particles ({} fluid, {} boundary), {} threads, backend {}",
                    version_line(), s.c.name, case_file.string(), scene.particles.size(), s.n_fluid,
                    scene.particles.n_boundary, omp_get_max_threads(), opt.backend));
    if (run_dir->replacing())
      rep->say(
          fmt::format("replacing the run directory {}: the old run is kept aside in {} until this run has "
                      "written its initial state and a checkpoint",
                      s.dir.string(), run_dir->aside().string()));
    scene.params.cuda = opt.backend == "cuda";
    s.solver = std::make_unique<Solver>(scene.params, scene.domain, std::move(scene.particles),
                                        std::move(scene.groups));
    s.outputs = std::make_unique<RunOutputs>(s.dir, s.c, stop_requested);
    if (stop_requested())
      return interrupted_before_start(s, *rep,
                                      run_dir->replacing()
                                          ? "nothing written; the previous run directory is restored"
                                          : "nothing written");
    return run_loop(s, *rep, opt.plots);
  } catch (const CaseError& e) {
    return bad_input(e, s);
  } catch (const io::WriteError& e) {
    return io_failure(e, s, rep.get());
  } catch (const io::IoError& e) {
    return bad_input(e, s);
  }
}

}  // namespace particula
