// Stored validation results (record.hpp): made from a run directory, written and read as TOML.
#include "particula/validation/record.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <toml++/toml.h>

#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "run_outcome.hpp"

namespace particula {

namespace fs = std::filesystem;

bool StoredResult::pass() const {
  if (exit_code != 0 || checks.empty()) return false;
  return std::all_of(checks.begin(), checks.end(), [](const ValidationCheck& c) { return c.pass || c.report_only; });
}

namespace {

/// At most `max_points` of the series' points: the first, the last and an even stride between.
void thin(PlotSeries& s, std::size_t max_points) {
  const std::size_t n = s.x.size();
  if (n <= max_points || max_points < 2) return;
  PlotSeries t;
  for (std::size_t k = 0; k < max_points; ++k) {
    const std::size_t i = k * (n - 1) / (max_points - 1);
    t.x.push_back(s.x[i]);
    t.y.push_back(s.y[i]);
  }
  s.x = std::move(t.x);
  s.y = std::move(t.y);
}

/// The lines of a resolved case that carry content (its comment header dropped).
std::vector<std::string> content_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  return lines;
}

toml::array string_array(const std::vector<std::string>& v) {
  toml::array a;
  for (const auto& s : v) a.push_back(s);
  return a;
}

toml::array number_array(const std::vector<double>& v) {
  toml::array a;
  for (const double x : v) a.push_back(x);
  return a;
}

toml::table check_table(const ValidationCheck& c) {
  toml::table t{{"quantity", c.quantity}, {"value", c.value},         {"shown", c.shown},          {"reference", c.reference},
                {"tolerance", c.tolerance}, {"pass", c.pass}, {"report_only", c.report_only}};
  if (std::isfinite(c.error)) t.insert("error", c.error);
  return t;
}

toml::table plot_table(const ValidationPlot& p) {
  toml::array series;
  for (const auto& s : p.series)
    series.push_back(toml::table{
        {"label", s.label}, {"reference", s.reference}, {"x", number_array(s.x)}, {"y", number_array(s.y)}});
  return toml::table{{"title", p.title}, {"x_label", p.x_label}, {"y_label", p.y_label}, {"series", series}};
}

// ---- reading ------------------------------------------------------------------------------------

/// Reading one table of a stored result; errors name the file and the key.
struct Reader {
  const toml::table& t;
  const std::string& source;
  std::string prefix;

  [[noreturn]] void fail(const std::string& key, const char* what) const {
    throw std::runtime_error(fmt::format("{}: {}{}: {}", source, prefix, key, what));
  }
  std::string str(const std::string& key) const {
    const auto v = t[key].value<std::string>();
    if (!v) fail(key, "missing or not a string");
    return *v;
  }
  double num(const std::string& key) const {
    const auto v = t[key].value<double>();  // integers convert
    if (!v) fail(key, "missing or not a number");
    return *v;
  }
  double num_or_nan(const std::string& key) const { return t.contains(key) ? num(key) : std::nan(""); }
  bool flag(const std::string& key) const {
    const toml::value<bool>* v = t[key].as_boolean();  // value<bool>() would take 1 for true
    if (!v) fail(key, "missing or not a boolean");
    return v->get();
  }
  const toml::array& array(const std::string& key) const {
    const toml::array* a = t[key].as_array();
    if (!a) fail(key, "missing or not an array");
    return *a;
  }
  std::vector<std::string> strings(const std::string& key) const {
    std::vector<std::string> out;
    for (const auto& n : array(key)) {
      const auto v = n.value<std::string>();
      if (!v) fail(key, "an element is not a string");
      out.push_back(*v);
    }
    return out;
  }
  std::vector<double> numbers(const std::string& key) const {
    std::vector<double> out;
    for (const auto& n : array(key)) {
      const auto v = n.value<double>();
      if (!v) fail(key, "an element is not a number");
      out.push_back(*v);
    }
    return out;
  }
  /// The tables of the array `key`, each with its reader prefix "key[i].".
  template <typename F>
  void each_table(const std::string& key, F&& f) const {
    const toml::array& a = array(key);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const toml::table* e = a[i].as_table();
      if (!e) fail(key, "an element is not a table");
      f(Reader{*e, source, fmt::format("{}{}[{}].", prefix, key, i)});
    }
  }
};

ValidationCheck read_check(const Reader& r) {
  ValidationCheck c;
  c.quantity = r.str("quantity");
  c.value = r.num("value");
  c.shown = r.str("shown");
  c.reference = r.str("reference");
  c.tolerance = r.str("tolerance");
  c.pass = r.flag("pass");
  c.report_only = r.flag("report_only");
  c.error = r.num_or_nan("error");
  return c;
}

ValidationPlot read_plot(const Reader& r) {
  ValidationPlot p;
  p.title = r.str("title");
  p.x_label = r.str("x_label");
  p.y_label = r.str("y_label");
  r.each_table("series", [&](const Reader& s) {
    PlotSeries ps;
    ps.label = s.str("label");
    ps.reference = s.flag("reference");
    ps.x = s.numbers("x");
    ps.y = s.numbers("y");
    if (ps.x.size() != ps.y.size()) s.fail("y", "not as long as x");
    p.series.push_back(std::move(ps));
  });
  return p;
}

}  // namespace

StoredResult make_stored_result(const ValidationEntry& entry, const fs::path& run_dir, const std::string& level,
                                int exit_code, std::size_t max_points) {
  const Case c = load_case(run_dir / "case.toml");
  StoredResult r;
  r.name = entry.name;
  r.group = group_name(entry.group);
  r.level = level;
  r.case_file = entry.case_file;
  r.d0 = c.d0;
  r.exit_code = exit_code;
  const RunOutcome o = read_outcome(run_dir);
  r.overrides = o.overrides;
  r.commit = o.commit;
  r.date = o.date;
  r.threads = o.threads;
  r.wall_seconds = o.wall_seconds;
  r.status = o.status;
  r.failure = o.failure;
  r.steps = o.steps;
  r.end_time = o.end_time;
  r.guards = o.guards;
  r.checks = entry.evaluate(run_dir, c);
  r.resolved_case = io::read_file(run_dir / "case.toml");
  if (entry.plot) {
    r.plot = entry.plot(run_dir, c);
    for (auto& s : r.plot.series) thin(s, max_points);
  }
  return r;
}

std::string stored_result_toml(const StoredResult& r) {
  toml::table guards;
  for (const auto& [name, n] : r.guards) guards.insert(name, n);
  toml::array checks;
  for (const auto& c : r.checks) checks.push_back(check_table(c));
  toml::table t{{"name", r.name},
                {"group", r.group},
                {"level", r.level},
                {"case_file", r.case_file},
                {"overrides", string_array(r.overrides)},
                {"d0", r.d0},
                {"commit", r.commit},
                {"date", r.date},
                {"threads", r.threads},
                {"wall_seconds", r.wall_seconds},
                {"exit_code", r.exit_code},
                {"status", r.status},
                {"failure", r.failure},
                {"steps", r.steps},
                {"end_time", r.end_time},
                {"guard_events", guards},
                {"check", checks},
                {"resolved_case", string_array(content_lines(r.resolved_case))}};
  if (!r.plot.series.empty()) t.insert("plot", plot_table(r.plot));
  std::ostringstream out;
  out << "# A stored validation result, written by `particula validate --record` (docs/validation.md is\n"
         "# generated from these files by `particula validate --report`).\n"
      << toml::toml_formatter(t, toml::format_flags::none) << "\n";
  return out.str();
}

StoredResult parse_stored_result(const std::string& text, const std::string& source) {
  toml::table t;
  try {
    t = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(fmt::format("{}:{}: {}", source, e.source().begin.line, e.description()));
  }
  const Reader rd{t, source, ""};
  StoredResult r;
  r.name = rd.str("name");
  r.group = rd.str("group");
  r.level = rd.str("level");
  if (r.level != level_name(true) && r.level != level_name(false)) rd.fail("level", "neither \"quick\" nor \"default\"");
  r.case_file = rd.str("case_file");
  r.overrides = rd.strings("overrides");
  r.d0 = rd.num("d0");
  r.commit = rd.str("commit");
  r.date = rd.str("date");
  r.threads = static_cast<int>(rd.num("threads"));
  r.wall_seconds = rd.num("wall_seconds");
  r.exit_code = static_cast<int>(rd.num("exit_code"));
  r.status = rd.str("status");
  r.failure = rd.str("failure");
  r.steps = static_cast<std::int64_t>(rd.num("steps"));
  r.end_time = rd.num("end_time");
  if (const toml::table* g = t["guard_events"].as_table())
    for (const auto& [key, node] : *g) r.guards.emplace_back(std::string(key.str()), node.value<double>().value_or(0));
  rd.each_table("check", [&](const Reader& c) { r.checks.push_back(read_check(c)); });
  for (const auto& line : rd.strings("resolved_case")) r.resolved_case += line + "\n";
  if (const toml::table* p = t["plot"].as_table()) r.plot = read_plot(Reader{*p, source, "plot."});
  return r;
}

fs::path stored_result_path(const fs::path& results_dir, const std::string& level, const std::string& name) {
  return results_dir / level / (name + ".toml");
}

void write_stored_result(const fs::path& results_dir, const StoredResult& r) {
  const fs::path path = stored_result_path(results_dir, r.level, r.name);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) throw io::WriteError(fmt::format("cannot create '{}': {}", path.parent_path().string(), ec.message()));
  io::write_file_atomic(path, stored_result_toml(r));
}

std::vector<StoredResult> read_stored_results(const fs::path& results_dir) {
  std::vector<fs::path> files;
  for (const char* level : {level_name(true), level_name(false)}) {
    std::error_code ec;
    if (!fs::is_directory(results_dir / level, ec)) continue;
    for (const auto& e : fs::directory_iterator(results_dir / level))
      if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<StoredResult> out;
  for (const auto& f : files) {
    StoredResult r = parse_stored_result(io::read_file(f), f.string());
    if (f.stem().string() != r.name || f.parent_path().filename().string() != r.level)
      throw std::runtime_error(fmt::format("{}: holds the {} result of '{}', not what its path says", f.string(),
                                           r.level, r.name));
    out.push_back(std::move(r));
  }
  return out;
}

fs::path default_results_dir() { return source_dir() / "validation" / "results"; }

std::vector<std::string> stale_lines(const StoredResult& r, std::size_t max_lines) {
  std::string now;
  try {
    now = resolved_case_toml(load_case(source_dir() / r.case_file, r.overrides));
  } catch (const std::exception& e) {
    return {fmt::format("the case no longer loads: {}", e.what())};
  }
  return resolved_case_differences(r.resolved_case, now, max_lines);
}

}  // namespace particula
