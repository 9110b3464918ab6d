// `particula validate`: runs the validation cases and compares each with its reference,
// writing DIR/report.md. The suite is a list of entries in four groups: the analytic cases, the
// paper's body cases (docs/method.md section 12, reference data in reference/), the benchmarks (the DFG
// flow past a cylinder, reference/schaefer_turek1996_dfg.csv) and the robustness
// cases (cases/robustness/: untuned cases at default numerics, checked for physical
// sanity rather than against a published curve); a new benchmark is one more entry in
// validation_entries(). `particula validate --check DIR` applies one entry's checks to an
// existing run directory. The validation module builds on the product (src/run and below), which
// never includes it.
#pragma once

#include <cmath>
#include <cstdint>
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
  /// A reported quantity without a pass/fail reference (e.g. the qualitative case 7.5): shown
  /// as "report" and never fails the case.
  bool report_only = false;
  /// The signed relative deviation from the reference where the check has a numerical one
  /// (value / reference - 1, or the error itself for an error norm); NaN otherwise. The
  /// observed order between two levels is computed from it (docs/validation.md).
  double error = std::nan("");
};

/// One curve of a validation plot: a run's time series or a reference's points.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool reference = false;  // published or exact data (drawn as points), else a run (a line)
};

/// The figure of a validation case: what the report draws for it (validation_plot.cpp).
struct ValidationPlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
};

/// The groups of `particula validate --group`.
enum class ValidationGroup { Analytic, Paper, Robustness, Benchmark, Random };

/// The group's name on the command line ("analytic", "paper", "robustness", "benchmark",
/// "random"). The random group has no entries: it is the batch of generated cases
/// (validate_random.cpp, run_random_batch).
const char* group_name(ValidationGroup g);

/// One validation case: a shipped case file run at the quick or the default level, and how to
/// judge the finished run directory.
struct ValidationEntry {
  std::string name;       // subdirectory of the validation output and report row
  ValidationGroup group = ValidationGroup::Analytic;
  std::string case_file;  // relative to the source tree, e.g. "cases/couette.toml"
  std::vector<std::string> overrides;  // extra --set for both modes
  /// The checks of a finished run (directory and resolved case). May throw io::IoError when an
  /// output is missing or malformed (the case then fails).
  std::function<std::vector<ValidationCheck>(const std::filesystem::path& run_dir, const Case& c)> evaluate;
  /// The case's figure from a finished run (the run's curves and the reference's); empty (no
  /// function) for a case without one. May throw io::IoError like `evaluate`.
  std::function<ValidationPlot(const std::filesystem::path& run_dir, const Case& c)> plot;
  /// How the two modes choose the level. Analytic cases (false): --quick runs the shipped
  /// resolution, the default twice as fine. Paper cases (true): the default runs the case file
  /// as shipped (the paper's resolution: hours), --quick adds `quick_overrides` (a coarse
  /// level, possibly an earlier end).
  /// Robustness cases use the analytic rule (--quick: the shipped, coarse level; default: twice
  /// as fine) unless `fine_overrides` is given: then the default adds these instead of halving
  /// d0 (for a case whose geometry is tied to d0, e.g. a gap of 0.1 d0).
  bool paper = false;
  std::vector<std::string> quick_overrides;
  std::vector<std::string> fine_overrides;
};

/// The validation suite, in report order.
std::vector<ValidationEntry> validation_entries();

// Checks used by the entries (exposed for tests and future entries).
/// `profile_error` of summary.json (fluid particles against the case's exact solution) < `limit`.
std::vector<ValidationCheck> check_profile_error(const std::filesystem::path& run_dir, double limit);
/// Spin-up in a circular container (validate_spin_up.cpp): the torque of the fluid on the
/// container (walls.csv) against the exact series at every output time with 0.02 s <= t <= 0.15 s
/// (while the torque is above 5 % of its value at 0.01 s), worst relative error within
/// `torque_tol`; and the velocity profile error of summary.json below `profile_limit`.
std::vector<ValidationCheck> check_spin_up(const std::filesystem::path& run_dir, const Case& c, double torque_tol,
                                           double profile_limit);
/// Taylor-Green: peak fluid speed of the last snapshot over the initial amplitude against
/// exp(-8 pi^2 nu t / L^2), within `rel_tol`.
std::vector<ValidationCheck> check_taylor_green_decay(const std::filesystem::path& run_dir, const Case& c,
                                                      double rel_tol);
/// Hydrostatic box: mean pressure of the bottom wall particles of the last snapshot against
/// p0 + rho g H within `rel_tol`, and peak fluid speed below `speed_frac` sqrt(g H).
std::vector<ValidationCheck> check_hydrostatic(const std::filesystem::path& run_dir, const Case& c, double rel_tol,
                                               double speed_frac);

// Checks of the paper's body cases, on bodies.csv of the run (body = index in the case's
// [[body]] list) against the curves of reference/ (see reference/README.md for the tolerances).
// Tolerances that depend on the level are tight at the paper's resolution (`c.d0` at most the
// shipped d0 of the case) and looser at coarser levels.

/// 7.2 falling cylinder: peak settling speed (and its time) against Glowinski's 0.0554 m/s, time
/// to 95 % of the run's own peak speed against 0.23 s, centre height against Zhang et al. 2019 where the run covers it.
std::vector<ValidationCheck> check_settling_cylinder(const std::filesystem::path& run_dir, const Case& c);
/// 7.1 shear migration: |y - H/2| at the end against Feng & Michaelides 2002 at the same time,
/// the trajectory y(t) for 5 s <= t <= 40 s, and the rotation rate at the end.
std::vector<ValidationCheck> check_shear_migration(const std::filesystem::path& run_dir, const Case& c);
/// 7.3 two cylinders in shear: the free cylinder's most negative vx and its time against the
/// paper's curve, and its largest |y - H/2| (it stays on the centreline).
std::vector<ValidationCheck> check_two_cylinders(const std::filesystem::path& run_dir, const Case& c);
/// 7.4 drafting-kissing-tumbling: the time the two centres are level (tumbling) against the
/// paper's window, the peak fall speed, and the drafting and kissing times (reported).
std::vector<ValidationCheck> check_dkt(const std::filesystem::path& run_dir, const Case& c);
/// 7.5 ellipse past an obstacle: the trajectory (tilt, drift, turn back, peak Re) as report
/// lines; the paper's description is qualitative, so nothing here fails.
std::vector<ValidationCheck> check_ellipse_obstacle(const std::filesystem::path& run_dir, const Case& c);

// Open boundaries (validate_open.cpp).
/// Poiseuille flow from an inlet to an outlet: the profile probe's last rows against the
/// inflow's parabola (RMS < 1 % of the peak), the flow rate through it (1 %), dp/dx along the
/// centre line over the middle 60 % (3 %), and the fluid mass against the fluxes (1e-12).
std::vector<ValidationCheck> check_poiseuille_open(const std::filesystem::path& run_dir, const Case& c);
/// DFG 2D-1: C_D and the pressure difference across the cylinder (means over the last third of
/// the run) against reference/schaefer_turek1996_dfg.csv, C_L reported, the mass balance.
std::vector<ValidationCheck> check_dfg_2d1(const std::filesystem::path& run_dir, const Case& c);
/// DFG 2D-2: the Strouhal number from the upward zero crossings of C_L over the second half of
/// the run, and the largest C_D and C_L of a fit with three harmonics of that frequency, against
/// the published ranges; the mass balance.
std::vector<ValidationCheck> check_dfg_2d2(const std::filesystem::path& run_dir, const Case& c);
/// The entries of the open-boundary cases (poiseuille_open: analytic; dfg_2d1, dfg_2d2: benchmark).
std::vector<ValidationEntry> open_boundary_entries();
/// The fluid mass against the fluxes of open_boundaries.csv: at each output time M(t) - M(0) less
/// the net inflow plus the net outflow, the largest over the run relative to M(0) (< 1e-12).
ValidationCheck open_mass_balance_check(const std::filesystem::path& run_dir, const Case& c);

struct ValidateOptions {
  bool quick = false;  // analytic cases at the shipped resolution, paper cases coarse; default:
                       // analytic cases twice as fine, paper cases at the paper's resolution
  std::filesystem::path out_dir = "runs/validate";
  int threads = 0;
  bool quiet = false;
  std::vector<std::string> only;  // run only these entries (empty: all of the selected groups)
  /// --set overrides applied to every case after its level's own (e.g. to try a numerics value
  /// on the whole suite); written into the report.
  std::vector<std::string> sets;
  /// The groups to run (empty: analytic, paper and benchmark, the suite before the robustness group was
  /// added; robustness cases are run only when asked for, by group or by --case).
  std::vector<ValidationGroup> groups;
  /// Store each case's result (validation/record.hpp) under `results_dir`/LEVEL/NAME.toml, the
  /// data `particula validate --report` generates docs/validation.md from.
  bool record = false;
  std::filesystem::path results_dir;  // empty: validation/results of the source tree
  /// The random group: this many seeds (0: 200, or 40 with --quick) from `random_first`.
  int random_seeds = 0;
  int random_first = 1;
};

/// The random group: the cases of `particula generate` for N seeds from the first (ValidateOptions), each
/// written to OUT/random/seed_N.toml and run to its end in OUT/random/seed_N. A case refused at
/// load is counted, not failed; the batch passes when no run ends with exit 3 (or any code but
/// 0) and no run's time step falls below kTimeStepDrop of its case's own. `markdown` is the
/// report's section: the counts (generated, refused, finished, exit 3, the smallest step ratio)
/// and a row per seed.
struct RandomBatch {
  int generated = 0, refused = 0, finished = 0, failed = 0, collapsed = 0;
  double smallest_ratio = 1e300;
  std::uint64_t smallest_seed = 0;
  bool interrupted = false;
  std::string markdown;
  bool pass() const { return failed == 0 && collapsed == 0 && !interrupted; }
};
RandomBatch run_random_batch(const ValidateOptions& opt);

/// The two levels of the suite, as named in stored results and in docs/validation.md.
inline const char* level_name(bool quick) { return quick ? "quick" : "default"; }

/// The --set overrides that run `entry` at the quick or the default level (the rules of
/// ValidationEntry), and the d0 they give. Throws what load_case throws.
std::vector<std::string> level_overrides(const ValidationEntry& entry, bool quick, double& d0);

/// Whether `entry` is run under `options` (its group is selected, or it is named by --case).
bool entry_selected(const ValidationEntry& entry, const ValidateOptions& options);

/// Runs the suite into out_dir/<name>, writes out_dir/report.md; exit 0 when every check
/// passes, 3 when one fails, 2 on bad input (e.g. an unwritable directory), 130 when interrupted.
/// Every run's outcome is reported (status, exit code, the failure message of an exit 3, steps,
/// the guard counters of summary.json); the checks of a run that stopped early are evaluated on
/// what it wrote, but the case fails.
int validate_command(const ValidateOptions& options);

/// `particula validate --check DIR [--case NAME]`: the checks of validation entry NAME (default:
/// the entry named as the run's case, case.toml's `name`) on the existing run directory DIR,
/// printed to standard output with their values, references, tolerances and verdicts. Exit 0
/// when every check passes, 1 when one fails, 2 on bad input (DIR not a run directory, an
/// unknown NAME, a case with no entry, outputs the checks cannot read: the message names DIR).
/// With `record`, the result is then stored under `results_dir` (empty: the source tree's
/// validation/results) at the level whose resolution the run has (exit 2, nothing stored, when
/// it has neither level's d0).
int validate_check_command(const std::filesystem::path& run_dir, const std::string& case_name, bool record = false,
                           const std::filesystem::path& results_dir = {});

/// The source tree the suite reads its case files and references from (cases/, reference/).
const std::filesystem::path& source_dir();

}  // namespace particula
