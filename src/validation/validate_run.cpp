// Running the validation suite (`particula validate`): which entries run, each case run into
// its own directory at the chosen level, the outcome and guard counts read back, the checks
// applied, the report (report.md) and the exit code; and `validate --check`, the
// checks of one entry on an existing run directory. The entries and their checks are in
// validate.cpp.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>

#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/csv.hpp"
#include "particula/io/json.hpp"
#include "particula/run/limits.hpp"
#include "particula/run/run_dir.hpp"
#include "particula/run/runner.hpp"
#include "particula/validation/robustness.hpp"
#include "particula/validation/validate.hpp"

namespace particula {

namespace fs = std::filesystem;

const fs::path& source_dir() {
  static const fs::path dir = PARTICULA_SOURCE_DIR;  // compiled in (CMakeLists.txt)
  return dir;
}

const char* group_name(ValidationGroup g) {
  switch (g) {
    case ValidationGroup::Analytic: return "analytic";
    case ValidationGroup::Paper: return "paper";
    case ValidationGroup::Robustness: return "robustness";
    case ValidationGroup::Benchmark: return "benchmark";
  }
  return "";
}

bool entry_selected(const ValidationEntry& entry, const ValidateOptions& opt) {
  if (!opt.only.empty()) return std::find(opt.only.begin(), opt.only.end(), entry.name) != opt.only.end();
  if (opt.groups.empty()) return entry.group != ValidationGroup::Robustness;
  return std::find(opt.groups.begin(), opt.groups.end(), entry.group) != opt.groups.end();
}

namespace {

/// What a run left behind: summary.json's status, steps and guard counters, and the failure
/// message of a numerical failure (log.txt's "error:" line), so that a case that stops early is
/// reported with why and where rather than as a bare exit code.
struct RunOutcome {
  std::string status;   // "completed", "failed", ... ("" when there is no summary.json)
  std::int64_t steps = -1;
  double end_time = std::nan("");
  std::vector<std::pair<std::string, double>> guards;
  std::string failure;  // the message of an exit 3
};

/// The last "error: " line of the run's log (without the timestamp and the prefix).
std::string failure_message(const fs::path& run_dir) {
  std::string text;
  try {
    text = io::read_file(run_dir / "log.txt");
  } catch (const std::exception&) {
    return "";
  }
  const std::size_t at = text.rfind("error: ");
  if (at == std::string::npos) return "";
  const std::size_t end = text.find('\n', at);
  return text.substr(at + 7, end == std::string::npos ? std::string::npos : end - at - 7);
}

RunOutcome read_outcome(const fs::path& run_dir) {
  RunOutcome o;
  o.failure = failure_message(run_dir);
  std::string summary;
  try {
    summary = io::read_file(run_dir / "summary.json");
  } catch (const std::exception&) {
    return o;
  }
  try {
    o.steps = static_cast<std::int64_t>(io::json_number_field(summary, "steps"));
    o.end_time = io::json_number_field(summary, "end_time");
    o.guards = io::json_object_numbers(summary, "guard_events");
    const std::size_t k = summary.find("\"status\"");
    const std::size_t q0 = summary.find('"', summary.find(':', k) + 1), q1 = summary.find('"', q0 + 1);
    if (k != std::string::npos && q1 != std::string::npos) o.status = summary.substr(q0 + 1, q1 - q0 - 1);
  } catch (const std::exception&) {
  }
  return o;
}

/// "name 12, other 0" (the guard counters as summary.json lists them).
std::string guards_text(const RunOutcome& o) {
  std::string s;
  for (const auto& [name, n] : o.guards) s += fmt::format("{}{} {:.0f}", s.empty() ? "" : ", ", name, n);
  return s.empty() ? "-" : s;
}

struct EntryResult {
  const ValidationEntry* entry = nullptr;
  fs::path dir;
  std::vector<std::string> sets;  // the --set overrides of the run
  double d0 = 0, wall = 0;
  int exit_code = 0;
  std::string error;  // why it could not be run or evaluated
  RunOutcome outcome;
  std::vector<ValidationCheck> checks;
  bool pass() const {
    if (exit_code != 0 || !error.empty() || checks.empty()) return false;
    return std::all_of(checks.begin(), checks.end(), [](const ValidationCheck& c) { return c.pass || c.report_only; });
  }
};

std::string cell(std::string s) {
  std::replace(s.begin(), s.end(), '|', '/');
  return s;
}

/// The run's own line of the report table: how it ended.
std::string run_row(const EntryResult& r, const std::string& name) {
  std::string what = r.error.empty() ? fmt::format("exit code {}", r.exit_code) : r.error;
  if (!r.outcome.failure.empty()) what += ": " + r.outcome.failure;
  return fmt::format("| {} | run | {} | exit 0 | | **FAIL** |\n", name, cell(what));
}

std::string report_markdown(const std::vector<EntryResult>& results, const ValidateOptions& opt) {
  std::string md = "# particula validation report\n\n";
  md += fmt::format("Mode: {} ({}); {} OpenMP threads. Generated by `particula validate{}`.\n\n",
                    opt.quick ? "quick" : "default",
                    opt.quick ? "analytic and robustness cases at the shipped resolution, paper cases at a coarse level"
                              : "analytic and robustness cases twice as fine as shipped, paper cases at the paper's "
                                "resolution",
                    omp_get_max_threads(), opt.quick ? " --quick" : "");
  if (!opt.sets.empty()) {
    md += "Overrides of every case:";
    for (const auto& s : opt.sets) md += fmt::format(" `--set {}`", s);
    md += "\n\n";
  }
  md += "| case | quantity | value | reference | tolerance | result |\n|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    const std::string name = fmt::format("[{}]({}/)", r.entry->name, r.entry->name);
    if (r.exit_code != 0 || !r.error.empty()) md += run_row(r, name);
    for (const auto& c : r.checks)
      md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", name, cell(c.quantity), cell(c.shown), cell(c.reference),
                        cell(c.tolerance), c.report_only ? "report" : c.pass ? "pass" : "**FAIL**");
  }
  const auto passed = std::count_if(results.begin(), results.end(), [](const EntryResult& r) { return r.pass(); });
  md += fmt::format("\n{} of {} cases pass.\n\n## How each run ended\n\n", passed, results.size());
  md += "| case | group | exit | status | steps | end time (s) | guard events | failure |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results)
    md += fmt::format("| {} | {} | {} | {} | {} | {:.6g} | {} | {} |\n", r.entry->name, group_name(r.entry->group),
                      r.exit_code, r.outcome.status.empty() ? "-" : r.outcome.status, r.outcome.steps,
                      r.outcome.end_time, cell(guards_text(r.outcome)),
                      cell(r.outcome.failure.empty() ? r.error : r.outcome.failure));
  md += "\n## Runs and plots\n\n";
  for (const auto& r : results) {
    std::string sets;
    for (const auto& o : r.sets) sets += fmt::format(" `--set {}`", o);
    md += fmt::format("### {}\n\n`{}`{} (resolution.d0 = {} m), {:.1f} s wall time; run directory [{}/]({}/).\n\n",
                      r.entry->name, r.entry->case_file, sets, r.d0, r.wall, r.entry->name, r.entry->name);
    std::vector<std::string> pngs;
    std::error_code ec;
    if (fs::is_directory(r.dir / "plots", ec))
      for (const auto& e : fs::directory_iterator(r.dir / "plots", ec))
        if (e.path().extension() == ".png") pngs.push_back(e.path().filename().string());
    std::sort(pngs.begin(), pngs.end());
    if (pngs.empty()) md += "No plots (python3-matplotlib missing, or the run failed).\n\n";
    if (std::find(pngs.begin(), pngs.end(), "bodies.png") != pngs.end())
      md += fmt::format("![{} bodies]({}/plots/bodies.png)\n\n", r.entry->name, r.entry->name);
    for (const auto& png : pngs) md += fmt::format("- [{}]({}/plots/{})\n", png, r.entry->name, png);
    if (!pngs.empty()) md += "\n";
  }
  return md;
}

/// The --set overrides of an entry at the chosen level, and its d0 (the level rules of
/// ValidationEntry).
std::vector<std::string> level_overrides(const ValidationEntry& entry, const fs::path& case_file, bool quick,
                                         double& d0) {
  std::vector<std::string> sets = entry.overrides;
  const std::vector<std::string>* extra = nullptr;
  if (entry.paper) extra = quick ? &entry.quick_overrides : nullptr;
  else if (!quick && !entry.fine_overrides.empty()) extra = &entry.fine_overrides;
  if (entry.paper || extra) {
    if (extra) sets.insert(sets.end(), extra->begin(), extra->end());
    d0 = load_case(case_file, sets).d0;
    return sets;
  }
  const Case base = load_case(case_file, entry.overrides);
  d0 = quick ? base.d0 : base.d0 / 2;
  sets.push_back(fmt::format("resolution.d0={}", d0));
  return sets;
}

/// Runs one entry into its directory and evaluates it (also a run that stopped early: its
/// checks then show how far it got).
EntryResult run_entry(const ValidationEntry& entry, const ValidateOptions& opt) {
  EntryResult r;
  r.entry = &entry;
  r.dir = opt.out_dir / entry.name;
  RunOptions run;
  run.out_dir = r.dir;
  run.overwrite = true;
  run.quiet = true;
  run.threads = opt.threads;
  const fs::path case_file = source_dir() / entry.case_file;
  try {
    run.overrides = level_overrides(entry, case_file, opt.quick, r.d0);
    run.overrides.insert(run.overrides.end(), opt.sets.begin(), opt.sets.end());
    if (!opt.sets.empty()) r.d0 = load_case(case_file, run.overrides).d0;
    r.sets = run.overrides;
    if (!opt.quiet)
      std::fprintf(stderr, "validate: %s (%s, resolution.d0 = %g m) ...\n", entry.name.c_str(),
                   entry.case_file.c_str(), r.d0);
    const auto t0 = std::chrono::steady_clock::now();
    r.exit_code = run_command(case_file, run);
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.outcome = read_outcome(r.dir);
    if (r.exit_code == 0 || r.exit_code == 3) r.checks = entry.evaluate(r.dir, load_case(r.dir / "case.toml"));
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

/// "  quantity: value (reference ..., tolerance): pass" for each check.
void print_checks(std::FILE* out, const std::vector<ValidationCheck>& checks) {
  for (const auto& c : checks)
    if (c.report_only)
      std::fprintf(out, "  %s: %s\n", c.quantity.c_str(), c.shown.c_str());
    else
      std::fprintf(out, "  %s: %s (reference %s, %s): %s\n", c.quantity.c_str(), c.shown.c_str(),
                   c.reference.c_str(), c.tolerance.c_str(), c.pass ? "pass" : "FAIL");
}

/// "  completed after N steps at t = T s; guard events: ..." when the run wrote summary.json.
void print_outcome(std::FILE* out, const RunOutcome& o) {
  if (o.steps >= 0)
    std::fprintf(out, "  %s after %lld steps at t = %g s; guard events: %s\n", o.status.c_str(),
                 static_cast<long long>(o.steps), o.end_time, guards_text(o).c_str());
}

void print_result(const EntryResult& r) {
  if (r.exit_code != 0 || !r.error.empty())
    std::fprintf(stderr, "  FAIL: %s%s\n",
                 r.error.empty() ? fmt::format("the run ended with exit code {}", r.exit_code).c_str() : r.error.c_str(),
                 r.outcome.failure.empty() ? "" : (": " + r.outcome.failure).c_str());
  print_outcome(stderr, r.outcome);
  print_checks(stderr, r.checks);
}

}  // namespace

namespace {
/// "\n  analytic: couette, ...": the names of the validation cases, by group.
std::string case_names_by_group(const std::vector<ValidationEntry>& entries) {
  std::string text;
  for (const ValidationGroup g : {ValidationGroup::Analytic, ValidationGroup::Paper, ValidationGroup::Benchmark,
                                  ValidationGroup::Robustness}) {
    std::string names;
    for (const auto& e : entries)
      if (e.group == g) names += (names.empty() ? "" : ", ") + e.name;
    if (!names.empty()) text += fmt::format("\n  {}: {}", group_name(g), names);
  }
  return text;
}

/// The error for an unknown `--case NAME`: the valid names, by group.
std::string unknown_case_message(const std::string& name, const std::vector<ValidationEntry>& entries) {
  return fmt::format("--case {}: no validation case of that name; the cases are:", name) + case_names_by_group(entries);
}
}  // namespace

int validate_command(const ValidateOptions& opt) {
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  std::vector<ValidationEntry> entries = validation_entries();
  // An unknown name is refused before anything is created (also no --out directory).
  for (const auto& name : opt.only)
    if (std::none_of(entries.begin(), entries.end(), [&](const ValidationEntry& e) { return e.name == name; })) {
      std::fprintf(stderr, "error: %s\n", unknown_case_message(name, entries).c_str());
      return 2;
    }
  // The output directory: particula's own (a marker) or new or empty; its run directories are
  // replaced under the rules of `run --overwrite`.
  try {
    prepare_validation_dir(opt.out_dir);
  } catch (const RunDirRefused& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const io::WriteError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return kExitIoFailure;
  }
  std::vector<EntryResult> results;
  for (const auto& entry : entries) {
    if (!entry_selected(entry, opt)) continue;
    EntryResult r = run_entry(entry, opt);
    if (!opt.quiet) print_result(r);
    const bool interrupted = r.exit_code == 130;
    results.push_back(std::move(r));
    if (interrupted) break;  // Ctrl-C stops the suite, not only the current run
  }
  const fs::path report = opt.out_dir / "report.md";
  try {
    io::write_file_atomic(report, report_markdown(results, opt));
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return kExitIoFailure;
  }
  if (!results.empty() && results.back().exit_code == 130) {
    std::fprintf(stderr, "validate: interrupted; partial report in %s\n", report.string().c_str());
    return 130;
  }
  const bool all = std::all_of(results.begin(), results.end(), [](const EntryResult& r) { return r.pass(); });
  std::fprintf(stderr, "validate: %s; report in %s\n", all ? "all cases pass" : "SOME CASES FAIL",
               report.string().c_str());
  return all ? 0 : 3;
}

// ---- validate --check: the checks of one entry on an existing run directory --------------------

namespace {

/// Bad input of `validate --check` (exit code 2); what() is the message.
class CheckRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The resolved case of run directory `dir` (its case.toml). Throws CheckRefused when `dir` is
/// not a run directory.
Case run_directory_case(const fs::path& dir) {
  const std::string d = dir.string();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw CheckRefused(fmt::format("{}: not a run directory ({})", d, fs::exists(dir, ec) ? "not a directory" : "no such directory"));
  std::optional<RunMarker> marker;
  try {
    marker = read_marker(dir);
  } catch (const io::IoError& e) {
    throw CheckRefused(fmt::format("{}: not a run directory: {}", d, e.what()));
  }
  if (marker && marker->kind == MarkedKind::Validation)
    throw CheckRefused(fmt::format("{}: a validation directory, not a run directory (its runs are its subdirectories)", d));
  if (!fs::is_regular_file(dir / "case.toml", ec))
    throw CheckRefused(fmt::format("{}: not a run directory (no case.toml)", d));
  try {
    return load_case(dir / "case.toml");
  } catch (const std::exception& e) {
    throw CheckRefused(fmt::format("{}: its case.toml does not load: {}", d, e.what()));
  }
}

/// The entry named `name`, or (`name` empty) the one named as the run's case. Throws CheckRefused.
const ValidationEntry& entry_for_check(const std::vector<ValidationEntry>& entries, const std::string& name,
                                       const Case& c, const fs::path& dir) {
  const std::string& wanted = name.empty() ? c.name : name;
  for (const auto& e : entries)
    if (e.name == wanted) return e;
  if (!name.empty()) throw CheckRefused(unknown_case_message(name, entries));
  throw CheckRefused(fmt::format("{}: its case '{}' is no validation case; name one with --case:", dir.string(),
                                 c.name) +
                     case_names_by_group(entries));
}

}  // namespace

int validate_check_command(const fs::path& run_dir, const std::string& case_name) {
  const std::vector<ValidationEntry> entries = validation_entries();
  std::vector<ValidationCheck> checks;
  try {
    const Case c = run_directory_case(run_dir);
    const ValidationEntry& entry = entry_for_check(entries, case_name, c, run_dir);
    std::printf("validate --check %s: the checks of %s (%s), resolution.d0 = %g m\n", run_dir.string().c_str(),
                entry.name.c_str(), group_name(entry.group), c.d0);
    print_outcome(stdout, read_outcome(run_dir));
    try {
      checks = entry.evaluate(run_dir, c);
    } catch (const std::exception& e) {
      throw CheckRefused(fmt::format("{}: the checks of {} cannot read the run: {}", run_dir.string(), entry.name, e.what()));
    }
  } catch (const CheckRefused& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  print_checks(stdout, checks);
  const auto failed =
      std::count_if(checks.begin(), checks.end(), [](const ValidationCheck& k) { return !k.pass && !k.report_only; });
  if (checks.empty()) std::printf("validate --check: FAIL: no checks\n");
  else if (failed) std::printf("validate --check: %lld of %zu checks FAIL\n", static_cast<long long>(failed), checks.size());
  else std::printf("validate --check: all checks pass\n");
  return failed == 0 && !checks.empty() ? 0 : 1;
}

}  // namespace particula
