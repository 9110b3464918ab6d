// The build's version and commit, from the header CMake generates at configure time
// (src/run/build_version.hpp.in), included here only, so a new commit recompiles nothing else.
#include "particula/run/version.hpp"

#include "particula_build_version.hpp"

namespace particula {

std::string version() { return PARTICULA_VERSION; }

std::string git_commit() { return PARTICULA_GIT_COMMIT; }

std::string version_line() { return "particula " + version() + " (commit " + git_commit() + ")"; }

}  // namespace particula
