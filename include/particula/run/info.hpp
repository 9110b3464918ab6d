// `particula info CASE`: what a run would be (particles, dt, steps, memory, time) without
// running it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace particula {

/// `timing`: time a few steps for the wall-time estimate (false: skip them, e.g. for tests).
int info_command(const std::filesystem::path& case_file, const std::vector<std::string>& overrides,
                 bool timing = true);

}  // namespace particula
