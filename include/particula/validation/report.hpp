// `particula validate --report`: docs/validation.md generated from the stored results
// (record.hpp) and a template of prose (validation/template.md). The template is Markdown in
// which a line holding only a directive is replaced by what the stored results say:
//
//   {{summary}}        a table of every validation case: its verdict and headline number per level
//   {{case NAME}}      the case's command, its checks at each stored level, how each run ended,
//                      where and when it was measured, the observed order between the levels,
//                      and its figure (docs/validation/NAME.svg)
//   {{group NAME}}     a compact table of every case of a group (the robustness cases)
//
// Every validation case must appear in a {{case}} or {{group}} directive, so that a new case
// cannot be left out of the documentation; a result whose case or defaults have changed since
// it was measured is marked stale with the lines that differ.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "particula/validation/record.hpp"

namespace particula {

/// A template that cannot be expanded (an unknown directive or case, a case left out);
/// what() names the template and its line.
class ReportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GeneratedReport {
  std::string markdown;
  /// The figures the Markdown links to: (file name, SVG text), e.g. ("couette.svg", "<svg ...").
  std::vector<std::pair<std::string, std::string>> figures;
};

/// Expands `template_text` (named `template_name` in errors) with `results` for the suite's
/// `entries`; figures are linked as `figure_dir`/NAME.svg. Throws ReportError.
GeneratedReport generate_report(const std::string& template_text, const std::string& template_name,
                                const std::vector<StoredResult>& results, const std::vector<ValidationEntry>& entries,
                                const std::string& figure_dir = "validation");

/// The SVG text of a figure (svg_plot.cpp): the curves of runs as lines, exact solutions as
/// dashed lines, published points as markers, a legend.
std::string svg_plot(const ValidationPlot& plot);

/// The figure of a case across its stored levels: each level's run curves (labelled with the
/// level and d0) and the reference curves once.
ValidationPlot combined_plot(const std::vector<const StoredResult*>& levels);

/// The observed order of convergence between two levels' errors: log(e_coarse / e_fine) /
/// log(d0_coarse / d0_fine); NaN when either error is not finite or zero, or the d0 are equal.
double observed_order(double e_coarse, double d0_coarse, double e_fine, double d0_fine);

struct ReportOptions {
  std::filesystem::path template_file;  // empty: validation/template.md of the source tree
  std::filesystem::path results_dir;    // empty: validation/results of the source tree
  std::filesystem::path doc;            // empty: docs/validation.md of the source tree
};

/// Writes `doc` and its figures (into the directory `validation/` next to it). Exit 0, 2 on a bad template or a malformed stored result
/// (the message names the file), 4 when a file cannot be written.
int validate_report_command(const ReportOptions& options);

}  // namespace particula
