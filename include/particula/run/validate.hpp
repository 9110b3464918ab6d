// `particula validate`: runs the validation cases and compares each with its reference,
// writing DIR/report.md. The suite is a list of entries; a new benchmark (e.g. a body case of
// the paper with reference data) is one more entry in validation_entries().
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "particula/case/case.hpp"

namespace particula {

/// One compared quantity of a validation case.
struct ValidationCheck {
  std::string quantity;   // what is compared, e.g. "bottom pressure / (rho g H)"
  double value = 0;       // the run's value
  std::string shown;      // the value as printed in the report
  std::string reference;  // the reference as printed, e.g. "0.6738 = exp(-8 pi^2 t/Re)"
  std::string tolerance;  // e.g. "< 1 %"
  bool pass = false;
};

/// One validation case: a shipped case file run at the quick (shipped) or the default (twice
/// as fine) resolution, and how to judge the finished run directory.
struct ValidationEntry {
  std::string name;       // subdirectory of the validation output and report row
  std::string case_file;  // relative to the source tree, e.g. "cases/couette.toml"
  std::vector<std::string> overrides;  // extra --set for both modes
  /// The checks of a finished run (directory and resolved case). May throw io::IoError when an
  /// output is missing or malformed (the case then fails).
  std::function<std::vector<ValidationCheck>(const std::filesystem::path& run_dir, const Case& c)> evaluate;
};

/// The validation suite, in report order.
std::vector<ValidationEntry> validation_entries();

// Checks used by the entries (exposed for tests and future entries).
/// `profile_error` of summary.json (fluid particles against the case's exact solution) < `limit`.
std::vector<ValidationCheck> check_profile_error(const std::filesystem::path& run_dir, double limit);
/// Taylor-Green: peak fluid speed of the last snapshot over the initial amplitude against
/// exp(-8 pi^2 nu t / L^2), within `rel_tol`.
std::vector<ValidationCheck> check_taylor_green_decay(const std::filesystem::path& run_dir, const Case& c,
                                                      double rel_tol);
/// Hydrostatic box: mean pressure of the bottom wall particles of the last snapshot against
/// p0 + rho g H within `rel_tol`, and peak fluid speed below `speed_frac` sqrt(g H).
std::vector<ValidationCheck> check_hydrostatic(const std::filesystem::path& run_dir, const Case& c, double rel_tol,
                                               double speed_frac);

struct ValidateOptions {
  bool quick = false;  // shipped resolution; default: twice as fine (resolution.d0 halved)
  std::filesystem::path out_dir = "runs/validate";
  int threads = 0;
  bool quiet = false;
  std::vector<std::string> only;  // run only these entries (empty: all)
};

/// Runs the suite into out_dir/<name>, writes out_dir/report.md; exit 0 when every check
/// passes, 3 when one fails, 2 on bad input (e.g. an unwritable directory), 130 when interrupted.
int validate_command(const ValidateOptions& options);

}  // namespace particula
