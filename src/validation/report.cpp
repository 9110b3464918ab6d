// `particula validate --report` (report.hpp): docs/validation.md from the template and the
// stored results.
#include "particula/validation/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "particula/io/atomic_file.hpp"
#include "particula/io/error.hpp"
#include "particula/run/runner.hpp"
#include "run_outcome.hpp"

namespace particula {

namespace fs = std::filesystem;

double observed_order(double e_coarse, double d0_coarse, double e_fine, double d0_fine) {
  if (!std::isfinite(e_coarse) || !std::isfinite(e_fine) || e_coarse == 0 || e_fine == 0) return std::nan("");
  if (!(d0_coarse > 0 && d0_fine > 0) || std::fabs(d0_coarse / d0_fine - 1) < 1e-9) return std::nan("");
  return std::log(std::fabs(e_coarse / e_fine)) / std::log(d0_coarse / d0_fine);
}

ValidationPlot combined_plot(const std::vector<const StoredResult*>& levels) {
  ValidationPlot out;
  std::set<std::string> references;
  for (const StoredResult* r : levels) {
    if (r->plot.series.empty()) continue;
    if (out.title.empty()) out.title = r->plot.title, out.x_label = r->plot.x_label, out.y_label = r->plot.y_label;
    for (const auto& s : r->plot.series) {
      if (s.reference) continue;
      PlotSeries run = s;
      run.label = fmt::format("{}{}{} (d0 = {:g} m)", r->level, s.label.empty() ? "" : ", ", s.label, r->d0);
      out.series.push_back(std::move(run));
    }
  }
  for (const StoredResult* r : levels)
    for (const auto& s : r->plot.series)
      if (s.reference && references.insert(s.label).second) out.series.push_back(s);
  return out;
}

namespace {

/// 124049 as "124 049".
std::string grouped(std::int64_t n) {
  std::string digits = std::to_string(n < 0 ? -n : n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ' ';
    out += digits[i];
  }
  return (n < 0 ? "-" : "") + out;
}

std::string table_cell(std::string s) {
  std::replace(s.begin(), s.end(), '|', '/');
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

std::string seconds(double s) { return s >= 10 ? fmt::format("{} s", grouped(std::llround(s))) : fmt::format("{:.2g} s", s); }

std::string verdict(const ValidationCheck& c) { return c.report_only ? "report" : c.pass ? "pass" : "**FAIL**"; }

/// The stored results by case and level.
class ResultIndex {
 public:
  explicit ResultIndex(const std::vector<StoredResult>& results) {
    for (const auto& r : results) by_[{r.name, r.level}] = &r;
  }
  const StoredResult* find(const std::string& name, const std::string& level) const {
    const auto it = by_.find({name, level});
    return it == by_.end() ? nullptr : it->second;
  }
  /// The stored levels of a case, quick first.
  std::vector<const StoredResult*> levels(const std::string& name) const {
    std::vector<const StoredResult*> v;
    for (const bool quick : {true, false})
      if (const StoredResult* r = find(name, level_name(quick))) v.push_back(r);
    return v;
  }

 private:
  std::map<std::pair<std::string, std::string>, const StoredResult*> by_;
};

/// "pass: 2.75e-05 %" (the first check that has a reference), "**FAIL**: quantity value", or
/// why the run did not complete; "(stale)" when the case changed since.
std::string summary_cell(const StoredResult* r) {
  if (!r) return "not stored";
  std::string cell;
  if (r->exit_code != 0) {
    cell = fmt::format("**FAIL**: exit {}{}", r->exit_code, r->failure.empty() ? "" : ", " + r->failure);
  } else if (r->pass()) {
    const auto it = std::find_if(r->checks.begin(), r->checks.end(), [](const ValidationCheck& c) { return !c.report_only; });
    cell = it == r->checks.end() ? "reported" : "pass: " + it->shown;
    if (it != r->checks.end() && std::isfinite(it->error) && it->shown.find('%') == std::string::npos)
      cell += fmt::format(" ({:+.2g} %)", 100 * it->error);
  } else {
    const auto it = std::find_if(r->checks.begin(), r->checks.end(), [](const ValidationCheck& c) { return !c.pass && !c.report_only; });
    cell = it == r->checks.end() ? "**FAIL**: no checks" : fmt::format("**FAIL**: {} {}", it->quantity, it->shown);
  }
  if (!stale_lines(*r).empty()) cell += " (stale)";
  return table_cell(cell);
}

std::string summary_table(const std::vector<ValidationEntry>& entries, const ResultIndex& index) {
  std::string md = "| case | group | quick | default |\n|---|---|---|---|\n";
  for (const auto& e : entries)
    md += fmt::format("| `{}` | {} | {} | {} |\n", e.name, group_name(e.group),
                      summary_cell(index.find(e.name, level_name(true))), summary_cell(index.find(e.name, level_name(false))));
  return md;
}

/// "completed (exit 0), 2 702 steps to t = 1.5 s, 0.64 s on 1 thread; guard events: none"
std::string run_text(const StoredResult& r) {
  std::string s = fmt::format("{} (exit {}){}, {} steps to t = {:g} s, {} on {} thread{}", r.status, r.exit_code,
                              r.failure.empty() ? "" : ": " + r.failure, grouped(r.steps), r.end_time,
                              seconds(r.wall_seconds), r.threads, r.threads == 1 ? "" : "s");
  return s + "; guard events: " + guards_text(r.guards);
}

std::string overrides_text(const StoredResult& r) {
  std::string s;
  for (const auto& o : r.overrides) s += fmt::format(" `--set {}`", o);
  return s.empty() ? " as shipped" : " with" + s;
}

std::string checks_table(const std::vector<const StoredResult*>& levels) {
  std::string md = "| level | quantity | value | reference | tolerance | result |\n|---|---|---|---|---|---|\n";
  for (const StoredResult* r : levels)
    for (const auto& c : r->checks)
      md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", r->level, table_cell(c.quantity), table_cell(c.shown),
                        table_cell(c.reference), table_cell(c.tolerance), verdict(c));
  return md;
}

/// The observed orders between the two levels, one line per check that has an error at both.
std::string orders_text(const StoredResult* quick, const StoredResult* fine) {
  if (!quick || !fine) return "";
  std::string lines;
  for (const auto& c : quick->checks)
    for (const auto& f : fine->checks)
      if (c.quantity == f.quantity) {
        const double p = observed_order(c.error, quick->d0, f.error, fine->d0);
        if (std::isfinite(p))
          lines += fmt::format("- {}: {:.3g} % to {:.3g} %, order {:.2f}\n", c.quantity, 100 * std::fabs(c.error),
                               100 * std::fabs(f.error), p);
      }
  if (lines.empty()) return "";
  return fmt::format("Observed order of convergence from quick to default (d0 = {:g} m to {:g} m), from the relative "
                     "error of each check with a numerical reference:\n\n{}\n",
                     quick->d0, fine->d0, lines);
}

std::string stale_text(const StoredResult& r) {
  const std::vector<std::string> lines = stale_lines(r);
  if (lines.empty()) return "";
  std::string s = fmt::format("**Stale** ({} level): the case resolves differently today than when it was measured; run "
                              "it again with `--record`. Differences:\n\n",
                              r.level);
  for (const auto& l : lines) s += "    " + l + "\n";
  return s + "\n";
}

std::string case_block(const ValidationEntry& e, const ResultIndex& index, const std::string& figure_dir,
                       GeneratedReport& out) {
  const std::vector<const StoredResult*> levels = index.levels(e.name);
  std::string md = fmt::format("    particula validate --case {} [--quick] [--record]\n\n", e.name);
  if (levels.empty()) return md + "Not stored at either level.\n";
  md += checks_table(levels) + "\n";
  for (const bool quick : {true, false}) {
    const StoredResult* r = index.find(e.name, level_name(quick));
    if (!r) {
      md += fmt::format("- **{}**: not stored.\n", level_name(quick));
      continue;
    }
    md += fmt::format("- **{}**: `{}`{} (d0 = {:g} m): {}. Measured {} at {}.\n", r->level, r->case_file,
                      overrides_text(*r), r->d0, run_text(*r), r->date, r->commit);
  }
  md += '\n';
  md += orders_text(index.find(e.name, level_name(true)), index.find(e.name, level_name(false)));
  const ValidationPlot plot = combined_plot(levels);
  if (!plot.series.empty()) {
    out.figures.emplace_back(e.name + ".svg", svg_plot(plot));
    md += fmt::format("![{}]({}/{}.svg)\n\n", e.name, figure_dir, e.name);
  }
  for (const StoredResult* r : levels) md += stale_text(*r);
  md.erase(md.find_last_not_of('\n') + 1);  // one line end, however the block ended
  return md + "\n";
}

std::string group_table(ValidationGroup g, const std::vector<ValidationEntry>& entries, const ResultIndex& index) {
  std::string md = "| case | level | result | run | checks | measured |\n|---|---|---|---|---|---|\n";
  for (const auto& e : entries) {
    if (e.group != g) continue;
    for (const bool quick : {true, false}) {
      const StoredResult* r = index.find(e.name, level_name(quick));
      if (!r) {
        md += fmt::format("| `{}` | {} | not stored | | | |\n", e.name, level_name(quick));
        continue;
      }
      std::string checks;
      for (const auto& c : r->checks)
        checks += fmt::format("{}{}: {} ({})", checks.empty() ? "" : "; ", c.quantity, c.shown, verdict(c));
      md += fmt::format("| `{}` | {} (d0 = {:g} m) | {} | {} | {} | {} at {} |\n", e.name, r->level, r->d0,
                        summary_cell(r), table_cell(run_text(*r)), table_cell(checks), r->date, r->commit);
    }
  }
  return md;
}

constexpr ValidationGroup kGroups[] = {ValidationGroup::Analytic, ValidationGroup::Paper, ValidationGroup::Benchmark,
                                       ValidationGroup::Robustness};

const ValidationEntry* find_entry(const std::vector<ValidationEntry>& entries, const std::string& name) {
  for (const auto& e : entries)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace

GeneratedReport generate_report(const std::string& template_text, const std::string& template_name,
                                const std::vector<StoredResult>& results, const std::vector<ValidationEntry>& entries,
                                const std::string& figure_dir) {
  const ResultIndex index(results);
  GeneratedReport out;
  std::set<std::string> documented;
  std::istringstream in(template_text);
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto fail = [&](const std::string& what) {
      throw ReportError(fmt::format("{}:{}: {}", template_name, line_no, what));
    };
    if (line.rfind("{{", 0) != 0) {
      out.markdown += line + "\n";
      continue;
    }
    if (line.size() < 4 || line.substr(line.size() - 2) != "}}") fail("a directive line must end with }}");
    const std::string body = line.substr(2, line.size() - 4);
    const std::size_t sp = body.find(' ');
    const std::string word = body.substr(0, sp), arg = sp == std::string::npos ? "" : body.substr(sp + 1);
    if (word == "summary" && arg.empty()) {
      out.markdown += summary_table(entries, index);
    } else if (word == "case") {
      const ValidationEntry* e = find_entry(entries, arg);
      if (!e) fail(fmt::format("{{{{case {}}}}}: no validation case of that name", arg));
      documented.insert(arg);
      out.markdown += case_block(*e, index, figure_dir, out);
    } else if (word == "group") {
      const ValidationGroup* group = nullptr;
      for (const ValidationGroup& g : kGroups)
        if (arg == group_name(g)) group = &g;
      if (!group) fail(fmt::format("{{{{group {}}}}}: no group of that name", arg));
      for (const auto& e : entries)
        if (e.group == *group) documented.insert(e.name);
      out.markdown += group_table(*group, entries, index);
    } else {
      fail(fmt::format("unknown directive '{}' (the directives are {{{{summary}}}}, {{{{case NAME}}}} and "
                       "{{{{group NAME}}}})",
                       line));
    }
  }
  for (const auto& e : entries)
    if (!documented.count(e.name))
      throw ReportError(fmt::format("{}: validation case '{}' appears in no {{{{case}}}} or {{{{group}}}} directive",
                                    template_name, e.name));
  for (const auto& r : results)
    if (!find_entry(entries, r.name))
      throw ReportError(fmt::format("a stored result of '{}' ({} level) names no validation case", r.name, r.level));
  return out;
}

int validate_report_command(const ReportOptions& opt) {
  const fs::path tmpl = opt.template_file.empty() ? source_dir() / "validation" / "template.md" : opt.template_file;
  const fs::path results_dir = opt.results_dir.empty() ? default_results_dir() : opt.results_dir;
  const fs::path doc = opt.doc.empty() ? source_dir() / "docs" / "validation.md" : opt.doc;
  GeneratedReport report;
  try {
    report = generate_report(io::read_file(tmpl), tmpl.string(), read_stored_results(results_dir), validation_entries());
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::runtime_error& e) {  // ReportError, a malformed stored result
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  try {
    const fs::path figures = doc.parent_path() / "validation";
    fs::create_directories(figures);
    for (const auto& [name, svg] : report.figures) io::write_file_atomic(figures / name, svg);
    io::write_file_atomic(doc, report.markdown);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return kExitIoFailure;
  }
  std::fprintf(stderr, "validate --report: %s and %zu figures written from %s\n", doc.string().c_str(),
               report.figures.size(), results_dir.string().c_str());
  return 0;
}

}  // namespace particula
