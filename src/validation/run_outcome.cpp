#include "run_outcome.hpp"

#include <fmt/format.h>

#include <cmath>
#include <exception>

#include "particula/io/atomic_file.hpp"
#include "particula/io/json.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

/// The last "error: " line of the run's log (without the timestamp and the prefix).
std::string log_failure(const std::string& log) {
  const std::size_t at = log.rfind("error: ");
  if (at == std::string::npos) return "";
  const std::size_t end = log.find('\n', at);
  return log.substr(at + 7, end == std::string::npos ? std::string::npos : end - at - 7);
}

/// The date of the log's first line ("2026-12-07 04:48:54.673  particula ..."), "" if none.
std::string log_date(const std::string& log) {
  if (log.size() < 10) return "";
  for (std::size_t i = 0; i < 10; ++i) {
    const bool dash = i == 4 || i == 7;
    if (dash ? log[i] != '-' : (log[i] < '0' || log[i] > '9')) return "";
  }
  return log.substr(0, 10);
}

/// The JSON string starting at the quote `text[q]`, unescaped (summary.json escapes only
/// quotes, backslashes and control characters); `end` is set past its closing quote.
std::string json_string_at(const std::string& text, std::size_t q, std::size_t& end) {
  std::string s;
  std::size_t i = q + 1;
  for (; i < text.size() && text[i] != '"'; ++i) {
    if (text[i] != '\\' || i + 1 >= text.size()) {
      s += text[i];
      continue;
    }
    const char e = text[++i];
    s += e == 'n' ? '\n' : e == 't' ? '\t' : e;
  }
  end = i + 1;
  return s;
}

/// The value of the first `"key": "..."` of the text, "" when absent.
std::string json_string_field(const std::string& text, const std::string& key) {
  const std::size_t k = text.find('"' + key + "\":");
  if (k == std::string::npos) return "";
  const std::size_t q = text.find_first_not_of(" \n", k + key.size() + 3);
  if (q == std::string::npos || text[q] != '"') return "";
  std::size_t end = 0;
  return json_string_at(text, q, end);
}

/// The strings of the first `"key": [...]` of the text.
std::vector<std::string> json_string_array(const std::string& text, const std::string& key) {
  std::vector<std::string> out;
  const std::size_t k = text.find('"' + key + "\":");
  if (k == std::string::npos) return out;
  std::size_t i = text.find('[', k);
  const std::size_t close = text.find(']', k);
  while (i != std::string::npos && i < close) {
    const std::size_t q = text.find('"', i);
    if (q == std::string::npos || q > close) break;
    std::size_t end = 0;
    out.push_back(json_string_at(text, q, end));
    i = end;
  }
  return out;
}

double number_or(const std::string& text, const std::string& key, double fallback) {
  try {
    return io::json_number_field(text, key);
  } catch (const std::exception&) {
    return fallback;
  }
}

}  // namespace

RunOutcome read_outcome(const fs::path& run_dir) {
  RunOutcome o;
  try {
    const std::string log = io::read_file(run_dir / "log.txt");
    o.failure = log_failure(log);
    o.date = log_date(log);
  } catch (const std::exception&) {
  }
  std::string summary;
  try {
    summary = io::read_file(run_dir / "summary.json");
  } catch (const std::exception&) {
    return o;
  }
  o.status = json_string_field(summary, "status");
  o.commit = json_string_field(summary, "commit");
  o.overrides = json_string_array(summary, "overrides");
  o.exit_code = static_cast<int>(number_or(summary, "exit_code", -1));
  o.steps = static_cast<std::int64_t>(number_or(summary, "steps", -1));
  o.end_time = number_or(summary, "end_time", std::nan(""));
  o.threads = static_cast<int>(number_or(summary, "threads", 0));
  o.dt_min_ratio = number_or(summary, "dt_min_ratio", std::nan(""));
  o.wall_seconds = number_or(summary, "wall_seconds", std::nan(""));
  try {
    o.guards = io::json_object_numbers(summary, "guard_events");
  } catch (const std::exception&) {
  }
  return o;
}

std::string guards_text(const std::vector<std::pair<std::string, double>>& guards) {
  std::string s;
  for (const auto& [name, n] : guards)
    if (n != 0) s += fmt::format("{}{} {:.0f}", s.empty() ? "" : ", ", name, n);
  return s.empty() ? "none" : s;
}

}  // namespace particula
