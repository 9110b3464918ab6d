// Stored validation results: what one validation case gave at one level, kept as a small TOML
// file in the repository (validation/results/LEVEL/NAME.toml) so that docs/validation.md is
// generated from runs (`particula validate --report`) rather than written by hand. A stored
// result holds the checks, how the run ended, where and when it ran, the run's resolved case
// (to tell when the case or a default has changed since: the result is then stale) and the
// curves of its figure.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "particula/validation/validate.hpp"

namespace particula {

struct StoredResult {
  std::string name;   // the validation case
  std::string group;  // group_name()
  std::string level;  // level_name(): "quick" or "default"
  std::string case_file;
  std::vector<std::string> overrides;  // the --set of the run (summary.json's "overrides")
  double d0 = 0;
  std::string commit;  // of the binary that ran the case (summary.json)
  std::string date;    // YYYY-MM-DD the run started (log.txt)
  int threads = 0;
  double wall_seconds = 0;
  int exit_code = 0;
  std::string status;   // summary.json's status
  std::string failure;  // the message of a numerical failure, if any
  std::int64_t steps = 0;
  double end_time = 0;
  std::vector<std::pair<std::string, double>> guards;  // summary.json's guard_events
  std::vector<ValidationCheck> checks;
  std::string resolved_case;  // the run's case.toml
  ValidationPlot plot;

  /// Exit 0 with at least one check and every check passing (or report-only).
  bool pass() const;
};

/// Reads what the finished run directory `run_dir` of `entry` at `level` gives: its checks
/// (entry.evaluate), its figure (entry.plot, each curve thinned to at most `max_points`), the
/// outcome in summary.json and log.txt, and case.toml. `exit_code` is the run's exit code.
/// Throws io::IoError when an output the checks need is missing or malformed.
StoredResult make_stored_result(const ValidationEntry& entry, const std::filesystem::path& run_dir,
                                const std::string& level, int exit_code, std::size_t max_points = 300);

/// The TOML text of a stored result (exact round trip through parse_stored_result).
std::string stored_result_toml(const StoredResult& r);
/// Parses the text of a stored result; throws std::runtime_error naming `source` and the key.
StoredResult parse_stored_result(const std::string& text, const std::string& source);

/// Where a result is stored: `results_dir`/LEVEL/NAME.toml.
std::filesystem::path stored_result_path(const std::filesystem::path& results_dir, const std::string& level,
                                         const std::string& name);
/// Writes `r` to its path under `results_dir` (atomically, creating the level's directory).
void write_stored_result(const std::filesystem::path& results_dir, const StoredResult& r);
/// Every stored result under `results_dir` (both levels; none when the directory is absent).
std::vector<StoredResult> read_stored_results(const std::filesystem::path& results_dir);

/// The default store: validation/results of the source tree.
std::filesystem::path default_results_dir();

/// Whether the stored result no longer describes what the case gives today: the case file with
/// the result's overrides resolves to a different case (a key of the case or a default changed).
/// Returns the differing lines ("- old" / "+ new", at most `max_lines`), empty when current.
std::vector<std::string> stale_lines(const StoredResult& r, std::size_t max_lines = 4);

}  // namespace particula
