// The random group of `particula validate` (validate.hpp, run_random_batch): the generated
// cases of seeds 1 to N, each run to its end, counted and reported.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "particula/case/error.hpp"
#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/run/runner.hpp"
#include "particula/solver/solver.hpp"
#include "particula/validation/random_case.hpp"
#include "particula/validation/validate.hpp"
#include "run_outcome.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

/// What the first line of a generated case says it drew ("L-shaped container", ...).
std::string container_of(const std::string& text) {
  const std::string first = text.substr(0, text.find('\n'));
  const std::size_t at = first.find("placed, ");
  std::string kind = at == std::string::npos ? "" : first.substr(at + 8);
  if (!kind.empty() && kind.back() == '.') kind.pop_back();
  return kind;
}

std::string table_cell(std::string s) {
  for (char& ch : s)
    if (ch == '|' || ch == '\n') ch = '/';
  return s;
}

}  // namespace

RandomBatch run_random_batch(const ValidateOptions& opt) {
  RandomBatch b;
  const int seeds = opt.random_seeds > 0 ? opt.random_seeds : (opt.quick ? 40 : 200);
  const fs::path dir = opt.out_dir / "random";
  std::string rows;
  fs::create_directories(dir);
  for (int n = 0; n < seeds; ++n) {
    const int k = opt.random_first + n;
    const auto seed = static_cast<std::uint64_t>(k);
    const std::string text = random_case_toml(seed);
    const fs::path case_file = dir / fmt::format("seed_{}.toml", seed);
    io::write_file_atomic(case_file, text);
    ++b.generated;
    const std::string kind = container_of(text);
    try {
      load_case(case_file);
    } catch (const CaseError& e) {
      ++b.refused;
      rows += fmt::format("| {} | {} | refused at load | | | {} |\n", seed, kind, table_cell(e.what()));
      if (!opt.quiet) std::fprintf(stderr, "validate: random seed %d refused at load\n", k);
      continue;
    }
    RunOptions run;
    run.out_dir = dir / fmt::format("seed_{}", seed);
    run.overwrite = true;
    run.quiet = true;
    run.threads = opt.threads;
    run.overrides = opt.sets;
    const auto t0 = std::chrono::steady_clock::now();
    const int code = run_command(case_file, run);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const RunOutcome o = read_outcome(run.out_dir);
    if (code == 130) {
      b.interrupted = true;
      break;
    }
    const double ratio = o.dt_min_ratio;
    const bool collapsed = !(ratio >= kTimeStepDrop);
    if (code == 0)
      ++b.finished;
    else
      ++b.failed;
    if (code == 0 && collapsed) ++b.collapsed;
    if (ratio < b.smallest_ratio) b.smallest_ratio = ratio, b.smallest_seed = seed;
    const std::string verdict = code == 0 ? (collapsed ? "**time step below 1e-3**" : "finished")
                                          : fmt::format("**exit {}**", code);
    rows += fmt::format("| {} | {} | {} | {} | {:.3g} | {} |\n", seed, kind, verdict, o.steps, ratio,
                        table_cell(o.failure.empty() ? fmt::format("{:.1f} s wall", wall) : o.failure));
    if (!opt.quiet)
      std::fprintf(stderr, "validate: random seed %d (%s): %s, %lld steps, smallest dt / case's %.3g, %.1f s\n", k,
                   kind.c_str(), code == 0 ? "finished" : "FAILED", static_cast<long long>(o.steps), ratio, wall);
  }
  b.markdown = fmt::format(
      "\n## Random cases\n\nThe cases of `particula generate --seed N` for N = {} to {} (`{}`), each run to its end "
      "with default numerics; a case refused at load is counted, not failed. Each is in `random/seed_N.toml` and "
      "its run in `random/seed_N/`.\n\n"
      "| generated | refused at load | finished | exit 3 or another failure | time step below 1e-3 of the case's | "
      "smallest step / the case's |\n|---|---|---|---|---|---|\n| {} | {} | {} | {} | {} | {:.3g} (seed {}) |\n\n"
      "| seed | container | outcome | steps | smallest step / the case's | failure or wall time |\n"
      "|---|---|---|---|---|---|\n",
      opt.random_first, opt.random_first + seeds - 1, "particula validate --group random", b.generated, b.refused, b.finished, b.failed, b.collapsed,
      b.smallest_ratio, b.smallest_seed);
  b.markdown += rows;
  std::fprintf(stderr,
               "validate: random cases: %d generated, %d refused at load, %d finished, %d failed, %d with the time "
               "step below 1e-3 of the case's; smallest step ratio %.3g (seed %llu)\n",
               b.generated, b.refused, b.finished, b.failed, b.collapsed, b.smallest_ratio,
               static_cast<unsigned long long>(b.smallest_seed));
  return b;
}

}  // namespace particula
