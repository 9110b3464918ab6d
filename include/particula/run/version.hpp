// Which particula made a run: the version (CMake's project version) and the git commit the
// build was configured from. Printed by `particula --version`, written to summary.json and
// log.txt.
#pragma once

#include <string>

namespace particula {

/// The version, e.g. "0.1.0".
std::string version();
/// The commit: `git describe --always --dirty --abbrev=12` at configure time (a "-dirty" suffix
/// when the checkout had uncommitted changes then), or "unknown" outside a git checkout.
std::string git_commit();
/// "particula 0.1.0 (commit 1a2b3c4d5e6f)", the line `--version` prints.
std::string version_line();

}  // namespace particula
