// `particula run`: loads a case, builds the scene, advances the solver and feeds the
// observers (progress, log, probes, body history, snapshots, summary). Returns the process
// exit code of the command-line contract (0 ok, 1 internal, 2 bad input, 3 numerical
// failure, 130 interrupted).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace particula {

struct RunOptions {
  std::filesystem::path out_dir;  // empty: runs/<case name>
  bool overwrite = false;
  bool quiet = false;
  bool plots = true;  // draw plots at the end (tools/plot_run.py) when matplotlib is present
  int threads = 0;  // 0: OpenMP default
  std::vector<std::string> overrides;
};

int run_command(const std::filesystem::path& case_file, const RunOptions& options);

}  // namespace particula
