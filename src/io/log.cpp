// Run log and progress line.
#include "particula/io/log.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>

namespace particula::io {
namespace {

/// Local wall-clock time as "YYYY-MM-DD HH:MM:SS.mmm".
std::string timestamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t secs = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  localtime_r(&secs, &tm);
  return fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02}.{:03}", tm.tm_year + 1900, tm.tm_mon + 1,
                     tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
}

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

// ---------------------------------------------------------------- RunLog

RunLog::RunLog(const std::filesystem::path& path, bool echo_to_stderr) : path_(path), echo_(echo_to_stderr) {
  file_.reset(std::fopen(path.c_str(), "a"));
  if (!file_) throw WriteError(fmt::format("cannot open log '{}': {}", path.string(), std::strerror(errno)));
}

void RunLog::line(std::string_view text) {
  std::lock_guard lock(mutex_);
  write_locked(text, echo_);
}

void RunLog::warn(std::string_view text) {
  std::lock_guard lock(mutex_);
  write_locked(fmt::format("warning: {}", text), true);
}

void RunLog::record(std::string_view text) {
  std::lock_guard lock(mutex_);
  write_locked(text, false);
}

void RunLog::set_before_echo(std::function<void()> hook) {
  std::lock_guard lock(mutex_);
  before_echo_ = std::move(hook);
}

void RunLog::write_locked(std::string_view text, bool echo) {
  if (file_) {
    const std::string stamp = timestamp();
    std::string out;
    for (std::size_t start = 0; start <= text.size();) {
      std::size_t nl = text.find('\n', start);
      if (nl == std::string_view::npos) nl = text.size();
      out += fmt::format("{}  {}\n", stamp, text.substr(start, nl - start));
      start = nl + 1;
    }
    // A failing log must not stop a run; the results are elsewhere.
    (void)std::fputs(out.c_str(), file_.get());
    (void)std::fflush(file_.get());
  }
  if (echo) {
    if (before_echo_) before_echo_();
    fmt::print(stderr, "{}\n", text);
    std::fflush(stderr);
  }
}

// ---------------------------------------------------------------- progress text

std::string format_duration(double s) {
  if (!(s >= 0) || !std::isfinite(s)) return "--";
  const auto n = static_cast<std::int64_t>(std::llround(s));
  if (n < 60) return fmt::format("{}s", n);
  if (n < 3600) return fmt::format("{}m{:02}s", n / 60, n % 60);
  if (n < 86400) return fmt::format("{}h{:02}m", n / 3600, n % 3600 / 60);
  return fmt::format("{}d{:02}h", n / 86400, n % 86400 / 3600);
}

std::string format_progress(const ProgressSample& s, double eta_s) {
  const double pct = s.t_end > 0 ? 100.0 * s.t / s.t_end : 0.0;
  return fmt::format(
      "step {}  t = {:.5g} / {:.5g} s ({:.1f}%)  dt = {:.3g} s  {:.3g} particle-steps/s  ETA {}", s.step, s.t,
      s.t_end, pct, s.dt, s.particle_steps_per_second, format_duration(eta_s));
}

// ---------------------------------------------------------------- ProgressLine

ProgressLine::ProgressLine(RunLog* log, ProgressOptions options) : log_(log), opt_(std::move(options)) {
  terminal_ = opt_.terminal.value_or(::isatty(::fileno(stderr)) == 1);
  if (log_ && terminal_ && !opt_.quiet) log_->set_before_echo([this] { end_live_line(); });
}

ProgressLine::~ProgressLine() {
  if (log_ && terminal_ && !opt_.quiet) log_->set_before_echo({});
  end_live_line();
}

double ProgressLine::now() const { return opt_.clock ? opt_.clock() : steady_seconds(); }

double ProgressLine::eta(const ProgressSample& s, double wall) const {
  const double elapsed = wall - start_wall_, advanced = s.t - start_t_;
  if (elapsed <= 0 || advanced <= 0) return -1;
  return std::max(0.0, s.t_end - s.t) * elapsed / advanced;
}

void ProgressLine::update(std::int64_t step, double t, double t_end, double dt,
                          double particle_steps_per_second) {
  const double wall = now();
  last_ = {step, t, t_end, dt, particle_steps_per_second};
  if (!have_sample_) {
    have_sample_ = true;
    start_wall_ = wall;
    start_t_ = t;
  }
  const bool log_due = wall - last_log_ >= opt_.plain_interval_s;
  const double print_interval = terminal_ ? opt_.live_interval_s : opt_.plain_interval_s;
  const bool print_due = !opt_.quiet && wall - last_print_ >= print_interval;
  if (!log_due && !print_due) return;
  const std::string text = format_progress(last_, eta(last_, wall));
  if (print_due) {
    print(text);
    last_print_ = wall;
  }
  if (log_due) {
    if (log_) log_->record(text);
    last_log_ = wall;
  }
}

void ProgressLine::finish() {
  if (finished_ || !have_sample_) return;
  finished_ = true;
  const std::string text = format_progress(last_, eta(last_, now()));
  if (!opt_.quiet) print(text);
  if (log_) log_->record(text);
  end_live_line();
}

void ProgressLine::print(const std::string& text) {
  std::lock_guard lock(print_mutex_);
  if (!terminal_) {
    fmt::print(opt_.out, "{}\n", text);
  } else {
    // Pad with spaces to erase the tail of a longer previous line.
    const std::size_t pad = live_width_ > text.size() ? live_width_ - text.size() : 0;
    fmt::print(opt_.out, "\r{}{:{}}", text, "", pad);
    live_width_ = text.size();
    live_open_ = true;
  }
  std::fflush(opt_.out);
}

void ProgressLine::end_live_line() {
  std::lock_guard lock(print_mutex_);
  if (!live_open_) return;
  fmt::print(opt_.out, "\n");
  std::fflush(opt_.out);
  live_open_ = false;
  live_width_ = 0;
}

}  // namespace particula::io
