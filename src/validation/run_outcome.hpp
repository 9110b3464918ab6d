// How a run ended, as its run directory tells it (summary.json and log.txt): read by the
// validation report, `validate --check` and the stored results.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace particula {

struct RunOutcome {
  std::string status;  // "completed", "failed", ... ("" when there is no summary.json)
  int exit_code = -1;  // summary.json's exit_code (-1 when absent)
  std::int64_t steps = -1;
  double end_time = 0;
  std::vector<std::pair<std::string, double>> guards;
  std::string failure;  // the message of an exit 3 (log.txt's last "error:" line)
  std::string commit;   // of the binary that ran (summary.json)
  std::vector<std::string> overrides;  // the run's --set (summary.json)
  double dt_min_ratio = 0;  // the smallest step over the case's own (summary.json time_step; NaN when absent)
  int threads = 0;
  double wall_seconds = 0;
  std::string date;  // YYYY-MM-DD of log.txt's first line ("" when absent)
};

/// What the run directory says about its run; fields it does not have keep their defaults.
RunOutcome read_outcome(const std::filesystem::path& run_dir);

/// "name 12, other 3" (the nonzero guard counters, in summary.json's order), "none" when all are 0.
std::string guards_text(const std::vector<std::pair<std::string, double>>& guards);

}  // namespace particula
