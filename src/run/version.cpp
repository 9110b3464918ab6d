// The build's version and commit, set by CMake on this file only (PARTICULA_VERSION,
// PARTICULA_GIT_COMMIT; see CMakeLists.txt), so a new commit recompiles nothing else.
#include "particula/run/version.hpp"

#ifndef PARTICULA_VERSION
#define PARTICULA_VERSION "unknown"
#endif
#ifndef PARTICULA_GIT_COMMIT
#define PARTICULA_GIT_COMMIT "unknown"
#endif

namespace particula {

std::string version() { return PARTICULA_VERSION; }

std::string git_commit() { return PARTICULA_GIT_COMMIT; }

std::string version_line() { return "particula " + version() + " (commit " + git_commit() + ")"; }

}  // namespace particula
