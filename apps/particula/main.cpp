// particula: command-line program (design.md, command-line contract).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "particula/case/schema.hpp"
#include "particula/io/error.hpp"
#include "particula/run/info.hpp"
#include "particula/run/limits.hpp"
#include "particula/run/plots.hpp"
#include "particula/run/runner.hpp"
#include "particula/run/version.hpp"
#include "particula/validation/random_case.hpp"
#include "particula/validation/report.hpp"
#include "particula/validation/validate.hpp"

namespace {

/// The --help footer of a command: examples, then where case files are documented.
std::string footer(const std::string& examples) {
  return "Examples:\n" + examples +
         "\nCase files: every key, its unit, default and range in docs/case-files.md; the README lists the "
         "outputs and exit codes.";
}

// ---- the commands and their options ----------------------------------------------------------

struct RunArgs {
  particula::RunOptions opt;
  std::string case_file;
  bool no_plots = false;
};

CLI::App* add_run(CLI::App& app, RunArgs& a) {
  auto* run = app.add_subcommand("run", "Run a case file and write its run directory");
  run->add_option("case", a.case_file, "Case file (TOML)")->required();
  run->add_option("--out", a.opt.out_dir, "Run directory (default runs/<case name>)");
  run->add_option("--set", a.opt.overrides, "Override a case key, e.g. --set resolution.d0=5e-5 (repeatable)");
  run->add_option("--threads", a.opt.threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, particula::kMaxThreads));
  run->add_option("--backend", a.opt.backend, "Compute backend: cpu (OpenMP) or cuda (GPU; needs a CUDA build)")
      ->check(CLI::IsMember({"cpu", "cuda"}));
  run->add_flag("--quiet", a.opt.quiet, "No progress line");
  run->add_flag("--no-plots", a.no_plots, "Do not draw plots at the end of the run");
  run->add_flag("--overwrite", a.opt.overwrite, "Replace an existing run directory");
  run->footer(footer("  particula run cases/couette.toml\n"
                     "  particula run cases/falling_cylinder.toml --out runs/demo --set resolution.d0=2.5e-4 "
                     "--set time.end=0.5"));
  return run;
}

struct ResumeArgs {
  particula::ResumeOptions opt;
  bool no_plots = false;
};

CLI::App* add_resume(CLI::App& app, ResumeArgs& a) {
  auto* resume = app.add_subcommand(
      "resume", "Continue a run from its checkpoint (DIR/checkpoint/state.bin), appending to its outputs");
  resume->add_option("dir", a.opt.run_dir, "Run directory")->required();
  resume->add_option("--set", a.opt.overrides,
                     "Override time.end or an output.* key, e.g. --set time.end=3 (repeatable)");
  resume->add_option("--threads", a.opt.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, particula::kMaxThreads));
  resume->add_option("--backend", a.opt.backend, "Compute backend: cpu or cuda")
      ->check(CLI::IsMember({"cpu", "cuda"}));
  resume->add_flag("--quiet", a.opt.quiet, "No progress line");
  resume->add_flag("--no-plots", a.no_plots, "Do not draw plots at the end of the run");
  resume->footer(footer("  particula resume runs/demo                      (after Ctrl-C or an I/O failure)\n"
                        "  particula resume runs/demo --set time.end=1     (continue a finished run)"));
  return resume;
}

struct InfoArgs {
  std::string case_file;
  std::vector<std::string> overrides;
  bool no_timing = false;
};

CLI::App* add_info(CLI::App& app, InfoArgs& a) {
  auto* info = app.add_subcommand("info", "Particle counts, time step, steps, memory and wall-time estimate of a case");
  info->add_option("case", a.case_file, "Case file (TOML)")->required();
  info->add_option("--set", a.overrides, "Override a case key (repeatable)");
  info->add_flag("--no-timing", a.no_timing, "Do not time a few steps (no wall-time estimate)");
  info->footer(footer("  particula info cases/dkt.toml --set resolution.d0=2e-4"));
  return info;
}

struct ValidateArgs {
  particula::ValidateOptions opt;
  std::vector<std::string> groups;
  std::string check_dir;  // --check: evaluate this run directory instead of running the suite
  bool report = false;    // --report: generate docs/validation.md from the stored results
  particula::ReportOptions report_opt;
};

CLI::App* add_validate(CLI::App& app, ValidateArgs& a) {
  auto* validate = app.add_subcommand(
      "validate",
      "Run the validation cases (exact solutions, the paper's five body cases and the DFG benchmark; the robustness "
      "cases with --group robustness) against their references and write DIR/report.md (exit 3 on a fail); with "
      "--check, apply one case's checks to an existing run directory (exit 1 on a fail)");
  auto* quick = validate->add_flag("--quick", a.opt.quick,
                                   "Analytic and robustness cases at the shipped resolution (else twice as fine); "
                                   "paper and benchmark cases at a coarse level (else as shipped)");
  auto* out = validate->add_option("--out", a.opt.out_dir, "Output directory (default runs/validate)");
  auto* threads = validate->add_option("--threads", a.opt.threads, "OpenMP threads (default: all cores)")
                      ->check(CLI::Range(1, particula::kMaxThreads));
  auto* sets = validate->add_option("--set", a.opt.sets,
                                    "Override a case key in every validation case, after its level's own overrides, "
                                    "e.g. --set numerics.shifting_beta=0.02 (repeatable)");
  validate->add_option("--case", a.opt.only,
                       "Run only this validation case, of any group (repeatable); with --check: whose checks to apply");
  auto* groups = validate->add_option("--group", a.groups,
                                      "Run only this group: analytic, paper, benchmark, robustness or random (repeatable; "
                                      "default: analytic, paper and benchmark, the robustness and random cases only when "
                                      "asked for). random: the cases of `particula generate` for seeds 1 to --seeds, each "
                                      "run to its end")
                     ->check(CLI::IsMember({"analytic", "paper", "benchmark", "robustness", "random"}));
  auto* seeds = validate->add_option("--seeds", a.opt.random_seeds,
                                     "With --group random: how many seeds (default 200; 40 with --quick)")
                    ->check(CLI::Range(1, 1000000));
  auto* first_seed = validate->add_option("--first-seed", a.opt.random_first,
                                          "With --group random: the first seed (default 1; to split a batch across "
                                          "processes)")
                         ->check(CLI::Range(1, 1000000000));
  auto* quiet = validate->add_flag("--quiet", a.opt.quiet, "Only the final line");
  validate->add_option("--check", a.check_dir,
                       "Run nothing: apply the checks of the run's validation case (or of --case NAME) to the existing "
                       "run directory DIR and print each with its value, tolerance and verdict (exit 0: all pass, "
                       "1: a check fails, 2: bad input)")
      ->excludes(quick)
      ->excludes(out)
      ->excludes(threads)
      ->excludes(sets)
      ->excludes(groups)
      ->excludes(seeds)
      ->excludes(first_seed)
      ->excludes(quiet);
  auto* record = validate->add_flag("--record", a.opt.record,
                                    "Store each case's result (checks, outcome, figure data) under validation/results "
                                    "of the source tree (or --results DIR), the data --report generates "
                                    "docs/validation.md from; with --check, store the checked run at its level");
  auto* results = validate->add_option("--results", a.opt.results_dir,
                                       "Where --record stores and --report reads results (default: validation/results "
                                       "of the source tree)");
  auto* report = validate->add_flag("--report", a.report,
                                    "Run nothing: write docs/validation.md (or --doc FILE) and its figures from the "
                                    "stored results and validation/template.md");
  auto* doc = validate->add_option("--doc", a.report_opt.doc, "With --report: the Markdown file to write");
  auto* tmpl = validate->add_option("--template", a.report_opt.template_file, "With --report: the template to expand");
  report->excludes(quick)->excludes(out)->excludes(threads)->excludes(sets)->excludes(groups)->excludes(record);
  doc->needs(report);
  tmpl->needs(report);
  (void)results;
  validate->footer(footer("  particula validate --quick --out runs/validate\n"
                          "  particula validate --case couette --case falling_cylinder --quick\n"
                          "  particula validate --group robustness --quick\n"
                          "  particula validate --group random --seeds 200 --out runs/random\n"
                          "  particula validate --check runs/validate/dkt\n"
                          "  particula validate --check runs/pile --case settling_pile\n"
                          "  particula validate --case dkt --quick --record && particula validate --report\n"
                          "An unknown --case name lists the valid names."));
  return validate;
}

int validate(ValidateArgs& a) {
  if (a.report) {
    if (!a.check_dir.empty() || !a.opt.only.empty()) {
      std::fprintf(stderr, "error: validate --report runs nothing: it takes no --check or --case\n");
      return 2;
    }
    a.report_opt.results_dir = a.opt.results_dir;
    return particula::validate_report_command(a.report_opt);
  }
  if (!a.check_dir.empty()) {
    if (a.opt.only.size() > 1) {
      std::fprintf(stderr, "error: validate --check takes at most one --case\n");
      return 2;
    }
    return particula::validate_check_command(a.check_dir, a.opt.only.empty() ? "" : a.opt.only.front(), a.opt.record,
                                             a.opt.results_dir);
  }
  for (const auto& g : a.groups)
    a.opt.groups.push_back(g == "analytic"    ? particula::ValidationGroup::Analytic
                           : g == "paper"     ? particula::ValidationGroup::Paper
                           : g == "benchmark" ? particula::ValidationGroup::Benchmark
                           : g == "random"    ? particula::ValidationGroup::Random
                                              : particula::ValidationGroup::Robustness);
  return particula::validate_command(a.opt);
}

struct GenerateArgs {
  std::uint64_t seed = 0;
  std::string out;
};

CLI::App* add_generate(CLI::App& app, GenerateArgs& a) {
  auto* generate = app.add_subcommand(
      "generate", "Write a random valid case file from a seed (bodies of every shape and motion in one of eight kinds of container; for robustness tests)");
  generate->add_option("--seed", a.seed, "Seed of the random case (the same seed gives the same file)")->required();
  generate->add_option("--out", a.out, "Case file to write (default: standard output)");
  generate->footer(footer("  particula generate --seed 7 --out seed7.toml && particula run seed7.toml"));
  return generate;
}

CLI::App* add_schema(CLI::App& app, bool& json) {
  auto* schema = app.add_subcommand(
      "schema", "Print the case-file schema: the key reference (markdown, = docs/case-files.md) or, with --json, a "
                "JSON Schema for editors");
  schema->add_flag("--json", json,
                   "A JSON Schema (draft-07) of case files: types, units, defaults, ranges, choices, required keys");
  schema->footer(footer("  particula schema --json > particula-case.schema.json\n"
                        "  (Even Better TOML / taplo: .taplo.toml associates cases/**/*.toml with "
                        "docs/case.schema.json)"));
  return schema;
}

/// Exit code 2 with the reason when a command that computes would run with OpenMP's default
/// team (no --threads) and OMP_NUM_THREADS asks for a count outside [1, kMaxThreads].
int check_default_threads(int threads) {
  if (threads > 0) return 0;
  const std::string why = particula::default_threads_problem();
  if (why.empty()) return 0;
  std::fprintf(stderr, "error: %s\n", why.c_str());
  return 2;
}

int print_schema(bool json) {
  const std::string text = json ? particula::case_json_schema() : particula::case_reference_markdown();
  std::fwrite(text.data(), 1, text.size(), stdout);
  return std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : particula::kExitIoFailure;
}

struct PlotArgs {
  std::string dir;
  std::string format = "png";
};

CLI::App* add_plot(CLI::App& app, PlotArgs& a) {
  auto* plot = app.add_subcommand("plot", "(Re)draw the plots of a run directory into DIR/plots (tools/plot_run.py)");
  plot->add_option("dir", a.dir, "Run directory")->required();
  plot->add_option("--format", a.format, "Image format: png (default), svg or pdf")
      ->check(CLI::IsMember(particula::plot_formats()));
  plot->footer(footer("  particula plot runs/demo\n  particula plot runs/demo --format svg"));
  return plot;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"particula: rigid bodies in viscous flow, weakly compressible SPH (Hashemi, Fatehi & Manzari 2012)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", particula::version_line(), "Print the version and git commit, then exit");
  app.footer(footer("  particula run cases/couette.toml --out runs/couette --set resolution.d0=2.5e-5\n"
                    "  particula info cases/falling_cylinder.toml\n"
                    "  particula COMMAND --help"));
  RunArgs run_args;
  ResumeArgs resume_args;
  InfoArgs info_args;
  ValidateArgs validate_args;
  GenerateArgs generate_args;
  bool schema_json = false;
  PlotArgs plot_args;
  auto* run = add_run(app, run_args);
  auto* resume = add_resume(app, resume_args);
  auto* info = add_info(app, info_args);
  auto* validate_cmd = add_validate(app, validate_args);
  auto* generate = add_generate(app, generate_args);
  auto* schema = add_schema(app, schema_json);
  auto* plot = add_plot(app, plot_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    run_args.opt.plots = !run_args.no_plots;
    resume_args.opt.plots = !resume_args.no_plots;
    const int threads = *run ? run_args.opt.threads : *resume ? resume_args.opt.threads
                                                  : *validate_cmd ? validate_args.opt.threads : 0;
    if (*run || *resume || *info || (*validate_cmd && validate_args.check_dir.empty()))
      if (const int code = check_default_threads(threads)) return code;
    if (*run) return particula::run_command(run_args.case_file, run_args.opt);
    if (*resume) return particula::resume_command(resume_args.opt);
    if (*info) return particula::info_command(info_args.case_file, info_args.overrides, !info_args.no_timing);
    if (*validate_cmd) return validate(validate_args);
    if (*generate) return particula::generate_command(generate_args.seed, generate_args.out);
    if (*plot) return particula::plot_command(plot_args.dir, plot_args.format);
    if (*schema) return print_schema(schema_json);
  } catch (const particula::io::WriteError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return particula::kExitIoFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 1;
}
