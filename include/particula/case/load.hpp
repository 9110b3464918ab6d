// Loading a case: TOML file -> --set overrides -> schema checks -> typed Case.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "particula/case/case.hpp"
#include "particula/case/error.hpp"

namespace particula {

/// Reads the TOML case `file`, applies `overrides` ("key=value", as given to --set; later ones
/// win), checks every key against the schema and returns the filled Case.
/// Override keys are dotted schema keys; members of arrays of tables are addressed by index,
/// e.g. "probe.0.points=81". Values are TOML values ("[0,-9.81]", "5e-5", "true"); a string or
/// choice key also takes a bare word ("numerics.laplacian=morris").
/// Throws CaseError for anything wrong with the file, its contents or the overrides.
Case load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// As load_case, for case text already in memory; `source` names it in messages and Case::source.
Case load_case_text(std::string_view text, const std::filesystem::path& source,
                    const std::vector<std::string>& overrides = {});

/// Limits the load checks apply (src/case/cost_checks.cpp; docs/case-files.md lists them).
/// All probes together have at most this many points (memory and output size).
inline constexpr double kMaxProbePoints = 1e6;
/// Probe points are at least d0 / kProbePointsPerD0 apart.
inline constexpr double kProbePointsPerD0 = 100;
/// A run takes at most this many steps to time.end (or time.max_steps).
inline constexpr double kMaxSteps = 1e9;
/// Each output stream (outputs, snapshots, checkpoints, each probe) writes at most this often.
inline constexpr double kMaxOutputs = 1e6;
/// time.dt_max (when set) and every output interval are at least this fraction of the stable
/// time step.
inline constexpr double kMinStepFraction = 1e-3;

/// The stable time step at t = 0 estimated from the case alone: P.30-P.31 with the nearest
/// pair of the perturbed lattice and the largest initial speed (walls, bodies, initial flow),
/// capped by time.dt_max when `capped`. The load checks compare time.dt_max, the output
/// intervals and the step count with it; `info --no-timing` prints it.
real estimated_dt(const Case& c, bool capped = true);

/// The fully resolved case as TOML: every key with its value, defaults filled in. Loading this
/// text again gives an identical Case (viscosity is always written as fluid.nu).
std::string resolved_case_toml(const Case& c);

/// The lines in which two resolved cases (resolved_case_toml texts) differ, each key line named
/// with its table ("[fluid] nu = 1e-06"; the n-th "[[body]]" as "[[body]]#n"): first the lines
/// of `before` that `after` lacks ("- ..."), then those of `after` that `before` lacks ("+ ..."),
/// at most `max_lines` in all. Empty when they say the same. Comment lines are ignored.
std::vector<std::string> resolved_case_differences(const std::string& before, const std::string& after,
                                                   std::size_t max_lines = 8);

}  // namespace particula
