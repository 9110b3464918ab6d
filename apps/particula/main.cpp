// particula: command-line program (design.md, command-line contract).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <exception>

#include "particula/case/schema.hpp"
#include "particula/io/error.hpp"
#include "particula/run/info.hpp"
#include "particula/run/plots.hpp"
#include "particula/run/runner.hpp"
#include "particula/run/version.hpp"
#include "particula/validation/random_case.hpp"
#include "particula/validation/validate.hpp"

namespace {

/// The --help footer of a command: examples, then where case files are documented.
std::string footer(const std::string& examples) {
  return "Examples:\n" + examples +
         "\nCase files: every key, its unit, default and range in docs/case-files.md; the README lists the "
         "outputs and exit codes.";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"particula: rigid bodies in viscous flow, weakly compressible SPH (Hashemi, Fatehi & Manzari 2012)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", particula::version_line(), "Print the version and git commit, then exit");
  app.footer(footer("  particula run cases/couette.toml --out runs/couette --set resolution.d0=2.5e-5\n"
                    "  particula info cases/falling_cylinder.toml\n"
                    "  particula COMMAND --help"));

  particula::RunOptions run_opt;
  std::string run_case;
  bool no_plots = false;
  auto* run = app.add_subcommand("run", "Run a case file and write its run directory");
  run->add_option("case", run_case, "Case file (TOML)")->required();
  run->add_option("--out", run_opt.out_dir, "Run directory (default runs/<case name>)");
  run->add_option("--set", run_opt.overrides, "Override a case key, e.g. --set resolution.d0=5e-5 (repeatable)");
  run->add_option("--threads", run_opt.threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 4096));
  run->add_option("--backend", run_opt.backend, "Compute backend: cpu (OpenMP) or cuda (GPU; needs a CUDA build)")
      ->check(CLI::IsMember({"cpu", "cuda"}));
  run->add_flag("--quiet", run_opt.quiet, "No progress line");
  run->add_flag("--no-plots", no_plots, "Do not draw plots at the end of the run");
  run->add_flag("--overwrite", run_opt.overwrite, "Replace an existing run directory");
  run->footer(footer("  particula run cases/couette.toml\n"
                     "  particula run cases/falling_cylinder.toml --out runs/demo --set resolution.d0=2.5e-4 "
                     "--set time.end=0.5"));

  particula::ResumeOptions resume_opt;
  bool resume_no_plots = false;
  auto* resume = app.add_subcommand(
      "resume", "Continue a run from its checkpoint (DIR/checkpoint/state.bin), appending to its outputs");
  resume->add_option("dir", resume_opt.run_dir, "Run directory")->required();
  resume->add_option("--set", resume_opt.overrides,
                     "Override time.end or an output.* key, e.g. --set time.end=3 (repeatable)");
  resume->add_option("--threads", resume_opt.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  resume->add_option("--backend", resume_opt.backend, "Compute backend: cpu or cuda")
      ->check(CLI::IsMember({"cpu", "cuda"}));
  resume->add_flag("--quiet", resume_opt.quiet, "No progress line");
  resume->add_flag("--no-plots", resume_no_plots, "Do not draw plots at the end of the run");
  resume->footer(footer("  particula resume runs/demo                      (after Ctrl-C or an I/O failure)\n"
                        "  particula resume runs/demo --set time.end=1     (continue a finished run)"));

  std::string info_case;
  std::vector<std::string> info_overrides;
  bool info_no_timing = false;
  auto* info = app.add_subcommand("info", "Particle counts, time step, steps, memory and wall-time estimate of a case");
  info->add_option("case", info_case, "Case file (TOML)")->required();
  info->add_option("--set", info_overrides, "Override a case key (repeatable)");
  info->add_flag("--no-timing", info_no_timing, "Do not time a few steps (no wall-time estimate)");
  info->footer(footer("  particula info cases/dkt.toml --set resolution.d0=2e-4"));

  particula::ValidateOptions validate_opt;
  auto* validate = app.add_subcommand(
      "validate",
      "Run the validation cases (exact solutions, the paper's five body cases and the DFG benchmark; the robustness "
      "cases with --group robustness) against their references and write DIR/report.md (exit 3 on a fail)");
  validate->add_flag("--quick", validate_opt.quick,
                     "Analytic and robustness cases at the shipped resolution (else twice as fine); paper and benchmark "
                     "cases at a coarse level (else as shipped)");
  validate->add_option("--out", validate_opt.out_dir, "Output directory (default runs/validate)");
  validate->add_option("--threads", validate_opt.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  validate->add_option("--set", validate_opt.sets,
                       "Override a case key in every validation case, after its level's own overrides, e.g. --set "
                       "numerics.shifting_beta=0.02 (repeatable)");
  validate->add_option("--case", validate_opt.only, "Run only this validation case, of any group (repeatable)");
  std::vector<std::string> validate_groups;
  validate->add_option("--group", validate_groups,
                       "Run only this group: analytic, paper, benchmark or robustness (repeatable; default: analytic, "
                       "paper and benchmark, the robustness cases only when asked for)")
      ->check(CLI::IsMember({"analytic", "paper", "benchmark", "robustness"}));
  validate->add_flag("--quiet", validate_opt.quiet, "Only the final line");
  validate->footer(footer("  particula validate --quick --out runs/validate\n"
                          "  particula validate --case couette --case falling_cylinder --quick\n"
                          "  particula validate --group robustness --quick\n"
                          "An unknown --case name lists the valid names."));

  std::uint64_t generate_seed = 0;
  std::string generate_out;
  auto* generate = app.add_subcommand(
      "generate", "Write a random valid case file from a seed (bodies, box or channel, forces; for robustness tests)");
  generate->add_option("--seed", generate_seed, "Seed of the random case (the same seed gives the same file)")
      ->required();
  generate->add_option("--out", generate_out, "Case file to write (default: standard output)");
  generate->footer(footer("  particula generate --seed 7 --out seed7.toml && particula run seed7.toml"));

  bool schema_json = false;
  auto* schema = app.add_subcommand(
      "schema", "Print the case-file schema: the key reference (markdown, = docs/case-files.md) or, with --json, a "
                "JSON Schema for editors");
  schema->add_flag("--json", schema_json,
                   "A JSON Schema (draft-07) of case files: types, units, defaults, ranges, choices, required keys");
  schema->footer(footer("  particula schema --json > particula-case.schema.json\n"
                        "  (Even Better TOML / taplo: .taplo.toml associates cases/**/*.toml with "
                        "docs/case.schema.json)"));

  std::string plot_dir;
  auto* plot = app.add_subcommand("plot", "(Re)draw the plots of a run directory into DIR/plots (tools/plot_run.py)");
  plot->add_option("dir", plot_dir, "Run directory")->required();
  plot->footer(footer("  particula plot runs/demo"));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    run_opt.plots = !no_plots;
    resume_opt.plots = !resume_no_plots;
    if (*run) return particula::run_command(run_case, run_opt);
    if (*resume) return particula::resume_command(resume_opt);
    if (*info) return particula::info_command(info_case, info_overrides, !info_no_timing);
    if (*validate) {
      for (const auto& g : validate_groups)
        validate_opt.groups.push_back(g == "analytic"    ? particula::ValidationGroup::Analytic
                                      : g == "paper"     ? particula::ValidationGroup::Paper
                                      : g == "benchmark" ? particula::ValidationGroup::Benchmark
                                                         : particula::ValidationGroup::Robustness);
      return particula::validate_command(validate_opt);
    }
    if (*generate) return particula::generate_command(generate_seed, generate_out);
    if (*plot) return particula::plot_command(plot_dir);
    if (*schema) {
      const std::string text = schema_json ? particula::case_json_schema() : particula::case_reference_markdown();
      std::fwrite(text.data(), 1, text.size(), stdout);
      return std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : particula::kExitIoFailure;
    }
  } catch (const particula::io::WriteError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return particula::kExitIoFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 1;
}
