// The run log (log.txt) and the progress line.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "particula/io/error.hpp"

namespace particula::io {

/// Appends timestamped lines ("YYYY-MM-DD HH:MM:SS.mmm  text", local time) to a log file,
/// flushed per line, optionally echoing the text to stderr. Thread-safe. A default-constructed
/// RunLog writes no file (but still echoes when asked).
class RunLog {
 public:
  RunLog() = default;
  /// Opens `path` in append mode; throws WriteError naming the file when it cannot.
  explicit RunLog(const std::filesystem::path& path, bool echo_to_stderr = false);

  /// Logs `text` (each of its lines gets a timestamp) and echoes it to stderr when enabled.
  void line(std::string_view text);
  /// Logs "warning: text" and always echoes it to stderr.
  void warn(std::string_view text);
  /// Logs `text` to the file only, never echoing.
  void record(std::string_view text);

  /// Called (under the log's lock) before each echo to stderr; ProgressLine uses it to end
  /// its live terminal line first. Pass an empty function to remove it.
  void set_before_echo(std::function<void()> hook);

  bool has_file() const { return file_ != nullptr; }
  const std::filesystem::path& path() const { return path_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  void write_locked(std::string_view text, bool echo);

  std::filesystem::path path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  bool echo_ = false;
  std::function<void()> before_echo_;
  std::mutex mutex_;
};

/// Options of ProgressLine; the defaults suit the command-line program.
struct ProgressOptions {
  bool quiet = false;             ///< print nothing (the log still receives progress)
  double plain_interval_s = 5.0;  ///< seconds between plain lines (not a terminal) and log lines
  double live_interval_s = 0.1;   ///< seconds between rewrites of the live terminal line
  std::optional<bool> terminal;   ///< default: isatty(stderr)
  std::FILE* out = stderr;        ///< where the line is printed
  std::function<double()> clock;  ///< wall seconds; default: a steady clock (tests inject one)
};

/// One progress sample.
struct ProgressSample {
  std::int64_t step = 0;
  double t = 0, t_end = 0, dt = 0;
  double particle_steps_per_second = 0;
};

/// The progress text: step, time, percentage, dt, throughput and ETA (negative eta_s: unknown).
std::string format_progress(const ProgressSample& s, double eta_s);

/// A duration as "42s", "3m07s", "2h05m" or "3d04h"; "--" when negative or not finite.
std::string format_duration(double seconds);

/// Prints progress: on a terminal, one live line rewritten with '\r' at most every
/// live_interval_s; otherwise a plain line every plain_interval_s. Every plain_interval_s the
/// text also goes to the RunLog (file only). The ETA uses the rate of simulated time since the
/// first update. Call update()/finish() from one thread; the RunLog may echo warnings from
/// any thread (the live line is ended first, under a lock). Not copyable or movable (the log
/// holds a hook to it).
class ProgressLine {
 public:
  explicit ProgressLine(RunLog* log = nullptr, ProgressOptions options = {});
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Reports the state after a step; prints and logs only when the intervals allow.
  void update(std::int64_t step, double t, double t_end, double dt, double particle_steps_per_second);
  /// Prints and logs the last state unconditionally and ends the line. Idempotent.
  void finish();

 private:
  double now() const;
  double eta(const ProgressSample& s, double wall) const;
  void print(const std::string& text);
  void end_live_line();

  RunLog* log_;
  ProgressOptions opt_;
  bool terminal_ = false;
  bool have_sample_ = false, finished_ = false, live_open_ = false;
  ProgressSample last_{};
  double start_wall_ = 0, start_t_ = 0;
  double last_print_ = -1e300, last_log_ = -1e300;
  std::size_t live_width_ = 0;
  std::mutex print_mutex_;  ///< guards the printed state; never held while calling the log
};

}  // namespace particula::io
