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

/// The fully resolved case as TOML: every key with its value, defaults filled in. Loading this
/// text again gives an identical Case (viscosity is always written as fluid.nu).
std::string resolved_case_toml(const Case& c);

}  // namespace particula
