#include "particula/run/plots.hpp"

#include <fcntl.h>
#include <signal.h>
#include <cerrno>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <vector>

extern char** environ;

namespace particula {

namespace {

/// Returned by run_program when `stop` asked to give up (the child was terminated).
constexpr int kStopped = -2;

/// Runs argv[0] (searched on the PATH) with its output appended to `log_file` (or inherited,
/// when empty; `silent` sends it to /dev/null). Returns the exit status, or -1 when it could not
/// run or ended on a signal. With `stop`, polled every 20 ms while the child runs: when it returns
/// true the child is sent SIGTERM and kStopped is returned once it has ended.
int run_program(const std::vector<std::string>& args, const std::filesystem::path& log_file, bool silent = false,
                const std::function<bool()>& stop = {}) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string out = silent ? "/dev/null" : log_file.string();
  if (!out.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) return -1;
  int status = 0;
  bool stopped = false;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, stop && !stopped ? WNOHANG : 0);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) return -1;
    if (r == 0) {
      if (stop()) {
        ::kill(pid, SIGTERM);
        stopped = true;
      } else {
        ::usleep(20000);
      }
    }
  }
  if (stopped) return kStopped;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::filesystem::path plot_script() { return std::filesystem::path(PARTICULA_SOURCE_DIR) / "tools" / "plot_run.py"; }

}  // namespace

const std::vector<std::string>& plot_formats() {
  static const std::vector<std::string> formats{"png", "svg", "pdf"};
  return formats;
}

std::vector<std::string> plot_file_names(const std::vector<std::string>& probes) {
  std::vector<std::string> stems{"flow_rates", "bodies", "coefficients", "snapshot_fields"};
  for (const std::string& p : probes)
    for (const char* what : {"profiles", "error", "points"}) stems.push_back(fmt::format("probe_{}_{}", p, what));
  std::vector<std::string> names;
  for (const std::string& format : plot_formats())
    for (const std::string& stem : stems) names.push_back(stem + "." + format);
  return names;
}

std::string plot_python() {
  std::error_code ec;
  return std::filesystem::exists("/usr/bin/python3", ec) ? "/usr/bin/python3" : "python3";
}

PlotOutcome draw_plots(const std::filesystem::path& run_dir, const std::filesystem::path& log_file,
                       const std::function<bool()>& stop, const std::string& format) {
  std::error_code ec;
  if (!std::filesystem::exists(plot_script(), ec)) return PlotOutcome::NoScript;
  const std::string python = plot_python();
  const int check = run_program({python, "-c", "import matplotlib"}, {}, true, stop);
  if (check == kStopped) return PlotOutcome::Interrupted;
  if (check != 0) return PlotOutcome::NoMatplotlib;
  const int drawn =
      run_program({python, plot_script().string(), run_dir.string(), "--format", format}, log_file, false, stop);
  if (drawn == kStopped) return PlotOutcome::Interrupted;
  return drawn == 0 ? PlotOutcome::Drawn : PlotOutcome::Failed;
}

int plot_command(const std::filesystem::path& run_dir, const std::string& format) {
  const auto& formats = plot_formats();
  if (std::find(formats.begin(), formats.end(), format) == formats.end()) {
    std::fprintf(stderr, "error: --format '%s': plots are drawn as %s; nothing drawn\n", format.c_str(),
                 fmt::format("{}", fmt::join(formats, ", ")).c_str());
    return 2;
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(run_dir, ec) || !std::filesystem::exists(run_dir / "case.toml", ec)) {
    std::fprintf(stderr, "error: '%s' is not a run directory (it has no case.toml)\n", run_dir.string().c_str());
    return 2;
  }
  switch (draw_plots(run_dir, {}, {}, format)) {
    case PlotOutcome::Drawn:
      std::fprintf(stderr, "plots in %s\n", (run_dir / "plots").string().c_str());
      return 0;
    case PlotOutcome::NoMatplotlib:
      std::fprintf(stderr,
                   "error: no plots drawn: matplotlib is not installed for %s (Debian's python3-matplotlib; "
                   "scripts/install-deps installs it)\n",
                   plot_python().c_str());
      return 2;
    case PlotOutcome::NoScript:
      std::fprintf(stderr, "error: no plots drawn: %s is missing\n", plot_script().string().c_str());
      return 1;
    case PlotOutcome::Failed: break;
    case PlotOutcome::Interrupted: return 130;
  }
  std::fprintf(stderr, "error: %s failed on '%s' (its messages are above)\n", plot_script().string().c_str(),
               run_dir.string().c_str());
  return 1;
}

}  // namespace particula
