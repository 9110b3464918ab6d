// The generated docs/validation.md: stored results (record.hpp) written, read and made from run
// directories; the report (report.hpp) expanded from a template, its errors, its figures; and
// the repository's docs/validation.md being what its template and stored results give.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "cli_process.hpp"
#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/validation/record.hpp"
#include "particula/validation/report.hpp"

namespace fs = std::filesystem;
using cli_test::cli;
using cli_test::fresh_dir;
using cli_test::read_text;
using particula::StoredResult;
using particula::ValidationCheck;

namespace {

const fs::path kSource = PARTICULA_SOURCE_DIR;

ValidationCheck check(std::string quantity, double value, double error, bool pass, bool report_only = false) {
  ValidationCheck c;
  c.quantity = std::move(quantity);
  c.value = value;
  c.shown = std::to_string(value);
  c.reference = "ref | with a bar";
  c.tolerance = "< 1 %";
  c.pass = pass;
  c.report_only = report_only;
  c.error = error;
  return c;
}

StoredResult result(const std::string& name, const std::string& level, double d0, double error) {
  StoredResult r;
  r.name = name;
  r.group = "analytic";
  r.level = level;
  r.case_file = "cases/couette.toml";
  r.overrides = {"resolution.d0=" + std::to_string(d0)};
  r.d0 = d0;
  r.commit = "abc123";
  r.date = "2026-12-07";
  r.threads = 1;
  r.wall_seconds = 1234.5;
  r.status = "completed";
  r.steps = 124049;
  r.end_time = 1.5;
  r.guards = {{"surface_pushed", 12}, {"gap_squeezed", 0}};
  r.checks = {check("error of x", error, error, true), check("a report line", 3, std::nan(""), true, true)};
  r.resolved_case = "name = \"couette\"\n[resolution]\nd0 = 5e-05\n";
  r.plot.title = "A <title>";
  r.plot.x_label = "t (s)";
  r.plot.y_label = "y";
  r.plot.series = {{"", {0, 1, 2}, {0, 1, 4}, false}, {"exact", {0, 1, 2}, {0, 1.1, 3.9}, true}};
  return r;
}

std::vector<particula::ValidationEntry> two_entries() {
  std::vector<particula::ValidationEntry> v(2);
  v[0].name = "couette";
  v[0].case_file = "cases/couette.toml";
  v[1].name = "settling_pile";
  v[1].group = particula::ValidationGroup::Robustness;
  v[1].case_file = "cases/robustness/settling_pile.toml";
  return v;
}

/// Two SVG texts equal but for the last digit of a coordinate: the figure's pixel positions are
/// computed, and a build that fuses multiply-adds differently (-march=native or not) may round a
/// coordinate at .x5 the other way. Other numbers (tick labels) and the text between the numbers
/// must be identical.
bool same_figure(const std::string& a, const std::string& b) {
  static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?)");
  auto ia = std::sregex_iterator(a.begin(), a.end(), number), ib = std::sregex_iterator(b.begin(), b.end(), number);
  std::size_t pa = 0, pb = 0;
  for (const std::sregex_iterator end; ia != end || ib != end; ++ia, ++ib) {
    if (ia == end || ib == end) return false;
    if (a.compare(pa, ia->position() - pa, b, pb, ib->position() - pb) != 0) return false;
    const std::string x = ia->str(), y = ib->str();
    const auto pixel = [](const std::string& v) { return v.size() > 2 && v[v.size() - 2] == '.'; };  // "{:.1f}"
    if (x != y && !(pixel(x) && pixel(y) && std::abs(std::stod(x) - std::stod(y)) <= 0.11)) return false;
    pa = ia->position() + ia->length();
    pb = ib->position() + ib->length();
  }
  return a.compare(pa, std::string::npos, b, pb, std::string::npos) == 0;
}

}  // namespace

TEST(StoredResult, RoundTripsThroughItsTomlText) {
  const StoredResult r = result("couette", "quick", 5e-5, 2.75e-7);
  const std::string text = particula::stored_result_toml(r);
  const StoredResult back = particula::parse_stored_result(text, "x.toml");
  EXPECT_EQ(particula::stored_result_toml(back), text);
  EXPECT_EQ(back.d0, r.d0);
  EXPECT_EQ(back.steps, 124049);
  ASSERT_EQ(back.checks.size(), 2u);
  EXPECT_EQ(back.checks[0].error, 2.75e-7);
  EXPECT_TRUE(std::isnan(back.checks[1].error));
  EXPECT_TRUE(back.checks[1].report_only);
  ASSERT_EQ(back.plot.series.size(), 2u);
  EXPECT_TRUE(back.plot.series[1].reference);
  EXPECT_EQ(back.plot.series[0].y, (std::vector<double>{0, 1, 4}));
  EXPECT_EQ(back.resolved_case, r.resolved_case);
  EXPECT_TRUE(back.pass());
}

TEST(StoredResult, MalformedTextNamesTheFileAndTheKey) {
  std::string text = particula::stored_result_toml(result("couette", "quick", 5e-5, 1e-3));
  const std::string bad = std::regex_replace(text, std::regex(R"(\nd0 = [^\n]*)"), "\nd0 = \"fine\"");
  ASSERT_NE(bad, text);
  try {
    particula::parse_stored_result(bad, "results/quick/couette.toml");
    FAIL() << "accepted a string d0";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("results/quick/couette.toml: d0"), std::string::npos) << e.what();
  }
  const std::string level = std::regex_replace(text, std::regex(R"(level = "quick")"), "level = \"fine\"");
  EXPECT_THROW(particula::parse_stored_result(level, "x"), std::runtime_error);
  const std::string check = std::regex_replace(text, std::regex(R"(pass = true)"), "pass = 1");
  try {
    particula::parse_stored_result(check, "x.toml");
    FAIL() << "accepted a number for pass";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("check[0].pass"), std::string::npos) << e.what();
  }
}

TEST(Report, ObservedOrderIsTheSlopeOfTheErrorsBetweenTwoResolutions) {
  EXPECT_NEAR(particula::observed_order(4e-3, 2e-4, 1e-3, 1e-4), 2.0, 1e-12);
  EXPECT_NEAR(particula::observed_order(-8e-3, 2e-4, 1e-3, 1e-4), 3.0, 1e-12);  // signed errors: magnitudes
  EXPECT_TRUE(std::isnan(particula::observed_order(0, 2e-4, 1e-3, 1e-4)));
  EXPECT_TRUE(std::isnan(particula::observed_order(std::nan(""), 2e-4, 1e-3, 1e-4)));
  EXPECT_TRUE(std::isnan(particula::observed_order(4e-3, 1e-4, 1e-3, 1e-4)));
}

TEST(Report, ExpandsTheDirectivesWithTheStoredLevels) {
  const std::string tmpl = "# Title\n\n{{summary}}\n\n## Couette\n\nprose\n\n{{case couette}}\n\n{{group robustness}}\n";
  const std::vector<StoredResult> results = {result("couette", "quick", 2e-4, 4e-3),
                                             result("couette", "default", 1e-4, 1e-3)};
  const auto report = particula::generate_report(tmpl, "t.md", results, two_entries());
  const std::string& md = report.markdown;
  EXPECT_NE(md.find("# Title\n\n| case | group | quick | default |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `settling_pile` | robustness | not stored | not stored |"), std::string::npos) << md;
  EXPECT_NE(md.find("| quick | error of x |"), std::string::npos) << md;
  EXPECT_NE(md.find("ref / with a bar"), std::string::npos) << "a | in a cell breaks the table: " << md;
  EXPECT_NE(md.find("124 049 steps to t = 1.5 s, 1 235 s on 1 thread; guard events: surface_pushed 12."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("Measured 2026-12-07 at abc123"), std::string::npos) << md;
  EXPECT_NE(md.find("- error of x: 0.4 % to 0.1 %, order 2.00"), std::string::npos) << md;
  EXPECT_EQ(md.find("a report line: "), std::string::npos) << "no order for a check without an error: " << md;
  EXPECT_NE(md.find("![couette](validation/couette.svg)"), std::string::npos) << md;
  ASSERT_EQ(report.figures.size(), 1u);
  EXPECT_EQ(report.figures[0].first, "couette.svg");
  EXPECT_NE(md.find("| `settling_pile` | quick | not stored |"), std::string::npos) << md;
}

TEST(Report, RefusesAnUnknownDirectiveOrCaseAndACaseLeftOut) {
  const auto entries = two_entries();
  const auto message = [&](const std::string& tmpl) {
    try {
      particula::generate_report(tmpl, "t.md", {}, entries);
    } catch (const particula::ReportError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("x\n{{case nosuch}}\n{{case couette}}\n{{group robustness}}\n").find("t.md:2: {{case nosuch}}"),
            std::string::npos);
  EXPECT_NE(message("{{case couette}}\n{{group robustness}}\n{{plot couette}}\n").find("t.md:3: unknown directive"),
            std::string::npos);
  EXPECT_NE(message("{{case couette}}\n{{group nosuch}}\n").find("t.md:2: {{group nosuch}}"), std::string::npos);
  EXPECT_NE(message("{{case couette}}\n").find("'settling_pile' appears in no"), std::string::npos);
  const std::vector<StoredResult> orphan = {result("gone", "quick", 1e-4, 1e-3)};
  EXPECT_THROW(particula::generate_report("{{case couette}}\n{{group robustness}}\n", "t.md", orphan, entries),
               particula::ReportError);
}

TEST(Report, FiguresCompareToTheirLastDigit) {
  EXPECT_TRUE(same_figure("<line x1=\"12.3\" y=\"4\"/>", "<line x1=\"12.4\" y=\"4\"/>"));
  EXPECT_FALSE(same_figure("<line x1=\"12.3\" y=\"4\"/>", "<line x1=\"12.6\" y=\"4\"/>"));
  EXPECT_FALSE(same_figure("<line x1=\"12.3\"/>", "<circle x1=\"12.3\"/>"));
  EXPECT_FALSE(same_figure("<text>1e-05</text>", "<text>2e-05</text>"));
  EXPECT_FALSE(same_figure("a 1 2", "a 1"));
}

TEST(Report, SvgFigureDrawsRunsAsLinesAndFewPointsAsMarkers) {
  const StoredResult r = result("couette", "quick", 5e-5, 1e-3);
  const std::string svg = particula::svg_plot(r.plot);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_NE(svg.find("A &lt;title&gt;"), std::string::npos);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  std::size_t circles = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, 3u + 1u) << "three reference points and the legend's marker";
  EXPECT_EQ(particula::svg_plot(r.plot), svg) << "the same data give the same bytes";
}

TEST(Report, CombinedFigureLabelsEachLevelAndDrawsTheReferenceOnce) {
  const StoredResult q = result("couette", "quick", 2e-4, 4e-3), d = result("couette", "default", 1e-4, 1e-3);
  const auto plot = particula::combined_plot({&q, &d});
  ASSERT_EQ(plot.series.size(), 3u);
  EXPECT_EQ(plot.series[0].label, "quick (d0 = 0.0002 m)");
  EXPECT_EQ(plot.series[1].label, "default (d0 = 0.0001 m)");
  EXPECT_EQ(plot.series[2].label, "exact");
}

TEST(Report, StaleWhenTheCaseResolvesDifferentlyToday) {
  StoredResult r = result("couette", "quick", 5e-5, 1e-3);
  r.overrides = {};
  r.resolved_case = particula::resolved_case_toml(particula::load_case(kSource / "cases" / "couette.toml"));
  EXPECT_TRUE(particula::stale_lines(r).empty());
  r.resolved_case = std::regex_replace(r.resolved_case, std::regex("nu = 1e-06"), "nu = 2e-06");
  const auto lines = particula::stale_lines(r);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "- [fluid] nu = 2e-06");
  EXPECT_EQ(lines[1], "+ [fluid] nu = 1e-06");
}

TEST(Report, CheckRecordStoresARunAtItsLevelAndRefusesAnotherResolution) {
  const fs::path dir = fresh_dir("report_record");
  const fs::path run = dir / "couette", store = dir / "results";
  auto r = cli({"run", (kSource / "cases" / "couette.toml").string(), "--out", run.string(), "--quiet", "--no-plots",
                "--threads", "1", "--set", "time.end=0.02"});
  ASSERT_EQ(r.code, 0) << r.output;
  r = cli({"validate", "--check", run.string(), "--record", "--results", store.string()});
  EXPECT_EQ(r.code, 0) << r.output;
  const fs::path stored = store / "quick" / "couette.toml";
  ASSERT_TRUE(fs::exists(stored)) << r.output;
  const StoredResult s = particula::parse_stored_result(read_text(stored), stored.string());
  EXPECT_EQ(s.level, "quick");
  EXPECT_EQ(s.status, "completed");
  EXPECT_NEAR(s.end_time, 0.02, 1e-12);
  EXPECT_FALSE(s.checks.empty());
  ASSERT_FALSE(s.plot.series.empty()) << "the profile figure";
  EXPECT_TRUE(particula::stale_lines(s).empty()) << "a fresh result is current";
  // A run at a resolution of neither level: refused, nothing stored.
  const fs::path odd = dir / "odd";
  r = cli({"run", (kSource / "cases" / "couette.toml").string(), "--out", odd.string(), "--quiet", "--no-plots",
           "--threads", "1", "--set", "time.end=0.01", "--set", "resolution.d0=4e-5"});
  ASSERT_EQ(r.code, 0) << r.output;
  r = cli({"validate", "--check", odd.string(), "--record", "--results", (dir / "other").string()});
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("is neither level of couette"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "other"));
}

TEST(Report, TheRepositorysValidationPageIsWhatItsTemplateAndResultsGive) {
  const auto report = particula::generate_report(
      read_text(kSource / "validation" / "template.md"), "validation/template.md",
      particula::read_stored_results(kSource / "validation" / "results"), particula::validation_entries());
  EXPECT_TRUE(report.markdown == read_text(kSource / "docs" / "validation.md"))
      << "docs/validation.md differs from what `particula validate --report` writes: run it and commit the page";
  std::set<std::string> figures;
  for (const auto& [name, svg] : report.figures) {
    figures.insert(name);
    EXPECT_TRUE(same_figure(svg, read_text(kSource / "docs" / "validation" / name)))
        << name << " differs: run validate --report";
  }
  if (fs::is_directory(kSource / "docs" / "validation")) {
    for (const auto& e : fs::directory_iterator(kSource / "docs" / "validation"))
      EXPECT_TRUE(figures.count(e.path().filename().string())) << e.path() << " is linked from nowhere";
  }
}
