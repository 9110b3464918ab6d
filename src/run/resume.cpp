// `particula resume DIR`: the run directory's marker, lock and checkpoint checked, its case (the
// checkpoint's, with the --set a resume may change) against an edited case.toml, the solver
// restarted exactly as it was, then the time loop `run` uses (run_loop.hpp).
#include <fmt/format.h>
#include <omp.h>

#include <cstdio>
#include <memory>
#include <optional>

#include "particula/case/load.hpp"
#include "particula/io/atomic_file.hpp"
#include "particula/run/checkpoint.hpp"
#include "particula/run/run_dir.hpp"
#include "particula/run/runner.hpp"
#include "particula/run/version.hpp"
#include "particula/scene/scene.hpp"
#include "particula/solver/solver.hpp"
#include "run_loop.hpp"

namespace particula {

namespace {
namespace fs = std::filesystem;
using namespace run_detail;
}  // namespace

bool resume_override_allowed(const std::string& assignment) {
  std::string key = assignment.substr(0, assignment.find('='));
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.pop_back();
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t')) key.erase(key.begin());
  return key == "time.end" || (key.rfind("output.", 0) == 0 && key.size() > 7);
}

namespace {

/// Whether every --set of a resume changes a key a resume may change (else says which does not).
bool resume_overrides_allowed(const std::vector<std::string>& overrides) {
  for (const auto& o : overrides)
    if (!resume_override_allowed(o)) {
      std::fprintf(
          stderr,
          "error: --set %s: only time.end and output.* keys can be changed when resuming (the checkpoint "
          "fixes the rest of the case)\n",
          o.c_str());
      return false;
    }
  return true;
}

/// The marker of a run directory `particula run` made. Says why not and returns nothing otherwise.
std::optional<RunMarker> resumable_run_marker(const fs::path& run_dir) {
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) {
    std::fprintf(stderr, "error: run directory '%s' does not exist\n", run_dir.string().c_str());
    return std::nullopt;
  }
  std::optional<RunMarker> marker;
  try {
    marker = read_marker(run_dir);
  } catch (const io::IoError& e) {
    bad_input(e);
    return std::nullopt;
  }
  if (!marker || marker->kind != MarkedKind::Run) {
    std::fprintf(
        stderr,
        "error: '%s' is not a particula run directory (it has no %s marker with a case; run directories are "
        "made by 'particula run')\n",
        run_dir.string().c_str(), kRunMarker);
    return std::nullopt;
  }
  return marker;
}

/// Takes the run directory's lock for the whole resume: 0, or the exit code (2: in use; 4: I/O).
int lock_for_resume(const fs::path& run_dir, RunDirLock& lock) {
  try {
    lock = RunDirLock(run_dir);
  } catch (const RunDirRefused& e) {
    return bad_input(e);
  } catch (const io::WriteError& e) {
    std::fprintf(stderr, "error: I/O failure: %s\n", e.what());
    return kExitIoFailure;
  }
  return 0;
}

/// Whether the run directory has its checkpoint `file` (says so when not).
bool has_checkpoint(const fs::path& run_dir, const fs::path& file) {
  std::error_code ec;
  if (fs::exists(file, ec)) return true;
  std::fprintf(stderr, "error: '%s' has no checkpoint to resume from ('%s' is missing)\n", run_dir.string().c_str(),
               file.string().c_str());
  return false;
}

/// Refuses (io::IoError) a resume whose run directory's case.toml says something else than the
/// case the resume runs: the checkpoint's (`checkpoint_case`) or that with the resume's --set
/// (`resumed_case`). A resume takes the case from its checkpoint, so an edit of case.toml would
/// otherwise be lost without a word. A missing case.toml is written again; comments and
/// formatting are not edits (both sides are compared resolved).
void check_case_file_unedited(const fs::path& run_dir, const std::string& checkpoint_case,
                              const std::string& resumed_case) {
  const fs::path file = run_dir / "case.toml";
  std::error_code ec;
  if (!fs::exists(file, ec)) return;
  std::string on_disk;
  try {
    on_disk = resolved_case_toml(load_case(file));
  } catch (const CaseError& e) {
    throw io::IoError(fmt::format("{}\n{} no longer loads, so a resume would replace it with the checkpoint's "
                                  "case: delete it (resume writes it again) or undo the edit",
                                  e.what(), file.string()));
  }
  if (on_disk == resumed_case || resolved_case_differences(checkpoint_case, on_disk).empty()) return;
  std::string lines;
  for (const auto& l : resolved_case_differences(checkpoint_case, on_disk)) lines += "\n    " + l;
  throw io::IoError(fmt::format(
      "{} was edited since the run wrote it; a resume takes the case from its checkpoint, so the edit would "
      "be lost (- the checkpoint's, + the file's):{}\nOnly time.end and output.* can change in a resumed run, "
      "with --set KEY=VALUE; to resume, undo the edit or delete {} (resume writes it again)",
      file.string(), lines, file.string()));
}

/// Reads the checkpoint `file` of the run the marker describes into `k`, and its case (with the
/// resume's overrides) into s.c; says why they cannot be resumed and returns false otherwise.
bool read_resume_state(const ResumeOptions& opt, const fs::path& file, const RunMarker& marker, Session& s,
                       Checkpoint& k) {
  try {
    k = read_checkpoint(file);
    if (k.case_hash != marker.case_hash)
      throw io::IoError(fmt::format(
          "checkpoint '{}' was written for another case (case identity {:016x}) than the one run directory "
          "'{}' was "
          "created for ({:016x}, in its {} marker): it does not belong to this run; resume refused",
          file.string(), k.case_hash, opt.run_dir.string(), marker.case_hash, kRunMarker));
    s.c = load_case_text(k.case_toml, file, opt.overrides);
    check_checkpoint_fits_case(k, s.c, file);
    check_case_file_unedited(opt.run_dir, k.case_toml, resolved_case_toml(s.c));
  } catch (const CaseError& e) {
    bad_input(e);
    return false;
  } catch (const io::IoError& e) {
    bad_input(e);
    return false;
  }
  if (s.c.t_end < k.time * (1 - 1e-12)) {
    std::fprintf(stderr, "error: key 'time.end': %.9g s is before the checkpoint's time %.9g s\n", s.c.t_end,
                 k.time);
    return false;
  }
  return true;
}

/// Removes the temporary files a killed particula left in the run directory, and says which.
void clean_stale_temp_files(const fs::path& dir, Reporter& rep) {
  const auto removed = remove_stale_temp_files(dir);
  if (removed.empty()) return;
  std::string names;
  for (const auto& r : removed) names += (names.empty() ? "" : ", ") + r.lexically_relative(dir).string();
  rep.say(fmt::format("removed {} temporary file(s) left by a particula that was killed while writing: {}",
                      removed.size(), names));
}

/// The solver at the checkpoint's state: its particles, groups, counters, fluxes and kept band.
std::unique_ptr<Solver> restarted_solver(const Case& c, Checkpoint& k, const std::string& backend) {
  const Domain domain{c.domain_min, c.domain_max, c.periodic_x, c.periodic_y};
  PhysicsParams prm = physics_params(c);
  prm.cuda = backend == "cuda";
  auto solver = std::make_unique<Solver>(prm, domain, std::move(k.particles), std::move(k.groups),
                                         SolverStart::Restart, k.time, k.step);
  solver->set_counters(k.counters);
  solver->set_open_flux(k.open_flux);
  solver->set_load_band_state(k.load_band);
  return solver;
}

}  // namespace

int resume_command(const ResumeOptions& opt) {
  if (!resume_overrides_allowed(opt.overrides)) return 2;
  if (!backend_usable(opt.backend)) return 2;
  SignalGuard signals;
  const fs::path file = checkpoint_path(opt.run_dir);
  const std::optional<RunMarker> marker = resumable_run_marker(opt.run_dir);
  if (!marker) return 2;
  RunDirLock lock;  // held until the resume has ended
  if (const int code = lock_for_resume(opt.run_dir, lock)) return code;
  if (!has_checkpoint(opt.run_dir, file)) return 2;
  Session s;
  Checkpoint k;
  if (!read_resume_state(opt, file, *marker, s, k)) return 2;
  s.dir = opt.run_dir;
  s.overrides = opt.overrides;
  s.progress = opt.progress;
  s.case_hash = k.case_hash;
  s.resumed = true;
  s.t_start = k.time;
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  std::unique_ptr<Reporter> rep;
  try {
    rep = std::make_unique<Reporter>(s.dir / "log.txt", opt.quiet);
    clean_stale_temp_files(s.dir, *rep);
    io::write_file_atomic(s.dir / "case.toml", resolved_case_toml(s.c));
    const Particles& P = k.particles;
    s.n_fluid = P.size() - P.n_boundary;
    rep->say(
        fmt::format("{}: resuming case '{}' in {} at t = {:.9g} s, step {} ({} particles), to t = {:.6g} s, "
                    "{} threads, backend {}",
                    version_line(), s.c.name, s.dir.string(), k.time, k.step, P.size(), s.c.t_end,
                    omp_get_max_threads(), opt.backend));
    s.solver = restarted_solver(s.c, k, opt.backend);
    s.outputs = std::make_unique<RunOutputs>(s.dir, s.c, k.marks, k.time, stop_requested);
    if (stop_requested()) return interrupted_before_start(s, *rep, "the run directory is as it was");
    return run_loop(s, *rep, opt.plots);
  } catch (const io::WriteError& e) {
    return io_failure(e, s, rep.get());
  } catch (const io::IoError& e) {
    return bad_input(e);
  }
}

}  // namespace particula
