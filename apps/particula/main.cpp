// particula: command-line program (design.md, command-line contract).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "particula/run/info.hpp"
#include "particula/run/runner.hpp"

int main(int argc, char** argv) {
  CLI::App app{"particula: rigid bodies in viscous flow, weakly compressible SPH (Hashemi, Fatehi & Manzari 2012)"};
  app.require_subcommand(1);

  particula::RunOptions run_opt;
  std::string run_case;
  std::string backend = "cpu";
  auto* run = app.add_subcommand("run", "Run a case file and write its run directory");
  run->add_option("case", run_case, "Case file (TOML)")->required();
  run->add_option("--out", run_opt.out_dir, "Run directory (default runs/<case name>)");
  run->add_option("--set", run_opt.overrides, "Override a case key, e.g. --set resolution.d0=5e-5 (repeatable)");
  run->add_option("--threads", run_opt.threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 4096));
  run->add_option("--backend", backend, "Compute backend")->check(CLI::IsMember({"cpu"}));
  run->add_flag("--quiet", run_opt.quiet, "No progress line");
  bool no_plots = false;
  run->add_flag("--no-plots", no_plots, "Do not draw plots at the end of the run");
  run->add_flag("--overwrite", run_opt.overwrite, "Replace an existing run directory");

  std::string info_case;
  std::vector<std::string> info_overrides;
  auto* info = app.add_subcommand("info", "Particle counts, time step, steps, memory and wall-time estimate of a case");
  info->add_option("case", info_case, "Case file (TOML)")->required();
  info->add_option("--set", info_overrides, "Override a case key (repeatable)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    run_opt.plots = !no_plots;
    if (*run) return particula::run_command(run_case, run_opt);
    if (*info) return particula::info_command(info_case, info_overrides);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    return 1;
  }
  return 1;
}
