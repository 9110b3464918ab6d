// What `particula run` and `resume` set up for their shared time loop (Session), what the loop
// measures (RunStats) and how a run ended (RunEnd), and summary.json built from them
// (run_summary.cpp). Private to src/run.
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "outputs.hpp"
#include "particula/case/case.hpp"
#include "particula/io/json.hpp"
#include "particula/run/run_dir.hpp"
#include "particula/run/runner.hpp"
#include "particula/solver/solver.hpp"

namespace particula::run_detail {

/// What the time loop measured: the summary's throughput and time-step range.
struct RunStats {
  std::chrono::steady_clock::time_point wall0 = std::chrono::steady_clock::now();
  double particle_steps = 0, interactions = 0;
  /// Range of the steps the stability limits chose (steps shortened to land on an output or end
  /// time are left out: their size says nothing about the run); NaN before such a step.
  real dt_min = std::numeric_limits<real>::quiet_NaN(), dt_max = std::numeric_limits<real>::quiet_NaN();
  /// Steps below kTimeStepDrop of the case's step: in all, in the current run of them, and the
  /// runs of kTimeStepDropSteps or more (each reported once in the log), with the first one's time.
  std::int64_t dt_drop_steps = 0, dt_drop_run = 0, dt_drop_reports = 0;
  real dt_drop_first_time = std::numeric_limits<real>::quiet_NaN();
  /// The steps each limit set (StepLimit order), shortened ones included.
  std::array<std::int64_t, kStepLimits> limited_by{};

  double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  }
  /// Counts a step of `dt`, `capped` when it was shortened to land on a time, against the
  /// case's own step `case_dt`. Returns true when this step completes a run of
  /// kTimeStepDropSteps steps below kTimeStepDrop case_dt (to be reported).
  bool add_step(real dt, bool capped, StepLimit limit, std::size_t particles, std::size_t pairs,
                real case_dt) {
    particle_steps += static_cast<double>(particles);
    interactions += static_cast<double>(pairs);
    ++limited_by[static_cast<std::size_t>(limit)];
    if (capped) return false;
    dt_min = std::isnan(dt_min) ? dt : std::min(dt_min, dt);
    dt_max = std::isnan(dt_max) ? dt : std::max(dt_max, dt);
    if (!(dt < kTimeStepDrop * case_dt)) {
      dt_drop_run = 0;
      return false;
    }
    ++dt_drop_steps;
    if (++dt_drop_run != kTimeStepDropSteps) return false;
    ++dt_drop_reports;
    return true;
  }
};

/// What `run` and `resume` set up for the shared loop.
struct Session {
  Case c;
  std::uint64_t case_hash = 0;  // the run's case identity (marker and every checkpoint)
  std::filesystem::path dir;
  RunDirectory* run_dir = nullptr;  // `run`: the new run directory, committed once the run has started
  std::unique_ptr<Solver> solver;
  std::unique_ptr<RunOutputs> outputs;
  std::size_t n_fluid = 0;
  bool resumed = false;
  real t_start = 0;
  std::vector<std::string> overrides;  // the --set list of this command
  RunStats stats;
  ProgressCallback progress;       // the caller's, or empty
  double next_progress_wall = 0;   // wall seconds of the run when it is due next
  bool stopped_by_caller = false;  // the progress callback asked the run to stop
};

/// How a run ended, for summary.json: status, exit code and, for exit 3, the failure.
struct RunEnd {
  std::string status;  // completed, max_steps, interrupted, failed, io_failure
  int exit_code = 0;
  std::optional<Failure> failure;
  std::string error;  // io_failure: the message
};

/// summary.json: what made the run (version, commit, backend, threads, overrides), its
/// resolution and time-step range, how it ended, its cost, the guard counters and profile errors.
io::JsonObject run_summary(const Session& s, const RunEnd& end, std::optional<double> profile_error);

}  // namespace particula::run_detail
