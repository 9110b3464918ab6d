// `particula run` and `particula resume`: load a case (or a checkpoint), advance the solver
// and feed the observers (progress, log, probes, body history, snapshots, checkpoints,
// summary). Both share one loop. They return the process exit code of the command-line
// contract (0 ok, 1 internal, 2 bad input, 3 numerical failure, 4 I/O failure, 130 interrupted).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace particula {

/// Exit code of a file-system failure while writing (disk full, permission denied, file too
/// large): not bad input; logged to log.txt when the run directory is kept.
inline constexpr int kExitIoFailure = 4;

/// Told the simulated time, time.end and the step count after a step, at most every
/// kProgressInterval seconds of wall time and after the last step (the Python module's progress
/// bar and callbacks). It returns false to stop the run, which then ends as an interrupted one
/// (outputs and a checkpoint written, exit 130); it must not throw.
using ProgressCallback = std::function<bool(double time, double t_end, std::int64_t step)>;
inline constexpr double kProgressInterval = 0.25;

struct RunOptions {
  std::filesystem::path out_dir;  // empty: runs/<case name>
  bool overwrite = false;
  bool quiet = false;
  bool plots = true;  // draw plots at the end (tools/plot_run.py) when matplotlib is present
  int threads = 0;  // 0: OpenMP default
  std::string backend = "cpu";  // "cpu" or "cuda"
  std::vector<std::string> overrides;
  /// The case's TOML text, when it does not come from a file (the Python module's
  /// particula.Case): `case_file` then only names it in messages.
  std::optional<std::string> case_text;
  ProgressCallback progress;
};

int run_command(const std::filesystem::path& case_file, const RunOptions& options);

struct ResumeOptions {
  std::filesystem::path run_dir;
  bool quiet = false;
  bool plots = true;
  int threads = 0;
  std::string backend = "cpu";  // "cpu" or "cuda" (a checkpoint resumes on either)
  /// Only time.end and output.* keys may change when resuming (anything else is exit 2).
  std::vector<std::string> overrides;
  ProgressCallback progress;
};

/// `particula resume DIR`: continues the run from DIR/checkpoint/state.bin to time.end,
/// appending to its output files.
int resume_command(const ResumeOptions& options);

/// Whether `--set key=value` may be given to `resume` (time.end and output.* keys).
bool resume_override_allowed(const std::string& assignment);

/// Name of the file a numerical failure writes its diagnostic checkpoint to (in DIR/checkpoint/);
/// state.bin keeps the last good state.
inline constexpr const char* kFailureCheckpoint = "failure.bin";

}  // namespace particula
