#include "particula/run/validate.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>

#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/io/json.hpp"
#include "particula/io/vtk.hpp"
#include "particula/run/limits.hpp"
#include "particula/run/runner.hpp"
#include "particula/solver/particles.hpp"

namespace particula {

namespace fs = std::filesystem;

namespace {

std::string percent(double fraction) { return fmt::format("{:.3g} %", 100 * fraction); }

/// The last snapshot of a run directory (particles.pvd's last entry).
io::VtpData last_snapshot(const fs::path& run_dir, double& time) {
  const io::PvdIndex index = io::PvdIndex::read(run_dir / "particles.pvd");
  if (index.entries().empty()) throw io::IoError(fmt::format("'{}': no snapshot", (run_dir / "particles.pvd").string()));
  time = index.entries().back().time;
  return io::read_vtp(run_dir / index.entries().back().file);
}

/// Largest speed of the fluid particles of a snapshot.
double peak_fluid_speed(const io::VtpData& vtp) {
  const auto& v = vtp.array("velocity");
  const auto& kind = vtp.int_array("kind");
  double peak = 0;
  for (std::size_t i = 0; i < vtp.num_points; ++i)
    if (kind.data[i] == static_cast<std::int32_t>(Kind::Fluid))
      peak = std::max(peak, std::hypot(v.data[3 * i], v.data[3 * i + 1]));
  return peak;
}

}  // namespace

std::vector<ValidationCheck> check_profile_error(const fs::path& run_dir, double limit) {
  const std::string summary = io::read_file(run_dir / "summary.json");
  double e = 0;
  try {
    e = io::json_number_field(summary, "profile_error");
  } catch (const std::exception&) {
    throw io::IoError(fmt::format("'{}': no profile_error", (run_dir / "summary.json").string()));
  }
  ValidationCheck c;
  c.quantity = "L2 error of vx (fluid particles, % of peak speed) at time.end";
  c.value = e;
  c.shown = percent(e);
  c.reference = "series solution";
  c.tolerance = "< " + percent(limit);
  c.pass = e < limit;  // false for NaN
  return {c};
}

std::vector<ValidationCheck> check_taylor_green_decay(const fs::path& run_dir, const Case& cs, double rel_tol) {
  double t = 0;
  const io::VtpData vtp = last_snapshot(run_dir, t);
  const double L = cs.domain_max.x - cs.domain_min.x;
  const double ratio = peak_fluid_speed(vtp) / cs.initial_amplitude;
  const double ref = std::exp(-8 * M_PI * M_PI * cs.nu * t / (L * L));
  ValidationCheck c;
  c.quantity = fmt::format("peak speed / U at t = {:.4g} s (last snapshot)", t);
  c.value = ratio;
  c.shown = fmt::format("{:.4f}", ratio);
  c.reference = fmt::format("{:.4f} = exp(-8 pi^2 t/Re)", ref);
  c.tolerance = "within " + percent(rel_tol);
  c.pass = std::fabs(ratio / ref - 1) < rel_tol;
  return {c};
}

std::vector<ValidationCheck> check_hydrostatic(const fs::path& run_dir, const Case& cs, double rel_tol,
                                               double speed_frac) {
  double t = 0;
  const io::VtpData vtp = last_snapshot(run_dir, t);
  const double g = norm(cs.gravity), H = cs.domain_max.y - cs.domain_min.y;
  // Bottom wall particles, corners excluded (their pressure also carries the side walls').
  const auto& p = vtp.array("pressure");
  const auto& kind = vtp.int_array("kind");
  const double tol = 1e-6 * cs.d0;
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < vtp.num_points; ++i) {
    const Vec2 x = vtp.points[i];
    if (kind.data[i] != static_cast<std::int32_t>(Kind::Boundary) || std::fabs(x.y - cs.domain_min.y) > tol) continue;
    if (x.x < cs.domain_min.x + tol || x.x > cs.domain_max.x - tol) continue;
    sum += p.data[i];
    ++n;
  }
  if (n == 0) throw io::IoError(fmt::format("'{}': no bottom wall particles in the last snapshot", run_dir.string()));
  const double bottom = sum / static_cast<double>(n), ref = cs.p0 + cs.rho0 * g * H;
  ValidationCheck pc;
  pc.quantity = fmt::format("mean bottom wall pressure at t = {:.4g} s (Pa)", t);
  pc.value = bottom;
  pc.shown = fmt::format("{:.2f}", bottom);
  pc.reference = fmt::format("{:.2f} = p0 + rho g H", ref);
  pc.tolerance = "within " + percent(rel_tol);
  pc.pass = std::fabs(bottom / ref - 1) < rel_tol;
  const double speed = peak_fluid_speed(vtp), scale = std::sqrt(g * H);
  ValidationCheck vc;
  vc.quantity = fmt::format("peak fluid speed / sqrt(g H) at t = {:.4g} s", t);
  vc.value = speed / scale;
  vc.shown = percent(speed / scale);
  vc.reference = "0 (at rest)";
  vc.tolerance = "< " + percent(speed_frac);
  vc.pass = speed / scale < speed_frac;
  return {pc, vc};
}

std::vector<ValidationEntry> validation_entries() {
  std::vector<ValidationEntry> v;
  v.push_back({"couette", "cases/couette.toml", {}, [](const fs::path& d, const Case&) {
                 return check_profile_error(d, 0.01);
               }});
  v.push_back({"poiseuille", "cases/poiseuille.toml", {}, [](const fs::path& d, const Case&) {
                 return check_profile_error(d, 0.01);
               }});
  v.push_back({"taylor_green", "cases/taylor_green.toml", {}, [](const fs::path& d, const Case& c) {
                 return check_taylor_green_decay(d, c, 0.03);
               }});
  v.push_back({"hydrostatic", "cases/hydrostatic.toml", {}, [](const fs::path& d, const Case& c) {
                 return check_hydrostatic(d, c, 0.01, 0.01);
               }});
  // Body cases of the paper (with reference data in ../shared/reference) go here.
  return v;
}

namespace {

struct EntryResult {
  const ValidationEntry* entry = nullptr;
  fs::path dir;
  double d0 = 0, wall = 0;
  int exit_code = 0;
  std::string error;  // why it could not be evaluated
  std::vector<ValidationCheck> checks;
  bool pass() const {
    if (exit_code != 0 || !error.empty() || checks.empty()) return false;
    return std::all_of(checks.begin(), checks.end(), [](const ValidationCheck& c) { return c.pass; });
  }
};

std::string cell(std::string s) {
  std::replace(s.begin(), s.end(), '|', '/');
  return s;
}

std::string report_markdown(const std::vector<EntryResult>& results, const ValidateOptions& opt) {
  std::string md = "# particula validation report\n\n";
  md += fmt::format("Mode: {} ({}); {} OpenMP threads. Generated by `particula validate{}`.\n\n",
                    opt.quick ? "quick" : "default", opt.quick ? "the shipped resolution" : "twice as fine as shipped",
                    omp_get_max_threads(), opt.quick ? " --quick" : "");
  md += "| case | quantity | value | reference | tolerance | result |\n|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    const std::string name = fmt::format("[{}]({}/)", r.entry->name, r.entry->name);
    if (r.exit_code != 0 || !r.error.empty()) {
      md += fmt::format("| {} | run | {} | exit 0 | | **FAIL** |\n", name,
                        cell(r.error.empty() ? fmt::format("exit code {}", r.exit_code) : r.error));
      continue;
    }
    for (const auto& c : r.checks)
      md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", name, cell(c.quantity), cell(c.shown), cell(c.reference),
                        cell(c.tolerance), c.pass ? "pass" : "**FAIL**");
  }
  const auto passed = std::count_if(results.begin(), results.end(), [](const EntryResult& r) { return r.pass(); });
  md += fmt::format("\n{} of {} cases pass.\n\n## Runs and plots\n\n", passed, results.size());
  for (const auto& r : results) {
    md += fmt::format("### {}\n\n`{}` with resolution.d0 = {} m, {:.1f} s wall time; run directory [{}/]({}/).\n\n",
                      r.entry->name, r.entry->case_file, r.d0, r.wall, r.entry->name, r.entry->name);
    std::vector<std::string> pngs;
    std::error_code ec;
    if (fs::is_directory(r.dir / "plots", ec))
      for (const auto& e : fs::directory_iterator(r.dir / "plots", ec))
        if (e.path().extension() == ".png") pngs.push_back(e.path().filename().string());
    std::sort(pngs.begin(), pngs.end());
    if (pngs.empty()) md += "No plots (python3-matplotlib missing, or the run failed).\n\n";
    for (const auto& png : pngs) md += fmt::format("- [{}]({}/plots/{})\n", png, r.entry->name, png);
    if (!pngs.empty()) md += "\n";
  }
  return md;
}

}  // namespace

int validate_command(const ValidateOptions& opt) {
  std::error_code ec;
  fs::create_directories(opt.out_dir, ec);
  if (ec || !fs::is_directory(opt.out_dir, ec)) {
    std::fprintf(stderr, "error: cannot create the validation directory '%s'\n", opt.out_dir.string().c_str());
    return 2;
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const fs::path source = PARTICULA_SOURCE_DIR;
  std::vector<ValidationEntry> entries = validation_entries();
  for (const auto& name : opt.only)
    if (std::none_of(entries.begin(), entries.end(), [&](const ValidationEntry& e) { return e.name == name; })) {
      std::fprintf(stderr, "error: no validation case '%s'\n", name.c_str());
      return 2;
    }
  std::vector<EntryResult> results;
  for (const auto& entry : entries) {
    if (!opt.only.empty() && std::find(opt.only.begin(), opt.only.end(), entry.name) == opt.only.end()) continue;
    EntryResult r;
    r.entry = &entry;
    r.dir = opt.out_dir / entry.name;
    RunOptions run;
    run.out_dir = r.dir;
    run.overwrite = true;
    run.quiet = true;
    run.threads = opt.threads;
    run.overrides = entry.overrides;
    const fs::path case_file = source / entry.case_file;
    try {
      Case base = load_case(case_file, entry.overrides);
      r.d0 = opt.quick ? base.d0 : base.d0 / 2;
      run.overrides.push_back(fmt::format("resolution.d0={}", r.d0));
      if (!opt.quiet)
        std::fprintf(stderr, "validate: %s (%s, resolution.d0 = %g m) ...\n", entry.name.c_str(),
                     entry.case_file.c_str(), r.d0);
      const auto t0 = std::chrono::steady_clock::now();
      r.exit_code = run_command(case_file, run);
      r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (r.exit_code == 0) r.checks = entry.evaluate(r.dir, load_case(r.dir / "case.toml"));
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    if (!opt.quiet) {
      if (r.exit_code != 0 || !r.error.empty())
        std::fprintf(stderr, "  FAIL: %s\n",
                     r.error.empty() ? fmt::format("the run ended with exit code {}", r.exit_code).c_str()
                                     : r.error.c_str());
      for (const auto& c : r.checks)
        std::fprintf(stderr, "  %s: %s (reference %s, %s): %s\n", c.quantity.c_str(), c.shown.c_str(),
                     c.reference.c_str(), c.tolerance.c_str(), c.pass ? "pass" : "FAIL");
    }
    const bool interrupted = r.exit_code == 130;
    results.push_back(std::move(r));
    if (interrupted) break;  // Ctrl-C stops the suite, not only the current run
  }
  const fs::path report = opt.out_dir / "report.md";
  try {
    io::write_file_atomic(report, report_markdown(results, opt));
  } catch (const io::IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (!results.empty() && results.back().exit_code == 130) {
    std::fprintf(stderr, "validate: interrupted; partial report in %s\n", report.string().c_str());
    return 130;
  }
  const bool all = std::all_of(results.begin(), results.end(), [](const EntryResult& r) { return r.pass(); });
  std::fprintf(stderr, "validate: %s; report in %s\n", all ? "all cases pass" : "SOME CASES FAIL",
               report.string().c_str());
  return all ? 0 : 3;
}

}  // namespace particula
